#pragma once
// The factory of each concrete integrator (each lives in its own file), what
// make_integrator() in integrator.cpp chooses among by IntegratorKind.
#include <memory>

#include "core/integrators/integrator.h"

namespace neurocloth {
std::unique_ptr<Integrator> make_network_propagation(const ClothNetwork& net,
                                                     bool implicit_damping = false);
std::unique_ptr<Integrator> make_explicit_euler(const ClothNetwork& net);
std::unique_ptr<Integrator> make_velocity_verlet(const ClothNetwork& net);
std::unique_ptr<Integrator> make_runge_kutta4(const ClothNetwork& net);
std::unique_ptr<Integrator> make_implicit_euler(const ClothNetwork& net, double min_step_fraction,
                                                double linear_tolerance,
                                                ImplicitPreconditioner preconditioner);
std::unique_ptr<Integrator> make_projective(const ClothNetwork& net, int iterations);
std::unique_ptr<Integrator> make_vertex_block_descent(const ClothNetwork& net, int iterations);
}  // namespace neurocloth
