// The scripted mode's timing rules, without a window: which events a frame
// carries out and where the cursor of a timed move is.
#include "app/viewer/viewer_script_player.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace neurocloth {
namespace {

// Records what the player asks of the window, one line per call.
class Recorder : public ScriptPlayer::Target {
 public:
  std::vector<std::string> calls;
  void cursor(double x, double y) override {
    calls.push_back("cursor " + std::to_string(int(x)) + " " + std::to_string(int(y)));
  }
  void button(int b, bool pressed, int) override {
    calls.push_back(std::string(pressed ? "press " : "release ") + std::to_string(b));
  }
  void scroll(double) override { calls.push_back("scroll"); }
  void key(int k, int) override { calls.push_back("key " + std::to_string(k)); }
  void set(double, const std::string& name, double) override { calls.push_back("set " + name); }
  void screenshot(const std::string& path, bool) override { calls.push_back("shot " + path); }
  void probe(double t, int) override { calls.push_back("probe " + std::to_string(int(t * 10))); }
  void resize(int, int) override { calls.push_back("resize"); }
  void load(const std::string& path) override { calls.push_back("load " + path); }
  void rules(const std::string& path) override { calls.push_back("rules " + path); }
  void reference(const ScriptEvent& e) override { calls.push_back("reference " + e.name); }
  void fit(const ScriptEvent& e) override { calls.push_back("fit " + e.name); }
  void quit() override { calls.push_back("quit"); }
};

ScriptEvent event(double t, ScriptEvent::Type type) {
  ScriptEvent e;
  e.t = t;
  e.type = type;
  return e;
}

TEST(ScriptPlayer, ASlowFrameDoesNotMergeTwoMoments) {
  Script s;
  s.events = {event(0.4, ScriptEvent::Type::probe), event(1.0, ScriptEvent::Type::probe),
              event(1.1, ScriptEvent::Type::quit)};
  ScriptPlayer player(s);
  Recorder r;
  player.advance(0.1, r);
  EXPECT_TRUE(r.calls.empty());
  player.advance(5.0, r);  // one frame that took seconds: everything is due
  EXPECT_EQ(r.calls, std::vector<std::string>{"probe 4"});
  player.advance(5.1, r);
  EXPECT_EQ(r.calls, (std::vector<std::string>{"probe 4", "probe 10"}));
  EXPECT_FALSE(player.done());
  player.advance(5.2, r);
  EXPECT_EQ(r.calls.back(), "quit");
  EXPECT_TRUE(player.done());
}

TEST(ScriptPlayer, EventsAtOneTimeShareTheirFrameInOrder) {
  Script s;
  ScriptEvent load = event(0.2, ScriptEvent::Type::load);
  load.name = "a.json";
  ScriptEvent shot = event(0.2, ScriptEvent::Type::screenshot);
  shot.name = "a.png";
  s.events = {load, shot, event(0.2, ScriptEvent::Type::quit)};
  ScriptPlayer player(s);
  Recorder r;
  player.advance(0.3, r);
  EXPECT_EQ(r.calls, (std::vector<std::string>{"load a.json", "shot a.png", "quit"}));
  EXPECT_TRUE(player.done());
}

TEST(ScriptPlayer, ATimedMoveIsSpreadOverTheFramesItSpans) {
  Script s;
  ScriptEvent start = event(0.0, ScriptEvent::Type::move);
  start.x = 100;
  start.y = 100;
  ScriptEvent drag = event(1.0, ScriptEvent::Type::move);
  drag.x = 300;
  drag.y = 100;
  drag.duration = 1.0;
  s.events = {start, drag};
  ScriptPlayer player(s);
  Recorder r;
  player.advance(0.0, r);
  EXPECT_EQ(r.calls.back(), "cursor 100 100");
  player.advance(1.0, r);
  EXPECT_EQ(r.calls.back(), "cursor 100 100");  // the drag starts where the cursor is
  player.advance(1.5, r);
  EXPECT_EQ(r.calls.back(), "cursor 200 100");
  EXPECT_FALSE(player.done());
  player.advance(2.5, r);
  EXPECT_EQ(r.calls.back(), "cursor 300 100");
  EXPECT_TRUE(player.done());
}

}  // namespace
}  // namespace neurocloth
