// The tables of deck kinds: one whole row per kind (keyword, one-line
// summary, schema, the parse that gives the run, figures, whether it runs
// on every MPI rank, whether it pauses).  `demvv run`, `demvv defaults`, `demvv plot` and
// `--help` read deck_kinds(); the deck reader is handed a table and knows
// no other.  dem_deck_kinds() is its DEM part (scene, prepare, uniaxial),
// the rows the fuzz targets read decks and run directories with: the same
// rows, not a copy.
#pragma once

#include "app/decks/deck.h"
#include "app/run/run.h"

#include <memory>
#include <utility>

namespace demvv
{
/// A kind's run on its parsed spec (DeckKind::parse): the spec is kept,
/// shared, in the closure through which `run(spec, options)` is called
/// (a callable, as each run_<kind> is overloaded on a spec and a deck).
template <class Spec, class Run>
ParsedRun parsed_run(Spec spec, Run run)
{
  auto kept = std::make_shared<const Spec>(std::move(spec));
  return [kept, run](const RunOptions &options) { return run(*kept, options).status; };
}

/// The DEM kinds (app/kinds/dem_kinds.cpp).
const DeckKinds &dem_deck_kinds();

/// Every kind: the DEM kinds, then the continuum and micro-macro kinds
/// (app/kinds/deck_kinds.cpp).
const DeckKinds &deck_kinds();
} // namespace demvv
