#pragma once
// Screenshots of the 3D view: the pixels the renderer drew this frame (before
// the panels are drawn over them), written as PNG.
#include <string>

namespace neurocloth {

class Renderer;

// "neurocloth_<scene>_<n>.png" in the working directory, n the first number
// whose file does not exist yet: screenshots never overwrite each other.
std::string next_screenshot_path(const std::string& scene_name);

// Reads the current framebuffer and writes it to `path`; throws
// std::runtime_error naming the path when it cannot be written.
void write_screenshot(const Renderer& renderer, const std::string& path, int width, int height);

}  // namespace neurocloth
