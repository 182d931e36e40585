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

/// Cross product written component-wise: for 3-vectors this compiles to
/// plain (fused) multiply-adds, where Eigen's packet version shuffles.
inline Vec3 cross(const Vec3 &a, const Vec3 &b)
{
  return Vec3(a.y() * b.z() - a.z() * b.y(), a.z() * b.x() - a.x() * b.z(), a.x() * b.y() - a.y() * b.x());
}

/// For the few small functions of the per-contact kernel: inlining them
/// keeps the vector registers live instead of spilling them around a call.
#define DEM_HOT_INLINE inline __attribute__((always_inline))
} // namespace dem
