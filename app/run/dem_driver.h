// The DEM run driver: the one time loop of every DEM deck kind.
//
// A deck kind builds its simulation and a DemProtocol (what moves, what is
// measured, when the test ends); the driver owns everything else:
//
//   - the step loop, through dem::Simulation::step(hooks): the protocol
//     acts at the named points of a step (before the forces, at the force
//     time, after integration), the driver never splits a step by hand;
//   - the output cadence: a row every `interval` of the protocol's clock
//     (simulated time or axial strain, named in the series header), taken
//     at the force time when positions, forces and walls are all at t, and
//     always a row at the last step;
//   - ParaView frames on their own cadence of the same clock;
//   - the bond-break log;
//   - the progress line on a terminal (percent, the protocol's state,
//     particle-steps per second, time left), nothing otherwise;
//   - a run that cannot end is refused before its first step: when the
//     protocol's time left needs more than max_run_steps steps even at the
//     largest step the simulation could take (dem::least_steps), the deck
//     key that sets the duration is named with the estimate (DeckError,
//     exit code 2; summary.json says "refused");
//   - fault capture: a NumericalFault ends the run with every output kept
//     and the diagnostic in summary.json (exit code 3);
//   - an energy ledger that doubts itself: at every row a runaway of the
//     kinetic plus strain energy, local damping that gives energy back, or
//     a broken balance (dem::LedgerLimits, dem::Simulation::
//     check_energy_ledger) stops the run as a fault like any other, and so
//     does a contact that overlaps by more than half a radius
//     (check_contact_overlaps);
//   - warnings: each entry of the summary's "warnings" (a protocol's own,
//     e.g. a uniaxial test that was not quasi-static) is printed as a
//     "demvv: warning:" line when the run ends;
//   - interruption: SIGINT or SIGTERM end the run at the end of the current
//     step; every output is flushed, summary.json says "interrupted" and a
//     checkpoint is written (exit code 130 or 143);
//   - checkpoints and resume: checkpoint/ in the run directory holds the
//     simulation state (a sample file) and the driver's own state (the
//     series in memory with exact doubles, the byte length of every file
//     written so far, the cadences, the ParaView frames).  A run resumed
//     from it truncates its files to those lengths and continues as if it
//     had never stopped: same series, same summary, bit for bit.
//     Checkpoints are also written every `checkpoint interval` seconds of
//     wall time when the deck asks for it.
#pragma once

#include "app/decks/deck.h"
#include "app/io/series.h"
#include "app/run/run.h"

#include "dem/simulation.h"

#include <nlohmann/json.hpp>

#include <limits>
#include <string>
#include <vector>

