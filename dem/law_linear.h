// LinearLaw: the PFC3D linear contact model (thesis §3.4.1).
//
//   normal (secant, eq. 3.2):       F_n = K^n U
//   shear (incremental, eq. 3.3-3.4): F_s <- F_s - K^s V_s dt
//
// with K^n, K^s the per-pair stiffnesses of the two entities in series
// (eq. 3.17-3.18) [N/m].  Slip and bonds are applied on top by the contact
// resolver (contact_resolve.h).  The law also knows its closed forms, which
// tests and `demvv verify` compare the engine against (Chung & Ooi 2011,
// undamped linear spring):
//
//   natural frequency   omega_0 = sqrt(K^n / m*)          [rad/s]
//   contact duration    t_c     = pi / omega_0             [s]
//   peak normal force   F_max   = v_0 sqrt(m* K^n)         [N]
//   restitution         e       = 1
//
// where m* = m_1 m_2 / (m_1 + m_2) (m* = m against a wall).
#pragma once

#include "dem/contact.h"

#include <array>
#include <string_view>
#include <vector>

namespace dem
{
class LinearLaw
{
public:
  static constexpr std::string_view keyword = "linear";
  /// No deck constants: the stiffnesses and friction are per ball.
  static std::vector<LawConstant> deck_constants() { return {}; }

  /// Law-specific history: none beyond ContactState's shear force, so the
  /// contact pass never touches the table's LawState slots.
  struct History
  {
  };
  static constexpr std::array<std::string_view, 0> state_fields{};
  static History load(const LawState & /*s*/) { return {}; }
  static void store(const History & /*h*/, LawState & /*s*/) {}

  /// Normal force from the current overlap (eq. 3.2).
  double normal_force(const ContactParams &p, double overlap, History & /*h*/, double /*dt*/) const
  {
    return p.kn * overlap;
  }

  /// New shear force from the rotated old one and the shear displacement
  /// increment of the step (eq. 3.3-3.4).
  Vec3 shear_force(const ContactParams &p, const Vec3 &rotated_force, const Vec3 &shear_increment, History & /*h*/,
                   double /*dt*/) const
  {
    return rotated_force - p.ks * shear_increment;
  }

  /// Nothing to precompute per step, no history to turn or to advance.
  void prepare(double /*dt*/) {}
  void rotate_history(History & /*h*/, const Vec3 & /*old_normal*/, const Vec3 & /*new_normal*/, double /*twist*/) const
  {
  }
  void commit(History & /*h*/, double /*overlap*/, double /*normal_force*/, const Vec3 & /*shear_before*/,
              const Vec3 & /*shear*/, double /*dt*/) const
  {
  }

  /// Elastic energy stored in the springs of a contact [J].
  double stored_energy(const ContactParams &p, double normal_force, const Vec3 &shear_force,
                       const History & /*h*/) const
  {
    double e = p.kn > 0 ? 0.5 * normal_force * normal_force / p.kn : 0.0;
    if (p.ks > 0)
      e += 0.5 * shear_force.squaredNorm() / p.ks;
    return e;
  }

  /// Stiffnesses the stability bound must use: the tangent ones.
  double normal_stiffness(const ContactParams &p) const { return p.kn; }
  double shear_stiffness(const ContactParams &p) const { return p.ks; }

  // --- closed forms (Chung & Ooi 2011, tests 1-3) -----------------------
  static double natural_frequency(double kn, double reduced_mass) { return std::sqrt(kn / reduced_mass); }
  static double collision_time(double kn, double reduced_mass) { return pi / natural_frequency(kn, reduced_mass); }
  static double peak_force(double kn, double reduced_mass, double approach_speed)
  {
    return approach_speed * std::sqrt(reduced_mass * kn);
  }
  static double restitution() { return 1.0; }
  static double reduced_mass(double m1, double m2) { return m1 * m2 / (m1 + m2); }
};
} // namespace dem
