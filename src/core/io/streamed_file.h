#pragma once
// An output file written piece by piece (a recording, a point cache) that
// appears at its path only when complete. The bytes go to a temporary file in
// the same folder, which finish() flushes to disk and renames into place; if
// anything fails, or the object dies first, the temporary file is removed and
// the path keeps what it held before (write_file_atomically's idea, for files
// too large, or too long in the making, to build in memory).
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>

namespace neurocloth {

class StreamedFile {
 public:
  // Creates the temporary file beside `path`. Throws std::runtime_error naming
  // `path` when the folder cannot be written.
  explicit StreamedFile(std::string path);
  ~StreamedFile();
  StreamedFile(const StreamedFile&) = delete;
  StreamedFile& operator=(const StreamedFile&) = delete;

  // Appends `size` bytes. Throws std::runtime_error naming the path.
  void append(const void* data, std::size_t size);
  // Rewrites bytes already written (a header's count, known only at the end).
  void overwrite(std::uint64_t offset, const void* data, std::size_t size);
  // Drops everything after the first `size` bytes.
  void truncate(std::uint64_t size);
  std::uint64_t size() const { return size_; }
  // Flushes, syncs and renames into place; afterwards nothing may be written.
  void finish();

  const std::string& path() const { return path_; }

 private:
  [[noreturn]] void fail(const char* what) const;
  std::string path_, temporary_;
  std::FILE* file_ = nullptr;
  std::uint64_t size_ = 0;
};

// Little-endian encodings: the files say so, whatever the machine.
void put_le32(unsigned char* out, std::uint32_t v);
void put_le64(unsigned char* out, std::uint64_t v);
std::uint32_t get_le32(const unsigned char* in);
std::uint64_t get_le64(const unsigned char* in);

}  // namespace neurocloth
