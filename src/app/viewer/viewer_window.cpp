#include "app/viewer/viewer_window.h"

// GLEW before any other OpenGL header (GLFW's included).
#include <GL/glew.h>
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include "app/viewer/viewer_input.h"
#include "render/gl_loader.h"

namespace neurocloth {

namespace {

// GLFW reports errors through a callback; the last one explains a failed call.
std::string g_last_glfw_error;

void remember_error(int /*code*/, const char* description) {
  g_last_glfw_error = description ? description : "unknown GLFW error";
}

}  // namespace

void ViewerWindow::connect() {
  glfwSetErrorCallback(remember_error);
  if (!glfwInit()) throw NoDisplay(g_last_glfw_error);  // a second call returns at once
}

ViewerWindow::ViewerWindow(int width, int height, const std::string& title, bool vsync) {
  connect();
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  window_ = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
  if (!window_) {
    glfwTerminate();
    throw std::runtime_error("cannot open an OpenGL 3.3 core window: " + g_last_glfw_error);
  }
  glfwSetWindowUserPointer(window_, this);
  glfwMakeContextCurrent(window_);
  glfwSwapInterval(vsync ? 1 : 0);

  // The renderer's loader, so the window and the headless snapshots accept the same GLEW outcomes.
  try {
    load_gl_functions("the window");
  } catch (...) {
    glfwDestroyWindow(window_);
    glfwTerminate();
    throw;
  }

  glfwGetFramebufferSize(window_, &fb_width_, &fb_height_);
  // Ours first: ImGui's backend then chains to them.
  install_callbacks();

  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini left in the working directory
  ImGui::StyleColorsDark();
  imgui_glfw_ = ImGui_ImplGlfw_InitForOpenGL(window_, true);
  imgui_gl_ = imgui_glfw_ && ImGui_ImplOpenGL3_Init("#version 330 core");
  if (!imgui_gl_) throw std::runtime_error("cannot start ImGui's OpenGL3 backend");
}

ViewerWindow::~ViewerWindow() {
  if (imgui_gl_) ImGui_ImplOpenGL3_Shutdown();
  if (imgui_glfw_) ImGui_ImplGlfw_Shutdown();
  if (ImGui::GetCurrentContext()) ImGui::DestroyContext();
  glfwDestroyWindow(window_);
  glfwTerminate();
}

ViewerWindow& ViewerWindow::of(GLFWwindow* w) {
  return *static_cast<ViewerWindow*>(glfwGetWindowUserPointer(w));
}

void ViewerWindow::install_callbacks() {
  glfwSetCursorPosCallback(window_, [](GLFWwindow* w, double x, double y) {
    ViewerWindow& self = of(w);
    if (self.live_ && self.handler_) self.handler_->cursor(x, y);
  });
  glfwSetMouseButtonCallback(window_, [](GLFWwindow* w, int button, int action, int mods) {
    ViewerWindow& self = of(w);
    if (self.live_ && self.handler_) self.handler_->button(button, action == GLFW_PRESS, mods);
  });
  glfwSetScrollCallback(window_, [](GLFWwindow* w, double /*dx*/, double dy) {
    ViewerWindow& self = of(w);
    if (self.live_ && self.handler_) self.handler_->scroll(dy);
  });
  glfwSetKeyCallback(window_, [](GLFWwindow* w, int key, int /*scancode*/, int action, int mods) {
    ViewerWindow& self = of(w);
    if (self.live_ && self.handler_ && action == GLFW_PRESS) self.handler_->key(key, mods);
  });
  // Sizes are tracked whoever drives the input: the window is real either way.
  glfwSetFramebufferSizeCallback(window_, [](GLFWwindow* w, int fb_width, int fb_height) {
    int width = 0, height = 0;
    glfwGetWindowSize(w, &width, &height);
    of(w).resized(width, height, fb_width, fb_height);
  });
}

void ViewerWindow::attach(InputHandler& handler, bool live) {
  handler_ = &handler;
  live_ = live;
  int w = 0, h = 0;
  glfwGetWindowSize(window_, &w, &h);
  handler.resize(w, h);
}

void ViewerWindow::poll() {
  glfwPollEvents();
}

bool ViewerWindow::close_requested() const {
  return glfwWindowShouldClose(window_);
}

void ViewerWindow::resized(int width, int height, int framebuffer_width, int framebuffer_height) {
  fb_width_ = framebuffer_width;
  fb_height_ = framebuffer_height;
  if (handler_) handler_->resize(width, height);
}

void ViewerWindow::request_size(int width, int height) {
  if (width > 0 && height > 0) glfwSetWindowSize(window_, width, height);
}

void ViewerWindow::begin_frame() {
  ImGui_ImplOpenGL3_NewFrame();
  ImGui_ImplGlfw_NewFrame();
  if (!live_ && handler_) {
    // A script moves a virtual mouse: ImGui must see that one, not the real pointer.
    ImGuiIO& io = ImGui::GetIO();
    io.MousePos =
        ImVec2(static_cast<float>(handler_->cursor_x()), static_cast<float>(handler_->cursor_y()));
    for (int b = 0; b < 3; ++b)
      io.MouseDown[b] = handler_->button_down(b);
    io.MouseWheel += static_cast<float>(scripted_wheel_);
    scripted_wheel_ = 0;
  }
  ImGui::NewFrame();
  const ImGuiIO& io = ImGui::GetIO();
  if (handler_) handler_->set_ui_capture(io.WantCaptureMouse, io.WantCaptureKeyboard);
}

void ViewerWindow::draw_ui() {
  ImGui::Render();
  glViewport(0, 0, fb_width_, fb_height_);
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
}

void ViewerWindow::swap() {
  glfwSwapBuffers(window_);
}

}  // namespace neurocloth
