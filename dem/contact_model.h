// ContactModel: the ball-ball contact law of a simulation, chosen by keyword
// from the registry (law_registry.cpp).
//
// The virtual call happens once per step; inside, LawModel<Law> runs the
// whole contact pass with the law inlined.  The pass is parallel over
// contacts and each contact writes only its own entries, so results do not
// depend on the thread count.
//
// A model holds the law's parameters and per-step constants only.  Every
// contact's history, the law's own included (LawState), lives in the
// ContactTable, so it follows the entries through rebuilds and goes into
// snapshots and sample files with them.  A law with no state fields (the
// linear law) never touches the LawState array.
//
// Ball-wall contacts always use the linear law with the wall's own
// properties (walls.h): walls are steel platens, and the viscoelastic laws
// describe the bitumen between grains.
#pragma once

#include "dem/contact_resolve.h"
#include "dem/contacts.h"
#include "dem/law_burgers.h"
#include "dem/law_linear.h"
#include "dem/stability.h"

#include <memory>
#include <string_view>
#include <vector>

namespace dem
{
/// Stability row terms of a ball-ball contact (stability.h) whose arms are
/// at most fi R_i and fj R_j.
DEM_HOT_INLINE StabilityTerms contact_stability_terms(const ParticleStore &p, Index i, Index j, double kn,
                                                     double ks, double fi, double fj)
{
  const double sbi = fi * p.sqrt_shear_mobility[i], sbj = fj * p.sqrt_shear_mobility[j];
  const double sqrt_ww = p.sqrt_inv_mass[i] * p.sqrt_inv_mass[j], sqrt_bb = sbi * sbj;
  return {stability_row_term(kn, ks, p.inv_mass[i], sbi * sbi, sqrt_ww, sqrt_bb),
          stability_row_term(kn, ks, p.inv_mass[j], sbj * sbj, sqrt_ww, sqrt_bb)};
}

class ContactModel
{
public:
  virtual ~ContactModel() = default;
  virtual std::string_view name() const = 0;

  /// Resolves every entry of the table at the current positions; dt is the
  /// step that produced the displacement since the last call.  Writes
  /// table.loads() and returns how many bonds broke.
  virtual std::size_t resolve_pairs(const ParticleStore &particles, ContactTable &table,
                                    double dt) = 0;

  /// Elastic energy stored in all ball-ball contacts [J].
  virtual double stored_energy(const ContactTable &table) const = 0;

  /// Tangent normal and shear stiffness of a contact [N/m] (kn, ks of the
  /// result; friction unused), as the stability bound sees them.
  virtual ContactParams tangent_stiffness(const Contact &c) const = 0;

  /// Recomputes every contact's compressive stability terms (after the
  /// table or the balls' masses changed).
  void update_stability_terms(const ParticleStore &p, ContactTable &table) const
  {
    for (Contact &c : table.entries())
    {
      const ContactParams k = tangent_stiffness(c);
      c.stability = contact_stability_terms(p, c.first, c.second, k.kn, k.ks, 1.0, 1.0);
    }
  }
};

/// Geometry of the ball-ball contact (i, j) at the current positions.
DEM_HOT_INLINE ContactGeometry sphere_sphere(const ParticleStore &p, Index i, Index j)
{
  ContactGeometry g;
  const Vec3 d = p.position[j] - p.position[i];
  const double dist = d.norm();
  g.normal = dist > 0 ? Vec3(d * (1.0 / dist)) : Vec3::UnitX();
  g.overlap = p.radius[i] + p.radius[j] - dist;
  g.arm_first = p.radius[i] - 0.5 * g.overlap;
  g.arm_second = p.radius[j] - 0.5 * g.overlap;
  g.velocity_difference = p.velocity[j] - p.velocity[i];
  g.spin_first = p.spin[i];
  g.spin_second = p.spin[j];
  return g;
}

template <class Law>
class LawModel final : public ContactModel
{
public:
  explicit LawModel(Law law) : law_(std::move(law)) {}

