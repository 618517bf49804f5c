#pragma once
// Readers that take a path (the OBJ builder, the window's script reader) get
// the fuzzer's bytes through a file of this process's own, in memory-backed
// /dev/shm when there is one: parallel fuzzing jobs never share it, and it is
// removed as soon as the reader has read it (only a crash inside the reader
// leaves it behind).
#include <cstddef>
#include <cstdint>
#include <string>

namespace neurocloth::fuzz {

class InputFile {
 public:
  // `name` ends the file name ("input.obj").
  explicit InputFile(const std::string& name);
  ~InputFile();
  InputFile(const InputFile&) = delete;
  InputFile& operator=(const InputFile&) = delete;

  // Replaces the file's contents with `data`; returns its path.
  const std::string& write(const std::uint8_t* data, std::size_t size);
  // Deletes the file once the reader is done with it: a finding aborts the
  // process without running destructors, and should leave nothing behind.
  void remove();
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

}  // namespace neurocloth::fuzz
