// Helpers shared by the check implementations (checks_*.cpp).
#pragma once

#include "verify/checks/check.h"
#include "verify/decks/deck.h"
#include "verify/kinds/scene.h"
#include "verify/io/series.h"

#include "dem/simulation.h"

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

/// Largest absolute value of a vector (NaN if empty).
double max_abs(const std::vector<double> &v);

/// Formats a number for notes.
std::string num(double v);

/// Small systems in a line or three (STYLE rule 8), for checks and tests.
dem::BallSpec ball(const dem::Vec3 &x, double r, double kn, double ks = 0, double mu = 0);
/// Settings for closed-form checks: no damping, no gravity; fixed_dt > 0 fixes the step.
dem::SimulationSettings undamped(double fixed_dt = 0, bool allow_unstable = false);
dem::Simulation linear_simulation(dem::ParticleStore p, dem::SimulationSettings s, dem::WallSet w = {});
} // namespace verify
