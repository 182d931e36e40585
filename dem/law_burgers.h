// Burger's contact laws (thesis §3.4.3, §7.2, appendix A).
//
// A Burger's element is a Maxwell pair (spring K_m = K0, dashpot C_m = C_inf)
// in series with a Kelvin pair (spring K_k = K1, dashpot C_k = C1).  Each
// direction of a contact (normal; shear as a vector in the contact plane)
// is one element with its own constants (Table 3.1, Table 7.2); the
// constants are contact properties, not per-ball values combined in series.
//
// Update: the thesis's Crank-Nicolson scheme (eq. 3.25-3.35).  With
//   A = 1 + K_k dt / (2 C_k),  B = 1 - K_k dt / (2 C_k),
//   C = dt / (2 C_k A) + 1/K_m + dt / (2 C_m),
//   D = dt / (2 C_k A) - 1/K_m + dt / (2 C_m),
// the force after a displacement increment u^{t+1} - u^t is (eq. 3.34)
//   f^{t+1} = (u^{t+1} - u^t + (1 - B/A) u_k^t - D f^t) / C
// and the Kelvin displacement follows (eq. 3.26)
//   u_k^{t+1} = (B u_k^t + dt/(2 C_k) (f^{t+1} + f^t)) / A.
// The scheme is the trapezoidal rule: second order, A-stable, not L-stable.
// When K_k dt / (2 C_k) > 1, B < 0 and the Kelvin displacement of a relaxing
// element alternates sign from step to step instead of decaying smoothly
// (check V14 shows it); the DEM time step is normally far
// below that limit.
//
// Directions and signs: the normal element is driven by the overlap U
// (compression positive, so tension is U < 0) and gives F_n (compression
// positive); the shear element is driven by minus the shear displacement
// increment and gives the shear force on the second ball, so that with
// C_m, C_k -> infinity it is the linear law F_s <- F_s - K_m dU_s.
//
// The force actually applied may differ from the element's trial force
// (slip, no tension without a bond, a break): the element then continues
// from the applied force, its Maxwell part absorbing the difference.
//
// Modified Burger's (§7.2.2): in normal compression (U >= 0) the contact is
// an elastic spring, F_n = E_0^n U; in normal tension and in shear it is a
// Burger's element.  The normal element's state is reset to rest (zero
// force, zero Kelvin displacement, reference U = 0) whenever the contact is
// in compression: tension always starts from a relaxed element at the point
// where the balls just touch, so the normal force is continuous when the
// overlap goes from compression to tension; when a loaded element returns
// to compression its viscous force is dropped and the elastic force
// (zero at U = 0) takes over.
//
// Stability: the instantaneous stiffness of an element is 1/C <= K_m, so
// the critical-step bound uses K_m (and E_0^n for the modified law).
//
// Closed forms (eq. 7.18, 2.15) live in burgers_closed_form.h; the law
// hands out its constants per direction so tests compare against them.
#pragma once

#include "dem/burgers_closed_form.h"
#include "dem/contact.h"

#include <algorithm>
#include <array>
#include <string_view>
#include <type_traits>
#include <vector>

namespace dem
{
/// The per-step coefficients of eq. 3.27 and 3.35 for a time step dt.
struct BurgersCoefficients
{
  double a = 1, b = 1, c = 1, d = 1, kelvin_rate = 0; ///< A, B, C, D and dt / (2 C_k)
  /// 1/C, 1/A and 1 - B/A, the same doubles the formulas would divide out
  /// each time, taken once per step (no division in the contact loop).
  double inverse_c = 1, inverse_a = 1, kelvin_carry = 0;

  BurgersCoefficients() = default;
  BurgersCoefficients(const BurgersConstants &k, double dt)
  {
    kelvin_rate = 0.5 * dt / k.kelvin_viscosity;
    a = 1 + k.kelvin_stiffness * kelvin_rate;
    b = 1 - k.kelvin_stiffness * kelvin_rate;
    const double viscous = kelvin_rate / a + 0.5 * dt / k.maxwell_viscosity;
    c = viscous + 1 / k.maxwell_stiffness;
    d = viscous - 1 / k.maxwell_stiffness;
    inverse_c = 1 / c;
    inverse_a = 1 / a;
    kelvin_carry = 1 - b / a;
  }

  /// Force after a displacement increment (eq. 3.34); T is double or Vec3.
  template <class T>
  T force(const T &increment, const T &kelvin, const T &force_before) const
  {
    return (increment + kelvin_carry * kelvin - d * force_before) * inverse_c;
  }

