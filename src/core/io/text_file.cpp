#include "core/io/text_file.h"

#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <system_error>

#include "core/io/input_error.h"

namespace neurocloth {

namespace {
std::string size_name(std::size_t bytes) {
  return bytes >= (1u << 20) ? std::to_string(bytes >> 20) + " MiB"
                             : std::to_string(bytes >> 10) + " KiB";
}
}  // namespace

std::string read_text_file(const std::string& path, const char* what, std::size_t max_bytes) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  const std::string too_large = std::string("larger than ") + size_name(max_bytes) + ": not a " +
                                what + " this program reads";
  if (fs::is_directory(status))
    throw InputError(path, "", std::string("is a directory, not a ") + what);
  // A device has no end of file (/dev/zero, /dev/urandom) or blocks (a tty).
  if (fs::is_character_file(status) || fs::is_block_file(status) || fs::is_socket(status))
    throw InputError(path, "", std::string("is a device, not a ") + what);
  if (fs::is_regular_file(status)) {
    const auto size = fs::file_size(path, ec);
    if (!ec && size > max_bytes) throw InputError(path, "", too_large);
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "", std::string("cannot open ") + what);
  // Read in blocks up to one byte past the limit all the same: a pipe has no
  // size, and a file may grow while it is read.
  std::string text;
  char block[1 << 16];
  while (in) {
    in.read(block, sizeof block);
    text.append(block, static_cast<std::size_t>(in.gcount()));
    if (text.size() > max_bytes) throw InputError(path, "", too_large);
  }
  if (in.bad()) throw InputError(path, "", std::string("cannot read ") + what);
  return text;
}

void write_file_atomically(const std::string& path,
                           const std::function<void(std::ostream&)>& write) {
  // mkstemp: a name no other writer (thread or process) of the same path uses.
  std::string tmp = path + ".XXXXXX";
  const int fd = ::mkstemp(tmp.data());
  if (fd < 0)
    throw std::runtime_error(path + ": cannot write output file (" + std::strerror(errno) + ")");
  // Whatever fails from here on (the stream, the encoder in `write`, the disk)
  // takes the temporary file with it. The descriptor stays open to fsync the
  // bytes the stream wrote: the rename must not reach the disk before they do.
  struct Temporary {
    int fd;
    const std::string& name;
    bool moved = false;
    ~Temporary() {
      if (fd >= 0) ::close(fd);
      if (!moved) std::remove(name.c_str());
    }
  } temporary{fd, tmp};
  ::fchmod(fd, 0644);  // mkstemp makes it private; an output is for everyone to read
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw std::runtime_error(path + ": cannot write output file");
    write(out);
    out.flush();
    if (!out) throw std::runtime_error(path + ": error while writing output file");
  }
  if (::fsync(fd) != 0)
    throw std::runtime_error(path + ": error while writing output file (" + std::strerror(errno) +
                             ")");
  if (std::rename(tmp.c_str(), path.c_str()) != 0)
    throw std::runtime_error(path + ": cannot move output file into place (" +
                             std::strerror(errno) + ")");
  temporary.moved = true;
}

void write_file_atomically(const std::string& path, const std::string& text) {
  write_file_atomically(path, [&text](std::ostream& out) { out << text; });
}

}  // namespace neurocloth
