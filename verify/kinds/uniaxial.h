// Uniaxial decks: constant-strain-rate compression of a bonded cylinder
// between frictionless platens (thesis §6.1-6.3, SPEC §5).
//
// Until sample preparation lands (thesis ch. 5) the sample is a regular
// lattice cylinder (simple cubic or FCC), a legitimate verification sample
// with closed-form porosity and coordination; every output says so.
//
// Outputs: series.csv (time, axial strain, nominal stress top/bottom/mean,
// radial strain, bond breakage, coordination, porosity, unbalanced force,
// inertial number, energies), summary.json (peak stress, strain at peak,
// strain at the maximum breakage rate, initial modulus and Poisson's ratio
// fitted over the stated strain window, counts, timings, provenance),
// bond_breaks.csv, deck.prm and optional ParaView frames.
#pragma once

#include "verify/decks/deck.h"
#include "verify/run/run.h"
#include "verify/io/series.h"

#include "dem/bonds.h"
#include "dem/simulation.h"

#include <nlohmann/json.hpp>

#include <memory>

namespace verify
{
void declare_uniaxial(DeckSchema &s);

struct UniaxialResult
{
  std::unique_ptr<dem::Simulation> sim;
  Series series;
  nlohmann::json summary;
  RunStatus status;
};

UniaxialResult run_uniaxial(const Deck &deck, const RunOptions &options);
} // namespace verify
