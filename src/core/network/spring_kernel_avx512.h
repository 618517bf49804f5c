#pragma once
// The hand-written AVX-512 kernel's entry points (spring_kernel.h): compiled
// for AVX-512 F and VL inside every x86-64 build (avx512_region.h), called
// only where resolved() chose SpringKernel::avx512, which it does only on a
// CPU that has them (cpu_features.h). Plain declarations: nothing here needs
// the instructions. Internal to the core.
#include <cstdint>

#include "core/network/cloth_network.h"
#include "core/network/spring_adjoint.h"

namespace neurocloth {

// ClothNetwork::net_forces' spring sweep for nodes [lo, hi) (with the damping
// term when `damped`): adds into F.
void spring_forces_avx512(const ClothNetwork& net, const ClothState& s, SpringPrecision precision,
                          bool damped, NodeVectors& F, std::int32_t lo, std::int32_t hi);

// ClothNetwork::spring_outputs: every force neuron's output (act sized).
void spring_outputs_avx512(const ClothNetwork& net, const ClothState& s, SpringPrecision precision,
                           SpringActivations& act);

// spring_forces_adjoint through this kernel's arithmetic (double, damped).
void spring_forces_adjoint_avx512(const ClothNetwork& net, const ClothState& s,
                                  const NodeVectors& adj_force, ClothState& adj,
                                  SpringGradients& g);

}  // namespace neurocloth