namespace demvv
{
/// Steps a run may need at most: 1e12 steps take about a day even for a
/// single ball and centuries for a sample of thousands (the engine does a
/// few million particle-steps per second per core: 4.8e6 measured on one
/// core for a 100000-ball sc bench, 2.2e6 for fcc).
constexpr double max_run_steps = 1e12;

/// The outputs section every DEM kind shares.
struct DemOutputSpec
{
  double interval = 0;            ///< clock units between series rows (0: every step)
  bool paraview = false;          ///< write ParaView frames
  double paraview_interval = 0;   ///< clock units between frames
  double checkpoint_interval = 0; ///< s of wall time between checkpoints (0: none)
};

/// Declares `checkpoint interval` inside the current (output) section.
void declare_checkpoint_interval(DeckSchema &s);

/// How many steps resolve the shortest contact period during a run.
///
/// The automatic step is a stability bound, not an accuracy choice.  With
/// the critical bound dt_c = 2 / omega_max (stability.h: a rigorous bound,
/// so omega_max is over-estimated), the shortest contact period is at least
/// T = 2 pi / omega_max = pi dt_c, resolved by N = pi dt_c / dt steps: about
/// 3.9 at the default safety 0.8, two steps per contact duration.  Centred
/// differences run a linear oscillator at the frequency
/// (2 / dt) asin(omega dt / 2), so the period (and an impact's duration) is
/// short by the factor (2 / theta) asin(theta / 2) - 1, theta = 2 pi / N:
/// 16 % at N = 3.9, 1 % at N = 12.8, 0.16 % at N = 32.  Quasi-static tests
/// need not resolve contact oscillations; dynamic ones (impacts, waves) do,
/// and a warning says so when the estimate exceeds 1 %.
class ContactResolution
{
public:
  /// At a force time: the current step against the current bound.
  void observe(const dem::Simulation &sim);
  /// Fewest steps per shortest contact period met during the run
  /// (infinite while no contact carried force).
  double steps_per_period() const { return steps_per_period_; }
  /// Relative error of the period at that resolution (closed form above).
  double period_error() const;
  /// The smallest critical step bound of the run [s], null if none.
  nlohmann::json smallest_bound_json() const;
  nlohmann::json to_json() const;
  /// One sentence when the period error exceeds 1 %, else "".
  std::string warning() const;
  /// Exact state for checkpoints.
  nlohmann::json state() const;
  void restore(const nlohmann::json &state);

private:
  double steps_per_period_ = inf;
  double smallest_bound_ = inf;
  double damping_factor_ = 1; ///< sqrt(1 + local damping) of the last observation
};

/// A series the run writes, and the file it streams to.
struct SeriesFile
{
  Series *series;
  std::string file;    ///< in the run directory
  std::string comment; ///< first line of the file: units and conventions
};

/// A DEM test as the driver sees it.  The StepHooks it inherits act on the
/// simulation (platen motion, servo); the rest says what to record.
class DemProtocol : public dem::StepHooks
{
public:
  /// "uniaxial t61_damage": the progress line's label.
  virtual std::string label() const = 0;
  /// The quantity rows are spaced in, e.g. "time_s" or "axial_strain".
  virtual std::string clock_name() const = 0;
  virtual double clock(const dem::Simulation &sim) const = 0;
  /// How far the test has come, in [0, 1].
  virtual double fraction_done(const dem::Simulation &sim) const = 0;
  /// True at the force time of the last step.
  virtual bool finished(const dem::Simulation &sim) const = 0;
  /// Simulated time until finished() [s] (the loading's own schedule).
  virtual double time_left(const dem::Simulation &sim) const = 0;
  /// Throws the one-line DeckError naming the deck key that sets how long
  /// the test runs, with its value and `expected`.
  [[noreturn]] virtual void refuse_duration(const std::string &expected) const = 0;
  /// A few words for the progress line ("strain 0.0123, stress 12.3 MPa").
  virtual std::string state_text(const dem::Simulation &sim) const = 0;
  /// Takes the row's measurements at the force time.
  virtual void measure(const dem::Simulation &sim) = 0;
  /// Completes the row after integration (energies at the force time) and
  /// adds it to the series.
  virtual void record(const dem::Simulation &sim) = 0;
  /// Every series of the run, in a fixed order.
  virtual std::vector<SeriesFile> series_files() = 0;
  /// True when the test is about contact dynamics (impacts, waves): the
  /// driver then warns when the step resolves contact periods poorly.
  virtual bool resolves_contact_dynamics() const { return false; }
  /// The bonds broken at this force time (positions at the break).
  virtual void observe_breaks(const dem::Simulation & /*sim*/, const std::vector<dem::BondBreak> & /*breaks*/) {}
  /// The protocol's own state that the simulation does not hold (a servo's
  /// integral, a running maximum), kept bit for bit by checkpoints.
  virtual std::vector<double> checkpoint_values() const { return {}; }
  virtual void restore_values(const std::vector<double> & /*values*/) {}
  /// summary.json (without status and provenance, which the driver adds);
  /// may write further files into `dir` (null when nothing is written).
  virtual nlohmann::json summary(const dem::Simulation &sim, const RunStatus &status,
                                 const ContactResolution &resolution, const RunDirectory *dir) const = 0;
};

/// What a DEM run ends with: its status and its summary (as written to
/// summary.json, less provenance).
struct DemOutcome
{
  RunStatus status;
  nlohmann::json summary;
};

/// Runs a protocol on a simulation until it finishes, faults or is
/// interrupted; see the header note.  `files` is the run's RunFiles (its
/// directory may be absent: then nothing is written and nothing can be
/// resumed).  With options.resume the simulation and the series continue
/// from the run directory's checkpoint.
DemOutcome run_dem(dem::Simulation &sim, DemProtocol &protocol, RunFiles &files, const DemOutputSpec &output,
                   const RunOptions &options);

/// The file names inside a run directory's checkpoint/: the driver's state
/// (written last) and the sample file of the step it names.
std::string checkpoint_state_file(const std::string &run_dir);
std::string checkpoint_sample_file(const std::string &run_dir, long step);

/// Refuses (DeckError) a resume whose run directory has no checkpoint, or
/// whose checkpoint was written by another deck than `deck` or by another
/// build (build_identity()).
void check_resumable(const std::string &run_dir, const Deck &deck);
} // namespace demvv
