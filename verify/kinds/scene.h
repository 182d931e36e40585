// Scene decks: explicit particles, walls, bonds and prescribed motions.
//
// The small systems of the verification catalogue (two balls, a ball on a
// wall, a bonded chain, a block on an incline) are scenes.  A scene deck
// names a particle CSV (x_m,y_m,z_m,radius_m and optional columns
// vx_mps,vy_mps,vz_mps, wx_radps,wy_radps,wz_radps, hold_velocity,
// hold_spin, density_kgpm3, kn_npm, ks_npm, friction), up to four planes and
// a cylinder, bonds, and what to track.  Running it records, at every output
// time:
//   series.csv     time, step, energies, contact and bond counts, wall forces
//   particles.csv  tracked balls: position, velocity, spin, resultant force
//   contacts.csv   tracked pairs: overlap, normal and shear force, bond state
//   bond_breaks.csv every bond break (time, pair, mode)
// plus summary.json and deck.prm.
#pragma once

#include "verify/decks/deck.h"
#include "verify/run/run.h"
#include "verify/io/series.h"

#include "dem/bonds.h"
#include "dem/simulation.h"

#include <memory>

namespace verify
{
void declare_scene(DeckSchema &s);

struct SceneResult
{
  std::unique_ptr<dem::Simulation> sim; ///< state at the end
  Series series;                        ///< series.csv
  Series particles;                     ///< particles.csv (tracked balls)
  Series contacts;                      ///< contacts.csv (tracked pairs)
  dem::BondReport bonds;
  RunStatus status;
};

/// Builds and runs a scene deck.  With options.out_dir empty nothing is
/// written (checks use this); otherwise the run directory is filled.
SceneResult run_scene(const Deck &deck, const RunOptions &options);
} // namespace verify
