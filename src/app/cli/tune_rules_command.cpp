// neurocloth-cli tune-rules: a rule base's terms tuned to examples of what it
// should give (docs/learning.md, "Tuning a rule base from examples"): least
// squares for Takagi-Sugeno consequents, the projected gradient for membership
// functions and Mamdani output sets, under constraints that keep the terms
// readable. Writes OUT.fcl and OUT.examples.csv.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "app/cli/commands.h"
#include "app/cli/long_run.h"
#include "app/cli/motion_outputs.h"
#include "app/cli/progress_line.h"
#include "core/fuzzy/formats/fcl_reader.h"
#include "core/fuzzy/formats/fcl_writer.h"
#include "core/fuzzy/formats/fis_reader.h"
#include "core/fuzzy/formats/fis_writer.h"
#include "core/fuzzy/formats/rule_file.h"
#include "core/io/input_error.h"
#include "core/io/text_file.h"
#include "learn/rules/rule_examples.h"
#include "learn/rules/rule_tuning.h"

namespace neurocloth {
namespace {

constexpr int kMaxIterations = 1000000;

// The one place a rule file is read: FCL (and other tools' dialects) or .fis.
fuzzy::FuzzySystem read_rules(const std::string& path) {
  return fuzzy::read_rule_file(path);
}

// OUT.fcl or OUT.fis -> OUT.examples.csv (any other name: OUT.examples.csv after it).
std::string examples_csv_name(const std::string& out) {
  std::string stem = out;
  if (stem.size() > 4) {
    std::string ext = stem.substr(stem.size() - 4);
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return std::tolower(c); });
    if (ext == ".fcl" || ext == ".fis") stem.resize(stem.size() - 4);
  }
  return stem + ".examples.csv";
}

// Every option checked before anything is read: InputError naming it.
void check_options(const TuneRulesOptions& o, RuleTuningOptions& tuning) {
  auto refuse = [](const char* field, const std::string& why) {
    throw InputError("command line", field, why);
  };
  if (!o.what.empty()) {
    tuning.input_terms = tuning.output_sets = tuning.consequents = false;
    for (const std::string& w : o.what) {
      if (w == "mf" || w == "inputs") tuning.input_terms = true;
      if (w == "mf" || w == "sets") tuning.output_sets = true;
      if (w == "consequents") tuning.consequents = true;
      if (w != "mf" && w != "inputs" && w != "sets" && w != "consequents")
        refuse("--what", "unknown '" + w +
                             "' (expected mf, consequents, or inputs or sets for half of mf; "
                             "comma-separated)");
    }
  }
  if (o.iterations < 1 || o.iterations > kMaxIterations)
    refuse("--iterations", "must be 1 to " + std::to_string(kMaxIterations) + " (got " +
                               std::to_string(o.iterations) + ")");
  if (!(o.time >= 0) || !std::isfinite(o.time))
    refuse("--time", "must be a finite number of seconds >= 0 (0: none)");
  if (o.out.empty()) refuse("--out", "must name the OUT.fcl to write");
  const std::filesystem::path folder = std::filesystem::absolute(o.out).parent_path();
  if (!std::filesystem::is_directory(folder))
    refuse("--out", "the folder " + folder.string() + " does not exist");
  for (const std::string& f : {o.out, examples_csv_name(o.out)})
    check_output_path("--out", f, {o.rules, o.examples});
  tuning.search.max_iterations = o.iterations;
  tuning.search.time_budget = o.time;
}

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

// Text inside an FCL comment: no comment end or start, no control bytes but newlines.
std::string comment_safe(std::string s) {
  for (char& c : s)
    if (static_cast<unsigned char>(c) < 0x20 && c != '\n') c = '?';
  for (std::size_t at; (at = s.find("*)")) != std::string::npos;)
    s.replace(at, 2, "* )");
  for (std::size_t at; (at = s.find("(*")) != std::string::npos;)
    s.replace(at, 2, "( *");
  return s;
}

