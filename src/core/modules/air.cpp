// Placeholder while the module is written (replaced before commit).
#include <stdexcept>

#include "module_factories.h"
namespace neurocloth {
std::shared_ptr<ForceModule> make_air_drag(const AirDragSpec&) { throw std::logic_error("todo"); }
std::shared_ptr<ForceModule> make_wind(const WindSpec&, const ClothTopology&) { throw std::logic_error("todo"); }
}
