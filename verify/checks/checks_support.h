// Helpers shared by the check implementations (checks_*.cpp).
#pragma once

#include "verify/run/analysis.h"

#include "verify/checks/check.h"
#include "verify/decks/deck.h"
#include "verify/kinds/scene.h"
#include "verify/io/series.h"

#include "dem/simulation.h"
#include "dem/small_systems.h"

#include <string>
#include <vector>

namespace verify
{
/// Loads cases/<name>/case.prm with overrides and runs it in memory.
SceneResult run_case(const CheckContext &ctx, const std::string &name,
                     const std::vector<std::string> &overrides = {});
/// Returns r, or throws (failing the check) if the run faulted or wrote nothing.
SceneResult completed(const std::string &name, SceneResult r);
Deck load_case(const CheckContext &ctx, const std::string &name, const std::vector<std::string> &overrides = {});

/// First time at which `values` crosses `level` upwards, linearly
/// interpolated between rows; NaN if it never does.
double first_crossing(const std::vector<double> &time, const std::vector<double> &values, double level);


/// Formats a number for notes.
std::string num(double v);

/// Small systems in a line or three (dem/small_systems.h).
using dem::small_systems::ball;
using dem::small_systems::undamped;
} // namespace verify
