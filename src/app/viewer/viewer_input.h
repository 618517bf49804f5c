#pragma once
// What the mouse and keys do in the window. Real GLFW callbacks and the script
// player call the same methods, so a scripted drag is handled exactly as a
// real one. The handler never touches the simulation: it reads published
// snapshots and posts commands (ApplyForce, ReleaseForce, SetPinned, ...).
//
//   left-drag on the cloth   pull the node under the cursor towards it
//   right-click              pin / unpin the node under the cursor
//   right-drag, alt+left     orbit        middle-drag, shift+left   pan
//   wheel                    zoom         F frame the cloth, R reset the camera
//   Space pause/resume, N one step (paused), F12 or P screenshot, Esc quit
#include <functional>
#include <memory>

#include "render/orbit_camera.h"
#include "ui/panel_context.h"

namespace neurocloth {

class ViewerReport;

class InputHandler {
 public:
  struct Wiring {
    SimulationThread& sim;
    OrbitCamera& camera;
    WindowRequests& requests;
    CommandSink post;
    std::function<double(int node)> node_mass;  // kg, for the drag force
    ViewerReport* report = nullptr;             // records picks, drags and pins when set
  };
  explicit InputHandler(Wiring wiring) : w_(std::move(wiring)) {}

  // Window size in screen pixels (what cursor positions are measured in).
  void resize(int width, int height);
  void cursor(double x, double y);
  void button(int button, bool pressed, int mods);
  void scroll(double steps);
  void key(int key, int mods);  // presses only
  // Once per frame: re-aims the drag force at the cursor (the node moves, the
  // camera may too) and posts it.
  void update();
  // Whether ImGui wants the mouse / keyboard (over a panel, typing): set each frame.
  void set_ui_capture(bool mouse, bool keyboard) {
    ui_mouse_ = mouse;
    ui_keyboard_ = keyboard;
  }

  double cursor_x() const { return x_; }
  double cursor_y() const { return y_; }
  bool button_down(int button) const { return button >= 0 && button < 3 && down_[button]; }
  bool quit_requested() const { return quit_; }
  int width() const { return width_; }
  int height() const { return height_; }

  // The drag's stiffness per kg of the dragged node, 1/s^2 (the View panel's
  // "drag strength"): every node is pulled with the same acceleration per metre
  // of separation, whatever its mass...
  void set_drag_gain(double gain) { drag_gain_ = gain; }
  // ... up to this separation: a cursor far away does not fling the cloth.
  static constexpr double kDragReach = 0.5;  // m

 private:
  enum class Gesture { none, drag_node, orbit, pan, right_click };
  void press(int button, int mods);
  void release(int button);
  void release_drag();
  Ray cursor_ray() const { return w_.camera.ray(x_, y_, width_, height_); }
  double pick_tolerance() const;

  Wiring w_;
  int width_ = 1, height_ = 1;
  double x_ = 0, y_ = 0;
  bool down_[3] = {false, false, false};
  bool ui_mouse_ = false, ui_keyboard_ = false, quit_ = false;
  Gesture gesture_ = Gesture::none;
  int gesture_button_ = -1;
  double press_x_ = 0, press_y_ = 0;
  double drag_gain_ = 4000;     // 1/s^2, see set_drag_gain
  int node_ = -1;               // the dragged node
  Vec3 grab_ = Vec3::Zero();    // where it was grabbed: the drag plane passes through it
  Vec3 target_ = Vec3::Zero();  // where the cursor pulled it last
};

}  // namespace neurocloth