void print_outputs_table(const fuzzy::FuzzySystem& s, const RuleExamples& e,
                         const RuleTuningResult& r) {
  const std::vector<double> before = rmse_per_output(e, r.before),
                            after = rmse_per_output(e, r.after);
  std::printf("%-20s %-22s %14s %14s %20s\n", "output", "range", "RMSE before", "RMSE after",
              "% of range");
  for (std::size_t k = 0; k < e.outputs.size(); ++k) {
    const auto& v = s.outputs[e.outputs[k]];
    const double range = v.max - v.min;
    const std::string span = number(v.min) + " .. " + number(v.max);
    char pct[48];
    std::snprintf(pct, sizeof pct, "%.3g%% -> %.3g%%", 100 * before[k] / range,
                  100 * after[k] / range);
    std::printf("%-20s %-22s %14.6g %14.6g %20s\n", v.name.c_str(), span.c_str(), before[k],
                after[k], pct);
  }
}

// At most `shown` examples, the worst after tuning first.
void print_examples_table(const fuzzy::FuzzySystem& s, const RuleExamples& e,
                          const RuleTuningResult& r, std::size_t shown) {
  const std::vector<double> before = rmse_per_example(s, e, r.before),
                            after = rmse_per_example(s, e, r.after);
  std::vector<std::size_t> order(e.size());
  for (std::size_t i = 0; i < order.size(); ++i)
    order[i] = i;
  if (order.size() > shown) {
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b) { return after[a] > after[b]; });
    order.resize(shown);
    std::printf("per example (the %zu worst after tuning; all in the CSV):\n", shown);
  } else {
    std::printf("per example:\n");
  }
  std::printf("  %-8s %18s %18s\n", "line", "RMSE % before", "RMSE % after");
  for (std::size_t i : order)
    std::printf("  %-8d %18.4g %18.4g\n", e.lines[i], 100 * before[i], 100 * after[i]);
}

std::string examples_csv(const fuzzy::FuzzySystem& s, const RuleExamples& e,
                         const RuleTuningResult& r) {
  const std::vector<double> before = rmse_per_example(s, e, r.before),
                            after = rmse_per_example(s, e, r.after);
  std::string out = "line";
  for (const auto& v : s.inputs)
    out += "," + v.name;
  for (int o : e.outputs) {
    const std::string& n = s.outputs[o].name;
    out += "," + n + "_target," + n + "_before," + n + "_after";
  }
  out += ",rmse_before,rmse_after\n";
  char buf[32];
  auto add = [&](double v) {
    std::snprintf(buf, sizeof buf, ",%.10g", v);
    out += buf;
  };
  for (std::size_t n = 0; n < e.size(); ++n) {
    out += std::to_string(e.lines[n]);
    for (double x : e.inputs[n])
      add(x);
    for (std::size_t k = 0; k < e.outputs.size(); ++k) {
      add(e.targets[n][k]);
      add(r.before[n][k]);
      add(r.after[n][k]);
    }
    add(before[n]);
    add(after[n]);
    out += "\n";
  }
  return out;
}

std::string tuned_text(const fuzzy::FuzzySystem& s, const RuleExamples& e,
                       const RuleTuningResult& r, const std::vector<std::string>& moved,
                       fuzzy::RuleFormat format) {
  const std::vector<double> before = rmse_per_output(e, r.before),
                            after = rmse_per_output(e, r.after);
  std::string c = "Tuned by neurocloth-cli tune-rules to " + std::to_string(e.size()) +
                  " examples from " + e.path + "\n   RMSE before -> after:";
  for (std::size_t k = 0; k < e.outputs.size(); ++k)
    c += " " + s.outputs[e.outputs[k]].name + " " + number(before[k]) + " -> " + number(after[k]) +
         (k + 1 < e.outputs.size() ? "," : "");
  c += "\n   moved:" + std::string(moved.empty() ? " nothing" : "");
  for (const std::string& m : moved)
    c += "\n     " + m;
  if (!r.active.empty()) c += "\n   held by the constraints:";
  for (const std::string& a : r.active)
    c += "\n     " + a;
  // What is written must read back (the writer's promise, checked before
  // anything reaches the disk).
  if (format == fuzzy::RuleFormat::fis) {
    std::string text;
    std::istringstream lines(c);
    for (std::string line; std::getline(lines, line);)
      text += "% " + line + "\n";
    text += fuzzy::write_fis(s);
    fuzzy::parse_fis(text, "the tuned rule base");
    return text;
  }
  const std::string text = "(* " + comment_safe(c) + " *)\n" + fuzzy::write_fcl(s);
  fuzzy::parse_fcl(text, "the tuned rule base");
  return text;
}

