#pragma once
// Replays a Script on the clock it is given (wall time, or simulated time
// under --lockstep): each frame, the earliest events that have come
// due (all those sharing one time stamp) are carried out in order through a
// Target (the window, which hands input events to the same InputHandler real
// input goes to). A move with a duration is spread over the frames it spans,
// so a scripted drag is a drag.
#include "app/viewer/viewer_script.h"

namespace neurocloth {

class ScriptPlayer {
 public:
  class Target {
   public:
    virtual ~Target() = default;
    virtual void cursor(double x, double y) = 0;
    virtual void button(int button, bool pressed, int mods) = 0;
    virtual void scroll(double steps) = 0;
    virtual void key(int key, int mods) = 0;
    virtual void set(double t, const std::string& name, double value) = 0;
    virtual void screenshot(const std::string& path, bool panels) = 0;
    virtual void probe(double t, int node) = 0;
    virtual void resize(int width, int height) = 0;
    virtual void load(const std::string& path) = 0;
    virtual void rules(const std::string& path) = 0;
    virtual void reference(const ScriptEvent& e) = 0;
    virtual void fit(const ScriptEvent& event) = 0;
    virtual void quit() = 0;
  };

  explicit ScriptPlayer(Script script) : script_(std::move(script)) {}

  // Carries out the earliest time stamp's events if due by `elapsed` seconds
  // since the first frame; later ones wait for the next frame.
  void advance(double elapsed, Target& target);
  // Every event has been carried out (the window then closes).
  bool done() const { return next_ >= script_.events.size() && !moving_; }

 private:
  void dispatch(const ScriptEvent& e, Target& target);
  void follow_move(double t, Target& target);  // the cursor of a move in progress at time t

  Script script_;
  std::size_t next_ = 0;
  double x_ = 0, y_ = 0;  // the cursor
  bool moving_ = false;
  double from_x_ = 0, from_y_ = 0, to_x_ = 0, to_y_ = 0, start_ = 0, duration_ = 0;
};

}  // namespace neurocloth
