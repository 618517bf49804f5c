#pragma once
// The GLFW window: an OpenGL 3.3 core context with GLEW loaded and ImGui (its
// GLFW and OpenGL3 backends) set up; torn down in reverse order. Input goes to
// an InputHandler; sizes are tracked from the window system's notices.
#include <stdexcept>
#include <string>

struct GLFWwindow;

namespace neurocloth {

class InputHandler;

// GLFW could not reach a window system (no DISPLAY, no X server).
class NoDisplay : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class ViewerWindow {
 public:
  // Reaches the window system (GLFW's init) without opening anything yet;
  // throws NoDisplay naming why not. The constructor does it too.
  static void connect();

  // Throws NoDisplay, or std::runtime_error when the context cannot be made.
  // `vsync`: wait for the display's refresh when swapping (off: as fast as it can draw).
  ViewerWindow(int width, int height, const std::string& title, bool vsync = true);
  ~ViewerWindow();
  ViewerWindow(const ViewerWindow&) = delete;
  ViewerWindow& operator=(const ViewerWindow&) = delete;

  // Real mouse and keys go to `handler` when `live`; a script drives it otherwise.
  void attach(InputHandler& handler, bool live);
  void poll();  // processes pending window-system events
  bool close_requested() const;

  // The window system said the window is now this size (also called by scripts:
  // 0 x 0 is what a minimised window reports).
  void resized(int width, int height, int framebuffer_width, int framebuffer_height);
  int framebuffer_width() const { return fb_width_; }
  int framebuffer_height() const { return fb_height_; }
  bool minimised() const { return fb_width_ <= 0 || fb_height_ <= 0; }

  // ImGui frame: begin (after poll), draw what the panels built, then show it.
  void begin_frame();
  void draw_ui();
  void swap();
  // A scripted wheel turn, for ImGui to see at the next frame (real ones reach it directly).
  void scripted_wheel(double steps) { scripted_wheel_ += steps; }
  // Tries to resize the real window (scripts); the size notice follows from GLFW.
  void request_size(int width, int height);

 private:
  static ViewerWindow& of(GLFWwindow* w);
  void install_callbacks();

  GLFWwindow* window_ = nullptr;
  InputHandler* handler_ = nullptr;
  bool live_ = true;
  int fb_width_ = 0, fb_height_ = 0;
  double scripted_wheel_ = 0;
  bool imgui_glfw_ = false, imgui_gl_ = false;
};

}  // namespace neurocloth
