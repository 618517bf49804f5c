#include "core/io/streamed_file.h"

#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace neurocloth {

StreamedFile::StreamedFile(std::string path) : path_(std::move(path)) {
  // mkstemp: a name no other writer of the same path uses.
  temporary_ = path_ + ".XXXXXX";
  const int fd = ::mkstemp(temporary_.data());
  if (fd < 0) {
    temporary_.clear();
    fail("cannot write output file");
  }
  ::fchmod(fd, 0644);  // mkstemp makes it private; an output is for everyone to read
  file_ = ::fdopen(fd, "wb");
  if (!file_) {
    ::close(fd);
    std::remove(temporary_.c_str());
    temporary_.clear();
    fail("cannot write output file");
  }
}

StreamedFile::~StreamedFile() {
  if (file_) std::fclose(file_);
  if (!temporary_.empty()) std::remove(temporary_.c_str());
}

void StreamedFile::fail(const char* what) const {
  const int e = errno;
  throw std::runtime_error(path_ + ": " + what +
                           (e ? std::string(" (") + std::strerror(e) + ")" : ""));
}

void StreamedFile::append(const void* data, std::size_t size) {
  if (!file_) throw std::logic_error(path_ + ": written after finish()");
  errno = 0;
  if (size && std::fwrite(data, 1, size, file_) != size) fail("error while writing output file");
  size_ += size;
}

void StreamedFile::overwrite(std::uint64_t offset, const void* data, std::size_t size) {
  if (!file_) throw std::logic_error(path_ + ": written after finish()");
  if (offset + size > size_) throw std::logic_error(path_ + ": overwrite past the end");
  errno = 0;
  if (std::fflush(file_) != 0) fail("error while writing output file");
  const auto written = ::pwrite(::fileno(file_), data, size, static_cast<off_t>(offset));
  if (written != static_cast<ssize_t>(size)) fail("error while writing output file");
}

void StreamedFile::truncate(std::uint64_t size) {
  if (!file_) throw std::logic_error(path_ + ": written after finish()");
  if (size >= size_) return;
  errno = 0;
  if (std::fflush(file_) != 0 || ::ftruncate(::fileno(file_), static_cast<off_t>(size)) != 0 ||
      ::fseeko(file_, static_cast<off_t>(size), SEEK_SET) != 0)
    fail("error while writing output file");
  size_ = size;
}

void StreamedFile::finish() {
  if (!file_) throw std::logic_error(path_ + ": finished twice");
  errno = 0;
  // The bytes reach the disk before the rename does: a crash leaves the old
  // file or the whole new one.
  const bool flushed = std::fflush(file_) == 0 && ::fsync(::fileno(file_)) == 0;
  const bool closed = std::fclose(file_) == 0;
  file_ = nullptr;
  if (!flushed || !closed) fail("error while writing output file");
  if (std::rename(temporary_.c_str(), path_.c_str()) != 0)
    fail("cannot move output file into place");
  temporary_.clear();
}

void put_le32(unsigned char* out, std::uint32_t v) {
  for (int i = 0; i < 4; ++i)
    out[i] = static_cast<unsigned char>(v >> (8 * i));
}

void put_le64(unsigned char* out, std::uint64_t v) {
  for (int i = 0; i < 8; ++i)
    out[i] = static_cast<unsigned char>(v >> (8 * i));
}

std::uint32_t get_le32(const unsigned char* in) {
  std::uint32_t v = 0;
  for (int i = 3; i >= 0; --i)
    v = (v << 8) | in[i];
  return v;
}

std::uint64_t get_le64(const unsigned char* in) {
  std::uint64_t v = 0;
  for (int i = 7; i >= 0; --i)
    v = (v << 8) | in[i];
  return v;
}

}  // namespace neurocloth
