#include "ui/ui_requests.h"

#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <iterator>
#include <nlohmann/json.hpp>

#include "core/io/input_error.h"
#include "core/io/json_fields.h"
#include "core/modules/module_reader.h"
#include "ui/accuracy_control.h"

namespace neurocloth {

namespace {

std::string number(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", v);
  return text;
}

}  // namespace

std::string range_text(const ParameterRange& range) {
  return number(range.min) + " .. " + number(range.max) +
         (range.unit.empty() ? "" : " " + range.unit);
}

std::string request_parameter(const SceneInfo& scene, UiValues& values, const CommandSink& post,
                              const ParameterId& id, double value) {
  const ParameterRange* range = scene.range(id);
  if (!range) return "no parameter '" + to_string(id, scene.names()) + "' in this scene";
  if (!std::isfinite(value) || value < range->min || value > range->max)
    return range->name + " = " + number(value) + " refused: valid range " + range_text(*range);
  values.assign(id, scene.names(), value);
  post(SetParameter{id, value});
  return "";
}

std::string request_parameter(const SceneInfo& scene, UiValues& values, const CommandSink& post,
                              const std::string& name, double value) {
  std::string why;
  const std::optional<ParameterId> id = parse_parameter(name, scene.names(), &why);
  if (!id) return why;
  return request_parameter(scene, values, post, *id, value);
}

std::string request_accuracy(const SceneInfo& scene, UiValues& values, const CommandSink& post,
                             double accuracy) {
  const AccuracyTrade& trade = scene.trade();
  if (!trade.table) return "accuracy: " + trade.note;
  if (!std::isfinite(accuracy) || accuracy <= 0)
    return "accuracy = " + number(accuracy) + " refused: a fraction of the cloth's size > 0";
  AccuracyPick pick;
  try {
    pick = pick_for_accuracy(trade, accuracy, scene.solver());
  } catch (const InputError& e) {
    return e.what();
  }
  post(pick.command);
  values.accuracy = static_cast<float>(accuracy);
  for (std::size_t i = 0; i < std::size(kAllIntegrators); ++i)
    if (kAllIntegrators[i] == pick.command.integrator) values.integrator = static_cast<int>(i);
  values.adaptive = pick.command.adaptive;
  values.dt = pick.command.dt;
  values.accuracy_pick = pick.description;
  return "";
}

std::string request_scene(const std::string& path, const CommandSink& post) {
  std::shared_ptr<const Scene> scene;
  try {
    scene = std::make_shared<const Scene>(load_scene(path));
  } catch (const std::exception& e) {
    return e.what();
  }
  post(LoadScene{path, std::move(scene)});
  return "";
}

std::string request_obstacle(const Scene& running, SceneInfo& info, const std::string& obj_path,
                             double scale, const Vec3& translate, const CommandSink& post) {
  if (obj_path.empty()) return "obstacle: give the path of an OBJ file";
  // Absolute, so the reader resolves it from the working directory (as the
  // scene path beside it is) rather than from the scene's folder.
  std::error_code ec;
  const std::filesystem::path absolute = std::filesystem::absolute(obj_path, ec);
  const nlohmann::json module = {{"type", "mesh"},
                                 {"obj", ec ? obj_path : absolute.lexically_normal().string()},
                                 {"scale", scale},
                                 {"translate", {translate.x(), translate.y(), translate.z()}}};
  auto scene = std::make_shared<Scene>(running);
  try {
    const JsonFields in(nlohmann::json{{"modules", nlohmann::json::array({module})}}.dump(),
                        "the Scene panel's obstacle");
    std::vector<int> pins = scene->pins;  // a mesh module pins nothing
    std::vector<ModuleDeclaration> added =
        read_modules(in, in.root().at("modules"), scene->topology, pins);
    scene->modules.insert(scene->modules.end(), added.begin(), added.end());
    info = SceneInfo(*scene);
  } catch (const std::exception& e) {
    return e.what();
  }
  post(LoadScene{scene->path, std::move(scene)});
  return "";
}

std::string request_rules(SceneInfo& scene, const std::string& path, const CommandSink& post) {
  if (!scene.fuzzy())
    return "this scene's material is given as numbers; a rule base needs a linguistic "
           "material (\"material\": {\"rules\", \"inputs\"})";
  // Read before replacing the view: a failed read keeps the current one. The
  // thread takes the rule base as read here rather than reading the file again.
  std::shared_ptr<const FuzzyMaterial> rules;
  try {
    rules = std::make_shared<const FuzzyMaterial>(FuzzyMaterial::load(path));
  } catch (const std::exception& e) {
    return e.what();
  }
  scene.fuzzy() = FuzzyView(path, rules);
  post(LoadRules{path, rules});
  return "";
}

}  // namespace neurocloth
