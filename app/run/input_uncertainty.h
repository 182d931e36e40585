// The input uncertainty u_input of a bulk result whose deck was fitted by
// demvv calibrate (app/studies/calibrate.h), as ASME V&V 20 budgets it: the
// fitted parameters' standard errors carried through the model's own
// sensitivity to them.
//
// The calibration's record (calibration.json) gives, for each fitted
// parameter j, its relative standard error r_j (the seeds' scatter and the
// target's own uncertainty: the fit's covariance, calibrate.h) and the
// correlation rho_jk between parameters; and, for each target quantity q,
// its fitted mean and the slope d q / d ln(parameter_j) measured by the fit's
// last Jacobian.  With g_j = (d q / d ln parameter_j) / q the elasticity,
//
//   u_input(q) / |q| = sqrt( sum_jk g_j g_k rho_jk r_j r_k ).
//
// Only the calibration's targets have a measured sensitivity: another
// quantity (the strain at peak of a peak-stress calibration) is "not
// estimated", said so.  The elasticity is measured at the calibration
// condition and carried to every other condition of the same deck (the
// held-out conditions of a validation): an estimate, said so in the block.
//
// A uniaxial deck names the record in `calibration/record` (calibrate's
// fitted.prm sets it).  The run then checks that the deck still holds the
// fitted values: a deck whose fitted entries were changed (set, varied by a
// sweep) is no longer the calibrated deck, and is refused with the one-line
// error naming the key, its value and the fitted one.
#pragma once

#include <nlohmann/json.hpp>

#include <limits>
#include <string>

namespace demvv
{
class Deck;

/// The deck entry that names the calibration record.
inline constexpr const char *calibration_record_key = "calibration/record";

/// The quantities of a bulk run whose u_input a block states.
inline const char *const calibrated_quantities[] = {"peak_stress_pa", "strain_at_peak", "initial_modulus_pa",
                                                    "poisson_ratio"};

/// u_input(q) / |q| of the target `quantity` of `calibration` (a
/// calibration.json), or NaN with `why` set when the record does not give it.
double calibrated_input_uncertainty(const nlohmann::json &calibration, const std::string &quantity,
                                    std::string *why = nullptr);

/// The "input_calibration" block of a run of `deck`: "estimated": false
/// with why when calibration/record is empty or not declared; else the
/// record's parameters and, per quantity, u_input_relative (null with why
/// where not estimated).  A record that cannot be read, is not a converged
/// calibration, or whose fitted values the deck no longer holds, is the
/// deck's one-line error (DeckError).
nlohmann::json input_uncertainty_block(const Deck &deck);
} // namespace demvv
