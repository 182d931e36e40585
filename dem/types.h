// demvv DEM engine: basic types and conventions.
//
// Units are SI throughout (m, kg, s, N, Pa, J).  Vectors are Eigen 3-vectors.
// Sign convention inside the engine: a contact's overlap U = R_A + R_B - d is
// positive when the spheres interpenetrate, and its normal force is positive
// in compression (thesis eq. 3.2); tension (bonded pairs only) is negative.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <cstdint>
#include <limits>

namespace dem
{
using Vec3 = Eigen::Vector3d;
using Index = std::int32_t;

inline constexpr double pi = 3.14159265358979323846;
inline constexpr double infinity = std::numeric_limits<double>::infinity();

inline Vec3 zero_vec() { return Vec3::Zero(); }
} // namespace dem
