#include "learn/motion/fabric_test_reference.h"

#include <cmath>

#include "core/io/input_error.h"
#include "core/io/physical_limits.h"
#include "core/scene/cantilever.h"

namespace neurocloth {

ReferenceMotion cantilever_reference(const Scene& scene, double bending_length, double time,
                                     const std::string& field) {
  const auto setup = cantilever_setup(scene);
  if (!setup)
    throw InputError(scene.path, field,
                     "the scene is no cantilever test: a grid pinned along exactly its first two "
                     "columns, level, under gravity (assets/scenes/cantilever.json)");
  if (!limits::kBendingLength.contains(bending_length))
    throw InputError("command line", field, limits::kBendingLength.refusal(bending_length));
  const double lambda = setup->overhang / bending_length;
  if (!(lambda > 0 && lambda <= kMaxOverhangRatio))
    throw InputError("command line", field,
                     "the strip overhangs " + show_number(lambda) +
                         " bending lengths; the elastica reads at most 4 (a chord of 77 "
                         "degrees): shorten the strip");
  if (!(time > 0) || !std::isfinite(time))
    throw InputError("command line", field, "the time the strip is read at must be > 0 s");
  double along = 0, down = 0;
  elastica_tip(lambda, along, down);
  ReferenceMotion ref;
  ref.path = "cantilever bending length " + show_number(bending_length) + " m";
  ref.source = ReferenceMotion::Source::markers;
  ReferenceFrame frame;
  frame.time = time;
  // Each row's tip lies where the elastica puts it from that row's clamp.
  for (std::size_t r = 0; r < setup->tip.size(); ++r) {
    const Vec3 clamp =
        scene.topology.rest_positions[setup->clamp_edge[r]] - setup->clamp_inset * setup->along;
    frame.nodes.push_back(scene.topology.numbering.source(setup->tip[r]));
    frame.positions.push_back(clamp + bending_length * (along * setup->along + down * setup->down));
  }
  ref.frames.push_back(frame);
  ref.note = "the tip of a strip of bending length " + show_number(1e3 * bending_length) +
             " mm at " + show_number(time) + " s (heavy elastica)";
  return ref;
}

}  // namespace neurocloth
