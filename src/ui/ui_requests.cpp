#include "ui/ui_requests.h"

#include <cmath>
#include <cstdio>
#include <exception>
#include <iterator>

#include "core/io/input_error.h"
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
