// demvv time-step: the time-step error of a bulk result, measured on seed
// ensembles so that a systematic change can be told apart from the scatter
// of a bond-break cascade.
//
//   demvv time-step BASE_DECK [--safety 0.8,0.4,0.2] [--seeds 5] [--set SECTION/KEY=VALUE]...
//                   --out DIR [--replace] [--threads N] [--quiet]
//
// The base deck (a uniaxial deck) is run at every time-step safety (the
// fraction of the critical step bound, motion/time step safety) with seeds
// 1..N at each level: a sweep (demvv sweep; rerun to resume, under mpirun
// the ranks share the members) whose varied keys are the safety, then the
// --set entries.  The same seed at every level draws the same packing and
// the same bond strengths (common random numbers), so the change between
// two levels is measured seed by seed, and its scatter is that of a
// difference, not of two independent ensembles.
//
// For each bulk quantity (peak stress, strain at peak, initial modulus),
// with levels s_1 > s_2 > ... > s_L (coarse to fine) and q_ij the value at
// level i of seed j:
//   - per level: mean, standard deviation, standard error, 95 % Student-t
//     half-width over the seeds;
//   - change between successive levels, paired: d_j = q_(i+1)j - q_ij, its
//     mean and 95 % half-width (t with n - 1 degrees of freedom).  It is
//     "resolved" when the interval excludes zero, else "not resolved" and
//     only its bound |mean| + half-width is quoted;
//   - observed order p = ln(d_12 / d_23) / ln r from three levels in a
//     constant ratio r = s_i / s_(i+1), only when both changes are resolved
//     and of one sign; its 95 % interval by the delta method over the
//     paired differences (their covariance included);
//   - extrapolated value q_L + d_(L-1,L) / (r^p - 1) where the finest order
//     is resolved (p > 0);
//   - U_num(s_i), a 95 % bound on the time-step error of a result at level
//     i: the paired bound on |q_L - q_i| (|mean| + half-width; zero at the
//     finest level) plus the finest level's own error, 1.25 |d_(L-1,L)| /
//     (r^p - 1) (Roache's factor of safety for three levels) when the order
//     is resolved, else the bound on |d_(L-1,L)| / (r - 1), which holds for
//     any order p >= 1 (the explicit step is first order at worst at
//     contact and break events).  As a standard uncertainty for an ASME
//     V&V 20 budget, u_num = U_num / 2.
//
// DIR/time_step_study.csv (a row per quantity and level) and
// DIR/time_step_study.json (the same, the verdicts, the sweep's provenance
// and the wall time) are written atomically; DIR/plots/time_step_*.svg
// draws each quantity's ensemble against the safety.  Bad input is refused
// before any member runs: fewer than 2 seeds, fewer than 3 levels, a
// safety outside (0, 1], a deck whose runs write no bulk quantity.
#pragma once

#include "app/studies/sweep.h"

#include <limits>
#include <string>
#include <vector>

namespace demvv
{
struct TimeStepStudyOptions
{
  std::string base_deck;
  std::vector<std::string> safety_text = {"0.8", "0.4", "0.2"}; ///< as typed: they name the members
  int seeds = 5;
  std::vector<std::string> sets; ///< "SECTION/KEY=VALUE", as demvv run --set
  SweepSettings settings;
};

/// The change of a quantity from one level to the next finer one, paired
/// over seeds (finer minus coarser).
struct LevelChange
{
  EnsembleStatistics difference;
  bool resolved = false; ///< the 95 % interval excludes zero
  double bound() const;  ///< |mean| + 95 % half-width
};

/// The observed order from three successive levels.
struct ObservedOrder
{
  bool resolved = false; ///< both changes resolved, of one sign
  double order = std::numeric_limits<double>::quiet_NaN();
  double low = std::numeric_limits<double>::quiet_NaN(); ///< 95 % interval
  double high = std::numeric_limits<double>::quiet_NaN();
};

/// A quantity's time-step study; every vector runs over the levels, coarse
/// to fine (changes and orders start at the coarser of their levels).
struct TimeStepAnalysis
{
  std::vector<double> safety;
  std::vector<EnsembleStatistics> level;
  std::vector<LevelChange> change;  ///< L - 1 entries
  std::vector<ObservedOrder> order; ///< L - 2 entries (empty when the ratios differ)
  double extrapolated = std::numeric_limits<double>::quiet_NaN();
  std::vector<double> error_bound; ///< U_num at each level, 95 % [the quantity's unit]
};

/// The analysis of values[level][seed] (NaN where a member gave none; a
/// seed counts in a paired change only where both levels have it) at
/// safeties in decreasing order.
TimeStepAnalysis analyse_time_step(const std::vector<double> &safety, const std::vector<std::vector<double>> &values);

/// Runs (or resumes) the study and writes its tables; 0, or 128 + signal
/// when interrupted.
int command_time_step(const TimeStepStudyOptions &options);
} // namespace demvv
