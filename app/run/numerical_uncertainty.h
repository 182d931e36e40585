// The numerical (time-step) uncertainty of a bulk result, as the time-step
// studies measured it (demvv time-step: seed ensembles at safeties 0.8,
// 0.4 and 0.2 with common random numbers, app/studies/time_step_study.h).
//
// The studies' results are kept in cases/s02_time_step_study/results_N.json
// (N balls), each written by the command its README gives, with its build
// and date.  A bulk (uniaxial) run states in summary.json, under
// "uncertainty"/"numerical_time_step", the 95 % bound U_num on the
// time-step error of its peak stress, strain at peak and initial modulus
// (relative, and u_num = U_num / 2 as a standard uncertainty) from the
// study that applies to it, and where that came from:
//   - the study whose sample is nearest in ball count, within a factor of
//     two (a 54-ball lattice has none);
//   - at the run's step: the bound of the finest studied level whose step
//     is at or above the run's (the error grows with the step: a finer step
//     than a studied level is covered by that level's bound); a step coarser
//     than every studied level is not covered.  Steps are compared as
//     fractions of the undamped critical bound: a safety s under local
//     damping alpha is s / sqrt(1 + alpha) of it (dem/stability.h).
//     Studies recorded before local damping entered the bound (no
//     "safety_bound": "damped" in their results) took their safeties of the
//     undamped bound, so their levels are those fractions as they stand.
// Otherwise the block says "not estimated" and why.  The studies ran on one
// recipe (thesis §6.2 damage test at 0.01 m/s, friction 0.5,
// cases/t66_friction); for other recipes (another law, rate or strength)
// the bound is an estimate carried over, said so in the block.
#pragma once

#include <nlohmann/json.hpp>

#include <string>

namespace demvv
{
/// The folder of the recorded studies (cases/s02_time_step_study in the source tree).
std::string time_step_study_dir();

/// The "numerical_time_step" block for a bulk run of `balls` balls at time-step
/// safety `safety` under local damping `local_damping`, read from the
/// studies in `study_dir`.
nlohmann::json numerical_time_step_uncertainty(double balls, double safety, double local_damping,
                                               const std::string &study_dir = time_step_study_dir());
} // namespace demvv
