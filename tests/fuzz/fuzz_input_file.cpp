#include "fuzz/fuzz_input_file.h"

#include <unistd.h>

#include <cstdio>
#include <filesystem>

#include "fuzz/fuzz_contract.h"

namespace neurocloth::fuzz {

InputFile::InputFile(const std::string& name) {
  std::error_code ec;
  const std::string dir = std::filesystem::is_directory("/dev/shm", ec) ? "/dev/shm" : "/tmp";
  path_ = dir + "/neurocloth-fuzz-" + std::to_string(getpid()) + "-" + name;
}

InputFile::~InputFile() {
  remove();
}

void InputFile::remove() {
  std::remove(path_.c_str());
}

const std::string& InputFile::write(const std::uint8_t* data, std::size_t size) {
  std::FILE* f = std::fopen(path_.c_str(), "wb");
  // Not the reader's fault: stop loudly rather than fuzz an empty file.
  if (f == nullptr) finding("harness", "cannot write the input file " + path_);
  const bool ok = size == 0 || std::fwrite(data, 1, size, f) == size;
  if (std::fclose(f) != 0 || !ok) finding("harness", "cannot write the input file " + path_);
  return path_;
}

}  // namespace neurocloth::fuzz
