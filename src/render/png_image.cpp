// PNG files through libpng's simplified API (write_png and read_png are
// declared in renderer.h).
#include <png.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <stdexcept>

#include "renderer.h"

namespace neurocloth {

void write_png(const std::string& path, const std::vector<std::uint8_t>& rgba, int width,
               int height) {
  if (width < 1 || height < 1 || rgba.size() != std::size_t(width) * std::size_t(height) * 4)
    throw std::runtime_error(path + ": " + std::to_string(rgba.size()) +
                             " bytes are not an RGBA image of " + std::to_string(width) + "x" +
                             std::to_string(height));
  // Written beside the destination and renamed into place, so a reader never
  // sees half a file and a failure leaves nothing behind.
  std::string temp = path + ".XXXXXX";
  const int fd = mkstemp(temp.data());
  if (fd < 0)
    throw std::runtime_error(path + ": cannot create a file there (" + std::strerror(errno) + ")");
  fchmod(fd, 0644);  // mkstemp makes it private; an image is for everyone to read
  FILE* file = fdopen(fd, "wb");
  if (!file) {
    ::close(fd);
    std::remove(temp.c_str());
    throw std::runtime_error(path + ": cannot write (" + std::strerror(errno) + ")");
  }
  png_image image;
  std::memset(&image, 0, sizeof image);
  image.version = PNG_IMAGE_VERSION;
  image.width = png_uint_32(width);
  image.height = png_uint_32(height);
  image.format = PNG_FORMAT_RGBA;
  const bool written =
      png_image_write_to_stdio(&image, file, 0, rgba.data(), width * 4, nullptr) != 0;
  const std::string message = written ? "" : image.message;
  png_image_free(&image);
  const bool flushed = std::fflush(file) == 0 && fsync(fileno(file)) == 0;
  const bool closed = std::fclose(file) == 0;
  if (!written || !flushed || !closed) {
    std::remove(temp.c_str());
    throw std::runtime_error(path + ": writing the PNG failed (" +
                             (written ? std::string(std::strerror(errno)) : message) + ")");
  }
  if (std::rename(temp.c_str(), path.c_str()) != 0) {
    const std::string reason = std::strerror(errno);
    std::remove(temp.c_str());
    throw std::runtime_error(path + ": cannot move the PNG into place (" + reason + ")");
  }
}

std::vector<std::uint8_t> read_png(const std::string& path, int& width, int& height) {
  png_image image;
  std::memset(&image, 0, sizeof image);
  image.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&image, path.c_str()))
    throw std::runtime_error(path + ": not a readable PNG (" + image.message + ")");
  image.format = PNG_FORMAT_RGBA;  // whatever the file holds, converted to RGBA
  std::vector<std::uint8_t> rgba(PNG_IMAGE_SIZE(image));
  if (!png_image_finish_read(&image, nullptr, rgba.data(), 0, nullptr)) {
    const std::string message = image.message;
    png_image_free(&image);
    throw std::runtime_error(path + ": reading the PNG failed (" + message + ")");
  }
  width = int(image.width);
  height = int(image.height);
  return rgba;
}

}  // namespace neurocloth