int exit_code(const RuleTuningResult& r) {
  if (!r.searched) return kExitOk;
  if (r.search.reason == StopReason::stopped) return kExitInterrupted;
  if (r.search.reason == StopReason::not_finite) return kExitDiverged;
  return kExitOk;
}

}  // namespace

int run_tune_rules(const TuneRulesOptions& o) {
  RuleTuningOptions tuning;
  check_options(o, tuning);
  const fuzzy::FuzzySystem system = read_rules(o.rules);
  // A .fis cannot hold every rule base (stacked hedges, nested conditions,
  // DEFAULT values): said before the search, not after it.
  if (fuzzy::rule_format(o.out) == fuzzy::RuleFormat::fis) try {
      fuzzy::write_fis(system);
    } catch (const std::invalid_argument& e) {
      throw InputError("command line", "--out", std::string("cannot write a .fis: ") + e.what());
    }
  const RuleExamples examples = read_rule_examples(o.examples, system);
  const RuleTuning problem(system, examples, tuning);

  std::string outputs;
  for (int k : examples.outputs)
    outputs += (outputs.empty() ? "" : ", ") + system.outputs[k].name;
  std::printf(
      "tune-rules: %s (%s) to %zu examples of %s: %zu membership/set parameters by projected "
      "gradient, %zu consequent constants by least squares\n",
      system.name.c_str(), o.rules.c_str(), examples.size(), outputs.c_str(),
      problem.shape_parameters().size(), problem.consequent_parameters().size());
  std::fflush(stdout);

  ProgressLine progress(o.iterations, o.time);
  const InterruptScope ctrl_c;
  tuning.search.should_stop = [] { return InterruptScope::interrupted(); };
  const RuleTuningResult result = tune_rules(problem, tuning, [&](const IterationInfo& it) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "loss %.6g  RMSE %.4g%% of range", it.loss,
                  100 * std::sqrt(it.loss));
    progress.show(it, buf);
    return !InterruptScope::interrupted();
  });
  progress.close();
  if (result.searched) {
    std::printf("stopped (%s) after %d iterations: %s\n", to_string(result.search.reason),
                result.search.iterations, result.search.message.c_str());
    if (std::isnan(result.search.best_loss)) {
      std::fprintf(stderr, result.search.reason == StopReason::stopped
                               ? "interrupted before the first evaluation; nothing written\n"
                               : "error: the rule base gives a non-finite loss; nothing written\n");
      return result.search.reason == StopReason::stopped ? kExitInterrupted : kExitDiverged;
    }
  } else {
    std::printf("least squares only (no membership function or set to tune)\n");
  }

  print_outputs_table(system, examples, result);
  print_examples_table(system, examples, result, 10);
  const std::vector<std::string> moved = changed_terms(system, result.tuned);
  std::printf("moved:%s\n", moved.empty() ? " nothing" : "");
  for (const std::string& m : moved)
    std::printf("  %s\n", m.c_str());
  if (!result.active.empty()) std::printf("held by the constraints:\n");
  for (const std::string& a : result.active)
    std::printf("  %s\n", a.c_str());

  const std::string fcl =
      tuned_text(result.tuned, examples, result, moved, fuzzy::rule_format(o.out));
  const std::string csv = examples_csv(system, examples, result);
  const std::string csv_path = examples_csv_name(o.out);
  write_file_atomically(o.out, fcl);
  write_file_atomically(csv_path, csv);
  std::printf("wrote %s, %s (loss %.6g -> %.6g)\n", o.out.c_str(), csv_path.c_str(),
              result.loss_before, result.loss_after);
  return exit_code(result);
}

}  // namespace neurocloth
