// demvv sweep: one base deck run over the Cartesian product of varied
// entries and seeds, each member an ordinary run directory.
//
//   demvv sweep BASE_DECK --vary SECTION/KEY=v1,v2,... [--vary ...] [--seeds N [--first-seed K]]
//               --out DIR [--replace] [--threads N] [--quiet]
//
// Members are numbered in the order of the product, the first --vary
// outermost and the seed innermost; member i runs the base deck with its
// values set as --set would, in DIR/members/<i>_<values>_s<seed>/, through
// the deck kind's own run function.  A --vary with one value sets that
// entry for every member (as --set would); a value holding a comma (a
// vector) cannot be varied.
//
// A seed s (--seeds N gives s = 1..N) sets every random seed of the member:
// `bonds/seed` (strength and removal draws) and `sample/seed` (a prepare
// deck's placement), where the deck has them; when the deck's sample is a prepare deck (sample/file
// names a .prm), that deck is prepared again with sample/seed = s (and its
// own bonds/seed = s), cached as any prepared sample is, and the member
// reads that sample (its deck.prm names the cached sample.json).  So every
// seed has its own packing and its own strengths.  A sample file (.json)
// keeps its packing and its bonds: a seed then changes only draws the run
// itself makes (bonds installed by the run).  Without --seeds, the seeds
// are the deck's.
//
// DIR/sweep.csv has a row per member (values, seed, status, peak stress,
// strain at peak, initial modulus, Poisson's ratio, bond breakage at the
// peak, the sample's ball count, run time); DIR/stats.csv has, per set of
// varied values, the mean, standard deviation and 95 % Student-t confidence
// half-width over the completed seeds, and the uncertainty budget of each
// mean: u_seed (its standard error), u_num (the time-step study's
// standard uncertainty for the members' sample size and step, empty where
// none applies: app/run/numerical_uncertainty.h) and u_input (the fitted
// inputs' standard uncertainty carried to the quantity, where the deck
// names the calibration that fitted it: app/run/input_uncertainty.h;
// empty otherwise).  Both are built from the members'
// run directories alone (summary.json, series.csv), rewritten atomically as
// members complete.  DIR/plots holds the study's figures, drawn when the
// sweep ends (gnuplot scripts and their data beside the SVG pictures): peak
// stress, strain at peak and initial modulus, the mean over seeds with its
// 95 % half-width and every member, and the budget of each mean
// (budget_*.svg: u_seed, u_num, u_input in per cent of it), against the
// first varied entry (its
// values when they are numbers, else the ball count of each value's sample
// when that tells them apart: a sweep over samples), one series per value
// of the other entries; else against the seed (a seed ensemble) or the
// point's number.  A
// member that faults or whose deck is refused is a row with its status
// and message; the others go on.  DIR/sweep.json holds the provenance.
//
// Rerunning the same sweep into DIR resumes it: a member whose directory
// holds a completed summary.json of the same resolved deck (deck.prm),
// made by this build, is kept, every other one runs (again).  --replace
// starts a sweep directory over; a non-empty directory that holds no
// sweep.json is never touched.
//
// Under `mpirun -np K` the ranks share the members round-robin by index
// (member i on rank i mod K), each member on one rank with its threads, so
// results do not depend on K; rank 0 writes the tables.  Samples are
// prepared first, each on one rank.  Kinds that run on every MPI rank (the
// continuum cylinder, mms) are refused under more than one rank, and a
// kind that refuses mpirun itself (compare) has its members refused there.
#pragma once

#include <nlohmann/json.hpp>

#include <array>
#include <limits>
#include <string>
#include <vector>