  /// Kelvin displacement after the step (eq. 3.26).
  template <class T>
  T kelvin(const T &kelvin_before, const T &force_before, const T &force_after) const
  {
    return (b * kelvin_before + kelvin_rate * (force_after + force_before)) * inverse_a;
  }
};

/// Elastic energy of an element carrying force f with Kelvin displacement u_k [J].
template <class T>
double burgers_energy(const BurgersConstants &k, const T &force, const T &kelvin)
{
  const auto square = [](const auto &v)
  {
    if constexpr (std::is_same_v<std::decay_t<decltype(v)>, double>)
      return v * v;
    else
      return v.squaredNorm();
  };
  return 0.5 * square(force) / k.maxwell_stiffness + 0.5 * k.kelvin_stiffness * square(kelvin);
}

/// Constants of a Burger's contact (Table 7.2 layout).
struct BurgersContactConstants
{
  /// Thesis Table 7.2 unless set: 0.5 MN/m and 0.5 MN s/m everywhere.
  BurgersConstants normal{0.5e6, 0.5e6, 0.5e6, 0.5e6}; ///< tension (and compression for the plain law)
  BurgersConstants shear{0.5e6, 0.5e6, 0.5e6, 0.5e6};
  double compression_stiffness = 0.5e6; ///< E_0^n, N/m (modified law only)

  /// True when every constant is positive and finite.
  bool valid() const
  {
    const auto ok = [](double v) { return v > 0 && std::isfinite(v); };
    for (const BurgersConstants *k : {&normal, &shear})
      if (!ok(k->maxwell_stiffness) || !ok(k->maxwell_viscosity) || !ok(k->kelvin_stiffness) ||
          !ok(k->kelvin_viscosity))
        return false;
    return ok(compression_stiffness);
  }
};

/// Per-contact state of a Burger's contact; all zero is an element at rest.
/// The contact table keeps it in a LawState slot, in the order and with the
/// names of `state_fields`.
struct BurgersHistory
{
  double overlap = 0;               ///< m, U at the last update (reference of the increment)
  double normal_force = 0;          ///< N, applied normal force of the element
  double normal_kelvin = 0;         ///< m, Kelvin displacement of the normal element
  Vec3 shear_kelvin = Vec3::Zero(); ///< m, Kelvin displacement of the shear element (force sense)

  static constexpr std::array<std::string_view, 6> state_fields = {{"reference_overlap_m", "element_normal_force_n",
                                                                    "normal_kelvin_m", "shear_kelvin_x_m",
                                                                    "shear_kelvin_y_m", "shear_kelvin_z_m"}};
  static_assert(state_fields.size() <= LawState::capacity, "a Burger's history must fit a LawState slot");

  static BurgersHistory load(const LawState &s)
  {
    const auto &v = s.value;
    return {v[0], v[1], v[2], Vec3(v[3], v[4], v[5])};
  }
  static void store(const BurgersHistory &h, LawState &s)
  {
    s.value = {
      {h.overlap, h.normal_force, h.normal_kelvin, h.shear_kelvin.x(), h.shear_kelvin.y(), h.shear_kelvin.z()}};
  }
};

/// Burger's contact in both directions (plain) or with an elastic normal
/// compression (modified, §7.2.2).
template <bool Modified>
class BurgersLawT
{
public:
  static constexpr std::string_view keyword = Modified ? "modified_burgers" : "burgers";
  using History = BurgersHistory;
  static constexpr auto state_fields = History::state_fields;
  static History load(const LawState &s) { return History::load(s); }
  static void store(const History &h, LawState &s) { History::store(h, s); }

  explicit BurgersLawT(const BurgersContactConstants &k) : k_(k) {}
  const BurgersContactConstants &constants() const { return k_; }

  /// The constants a deck sets (Table 7.2 layout, Table 7.2 defaults).
  static std::vector<LawConstant> deck_constants()
  {
    std::vector<LawConstant> c = {
      {"normal maxwell stiffness", 0.5e6, "N/m",
       "Burger's K_0 (K_m) of the normal element (tension only for modified_burgers), a contact property "
       "(Table 7.2: 0.5 MN/m).",
       RateScaled::stiffness},
      {"normal maxwell viscosity", 0.5e6, "N s/m",
       "Burger's C_inf (C_m) of the normal element (tension only for modified_burgers) (Table 7.2: 0.5 MN s/m).",
       RateScaled::viscosity},
      {"normal kelvin stiffness", 0.5e6, "N/m",
       "Burger's K_1 (K_k) of the normal element (tension only for modified_burgers) (Table 7.2: 0.5 MN/m).",
       RateScaled::stiffness},
      {"normal kelvin viscosity", 0.5e6, "N s/m",
       "Burger's C_1 (C_k) of the normal element (tension only for modified_burgers) (Table 7.2: 0.5 MN s/m).",
       RateScaled::viscosity},
      {"shear maxwell stiffness", 0.5e6, "N/m",
       "Burger's K_0 (K_m) of the shear element, a contact property (Table 7.2: 0.5 MN/m).", RateScaled::stiffness},
      {"shear maxwell viscosity", 0.5e6, "N s/m", "Burger's C_inf (C_m) of the shear element (Table 7.2: 0.5 MN s/m).",
       RateScaled::viscosity},
      {"shear kelvin stiffness", 0.5e6, "N/m", "Burger's K_1 (K_k) of the shear element (Table 7.2: 0.5 MN/m).",
       RateScaled::stiffness},
      {"shear kelvin viscosity", 0.5e6, "N s/m", "Burger's C_1 (C_k) of the shear element (Table 7.2: 0.5 MN s/m).",
       RateScaled::viscosity}};
    if (Modified)
      c.push_back({"compression stiffness", 0.5e6, "N/m",
                   "E_0^n of modified_burgers: elastic normal stiffness in compression (Table 7.2: 0.5 MN/m).",
                   RateScaled::stiffness});
    return c;
  }

