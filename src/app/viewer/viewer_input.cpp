#include "app/viewer/viewer_input.h"

#include <GLFW/glfw3.h>

#include <algorithm>
#include <cmath>

#include "app/viewer/viewer_report.h"
#include "render/picking.h"

namespace neurocloth {

namespace {

// A right press that moves less than this is a click (pin), more is an orbit.
constexpr double kClickSlop = 4;  // px
// Picking reaches this many pixels beside the cloth's edge.
constexpr double kPickPixels = 8;

}  // namespace

void InputHandler::resize(int width, int height) {
  width_ = width;
  height_ = height;
}

double InputHandler::pick_tolerance() const {
  // Metres that kPickPixels cover at the target's distance.
  return kPickPixels * w_.camera.distance * w_.camera.fov_y / std::max(height_, 1);
}

void InputHandler::cursor(double x, double y) {
  const double dx = x - x_, dy = y - y_;
  x_ = x;
  y_ = y;
  if (gesture_ == Gesture::right_click && std::hypot(x - press_x_, y - press_y_) > kClickSlop)
    gesture_ = Gesture::orbit;
  if (gesture_ == Gesture::orbit) w_.camera.rotate(dx, dy);
  if (gesture_ == Gesture::pan) w_.camera.pan(dx, dy, std::max(height_, 1));
}

void InputHandler::button(int button, bool pressed, int mods) {
  if (button < 0 || button >= 3) return;
  down_[button] = pressed;
  if (pressed)
    press(button, mods);
  else
    release(button);
}

void InputHandler::press(int button, int mods) {
  if (gesture_ != Gesture::none || ui_mouse_ || width_ <= 0 || height_ <= 0) return;
  gesture_button_ = button;
  press_x_ = x_;
  press_y_ = y_;
  if (button == GLFW_MOUSE_BUTTON_MIDDLE ||
      (button == GLFW_MOUSE_BUTTON_LEFT && (mods & GLFW_MOD_SHIFT))) {
    gesture_ = Gesture::pan;
  } else if (button == GLFW_MOUSE_BUTTON_LEFT && (mods & GLFW_MOD_ALT)) {
    gesture_ = Gesture::orbit;
  } else if (button == GLFW_MOUSE_BUTTON_RIGHT) {
    gesture_ = Gesture::right_click;  // becomes an orbit if it moves
  } else if (button == GLFW_MOUSE_BUTTON_LEFT) {
    const std::shared_ptr<const FrameSnapshot> snapshot = w_.sim.latest();
    const Pick pick = pick_node(cursor_ray(), *snapshot, pick_tolerance());
    if (w_.report) w_.report->picked(pick.node, x_, y_, *snapshot);
    if (pick.node < 0) return;
    gesture_ = Gesture::drag_node;
    node_ = pick.node;
    grab_ = target_ = pick.point;
  }
}

void InputHandler::release(int button) {
  if (button != gesture_button_) return;
  if (gesture_ == Gesture::drag_node) release_drag();
  if (gesture_ == Gesture::right_click) {
    // A click: toggle the pin of the node under the cursor, as the snapshot shows it.
    const std::shared_ptr<const FrameSnapshot> snapshot = w_.sim.latest();
    const Pick pick = pick_node(cursor_ray(), *snapshot, pick_tolerance());
    if (pick.node >= 0) {
      const bool pinned = !snapshot->pinned.at(pick.node);
      w_.post(SetPinned{pick.node, pinned});
      if (w_.report) w_.report->pinned(pick.node, pinned, *snapshot);
    }
  }
  gesture_ = Gesture::none;
  gesture_button_ = -1;
}

void InputHandler::release_drag() {
  w_.post(ReleaseForce{node_});
  if (w_.report) w_.report->released(node_, target_, *w_.sim.latest());
  node_ = -1;
}

void InputHandler::update() {
  if (gesture_ != Gesture::drag_node || width_ <= 0 || height_ <= 0) return;
  const std::shared_ptr<const FrameSnapshot> snapshot = w_.sim.latest();
  if (static_cast<std::size_t>(node_) >= snapshot->geometry->node_count) {
    // Another scene was loaded under the drag: its node numbers mean something else.
    gesture_ = Gesture::none;
    node_ = -1;
    return;
  }
  target_ = drag_point(cursor_ray(), grab_, w_.camera);
  Vec3 pull = target_ - snapshot->node(node_);
  if (pull.norm() > kDragReach) pull *= kDragReach / pull.norm();
  w_.post(ApplyForce{node_, w_.node_mass(node_) * drag_gain_ * pull, target_});
}

void InputHandler::scroll(double steps) {
  if (!ui_mouse_) w_.camera.zoom(steps);
}

void InputHandler::key(int key, int /*mods*/) {
  if (ui_keyboard_) return;  // typing into a field
  switch (key) {
    case GLFW_KEY_F:
      w_.requests.frame_camera = true;
      break;
    case GLFW_KEY_R:
      w_.requests.reset_camera = true;
      break;
    case GLFW_KEY_F12:
    case GLFW_KEY_P:
      w_.requests.screenshot = true;
      break;
    case GLFW_KEY_SPACE:
      w_.post(SetPaused{!w_.sim.status().paused});
      break;
    case GLFW_KEY_N:
      w_.post(SingleStep{});
      break;
    case GLFW_KEY_ESCAPE:
      quit_ = true;
      break;
    default:
      break;
  }
}

}  // namespace neurocloth
