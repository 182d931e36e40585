// Deck sections shared by several kinds: the contact law, the rate, the
// motion settings, the bonds, ball and wall properties.  Each section has a
// declare function (schema) and a parse function (deck -> typed spec or
// engine settings), side by side, so that a key is declared and read in one
// place, once, and validated there with the one-line errors of deck.h.
// What needs the run's own numbers (the loading rate of a sample) is
// applied later from the spec, and still names the deck and key on error.
#pragma once

#include "app/decks/deck.h"

#include "dem/bonds.h"
#include "dem/contact_model.h"
#include "dem/simulation.h"

#include <nlohmann/json.hpp>

#include <memory>
#include <string>

namespace demvv
{
/// subsection "rate": temperature, the physical and the simulated strain
/// rate, and what depends on them (thesis eq. 4.3, 7.21, 7.23).
struct RateScaling
{
  double temperature = 283;    ///< K
  double physical_rate = 0;    ///< 1/s, the test being represented
  double compensated_rate = 0; ///< 1/s, rate_T of eq. 4.3 at the physical rate and temperature
  double run_rate = 0;         ///< 1/s, the test being run
  double viscosity_factor = 1; ///< on both viscosities, rate_T / run (eq. 7.21 at the compensated rate, §7.5.3)
  double strength_factor = 1;  ///< on bond strengths (eq. 7.23 at the physical rate)
  double stiffness_factor = 1; ///< on contact stiffnesses (eq. 7.23 at the physical rate)

  /// Multiplies every ball's kn and ks by the stiffness factor.
  void scale_ball_stiffness(dem::ParticleStore &p) const;
  /// The "rate" block of summary.json.
  nlohmann::json to_json() const;
};
void declare_rate(DeckSchema &s);

/// The rate section as written.
struct RateSpec
{
  std::string deck;         ///< the deck file, for errors found later
  double temperature = 283; ///< K
  double physical_rate = 0; ///< 1/s, 0: the run's own rate
  double run_rate = 0;      ///< 1/s, for kinds without a loading rate of their own
  std::string dependence = "none";

  static RateSpec parse(const Deck &d);
  /// The scaling for a run at `run_rate` [1/s] (0: the deck's run strain
  /// rate); DeckError naming the key when the deck lacks a rate it needs.
  RateScaling scaling(double run_rate) const;
};

/// subsection "contact law": the keyword of a registered law and every
/// law's deck constants (dem::LawEntry::deck_constants), each key once.
void declare_contact_law(DeckSchema &s);

struct LawSpec
{
  std::string keyword = "linear";
  dem::LawParameters constants; ///< every law's deck constants by key, unscaled, as written

  static LawSpec parse(const Deck &d);
  /// The law with its stiffnesses and viscosities scaled by `rate`.
  std::unique_ptr<dem::ContactModel> make(const RateScaling &rate) const;
  /// The constants with their stiffnesses and viscosities scaled by `rate`.
  dem::LawParameters scaled_constants(const RateScaling &rate) const;
};

/// subsection "motion": gravity, damping, time step, neighbour skin.
void declare_motion(DeckSchema &s, const std::string &default_gravity, double default_damping);
dem::SimulationSettings parse_motion(const Deck &d);

/// subsection "bonds": how bonds are installed and their strengths.
/// `modes` lists the allowed values of "install" (first is the default).
/// `test` adds the entries that only act during a test (the displacement
/// criterion), not during preparation.
void declare_bonds(DeckSchema &s, const std::vector<std::string> &modes, bool test = true);
dem::BondSettings parse_bond_settings(const Deck &d);

struct BondSpec
{
  std::string install;   ///< one of the modes the kind declared
  std::string list_file; ///< for install = list, resolved against the deck
  dem::BondSettings settings;
  double break_displacement = 0; ///< m, 0: off (appendix A)

  static BondSpec parse(const Deck &d, bool test = true);
  /// After bonds are installed: rate-dependent strengths and the
  /// displacement criterion (appendix A) measured from the current distances.
  void finish(dem::ContactTable &table, const dem::ParticleStore &p, const RateScaling &rate) const;
};

/// subsection "balls": per-ball contact properties and density.
void declare_ball_properties(DeckSchema &s);
/// Density, kn, ks and friction of every ball, as written.
dem::BallSpec parse_ball_properties(const Deck &d);
/// The same with kn and ks scaled by the rate's stiffness factor.
dem::BallSpec scaled(dem::BallSpec ball, const RateScaling &rate);

/// Per-wall contact properties (inside the current subsection).
void declare_wall_properties(DeckSchema &s, double kn, double ks, double friction);
/// Refuses a friction with zero shear stiffness: the wall could carry no
/// shear force, so its friction would do nothing.
dem::WallProps parse_wall_properties(const Deck &d, const std::string &section);

/// "x, y, z" deck entry as a vector; `nonzero` refuses the zero vector.
dem::Vec3 parse_vec3(const Deck &d, const std::string &key, bool nonzero = false);
} // namespace demvv
