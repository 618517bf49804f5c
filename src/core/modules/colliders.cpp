// Placeholder while the module is written (replaced before commit).
#include <stdexcept>

#include "module_factories.h"
namespace neurocloth {
std::unique_ptr<ConstraintModule> make_collider(const PlaneSpec&) { throw std::logic_error("todo"); }
std::unique_ptr<ConstraintModule> make_collider(const BoxSpec&) { throw std::logic_error("todo"); }
std::unique_ptr<ConstraintModule> make_collider(const SphereSpec&) { throw std::logic_error("todo"); }
std::unique_ptr<ConstraintModule> make_collider(const CapsuleSpec&) { throw std::logic_error("todo"); }
}
