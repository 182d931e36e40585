// Contact geometry, per-contact parameters and per-contact history.
//
// The split follows MercuryDPM/YADE: the geometry of a contact is computed
// once per step (ContactGeometry, "Ig2"), the parameters of a pair are fixed
// when the pair is created (ContactParams, "Ip2"), and everything that evolves
// lives in ContactState, owned by the ContactTable (ball-ball) or the WallSet
// (ball-wall).  A contact law ("Law2") reads the first two and updates the
// third; laws themselves hold only model constants and per-step constants.
// A law that needs more history than ContactState (a Burger's element) keeps
// it in a LawState slot, which the ContactTable stores beside the entries.
//
// Frame: the unit normal n points from the first entity to the second (for a
// ball-wall contact the wall is first).  The force stored in a contact is the
// force on the second entity: F = F_n n + F_s, with F_n > 0 in compression
// (thesis eq. 3.1-3.2).  The first entity receives -F.
#pragma once

#include "dem/types.h"

#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <map>
#include <string>
#include <string_view>
#include <type_traits>

namespace dem
{
/// Pair constants fixed when the pair is created.
struct ContactParams
{
  double kn = 0;       ///< N/m, normal stiffness K^n of the pair (eq. 3.17)
  double ks = 0;       ///< N/m, shear stiffness K^s of the pair (eq. 3.18)
  double friction = 0; ///< -, Coulomb coefficient of the pair
};

/// Two stiffnesses in series, k_A k_B / (k_A + k_B) (eq. 3.17-3.18); zero if
/// either is zero (a frictionless, shear-free platen has ks = 0).
inline double in_series(double a, double b) { return (a > 0 && b > 0) ? a * b / (a + b) : 0.0; }

/// PFC3D contact bond (thesis §3.4.2): strengths are forces.  Whether a
/// contact's bond holds is a flag of the contact (`bonded`, contacts.h),
/// kept beside the pair's other small fields where it costs no padding.
struct ContactBond
{
  double normal_strength = 0;                                      ///< N, tensile strength phi_n
  double shear_strength = 0;                                       ///< N, shear strength phi_s
  double break_distance = std::numeric_limits<double>::infinity(); ///< m, centre distance that breaks it (appendix A)
};

/// How a bond broke; recorded in the break log.
enum class BreakMode : std::uint8_t
{
  none = 0,
  tension = 1,
  shear = 2,
  displacement = 3, ///< centre distance grew by delta_c (appendix A)
};

/// Trial forces of a contact whose bond broke at this step: the law's
/// forces before the bond and slip rules changed them.  Recorded only on a
/// break, so the contact pass pays nothing for them otherwise.
struct BreakForces
{
  double normal = 0; ///< N, trial normal force (compression positive)
  double shear = 0;  ///< N, magnitude of the trial shear force
};

/// History of one contact.  Reset when the entities separate.
struct ContactState
{
  Vec3 shear_force = Vec3::Zero(); ///< N, F_s on the second entity
  Vec3 normal = Vec3::Zero();      ///< unit normal at the last update if it carried a force, else zero
  double normal_force = 0;         ///< N, F_n (compression positive)
  double overlap = 0;              ///< m, U at the last update
  double friction_work = 0;        ///< J, energy dissipated by Coulomb slip so far
  double bond_energy = 0;          ///< J, elastic energy released by the bond's break

  /// Whether the contact carried a force at the last update: its normal is
  /// then a unit vector, never zero, so no flag (eight bytes with padding,
  /// in every contact entry) is needed.
  bool touching() const { return normal.x() != 0 || normal.y() != 0 || normal.z() != 0; }
};

/// A contact law's own history of one contact, beyond ContactState: a fixed
/// number of doubles, so that the ContactTable can keep one slot per entry
/// in a plain array beside the entries (a law without such history never
/// loads it) and a file can write it without knowing the law.  Each law
/// maps its History to and from the values and names them, with units, in
/// its `state_fields`; the all-zero slot is every law's state at rest.
struct LawState
{
  static constexpr std::size_t capacity = 6; ///< doubles; the largest History (Burger's) needs six
  std::array<double, capacity> value{};

  friend bool operator==(const LawState &a, const LawState &b) { return a.value == b.value; }
};
static_assert(std::is_trivially_copyable_v<LawState>, "the table copies slots as plain bytes");

/// What the rate scaling of a test (thesis eq. 7.21, 7.23) multiplies a
/// law constant by: the stiffness factor or the viscosity factor.
enum class RateScaled
{
  stiffness,
  viscosity,
};

/// A constant of a contact law that a deck sets, declared by the law beside
/// its keyword (its `deck_constants`): decks, `demvv defaults` and the rate
/// scaling read these, so a new law with constants touches no deck code.
struct LawConstant
{
  std::string_view key;  ///< deck key inside `subsection contact law`
  double default_value;  ///< in `unit`
  std::string_view unit; ///< SI
  std::string_view help;
  RateScaled scaling;
};

/// Law constants by deck key, as a deck gives them; a law reads the ones it
/// declares, and a key left out takes its declared default.
struct LawParameters
{
  std::map<std::string, double, std::less<>> values;

  double operator[](const LawConstant &c) const
  {
    const auto it = values.find(c.key);
    return it == values.end() ? c.default_value : it->second;
  }
};

/// Geometry of a contact at time t, computed once per step, with the
/// velocities of the interval (t - dt, t) that the centred-difference scheme
/// stores (eq. 3.8).
struct ContactGeometry
{
  Vec3 normal;              ///< unit, first -> second, at t
  double overlap;           ///< m, U > 0 when interpenetrating
  Vec3 velocity_difference; ///< m/s, centre velocity of second minus first (wall: its surface velocity)
  Vec3 spin_first;          ///< rad/s (zero for walls)
  Vec3 spin_second;         ///< rad/s
  double arm_first;         ///< m, centre of first to contact point (0 for walls)
  double arm_second;        ///< m, centre of second to contact point
};

/// Rotates a shear vector with the contact plane, as PFC3D does each step:
/// by the rotation vector phi = n_old x n_new + twist n_mean (the tilt of
/// the plane plus the mean spin of the two entities about the normal times
/// dt), through the second-order Taylor expansion of the rotation,
///   r = v + phi x v + phi x (phi x v) / 2,
/// then projected onto the new plane.  The turn is exact to third order in
/// the angle per step and |r| = |v| (1 + O(phi^4)), so no renormalisation
/// is needed: over a run both errors are second order (check V04 measures
/// them).  A first-order turn would shrink the part of v normal
/// to phi by |phi|^2/2 per step, a first-order error over a run.
DEM_HOT_INLINE Vec3 rotate_with_contact_plane(const Vec3 &v, const Vec3 &old_normal, const Vec3 &new_normal,
                                              double twist_angle)
{
  // The twist acts about the mean normal: the symmetric choice keeps the
  // error of a step third order in its angle.
  const Vec3 phi = cross(old_normal, new_normal) + (0.5 * twist_angle) * (old_normal + new_normal);
  const Vec3 turn = cross(phi, v);
  Vec3 r = v + turn + 0.5 * cross(phi, turn);
  return r - r.dot(new_normal) * new_normal;
}
} // namespace dem
