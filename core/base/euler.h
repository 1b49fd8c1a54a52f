#pragma once
#include "base/math.h"

namespace dp {

/// Euler XYZ angles in degrees to a rotation matrix: X applied first, then Y, then Z
/// (the convention of project transforms and of the probe's rotation).
glm::mat3 euler_xyz_deg(const vec3& deg);

/// Euler XYZ angles in degrees (as euler_xyz_deg reads them) of a rotation matrix; at gimbal
/// lock the whole free angle goes to Z.
vec3 euler_xyz_from_matrix(const glm::mat3& R);

}  // namespace dp
