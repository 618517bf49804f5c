// PNG files through libpng's simplified API (write_png and read_png are
// declared in renderer.h).
#include <png.h>

#include <cstring>
#include <ostream>
#include <stdexcept>

#include "core/io/text_file.h"
#include "render/renderer.h"

namespace neurocloth {

void write_png(const std::string& path, const std::vector<std::uint8_t>& rgba, int width,
               int height) {
  if (width < 1 || height < 1 || rgba.size() != std::size_t(width) * std::size_t(height) * 4)
    throw std::runtime_error(path + ": " + std::to_string(rgba.size()) +
                             " bytes are not an RGBA image of " + std::to_string(width) + "x" +
                             std::to_string(height));
  png_image image;
  std::memset(&image, 0, sizeof image);
  image.version = PNG_IMAGE_VERSION;
  image.width = png_uint_32(width);
  image.height = png_uint_32(height);
  image.format = PNG_FORMAT_RGBA;
  // Encoded in memory (libpng's simplified API writes to memory or stdio, not
  // to a stream), then written so that a reader never sees half a file.
  std::vector<char> encoded;
  png_alloc_size_t size = 0;
  bool ok = png_image_write_get_memory_size(image, size, 0, rgba.data(), width * 4, nullptr) != 0;
  if (ok) {
    encoded.resize(size);
    ok = png_image_write_to_memory(&image, encoded.data(), &size, 0, rgba.data(), width * 4,
                                   nullptr) != 0;
  }
  const std::string message = ok ? "" : image.message;
  png_image_free(&image);
  if (!ok) throw std::runtime_error(path + ": writing the PNG failed (" + message + ")");
  write_file_atomically(
      path, [&](std::ostream& out) { out.write(encoded.data(), std::streamsize(size)); });
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