  std::string_view name() const override { return Law::keyword; }
  const Law &law() const { return law_; }

  std::size_t resolve_pairs(const ParticleStore &p, ContactTable &table, double dt) override
  {
    std::vector<Contact> &contacts = table.entries();
    std::vector<ContactLoad> &loads = table.loads();
    LawState *const states = table.law_states().data();
    BreakForces *const trial = table.break_forces().data();
    law_.prepare(dt);
    const auto n = static_cast<std::ptrdiff_t>(contacts.size());
    std::size_t breaks = 0;
#pragma omp parallel for schedule(static) reduction(+ : breaks)
    for (std::ptrdiff_t c = 0; c < n; ++c)
    {
      Contact &k = contacts[c];
      ContactLoad &load = loads[c];
      const Index i = k.first, j = k.second;
      if (!k.bond.intact && !k.state.touching)
      {
        // Fast exit for candidates that are not touching.
        const double reach = p.radius[i] + p.radius[j];
        if ((p.position[j] - p.position[i]).squaredNorm() >= reach * reach)
        {
          load = ContactLoad{};
          continue;
        }
      }
      const ContactGeometry g = sphere_sphere(p, i, j);
      typename Law::History history = Law::load(states[c]);
      const ResolvedContact r = resolve_contact(law_, k.params, k.bond, k.state, history, g, dt);
      if constexpr (stateful)
        Law::store(history, states[c]);
      if (r.broke != BreakMode::none)
      {
        ++breaks;
        trial[c] = r.trial;
      }
      if (!r.touching)
      {
        load = ContactLoad{};
        load.broke = r.broke;
        continue;
      }
      load.broke = r.broke;
      load.force = r.force;
      load.lever = cross(g.normal, k.state.shear_force);
      load.arm_first = g.arm_first;
      load.arm_second = g.arm_second;
      // In compression the arms are at most the radii and the precomputed
      // terms hold; a bonded pair in tension has longer arms.
      StabilityTerms bound = k.stability;
      if (g.overlap < 0)
        bound = contact_stability_terms(p, i, j, law_.normal_stiffness(k.params), law_.shear_stiffness(k.params),
                                        arm_factor(g.arm_first, p.inv_radius[i]),
                                        arm_factor(g.arm_second, p.inv_radius[j]));
      load.bound_first = bound.first;
      load.bound_second = bound.second;
    }
    return breaks;
  }

  double stored_energy(const ContactTable &table) const override
  {
    double e = 0;
    for (std::size_t c = 0; c < table.size(); ++c)
    {
      const ContactState &s = table[c].state;
      if (s.touching)
        e += law_.stored_energy(table[c].params, s.normal_force, s.shear_force, Law::load(table.law_states()[c]));
    }
    return e;
  }

  ContactParams tangent_stiffness(const Contact &c) const override
  {
    return {law_.normal_stiffness(c.params), law_.shear_stiffness(c.params), 0};
  }

private:
  static constexpr bool stateful = !Law::state_fields.empty();
  static_assert(Law::state_fields.size() <= LawState::capacity, "a law's history must fit a LawState slot");

  Law law_;
};

/// The registry: one row per law keyword (law_registry.cpp).
struct LawEntry
{
  std::string_view keyword;
  std::unique_ptr<ContactModel> (*make)(const LawParameters &);
  std::string_view summary;
  std::vector<std::string_view> state_fields; ///< names (with units) of the law's LawState values, in order
  std::vector<LawConstant> deck_constants;    ///< what a deck sets for this law
};

const std::vector<LawEntry> &law_registry();
/// The registry row of a keyword, or nullptr if the keyword is unknown.
const LawEntry *find_law(std::string_view keyword);
/// The model for a keyword, or nullptr if the keyword is unknown.
std::unique_ptr<ContactModel> make_contact_model(std::string_view keyword, const LawParameters &p);
} // namespace dem
