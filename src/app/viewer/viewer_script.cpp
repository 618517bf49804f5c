#include "app/viewer/viewer_script.h"

#include <GLFW/glfw3.h>

#include <cstdlib>
#include <utility>

#include "core/io/input_error.h"
#include "core/io/json_fields.h"
#include "core/io/text_file.h"

namespace neurocloth {

namespace {

using Type = ScriptEvent::Type;

const std::pair<const char*, Type> kTypes[] = {{"move", Type::move},
                                               {"press", Type::press},
                                               {"release", Type::release},
                                               {"scroll", Type::scroll},
                                               {"key", Type::key},
                                               {"set", Type::set},
                                               {"screenshot", Type::screenshot},
                                               {"probe", Type::probe},
                                               {"resize", Type::resize},
                                               {"load", Type::load},
                                               {"rules", Type::rules},
                                               {"reference", Type::reference},
                                               {"fit", Type::fit},
                                               {"quit", Type::quit}};

const std::pair<const char*, int> kFitActions[] = {
    {"start", 0}, {"stop", 1}, {"wait", 2}, {"apply", 3}};

const std::pair<const char*, int> kButtons[] = {{"left", GLFW_MOUSE_BUTTON_LEFT},
                                                {"right", GLFW_MOUSE_BUTTON_RIGHT},
                                                {"middle", GLFW_MOUSE_BUTTON_MIDDLE}};

const std::pair<const char*, int> kMods[] = {
    {"shift", GLFW_MOD_SHIFT}, {"ctrl", GLFW_MOD_CONTROL}, {"alt", GLFW_MOD_ALT}};

const std::pair<const char*, int> kNamedKeys[] = {{"space", GLFW_KEY_SPACE},
                                                  {"escape", GLFW_KEY_ESCAPE},
                                                  {"enter", GLFW_KEY_ENTER},
                                                  {"tab", GLFW_KEY_TAB}};

std::string lower(std::string s) {
  for (char& c : s)
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  return s;
}

// "F12", "P", "space", "7" -> a GLFW key code; 0 when unknown.
int key_code(const std::string& name) {
  const std::string n = lower(name);
  if (n.size() == 1 && n[0] >= 'a' && n[0] <= 'z') return GLFW_KEY_A + (n[0] - 'a');
  if (n.size() == 1 && n[0] >= '0' && n[0] <= '9') return GLFW_KEY_0 + (n[0] - '0');
  if (n.size() >= 2 && n.size() <= 3 && n[0] == 'f') {
    const int f = std::atoi(n.c_str() + 1);
    if (f >= 1 && f <= 25 && n.substr(1) == std::to_string(f)) return GLFW_KEY_F1 + f - 1;
  }
  for (const auto& [k, code] : kNamedKeys)
    if (n == k) return code;
  return 0;
}

template <class T, std::size_t N>
T lookup(const JsonFields& in, const nlohmann::json& v, const std::string& field,
         const std::pair<const char*, T> (&table)[N]) {
  const std::string name = in.string(v, field);
  std::string known;
  for (const auto& [k, value] : table) {
    if (name == k) return value;
    known += (known.empty() ? "" : ", ") + std::string(k);
  }
  in.fail(field, "unknown '" + name + "' (expected one of: " + known + ")");
}

int modifiers(const JsonFields& in, const nlohmann::json& e, const std::string& field) {
  if (!e.contains("mods")) return 0;
  const std::string f = JsonLocator::member(field, "mods");
  const nlohmann::json& list = e.at("mods");
  if (!list.is_array()) in.fail(f, "expected an array such as [\"alt\"]");
  int mods = 0;
  for (std::size_t i = 0; i < list.size(); ++i)
    mods |= lookup(in, list[i], JsonLocator::element(f, i), kMods);
  return mods;
}

ScriptEvent read_event(const JsonFields& in, const nlohmann::json& e, const std::string& field) {
  const auto at = [&](const char* key) { return in.member(e, field, key); };
  const auto name = [&](const char* key) { return JsonLocator::member(field, key); };
  in.require_object(e, field);
  ScriptEvent ev;
  ev.field = field;
  ev.t = in.number(at("t"), name("t"));
  if (ev.t < 0) in.fail(name("t"), "must be >= 0 (seconds since the first frame)");
  ev.type = lookup(in, at("type"), name("type"), kTypes);
  switch (ev.type) {
    case Type::move:
      in.allow_only(e, field, {"t", "type", "x", "y", "duration"});
      ev.x = in.number(at("x"), name("x"));
      ev.y = in.number(at("y"), name("y"));
      if (e.contains("duration")) ev.duration = in.number(at("duration"), name("duration"));
      if (ev.duration < 0) in.fail(name("duration"), "must be >= 0");
      break;
    case Type::press:
    case Type::release:
      in.allow_only(e, field, {"t", "type", "button", "mods"});
      ev.button = lookup(in, at("button"), name("button"), kButtons);
      ev.mods = modifiers(in, e, field);
      break;
    case Type::scroll:
      in.allow_only(e, field, {"t", "type", "steps"});
      ev.amount = in.number(at("steps"), name("steps"));
      break;
    case Type::key:
      in.allow_only(e, field, {"t", "type", "key", "mods"});
      ev.key = key_code(in.string(at("key"), name("key")));
      if (ev.key == 0)
        in.fail(name("key"), "unknown key (a letter, a digit, F1..F25, space, escape, enter, tab)");
      ev.mods = modifiers(in, e, field);
      break;
    case Type::set:
      in.allow_only(e, field, {"t", "type", "name", "value"});
      ev.name = in.string(at("name"), name("name"));
      ev.amount = in.number(at("value"), name("value"));
      break;
    case Type::fit:
      in.allow_only(e, field, {"t", "type", "action", "online", "max_iterations", "params"});
      lookup(in, at("action"), name("action"), kFitActions);
      ev.name = in.string(at("action"), name("action"));
      if (e.contains("online")) ev.online = in.boolean(at("online"), name("online"));
      if (e.contains("max_iterations")) {
        ev.max_iterations = in.integer(at("max_iterations"), name("max_iterations"));
        if (ev.max_iterations < 1) in.fail(name("max_iterations"), "must be >= 1");
      }
      if (e.contains("params")) ev.params = in.string(at("params"), name("params"));
      if (ev.name != "start" &&
          (e.contains("online") || e.contains("max_iterations") || e.contains("params")))
        in.fail(field, "online, max_iterations and params go with action \"start\"");
      break;
    case Type::screenshot:
    case Type::load:
    case Type::rules:
    case Type::reference:
      if (ev.type == Type::screenshot)
        in.allow_only(e, field, {"t", "type", "path", "panels"});
      else if (ev.type == Type::reference)
        in.allow_only(e, field, {"t", "type", "path", "fps", "start", "mesh"});
      else
        in.allow_only(e, field, {"t", "type", "path"});
      if (e.contains("fps")) ev.fps = in.number(at("fps"), name("fps"));
      if (e.contains("start")) ev.start = in.number(at("start"), name("start"));
      if (e.contains("mesh")) ev.mesh = in.string(at("mesh"), name("mesh"));
      ev.name = in.string(at("path"), name("path"));
      if (ev.name.empty()) in.fail(name("path"), "must not be empty");
      if (e.contains("panels")) ev.panels = in.boolean(at("panels"), name("panels"));
      break;
    case Type::probe:
      in.allow_only(e, field, {"t", "type", "node"});
      ev.node = in.integer(at("node"), name("node"));
      if (ev.node < 0) in.fail(name("node"), "must be >= 0");
      break;
    case Type::resize:
      in.allow_only(e, field, {"t", "type", "width", "height"});
      ev.x = in.integer(at("width"), name("width"));
      ev.y = in.integer(at("height"), name("height"));
      if (ev.x < 0 || ev.y < 0) in.fail(field, "width and height must be >= 0");
      break;
    case Type::quit:
      in.allow_only(e, field, {"t", "type"});
      break;
  }
  return ev;
}

}  // namespace

const char* script_event_types() {
  return "move, press, release, scroll, key, set, screenshot, probe, resize, load, rules, "
         "reference, fit, quit";
}

Script load_script(const std::string& path) {
  const JsonFields in(read_text_file(path, "script file", kMaxSceneBytes), path);
  in.allow_only(in.root(), "", {"events", "description"});
  const nlohmann::json& events = in.member(in.root(), "", "events");
  if (!events.is_array()) in.fail("events", "expected an array of events");
  Script script;
  script.path = path;
  for (std::size_t i = 0; i < events.size(); ++i) {
    const std::string field = JsonLocator::element("events", i);
    script.events.push_back(read_event(in, events[i], field));
    if (i > 0 && script.events[i].t < script.events[i - 1].t)
      in.fail(JsonLocator::member(field, "t"), "events must be in time order");
  }
  return script;
}

}  // namespace neurocloth
