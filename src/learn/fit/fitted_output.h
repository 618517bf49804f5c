#pragma once
// What `fit` writes (docs/learning.md, "Fitting"):
//  FITTED.json          the original scene file with the fitted values: a numeric
//                       material in place of the old one (numbers or words) or,
//                       when the fit was of a material's inputs, the material in
//                       words at the fitted inputs,
//                       module parameters patched, paths rewritten to resolve
//                       from FITTED.json's folder, a "fitted" note (source,
//                       reference, loss, RMS, each parameter with its uncertainty)
//                       and, when the network differs from what the material
//                       alone builds, "element_weights" naming
//  FITTED.weights.json  every spring's stiffness, damping, rest length and every
//                       node's mass (element_weights.h);
//  FITTED.loss.csv      iteration, loss, rms_mm, seconds, each parameter;
//  FITTED.loss.png      the loss curve;
//  FITTED.example.csv   for a material in words: the example it gives tune-rules.
// `simulate` and the viewer load FITTED.json as it is.
#include <nlohmann/json.hpp>

#include <optional>
#include <string>
#include <vector>

#include "core/scene/scene.h"
#include "learn/optim/uncertainty.h"

namespace neurocloth {

// The fitted values, as FitProblem gives them at the best theta.
struct FittedModel {
  Scene scene;                       // fitted_scene(theta): family values in material and modules
  MaterialWeights weights;           // element_weights(theta): empty vectors where not per element
  std::vector<double> rest_lengths;  // element_rest_lengths(theta): empty unless fitted

  // The network the fit ran on at theta: the scene's network with the
  // per-element weights over it.
  ClothNetwork network() const;
};

// The "fitted" note's contents.
struct FitSummary {
  std::string reference;  // the reference motion's file
  std::string optimizer;  // "lbfgs" | "gd"
  std::string stop_reason, stop_message;
  int iterations = 0;
  double loss = 0;   // m^2
  double rms_m = 0;  // m
  // Each parameter (a per-element block as its geometric mean) with its
  // uncertainty; sd and relative_sd NaN when it was not estimated.
  std::vector<ParameterUncertainty> parameters;
  std::string uncertainty;  // how it was estimated, or why it was skipped
  // A fit of a material's inputs: each fitted input in the rule base's words
  // ("elasticity 0.712: big 0.80, medium 0.20").
  std::vector<std::string> words;
};

// One row of FITTED.loss.csv.
struct FitHistoryRow {
  int iteration = 0;
  double loss = 0, rms_m = 0, seconds = 0;
  std::vector<double> parameters;  // one per FitHistory::columns entry
};
struct FitHistory {
  std::vector<std::string> columns;  // the parameters' names
  std::vector<FitHistoryRow> rows;
};

struct FittedFiles {
  std::string scene, weights, csv, png;
  std::string example;  // FITTED.example.csv, or "" when none is written
};
// FITTED.json -> FITTED.weights.json, FITTED.loss.csv, FITTED.loss.png (any
// extension of `out` is replaced; none is added to the scene's own name).
FittedFiles fitted_file_names(const std::string& out);

// `written` (a path as the scene `from` wrote it) as a path that resolves to
// the same file from `to` (a file in another folder): relative when one
// exists, else absolute.
std::string rebased_path(const std::string& from, const std::string& written,
                         const std::string& to);

// The side file's document, or nothing when the numeric material alone
// builds the model's network (then FITTED.json names no side file).
std::optional<nlohmann::json> fitted_weights_json(const FittedModel& model);
// FITTED.json's document. `original` is the scene as loaded (its file is read
// again, so that every key the user wrote is kept, in the file's order);
// `weights_file` is the side file's name as FITTED.json names it ("" for none).
nlohmann::ordered_json fitted_scene_json(const Scene& original, const FittedModel& model,
                                         const FitSummary& summary, const std::string& out,
                                         const std::string& weights_file);
std::string loss_csv(const FitHistory& history);
// What a fit of numbers to a material in words teaches its rule base: one
// example for `tune-rules` (rule_examples.h), the scene's inputs and the
// fitted family values of the rule base's outputs (spring_constant,
// node_mass, viscosity, friction), as FITTED.example.csv. Nothing for a
// numeric material, a fit of the inputs, or a fit of none of those outputs.
std::optional<std::string> tuning_example(const Scene& original, const FitSummary& summary);

// Writes the four files (three when there is no side file). Everything is
// made in memory first and each file is written atomically; if a write fails,
// the files this call already wrote are removed. Returns the names written.
FittedFiles write_fit_outputs(const Scene& original, const FittedModel& model,
                              const FitSummary& summary, const FitHistory& history,
                              const std::string& out);

}  // namespace neurocloth
