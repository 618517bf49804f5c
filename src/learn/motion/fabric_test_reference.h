#pragma once
// A fabric lab's test as a reference motion (docs/materials.md, "Fitting from
// a fabric test"): a cantilever's bending length says where the strip's tip
// comes to rest (the heavy elastica, core/scene/cantilever.h), which is a
// marker at the tip's nodes that a fit can match by its gradient, the
// bending module's rigidity among its unknowns.
#include "core/scene/scene.h"
#include "learn/motion/reference_motion.h"

namespace neurocloth {

// One frame at `time` (s; long enough for the strip to settle): every tip
// node where a strip of bending length `bending_length` (m) rests. Throws
// InputError naming `field` when the scene is no cantilever test
// (cantilever_setup) or the length is outside what the elastica reads
// (overhang / length in (0, 4]).
ReferenceMotion cantilever_reference(const Scene& scene, double bending_length, double time,
                                     const std::string& field);

}  // namespace neurocloth
