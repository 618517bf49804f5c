#include "app/viewer/viewer_screenshot.h"

#include <cctype>
#include <filesystem>

#include "render/renderer.h"

namespace neurocloth {

std::string next_screenshot_path(const std::string& scene_name) {
  std::string stem = "neurocloth_";
  for (char c : scene_name.empty() ? std::string("scene") : scene_name)
    stem += std::isalnum(static_cast<unsigned char>(c)) || c == '-' ? c : '_';
  for (int n = 1;; ++n) {
    const std::string path = stem + "_" + std::to_string(n) + ".png";
    if (!std::filesystem::exists(path)) return path;
  }
}

void write_screenshot(const Renderer& renderer, const std::string& path, int width, int height) {
  write_png(path, renderer.read_pixels(width, height), width, height);
}

}  // namespace neurocloth
