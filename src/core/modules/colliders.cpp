// Contact with the analytic solids (plane, box, sphere, capsule, cylinder), with Coulomb
// friction (contact_response.h). A collider is a projection run after each
// integrator step: a free node that ended the step closer than `thickness` to
// the surface (or inside) is moved out along the surface normal.
//
// Node contact only: an edge between two nodes outside a shape may still cut
// through a corner or a thin part of it (the mesh collider tests the cloth's
// edges against its sharp edges). A box or a cylinder catches a node whose
// step crosses it entirely; a sphere or capsule judges by where the step ends,
// so a node moving more than about its radius in one step may pass through.
#include "core/modules/collider_motion.h"
#include "core/modules/collider_shapes.h"
#include "core/modules/module_factories.h"
#include "core/modules/shape_collider.h"

namespace neurocloth {
namespace {

using collider_shapes::BoxShape;
using collider_shapes::CapsuleShape;
using collider_shapes::CylinderShape;
using collider_shapes::PlaneShape;
using contact_response::ColliderFrame;

template <class Shape>
class Collider final : public ConstraintModule {
 public:
  Collider(const char* type, const Shape& shape, const ContactSpec& contact,
           const ModuleSpec& declared)
      : type_(type),
        shape_(shape),
        spec_(contact),
        declared_(declared),
        posed_(collider_posed(declared)) {}
  const char* type() const override { return type_; }
  Phase phase() const override { return ConstraintModule::contact; }

  void apply(const ClothNetwork& net, const StepSpan& span, const StepStart& before,
             ClothState& after, ModuleState*) const override {
    if (!posed_)
      return contact_response::collide_nodes(shape_, spec_, nullptr, net, span, before, after);
    const ColliderFrame frame = contact_response::frame_over(declared_, span);
    contact_response::collide_nodes(shape_, spec_, &frame, net, span, before, after);
  }

  bool has_adjoint() const override { return true; }
  bool set_parameter(const ParameterId& id, double value) override {
    if (id.parameter != ModuleParameter::friction || !spec_.friction) return false;
    spec_.friction = value;
    return true;
  }
  std::optional<double> parameter(const ParameterId& id) const override {
    if (id.parameter != ModuleParameter::friction) return std::nullopt;
    return spec_.friction;
  }

  void apply_adjoint(const ClothNetwork& net, const StepSpan& span, const StepStart& before,
                     const ClothState& after, ClothState& adj, NodeVectors& adj_before,
                     double* adj_friction, double* params) const override {
    double* friction_slot = params ? &params[module_slot(ModuleParameter::friction, -1)] : nullptr;
    if (!posed_)
      return contact_response::collide_nodes_adjoint(shape_, spec_, nullptr, net, span, before,
                                                     after, adj, adj_before, adj_friction,
                                                     friction_slot);
    const ColliderFrame frame = contact_response::frame_over(declared_, span);
    contact_response::collide_nodes_adjoint(shape_, spec_, &frame, net, span, before, after, adj,
                                            adj_before, adj_friction, friction_slot);
  }

 private:
  const char* type_;
  Shape shape_;
  ContactSpec spec_;
  ModuleSpec declared_;  // its pose in time (collider_motion.h)
  bool posed_;
};

template <class Shape, class Spec>
std::unique_ptr<ConstraintModule> make(const char* type, const Shape& shape, const Spec& spec) {
  return std::make_unique<Collider<Shape>>(type, shape, spec.contact, ModuleSpec(spec));
}

}  // namespace

std::unique_ptr<ConstraintModule> make_collider(const PlaneSpec& spec) {
  return make("plane", PlaneShape(spec), spec);
}
std::unique_ptr<ConstraintModule> make_collider(const BoxSpec& spec) {
  return make("box", BoxShape(spec), spec);
}
std::unique_ptr<ConstraintModule> make_collider(const SphereSpec& spec) {
  return make("sphere", CapsuleShape(spec.center, spec.center, spec.radius), spec);
}
std::unique_ptr<ConstraintModule> make_collider(const CapsuleSpec& spec) {
  return make("capsule", CapsuleShape(spec.a, spec.b, spec.radius), spec);
}
std::unique_ptr<ConstraintModule> make_collider(const CylinderSpec& spec) {
  return make("cylinder", CylinderShape(spec), spec);
}

}  // namespace neurocloth
