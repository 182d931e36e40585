// burgers_ode decks: one Burger's chain (a contact, or a material point in
// one dimension) under a prescribed displacement or force history,
// integrated with SUNDIALS CVODE (continuum/burgers_ode.h), written beside
// its closed form (continuum_reference.h).
//
// Outputs: series.csv (time, displacement or strain, force or stress, the
// closed form of the computed quantity, Kelvin and dashpot displacements;
// units in the column names), summary.json (constants, history, solver
// statistics, largest error against the closed form, provenance), deck.prm.
#pragma once

#include "app/decks/deck.h"
#include "app/io/series.h"
#include "app/run/run.h"

#include "continuum/burgers_chain.h"
#include "continuum/burgers_ode.h"

#include <nlohmann/json.hpp>

namespace demvv
{
void declare_burgers_ode(DeckSchema &s);

struct OdeResult
{
  Series series;
  nlohmann::json summary;
  RunStatus status;
  /// max_t |x - x_closed| / max_t |x_closed| for the computed quantity x
  /// (force under displacement control, displacement under force); NaN
  /// without a closed form.
  double relative_error = 0;
};

/// A burgers_ode deck, parsed and validated.
struct BurgersOdeSpec
{
  DeckRecord deck;
  std::string title;
  continuum::BurgersChain chain;
  bool contact = true; ///< a contact (N, m) or a material point (Pa, strain)
  continuum::Control control = continuum::Control::displacement;
  std::string control_name, history_name;
  continuum::History history;
  double duration = 0, interval = 0; ///< s
  continuum::OdeTolerances tolerances;
};

BurgersOdeSpec parse_burgers_ode(const Deck &deck);
OdeResult run_burgers_ode(const BurgersOdeSpec &spec, const RunOptions &options);
/// parse_burgers_ode then run_burgers_ode.
OdeResult run_burgers_ode(const Deck &deck, const RunOptions &options);
} // namespace demvv
