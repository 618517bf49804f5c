#include "core/integrators/integrator.h"

#include <stdexcept>

#include "core/integrators/integrator_factory.h"

namespace neurocloth {

const char* to_string(IntegratorKind k) {
  switch (k) {
    case IntegratorKind::network:
      return "network";
    case IntegratorKind::explicit_euler:
      return "explicit_euler";
    case IntegratorKind::verlet:
      return "verlet";
    case IntegratorKind::rk4:
      return "rk4";
    case IntegratorKind::implicit_euler:
      return "implicit_euler";
    case IntegratorKind::projective:
      return "projective";
    case IntegratorKind::vbd:
      return "vbd";
  }
  return "?";
}

std::optional<IntegratorKind> parse_integrator(const std::string& name) {
  for (IntegratorKind k : kAllIntegrators)
    if (name == to_string(k)) return k;
  return std::nullopt;
}

std::string integrator_names() {
  std::string s;
  for (IntegratorKind k : kAllIntegrators)
    s += (s.empty() ? "" : ", ") + std::string(to_string(k));
  return s;
}

std::unique_ptr<Integrator> make_integrator(IntegratorKind kind, const ClothNetwork& net,
                                            double min_step_fraction, int iterations,
                                            double linear_tolerance,
                                            ImplicitPreconditioner preconditioner,
                                            bool implicit_damping) {
  if (implicit_damping && kind != IntegratorKind::network)
    throw std::invalid_argument(std::string("solver.damping \"implicit\" is for the network "
                                            "integrator, not ") +
                                to_string(kind));
  switch (kind) {
    case IntegratorKind::network:
      return make_network_propagation(net, implicit_damping);
    case IntegratorKind::explicit_euler:
      return make_explicit_euler(net);
    case IntegratorKind::verlet:
      return make_velocity_verlet(net);
    case IntegratorKind::rk4:
      return make_runge_kutta4(net);
    case IntegratorKind::implicit_euler:
      return make_implicit_euler(net, min_step_fraction, linear_tolerance, preconditioner);
    case IntegratorKind::projective:
      return make_projective(net, iterations);
    case IntegratorKind::vbd:
      return make_vertex_block_descent(net, iterations);
  }
  return nullptr;
}

}  // namespace neurocloth
