// mms decks: a manufactured-solution convergence study of the viscoelastic
// cylinder (continuum/mms.h, VERIFICATION 21), in space (mesh levels) or in
// time (step halvings).
//
// Outputs: convergence.csv (level, mesh, step, relative errors of the
// displacement in L2 and H1, of the stress and the Kelvin strain, with the
// observed order against the previous level), convergence.txt (the same
// as deal.II's ConvergenceTable prints it), summary.json (the observed
// orders on the finest levels and the expected ones, provenance), deck.prm.
#pragma once

#include "verify/checks/check.h"
#include "verify/decks/deck.h"
#include "verify/run/run.h"

#include "continuum/mms.h"

#include <nlohmann/json.hpp>

#include <vector>

namespace verify
{
void declare_mms(DeckSchema &s);

/// The study a deck describes.
continuum::MmsSpec read_mms_spec(const Deck &deck);

struct MmsResult
{
  std::vector<continuum::MmsLevel> levels;
  nlohmann::json summary;
  RunStatus status;
};

/// Validates an mms deck without running it (read_mms_spec).
inline continuum::MmsSpec parse_mms(const Deck &deck) { return read_mms_spec(deck); }

MmsResult run_mms_deck(const Deck &deck, const RunOptions &options);

/// One convergence table per error (displacement L2 and H1, stress, Kelvin
/// strain) against h or dt, with the expected orders (space: p + 1, p, p,
/// p; time: 2 for the stress and Kelvin strain, 0 for the displacement,
/// which is exact there up to the solver tolerance).
std::vector<ConvergenceTable> mms_tables(const std::vector<continuum::MmsLevel> &levels,
                                         const continuum::MmsSpec &spec);
} // namespace verify
