// ParticleStore: the balls of a DEM model as a structure of arrays.
//
// Rigid spheres (thesis §3.3): radius R [m], density rho [kg/m^3], mass
// m = rho * 4/3 pi R^3 [kg], moment of inertia I = 2/5 m R^2 [kg m^2].
// Each ball carries its own contact properties as in PFC3D: normal and shear
// stiffness kn, ks [N/m] (combined in series per contact, eq. 3.17-3.18) and
// a friction coefficient [-].
//
// Velocities are the centred-difference mid-step values v(t - dt/2)
// (eq. 3.7-3.9); positions, forces and torques are at t.
//
// A particle's translation and rotation can each be held: its velocity (or
// spin) then stays at the prescribed value whatever force acts on it, which
// is how a scene fixes a ball or drives it at constant velocity.
#pragma once

#include "dem/types.h"

#include <vector>

namespace dem
{
/// One ball as a user describes it; ParticleStore::add derives the rest.
struct BallSpec
{
  Vec3 position = Vec3::Zero(); ///< m
  double radius = 0;            ///< m
  double density = 2650;        ///< kg/m^3
  Vec3 velocity = Vec3::Zero(); ///< m/s
  Vec3 spin = Vec3::Zero();     ///< rad/s
  double kn = 0;                ///< N/m, ball normal stiffness
  double ks = 0;                ///< N/m, ball shear stiffness
  double friction = 0;          ///< -, ball friction coefficient
  bool hold_velocity = false;   ///< translation prescribed
  bool hold_spin = false;       ///< rotation prescribed
};

enum Motion : std::uint8_t
{
  free_motion = 0,
  velocity_held = 1,
  spin_held = 2,
};

class ParticleStore
{
public:
  Index add(const BallSpec &spec);
  Index size() const { return static_cast<Index>(radius.size()); }
  void reserve(std::size_t n);

  /// Sets the radius of ball p and the mass and inertia that follow from it.
  void set_radius(Index p, double r);
  /// Holds or frees the translation / rotation of ball p.
  void set_motion(Index p, bool hold_velocity, bool hold_spin);

  double volume(Index p) const { return 4.0 / 3.0 * pi * radius[p] * radius[p] * radius[p]; }
  bool holds_velocity(Index p) const { return (motion[p] & velocity_held) != 0; }
  bool holds_spin(Index p) const { return (motion[p] & spin_held) != 0; }
  double max_radius() const;
  double min_radius() const;

  std::vector<Vec3> position;              // m
  std::vector<Vec3> velocity;              // m/s, at t - dt/2
  std::vector<Vec3> spin;                  // rad/s, at t - dt/2
  std::vector<Vec3> force;                 // N, resultant at t (contacts + walls + gravity)
  std::vector<Vec3> torque;                // N m, resultant at t
  std::vector<double> radius;              // m
  std::vector<double> density;             // kg/m^3
  std::vector<double> mass;                // kg
  std::vector<double> inertia;             // kg m^2
  std::vector<double> inv_mass;            // 1/kg, zero when the velocity is held
  std::vector<double> inv_inertia;         // 1/(kg m^2), zero when the spin is held
  std::vector<double> inv_radius;          // 1/m
  std::vector<double> sqrt_inv_mass;       // 1/sqrt(kg), for the stability bound
  std::vector<double> sqrt_shear_mobility; // sqrt(1/m + R^2/I), for the stability bound
  std::vector<double> kn;                  // N/m
  std::vector<double> ks;                  // N/m
  std::vector<double> friction;            // -
  std::vector<std::uint8_t> motion;
};
/// The point where the line of centres of balls i and j meets their
/// surfaces in the ratio of the radii [m]: the contact point of two
/// touching balls, the midpoint of equal ones (where a bond broke).
inline Vec3 centre_line_point(const ParticleStore &p, Index i, Index j)
{
  return p.position[i] + (p.position[j] - p.position[i]) * (p.radius[i] / (p.radius[i] + p.radius[j]));
}
} // namespace dem
