// demvv calibrate: deck parameters fitted to target quantities of DEM runs
// at one condition, by GSL's nonlinear least squares.
//
//   demvv calibrate BASE_DECK --fit KEY[+KEY...]=START [--fit ...]
//                   --target QUANTITY=VALUE[,UNCERTAINTY] [--target ...]
//                   [--at KEY=VALUE ...] [--seeds N] [--first-seed K]
//                   [--step H] [--tolerance T] [--max-iterations M]
//                   --out DIR [--replace] [--threads N] [--quiet]
//
// A fitted parameter sets one or more deck entries to one value (`+` joins
// entries that move together, e.g. the normal and the shear bond
// strength); it must be positive: the fit works on x = ln(value), so steps
// are relative and the value stays positive.  A target is a quantity of a
// uniaxial run's summary (peak_stress_pa, strain_at_peak,
// initial_modulus_pa, poisson_ratio) with its value and, optionally, the
// standard uncertainty of that value (the experiment's scatter).  `--at`
// sets the calibration condition (as --set would) for every evaluation:
// demvv calibrates at one condition, so that every other condition is left
// for validation.
//
// Each evaluation of the model at x is the mean over N seeds (the sweep's
// seeds, first-seed ... first-seed + N - 1: each its own packing and bond
// draws) of the target quantities.  Residuals are relative,
// r_i = (mean_i - target_i) / |target_i|.  The Jacobian is a forward
// difference in ln(value) with step H (default 0.05), evaluated with the
// same seeds as the centre (common random numbers: the seed-to-seed scatter
// cancels in the difference as far as the runs stay alike), and run in the
// same sweep as the centre so that the N (p + 1) members share out among MPI
// ranks; the slope's own noise (its standard error over seeds) is recorded,
// and a step whose slope is not resolved above twice that noise is doubled
// for the next Jacobian (up to 0.4).  gsl_multifit_nlinear (trust region,
// Levenberg-Marquardt) takes the steps.
//
// The fit stops when every target is met within its seed-ensemble standard
// error of the mean or within the tolerance T (relative, default 0.005),
// or when the step in every ln(value) is below 1e-4 (converged), or after M
// iterations (not converged: exit code 3).  The parameters' covariance is
// (A^T S^-1 A)^-1, A the Jacobian of the target means in ln(value), S the
// diagonal of the seed-ensemble variance of each mean plus the target's own
// uncertainty squared; standard errors are given with the seed ensemble
// alone and with both, with the correlation matrix.
//
// DIR/evaluations/NNN/ is the sweep of evaluation NNN (its members are
// ordinary run directories); DIR/evaluations.csv has one row per point
// evaluated (the history); DIR/calibration.json the targets, the fitted
// values, their standard errors and correlation, the residuals, the status
// and the provenance; DIR/fitted.prm the base deck with the fitted values,
// the condition set and calibration/record naming DIR/calibration.json (its
// runs state the fit's input uncertainty: app/run/input_uncertainty.h).  Everything is rewritten atomically after every
// evaluation (fitted.prm once converged).  Rerunning the same command resumes: evaluations already in
// DIR are read back (the fit's path is the same), the rest run; a
// calibration another build of demvv began is refused (--replace starts it
// over).  A member
// that faults or is refused stops the fit with exit code 3 (numerical) or 2
// (its deck), everything up to there kept.
#pragma once

#include "app/studies/sweep.h"

#include <string>
#include <vector>

namespace demvv
{
struct CalibrationOptions
{
  std::string base_deck;
  std::vector<std::string> fit;     ///< "KEY[+KEY...]=START"
  std::vector<std::string> targets; ///< "QUANTITY=VALUE[,UNCERTAINTY]"
  std::vector<std::string> at;      ///< "KEY=VALUE", the calibration condition
  int seeds = 3;
  int first_seed = 1;
  double step = 0.05;       ///< finite-difference step in ln(value)
  double tolerance = 0.005; ///< relative residual that counts as met
  int max_iterations = 10;
  SweepSettings settings;
};

/// Runs (or resumes) a calibration; returns 0 (converged), 3 (not
/// converged, or an evaluation faulted), or 128 + signal when interrupted.
/// Bad input is a DeckError before anything runs.
int command_calibrate(const CalibrationOptions &options);
} // namespace demvv