namespace demvv
{
class Deck;

/// Where and how a sweep's members run.
struct SweepSettings
{
  std::string out_dir;
  bool replace = false;
  int threads = 0;
  bool progress = true;
  bool figures = true; ///< draw DIR/plots when the sweep ends
  /// The most members a sweep plans; more are refused before any is
  /// planned (a mistyped --seeds or list would plan for minutes, then run
  /// for years).  --max-members raises it knowingly.
  std::size_t max_members = 10000;
  std::string command_line; ///< as typed, for sweep.json
};

struct SweepOptions
{
  std::string base_deck;
  std::vector<std::string> vary; ///< "SECTION/KEY[+SECTION/KEY...]=v1,v2,..."
  int seeds = 0;                 ///< 0: the deck's own seeds
  int first_seed = 1;            ///< the seeds are first_seed ... first_seed + seeds - 1
  SweepSettings settings;
};

/// What a sweep runs: the base deck at each point (one value per key, set
/// as --set would), each point with `seeds` seeds (0: the deck's own).
/// `demvv sweep` makes the points the product of its --vary values; the
/// calibration makes them its trial parameters and their finite-difference
/// neighbours.
struct SweepPlan
{
  std::string base_deck;
  std::vector<std::string> keys;
  std::vector<std::vector<std::string>> points;
  int seeds = 0;      ///< seeds per point; 0: the deck's own
  int first_seed = 1; ///< the seeds are first_seed ... first_seed + seeds - 1
  /// keys[0 .. first_factor_keys) are tied (one value each point): the
  /// first factor, the figures' abscissa.
  std::size_t first_factor_keys = 1;
};

/// A run's relative standard uncertainties of one quantity, as its
/// summary.json states them; NaN where not estimated.
struct StatedUncertainty
{
  double num = std::numeric_limits<double>::quiet_NaN();   ///< u_num / |q|: uncertainty/numerical_time_step
  double input = std::numeric_limits<double>::quiet_NaN(); ///< u_input / |q|: uncertainty/input_calibration
};

/// One member's outcome, read from its run directory: status "pending",
/// "completed", "fault", "refused", "interrupted"; the measured quantities
/// NaN unless completed.
struct SweepRow
{
  std::string status = "pending";
  std::string message;
  std::string directory;                                  ///< the member's run directory (its series.csv, summary.json)
  double peak = std::numeric_limits<double>::quiet_NaN(); ///< peak axial stress [Pa]
  double strain = std::numeric_limits<double>::quiet_NaN();    ///< axial strain at the peak [-]
  double modulus = std::numeric_limits<double>::quiet_NaN();   ///< initial (fitted) modulus [Pa]
  double poisson = std::numeric_limits<double>::quiet_NaN();   ///< Poisson's ratio [-]
  double broken = std::numeric_limits<double>::quiet_NaN();    ///< bonds broken at the peak [-]
  double particles = std::numeric_limits<double>::quiet_NaN(); ///< balls in the sample [-]
  double seconds = std::numeric_limits<double>::quiet_NaN();   ///< run time [s]
  /// The standard uncertainties of peak stress, strain at peak and initial
  /// modulus (in that order) that the member's summary states.
  std::array<StatedUncertainty, 3> stated;
};

struct SweepOutcome
{
  int exit_code = 0;          ///< 0, or 128 + signal when interrupted
  std::vector<SweepRow> rows; ///< one per member: point after point, seed innermost (on every rank)
  std::string summary;        ///< one line: members by status, where the table is (rank 0)
};

/// The statistics of a seed ensemble over its finite values (n counts
/// them): mean, sample standard deviation, standard error of the mean and
/// the 95 % Student-t half-width (t with n - 1 degrees of freedom); the last
/// three need two values, NaN otherwise.
struct EnsembleStatistics
{
  std::size_t n = 0;
  double mean = std::numeric_limits<double>::quiet_NaN();
  double sd = std::numeric_limits<double>::quiet_NaN();
  double se = std::numeric_limits<double>::quiet_NaN();
  double ci95 = std::numeric_limits<double>::quiet_NaN();
};

EnsembleStatistics ensemble_statistics(const std::vector<double> &values);

/// A number as a CSV cell of the study tables: empty when not finite.
std::string csv_cell(double v);
/// A number for a JSON document: null when not finite (JSON has no NaN).
nlohmann::json finite_or_null(double v);

/// Runs (or resumes) the members of a plan in settings.out_dir.  Bad input
/// (the base deck, a key, a directory holding something else) is a
/// DeckError before any member runs.
SweepOutcome run_sweep(const SweepPlan &plan, const SweepSettings &settings);

/// Runs (or resumes) a sweep; returns 0, or 128 + signal when interrupted.
/// Bad input (the base deck, a --vary, a directory holding something else)
/// is a DeckError before any member runs.
int command_sweep(const SweepOptions &options);

} // namespace demvv
