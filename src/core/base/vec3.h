#pragma once
// Cold-path 3-vectors. Hot loops never use this type: they walk flat arrays
// (see cloth_state.h) so that the compiler can vectorise them.
#include <Eigen/Core>
#include <Eigen/Geometry>

namespace neurocloth {
using Vec3 = Eigen::Vector3d;
inline constexpr double kPi = 3.14159265358979323846;
}  // namespace neurocloth
