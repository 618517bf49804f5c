#include "app/viewer/viewer_script_player.h"

#include <algorithm>

namespace neurocloth {

void ScriptPlayer::advance(double elapsed, Target& target) {
  // One time stamp per frame: events written for different moments never share
  // a frame, even when a slow frame (a loaded machine, a sanitizer build) lets
  // several come due at once. The window draws and the simulation runs between
  // them, as they would between a person's actions, so "probe, later probe"
  // always sees time pass. Events with the same time stay together, in order.
  const auto& events = script_.events;
  if (next_ < events.size() && events[next_].t <= elapsed) {
    const double t = events[next_].t;
    while (next_ < events.size() && events[next_].t == t) {
      const ScriptEvent& e = events[next_++];
      if (moving_) follow_move(e.t, target);  // where the cursor is when this happens
      dispatch(e, target);
    }
  }
  if (moving_) follow_move(elapsed, target);
}

void ScriptPlayer::follow_move(double t, Target& target) {
  const double f = duration_ > 0 ? std::clamp((t - start_) / duration_, 0.0, 1.0) : 1.0;
  x_ = from_x_ + f * (to_x_ - from_x_);
  y_ = from_y_ + f * (to_y_ - from_y_);
  target.cursor(x_, y_);
  if (f >= 1) moving_ = false;
}

void ScriptPlayer::dispatch(const ScriptEvent& e, Target& target) {
  using Type = ScriptEvent::Type;
  switch (e.type) {
    case Type::move:
      moving_ = true;
      from_x_ = x_;
      from_y_ = y_;
      to_x_ = e.x;
      to_y_ = e.y;
      start_ = e.t;
      duration_ = e.duration;
      if (e.duration <= 0) follow_move(e.t, target);
      break;
    case Type::press:
    case Type::release:
      target.button(e.button, e.type == Type::press, e.mods);
      break;
    case Type::scroll:
      target.scroll(e.amount);
      break;
    case Type::key:
      target.key(e.key, e.mods);
      break;
    case Type::set:
      target.set(e.t, e.name, e.amount);
      break;
    case Type::screenshot:
      target.screenshot(e.name, e.panels);
      break;
    case Type::probe:
      target.probe(e.t, e.node);
      break;
    case Type::resize:
      target.resize(static_cast<int>(e.x), static_cast<int>(e.y));
      break;
    case Type::load:
      target.load(e.name);
      break;
    case Type::rules:
      target.rules(e.name);
      break;
    case Type::reference:
      target.reference(e);
      break;
    case Type::fit:
      target.fit(e);
      break;
    case Type::quit:
      next_ = script_.events.size();  // nothing after a quit
      moving_ = false;
      target.quit();
      break;
  }
}

}  // namespace neurocloth
