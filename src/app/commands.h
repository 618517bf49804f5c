#pragma once
// The subcommands of neurocloth-cli. Each returns the process exit code:
// 0 ok, 3 diverged (result still written), 4 relax did not converge (result
// written), 1 bad input (nothing written).
#include <optional>
#include <string>
#include <vector>

#include "integrator.h"

namespace neurocloth {

inline constexpr int kExitOk = 0;
inline constexpr int kExitInputError = 1;
inline constexpr int kExitUsage = 2;
inline constexpr int kExitDiverged = 3;
inline constexpr int kExitNotConverged = 4;

struct SimulateOptions {
  std::string scene;
  double seconds = 0;
  std::optional<std::string> integrator;
  std::optional<double> dt;
  bool adaptive = false;
  bool fixed_step = false;
  std::string out;
};
int run_simulate(const SimulateOptions& options);

struct RelaxOptions {
  std::string scene;
  std::string out;
};
int run_relax(const RelaxOptions& options);

struct BenchOptions {
  int size = 64;
  int steps = 200;
  int repeat = 5;
  std::string integrator = "network";
  bool json = false;
};
int run_bench(const BenchOptions& options);

struct MaterialOptions {
  std::string rules;                  // --rules FILE.fcl
  std::vector<std::string> inputs;    // --input NAME=VALUE ...
  std::optional<std::string> preset;  // --preset NAME
  bool json = false;
};
int run_material(const MaterialOptions& options);

// Renders a scene after `seconds` to a PNG without a display (OSMesa). Built
// only with NEUROCLOTH_BUILD_VIEWER (snapshot_command.cpp).
struct SnapshotOptions {
  std::string scene;
  double seconds = 0;
  std::string out;                    // FILE.png
  std::string size = "1280x720";      // WIDTHxHEIGHT
  std::optional<std::string> camera;  // yaw,pitch,distance[,tx,ty,tz]; default frames the scene
  bool wireframe = false;
  bool springs = false;
  bool nodes = false;
  bool strain = false;
  std::optional<double> strain_max;  // the red end of the strain map, as a fraction
  bool verbose = false;
};
int run_snapshot(const SnapshotOptions& options);

}  // namespace neurocloth
