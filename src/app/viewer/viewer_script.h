#pragma once
// A scripted session for tests and demos: timed input events read from JSON
// and replayed through the same handlers as real input (docs/viewer.md has
// the format). Times are seconds since the window's first frame: wall seconds,
// or simulated seconds under --lockstep (the deterministic mode).
#include <string>
#include <vector>

namespace neurocloth {

struct ScriptEvent {
  enum class Type {
    move,
    press,
    release,
    scroll,
    key,
    set,
    screenshot,
    probe,
    resize,
    load,
    rules,
    reference,
    fit,
    quit
  };
  double t = 0;
  Type type = Type::quit;
  std::string field;  // "events[3]", for messages
  // move: to (x, y) px, linearly over `duration` s; resize: width x height (x, y)
  double x = 0, y = 0, duration = 0;
  int button = 0;       // press / release: a GLFW mouse button
  int mods = 0;         // press / release / key: GLFW modifier bits
  int key = 0;          // key: a GLFW key code
  double amount = 0;    // scroll: wheel steps (> 0 zooms in); set: the value
  std::string name;     // set: parameter name; screenshot / load: path
  int node = -1;        // probe: node (as scenes count: a mesh's file vertex) to report
  bool panels = false;  // screenshot: the whole window, controls included
  // fit: `name` is the action (start, stop, wait, apply); start's settings
  // (0 / empty: the panel's own).
  bool online = false;
  int max_iterations = 0;
  std::string params;
  // reference: `name` is the path; a frame sequence's or PC2 cache's frames
  // per second and start (0: not given), a cache's OBJ mesh.
  double fps = 0, start = 0;
  std::string mesh;
};

struct Script {
  std::string path;
  std::vector<ScriptEvent> events;  // in time order
};

// Throws InputError naming the file, the field ("events[2].button") and its line.
Script load_script(const std::string& path);

// Names every event type, for messages and docs.
const char* script_event_types();

}  // namespace neurocloth
