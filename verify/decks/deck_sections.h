// Deck sections shared by several kinds: the contact law, the motion
// settings and the bonds.  Each section has a declare_* function (schema)
// and a read_* function (deck -> engine settings), side by side, so that a
// key is declared and read in one place.
#pragma once

#include "verify/decks/deck.h"

#include "dem/bonds.h"
#include "dem/contact_model.h"
#include "dem/simulation.h"

#include <nlohmann/json.hpp>

#include <memory>

namespace verify
{
/// subsection "rate": temperature, the physical and the simulated strain
/// rate, and what depends on them (thesis eq. 4.3, 7.21, 7.23).
struct RateScaling
{
  double temperature = 283;     ///< K
  double physical_rate = 0;     ///< 1/s, the test being represented
  double run_rate = 0;          ///< 1/s, the test being run
  double viscosity_factor = 1;  ///< on both viscosities, physical / run (eq. 7.21)
  double strength_factor = 1;   ///< on bond strengths (eq. 7.23 at the physical rate)
  double stiffness_factor = 1;  ///< on contact stiffnesses (eq. 7.23 at the physical rate)

  /// Multiplies every ball's kn and ks by the stiffness factor.
  void scale_ball_stiffness(dem::ParticleStore &p) const;
  /// The "rate" block of summary.json.
  nlohmann::json to_json() const;
};
void declare_rate(DeckSchema &s);
/// The scaling for a run at `run_rate` [1/s] (0 if the run has no strain rate).
RateScaling read_rate(const Deck &d, double run_rate);

/// subsection "contact law": the keyword of a registered law and the
/// constants of the Burger's laws (Table 7.2 layout), scaled by `rate`.
void declare_contact_law(DeckSchema &s);
std::unique_ptr<dem::ContactModel> read_contact_law(const Deck &d, const RateScaling &rate = {});

/// subsection "motion": gravity, damping, time step, neighbour skin.
void declare_motion(DeckSchema &s, const std::string &default_gravity, double default_damping);
dem::SimulationSettings read_motion(const Deck &d);

/// subsection "bonds": how bonds are installed and their strengths.
/// `modes` lists the allowed values of "install" (first is the default).
/// `test` adds the entries that only act during a test (the displacement
/// criterion), not during preparation.
void declare_bonds(DeckSchema &s, const std::vector<std::string> &modes, bool test = true);
dem::BondSettings read_bond_settings(const Deck &d);
/// After bonds are installed: rate-dependent strengths and the
/// displacement criterion (appendix A) measured from the current distances.
void finish_bonds(const Deck &d, dem::ContactTable &table, const dem::ParticleStore &p, const RateScaling &rate);

/// subsection "balls": per-ball contact properties and density.
void declare_ball_properties(DeckSchema &s);
/// Fills density, kn, ks, friction of a ball from the deck.
void apply_ball_properties(const Deck &d, dem::BallSpec &b, const RateScaling &rate = {});

/// Per-wall contact properties (inside the current subsection).
void declare_wall_properties(DeckSchema &s, double kn, double ks, double friction);
dem::WallProps read_wall_properties(const Deck &d, const std::string &section);

/// "x, y, z" deck entry as a vector.
dem::Vec3 read_vec3(const Deck &d, const std::string &key);
} // namespace verify