  /// The law's constants from a deck's values (defaults where absent).
  static BurgersContactConstants constants_from(const LawParameters &p)
  {
    const std::vector<LawConstant> c = deck_constants();
    BurgersContactConstants k;
    k.normal = {p[c[0]], p[c[1]], p[c[2]], p[c[3]]};
    k.shear = {p[c[4]], p[c[5]], p[c[6]], p[c[7]]};
    if (Modified)
      k.compression_stiffness = p[c[8]];
    return k;
  }

  /// Computes the coefficients of eq. 3.27 and 3.35 once per step (the
  /// contact pass calls this before its parallel loop).
  void prepare(double dt)
  {
    if (dt == dt_)
      return;
    dt_ = dt;
    normal_ = BurgersCoefficients(k_.normal, dt);
    shear_ = BurgersCoefficients(k_.shear, dt);
  }

  double normal_force(const ContactParams & /*p*/, double overlap, History &h, double dt) const
  {
    if (Modified && overlap >= 0)
      return k_.compression_stiffness * overlap;
    return normal_step(dt).force(overlap - h.overlap, h.normal_kelvin, h.normal_force);
  }

  Vec3 shear_force(const ContactParams & /*p*/, const Vec3 &rotated_force, const Vec3 &shear_increment, History &h,
                   double dt) const
  {
    return shear_step(dt).force(Vec3(-shear_increment), h.shear_kelvin, rotated_force);
  }

  /// The Kelvin displacement turns with the contact plane like the shear force.
  void rotate_history(History &h, const Vec3 &old_normal, const Vec3 &new_normal, double twist) const
  {
    h.shear_kelvin = rotate_with_contact_plane(h.shear_kelvin, old_normal, new_normal, twist);
  }

  /// Advances the element state with the forces actually applied.
  void commit(History &h, double overlap, double normal_force, const Vec3 &shear_before, const Vec3 &shear,
              double dt) const
  {
    if (Modified && overlap >= 0)
      h.overlap = h.normal_force = h.normal_kelvin = 0;
    else
    {
      h.normal_kelvin = normal_step(dt).kelvin(h.normal_kelvin, h.normal_force, normal_force);
      h.normal_force = normal_force;
      h.overlap = overlap;
    }
    h.shear_kelvin = shear_step(dt).kelvin(h.shear_kelvin, shear_before, shear);
  }

  double stored_energy(const ContactParams & /*p*/, double normal_force, const Vec3 &shear_force,
                       const History &h) const
  {
    double e = burgers_energy(k_.shear, shear_force, h.shear_kelvin);
    if (Modified && normal_force > 0 && h.normal_force == 0)
      e += 0.5 * normal_force * normal_force / k_.compression_stiffness;
    else
      e += burgers_energy(k_.normal, normal_force, h.normal_kelvin);
    return e;
  }

  double normal_stiffness(const ContactParams & /*p*/) const
  {
    return Modified ? std::max(k_.normal.maxwell_stiffness, k_.compression_stiffness) : k_.normal.maxwell_stiffness;
  }
  double shear_stiffness(const ContactParams & /*p*/) const { return k_.shear.maxwell_stiffness; }

private:
  BurgersCoefficients normal_step(double dt) const { return dt == dt_ ? normal_ : BurgersCoefficients(k_.normal, dt); }
  BurgersCoefficients shear_step(double dt) const { return dt == dt_ ? shear_ : BurgersCoefficients(k_.shear, dt); }

  BurgersContactConstants k_;
  double dt_ = -1; ///< s, step of the cached coefficients
  BurgersCoefficients normal_, shear_;
};

using BurgersLaw = BurgersLawT<false>;
using ModifiedBurgersLaw = BurgersLawT<true>;
} // namespace dem
