// `neurocloth-cli compare A.json B.json`: how far apart two results of one cloth
// are, in every metric the trade knows (cloth_metrics.h), as one JSON object on
// stdout: what a user checks a run against another with, and what the Blender
// peer's ensemble is measured with (bench/peers).
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "app/cli/commands.h"
#include "core/io/input_error.h"
#include "core/io/json_fields.h"
#include "core/io/physical_limits.h"
#include "core/io/text_file.h"
#include "core/scene/scene.h"
#include "tradeoff/cloth_metrics.h"

namespace neurocloth {
namespace {

// The parts of a RESULT.json (ours, or bench/peers' Blender result) compare reads.
struct ResultFile {
  std::string path;
  std::string scene;              // its "scene", or empty
  std::vector<double> positions;  // x0 y0 z0 ... in the file's vertex order
  double energy = std::nan("");   // "energy.total", when it has one
};

ResultFile read_result(const std::string& path) {
  ResultFile r;
  r.path = path;
  const JsonFields doc(read_text_file(path, "result file", kMaxMeshBytes), path);
  doc.require_object(doc.root(), "result");
  if (doc.has(doc.root(), "scene")) r.scene = doc.string(doc.root()["scene"], "scene");
  const nlohmann::json& positions = doc.member(doc.root(), "result", "positions");
  if (!positions.is_array() || positions.empty())
    doc.fail("positions", "must be a non-empty array of [x, y, z]");
  r.positions.reserve(3 * positions.size());
  for (std::size_t i = 0; i < positions.size(); ++i) {
    const Vec3 p =
        doc.vec3(positions[i], "positions[" + std::to_string(i) + "]", limits::kCoordinate);
    r.positions.insert(r.positions.end(), {p.x(), p.y(), p.z()});
  }
  if (doc.has(doc.root(), "energy") && doc.root()["energy"].is_object() &&
      doc.root()["energy"].contains("total"))
    r.energy = doc.number(doc.root()["energy"]["total"], "energy.total");
  return r;
}

// The scene both results are of, at their node count: a grid scene is resized
// to N x N when the results have N^2 nodes and it has not (`--size` runs).
Scene compared_scene(const CompareOptions& o, const ResultFile& a, const ResultFile& b,
                     std::string& scene_path) {
  scene_path = o.scene ? *o.scene : !a.scene.empty() ? a.scene : b.scene;
  if (scene_path.empty())
    throw InputError("command line", "--scene",
                     "needed: neither " + a.path + " nor " + b.path +
                         " says which scene it is of (a field \"scene\")");
  Scene scene = load_scene(scene_path);
  const std::size_t nodes = a.positions.size() / 3;
  if (o.size) return sized_scene(scene, scene_path, o.size);
  if (scene.topology.rest_positions.size() != nodes && scene.grid &&
      scene.grid->rows == scene.grid->cols) {
    const auto n = static_cast<int>(std::lround(std::sqrt(static_cast<double>(nodes))));
    if (static_cast<std::size_t>(n) * static_cast<std::size_t>(n) == nodes)
      return sized_scene(scene, scene_path, n);
  }
  return scene;
}

// A result lists the file's vertices in order (result_json.h); the metrics
// index nodes, which a mesh scene may have renumbered.
std::vector<double> node_order(const std::vector<double>& file_order, const NodeNumbering& n) {
  std::vector<double> out(file_order.size());
  for (std::size_t k = 0; k < file_order.size() / 3; ++k) {
    const auto i = static_cast<std::size_t>(n.node(static_cast<int>(k)));
    for (int d = 0; d < 3; ++d)
      out[3 * i + static_cast<std::size_t>(d)] = file_order[3 * k + static_cast<std::size_t>(d)];
  }
  return out;
}

}  // namespace

int run_compare(const CompareOptions& o) {
  const ResultFile a = read_result(o.a), b = read_result(o.b);
  if (a.positions.size() != b.positions.size())
    throw InputError(o.a + ", " + o.b, "positions",
                     "the results have different node counts (" +
                         std::to_string(a.positions.size() / 3) + " and " +
                         std::to_string(b.positions.size() / 3) + "): not the same cloth");
  std::string scene_path;
  const Scene scene = compared_scene(o, a, b, scene_path);
  const std::size_t nodes = a.positions.size() / 3;
  if (scene.topology.rest_positions.size() != nodes)
    throw InputError(o.a + ", " + o.b, "positions",
                     std::to_string(nodes) + " nodes, but " + scene_path + " has " +
                         std::to_string(scene.topology.rest_positions.size()) +
                         (o.size ? " at --size " + std::to_string(*o.size) : std::string()));
  const MetricContext context = metric_context(scene);
  if (o.scene && !context.support)
    throw InputError(
        *o.scene, "modules",
        "no box, sphere or cylinder for the cloth to drape over (compare's --scene is for "
        "the support)");
  const std::vector<double> xa = node_order(a.positions, scene.topology.numbering),
                            xb = node_order(b.positions, scene.topology.numbering);
  const FrameShape sa = frame_shape(xa.data(), context), sb = frame_shape(xb.data(), context);
  const bool energy = std::isfinite(a.energy) && std::isfinite(b.energy);
  const MetricValues v = compare_frames(xa.data(), sa, energy ? a.energy : 0, xb.data(), sb,
                                        energy ? b.energy : 0, context);
  nlohmann::ordered_json out;
  out["a"] = o.a;
  out["b"] = o.b;
  out["scene"] = scene_path;
  out["nodes"] = nodes;
  out["cloth_size_m"] = context.size;
  // Percent of the cloth's size, as the tradeoff writes its errors.
  for (Metric m : {Metric::node_max, Metric::node_rms, Metric::surface_mean, Metric::surface_max})
    out[to_string(m)] = 100 * v[slot(m)];
  if (context.support) {
    out["support"] = to_string(context.support->shape);
    out["drape_coefficient_a"] = sa.drape;
    out["drape_coefficient_b"] = sb.drape;
    out["folds_a"] = sa.folds;
    out["folds_b"] = sb.folds;
  }
  out["strain_max_a"] = sa.strain_max;
  out["strain_max_b"] = sb.strain_max;
  out["strain_mean_a"] = sa.strain_mean;
  out["strain_mean_b"] = sb.strain_mean;
  // Percent of the work gravity does dropping the cloth by its size.
  if (energy) out["energy"] = 100 * v[slot(Metric::energy)];
  std::printf("%s\n", out.dump(2).c_str());
  return kExitOk;
}

}  // namespace neurocloth
