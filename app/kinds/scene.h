// Scene decks: explicit particles, walls, bonds and prescribed motions.
//
// The small systems of the verification catalogue (two balls, a ball on a
// wall, a bonded chain, a block on an incline, a box of six planes) are
// scenes.  A scene deck names a particle CSV (x_m,y_m,z_m,radius_m and
// optional columns vx_mps,vy_mps,vz_mps, wx_radps,wy_radps,wz_radps,
// hold_velocity, hold_spin, density_kgpm3, kn_npm, ks_npm, friction), any
// number of planes and cylinders (`subsection plane NAME`, `subsection
// cylinder NAME` inside `walls`), bonds, and what to track.  Running it
// records, at every output time:
//   series.csv     time, step, energies, contact and bond counts, the force
//                  of the balls on every wall
//   particles.csv  tracked balls: position, velocity, spin, resultant force
//   contacts.csv   tracked pairs: overlap, normal and shear force, bond state
//   bond_breaks.csv every bond break (time, pair, mode, the point on the
//                   pair's line of centres)
// plus summary.json (with how many steps resolve the shortest contact
// period: the automatic step is a stability bound, not an accuracy choice)
// and deck.prm.
#pragma once

#include "app/decks/deck.h"
#include "app/decks/deck_sections.h"
#include "app/io/series.h"
#include "app/run/dem_driver.h"
#include "app/run/run.h"

#include "dem/bonds.h"
#include "dem/simulation.h"

#include <memory>

namespace demvv
{
void declare_scene(DeckSchema &s);

/// A bonded pair of a bond list file.
struct ListedBond
{
  dem::Index first = 0, second = 0;
  double normal_strength = 0, shear_strength = 0; ///< N
};

/// A scene deck, parsed and validated.
struct SceneSpec
{
  DeckRecord deck;
  std::string title;
  dem::ParticleStore particles; ///< as written (stiffnesses not yet rate-scaled)
  dem::WallSet walls;
  LawSpec law;
  RateScaling rate; ///< scenes have no loading rate: known at parse time
  dem::SimulationSettings motion;
  BondSpec bonds;
  std::vector<ListedBond> bond_list; ///< install = list
  double duration = 0;               ///< s
  DemOutputSpec output;              ///< clock: simulated time [s]
  /// Balls, bonds and tracked balls are numbered along a Morton curve
  /// (dem/spatial_order.h); file_row[k] is ball k's row in the particle
  /// file, the number every output and message gives it.
  std::vector<dem::Index> file_row;
  std::vector<dem::Index> tracked;      ///< in the deck's order
  std::vector<dem::Pair> tracked_pairs; ///< (first, second) by the run's numbering
};

SceneSpec parse_scene(const Deck &deck);

struct SceneResult
{
  std::unique_ptr<dem::Simulation> sim; ///< state at the end
  Series series;                        ///< series.csv
  Series particles;                     ///< particles.csv (tracked balls)
  Series contacts;                      ///< contacts.csv (tracked pairs)
  dem::BondReport bonds;
  RunStatus status;
};

/// Builds and runs a scene.  With options.out_dir empty nothing is written
/// (checks use this); otherwise the run directory is filled.
SceneResult run_scene(const SceneSpec &spec, const RunOptions &options);
/// parse_scene then run_scene.
SceneResult run_scene(const Deck &deck, const RunOptions &options);
} // namespace demvv
