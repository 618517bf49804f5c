// Placeholder while the module is written (replaced before commit).
#include <stdexcept>

#include "module_factories.h"
namespace neurocloth {
std::unique_ptr<ConstraintModule> make_self_collision(const SelfCollisionSpec&, const ClothTopology&) { throw std::logic_error("todo"); }
}
