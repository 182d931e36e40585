// mms decks: a manufactured-solution convergence study of the viscoelastic
// cylinder (continuum/mms.h, check V21), in space (mesh levels) or in
// time (step halvings).
//
// Outputs: convergence.csv (level, mesh, step, relative errors of the
// displacement in L2 and H1, of the stress and the Kelvin strain, with the
// observed order against the previous level), convergence.txt (the same
// as deal.II's ConvergenceTable prints it), summary.json (the observed
// orders on the finest levels and the expected ones, provenance), deck.prm.
#pragma once

#include "app/decks/deck.h"
#include "app/reference/convergence.h"
#include "app/run/run.h"

#include "continuum/mms.h"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace demvv
{
void declare_mms(DeckSchema &s);

/// An mms deck, parsed and validated.
struct MmsDeckSpec
{
  DeckRecord deck;
  std::string title;
  continuum::MmsSpec study; ///< geometry, the material's solid, levels, duration, steps, solver
  nlohmann::json material;  ///< the material's route, inputs and moduli (summary.json)
};

/// Reads and validates every key of an mms deck (geometry, material, study).
MmsDeckSpec parse_mms(const Deck &deck);

struct MmsResult
{
  std::vector<continuum::MmsLevel> levels;
  nlohmann::json summary;
  RunStatus status;
};

MmsResult run_mms_deck(const MmsDeckSpec &spec, const RunOptions &options);
/// parse_mms then run_mms_deck.
MmsResult run_mms_deck(const Deck &deck, const RunOptions &options);

/// One convergence table per error (displacement L2 and H1, stress, Kelvin
/// strain) against h or dt, with the expected orders (space: p + 1, p, p,
/// p; time: 2 for the stress and Kelvin strain, 0 for the displacement,
/// which is exact there up to the solver tolerance).
std::vector<ConvergenceTable> mms_tables(const std::vector<continuum::MmsLevel> &levels,
                                         const continuum::MmsSpec &spec);
} // namespace demvv
