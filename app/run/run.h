// What every run shares: options, status, the run directory.
//
// A run directory holds deck.prm (the resolved deck, written first),
// summary.json (written at the start with status "running", rewritten
// atomically at the end or at a fault) and the series files, which grow a
// complete row at a time.  A run stopped by a numerical fault keeps all of
// them valid and records the diagnostic (step, time, particle) in
// summary.json; the command then exits with code 3.  A DEM run refused
// before its first step (it could never end, dem_driver.h) leaves
// summary.json with status "refused" and the one-line error (exit code 2).
// `demvv run` writes only into a new or empty directory, or replaces a run
// directory whole on request (claim_run_directory); --resume continues in
// its own.
#pragma once

#include "app/decks/deck.h"

#include "continuum/numerical_failure.h"
#include "dem/simulation.h"
#include "dem/spatial_order.h"

#include <nlohmann/json.hpp>

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace demvv
{
struct RunOptions
{
  std::string out_dir;  ///< empty: keep results in memory only
  int threads = 0;      ///< OpenMP threads (0: leave the default)
  bool progress = true; ///< show progress on a terminal
  bool resume = false;  ///< continue the run in out_dir from its checkpoint
  long pause_after = 0; ///< > 0: stop after this many steps as an interruption would (batch-queue jobs)
  bool replace = false; ///< demvv run --replace: a non-empty out_dir holding a run is replaced whole
  /// > 0: `threads` is where a DEM run starts, and it may move between one
  /// thread and this many (ThreadGovernor): --threads N, or a sweep's share
  /// of the cores that demvv chose.  0 with `threads` > 0: exactly that many.
  int most_threads = 0;
  /// Whether a stopped run can be continued on its own, by `demvv run DECK
  /// --resume out_dir`: false for a part of a larger run (a comparison's
  /// parts, a sweep's members), which that run starts again instead.
  bool resumable_alone = true;

  /// Options that start a run on `threads` and never use more (0: demvv's
  /// choice): what --threads means.
  static RunOptions at_most(int threads)
  {
    RunOptions o;
    o.threads = threads;
    o.most_threads = threads;
    return o;
  }
};

struct RunStatus
{
  bool fault = false;
  int interrupted_by = 0; ///< the signal (SIGINT, SIGTERM) that stopped the run, 0 if none
  bool paused = false;    ///< stopped by RunOptions::pause_after, checkpoint written
  long step = 0;          ///< fault step (or steps run)
  double time = 0;        ///< s
  dem::Index particle = -1;
  std::string message;
  /// A comparison's verdict, said on the run's last line ("" for other kinds).
  std::string verdict;
  double wall_seconds = 0;
  long steps = 0;
  /// False on the MPI ranks that leave the run directory to rank 0.
  bool writes_run_directory = true;

  nlohmann::json to_json() const;
  /// One-line diagnostic for stderr.
  std::string diagnostic() const;
  /// The exit code the command returns: 0, 3 (fault), 128 + signal.
  int exit_code() const;
};

class RunDirectory
{
public:
  /// Creates the directory, writes deck.prm and a "running" summary.json;
  /// `resuming`: the directory's deck.prm and summary stay as they are until
  /// the checkpoint has been read back (a refused resume leaves the paused
  /// run's summary and its resume command).
  RunDirectory(const std::string &dir, const DeckRecord &deck, int threads, long long seed, bool resuming = false);
  std::string path(const std::string &file) const { return dir_ + "/" + file; }
  /// Rewrites summary.json atomically; provenance is added.
  void write_summary(nlohmann::json summary) const;
  /// Identifies the resolved deck (a resumed run must have the same).
  const std::string &deck_hash() const { return deck_hash_; }
  /// The deck the run was started from.
  const DeckRecord &deck() const { return deck_; }
  /// FNV-1a of each file the deck names ({path: hash}), as the run read
  /// them: a checkpoint records them, a resume on changed files is refused.
  const nlohmann::json &input_hashes() const { return input_hashes_; }

private:
  std::string dir_;
  std::string deck_hash_;
  DeckRecord deck_;
  nlohmann::json provenance_;
  nlohmann::json input_hashes_ = nlohmann::json::object();
};

/// {path: FNV-1a of its contents} of the files that exist among `paths`.
nlohmann::json hash_input_files(const std::vector<std::string> &paths);

class ParaviewWriter;
class CsvSeries;

/// The files a DEM run writes besides its series: the run directory (when
/// an output directory is given), the bond-break log and, on request,
/// ParaView frames.  Without an output directory everything is a no-op.
class RunFiles
{
public:
  RunFiles(const RunOptions &options, const DeckRecord &deck, int threads, long long seed,
           const std::string &convention, bool paraview);
  ~RunFiles();
  RunDirectory *directory() { return dir_.get(); }
  const RunDirectory *directory() const { return dir_.get(); }
  ParaviewWriter *paraview() { return paraview_.get(); }
  /// How the files name ball k: ids[k], its row in the user's particle file
  /// where the run renumbered the balls (dem/spatial_order.h); by default k.
  void set_ball_ids(std::vector<dem::Index> ids);
  dem::Index ball_id(dem::Index ball) const { return dem::file_row(ids_, ball); }
  /// Takes the simulation's new bond breaks into bond_breaks.csv (first <
  /// second, by ball_id) and the ParaView break log; returns them.
  std::vector<dem::BondBreak> drain_breaks(dem::Simulation &sim);

  /// What a checkpoint records of these files (bond_breaks.csv length,
  /// ParaView state), and continuing from it.
  nlohmann::json checkpoint_state() const;
  void resume(const nlohmann::json &state);

private:
  std::unique_ptr<RunDirectory> dir_;
  std::unique_ptr<CsvSeries> breaks_;
  std::unique_ptr<ParaviewWriter> paraview_;
  std::vector<dem::Index> ids_;
};

// Ownership.  A directory demvv made holds the marker file `.demvv` (JSON:
// what it holds, "run", "sweep" or "calibration", and the names of the
// entries such a directory's runs write); only a directory with the marker
// is ever resumed, emptied or replaced, and then only the entries of those
// names are removed: a user's own files beside them stay.  A process that
// works in a directory (a run, a resume, a sweep, a calibration) holds an
// exclusive lock on it (flock(2) on `.demvv.lock`) for its whole life; a
// second one is refused with the one-line error (exit 2), so two writers
// never mix their rows.

/// The marker's name, and the lock file's.
constexpr const char *ownership_marker = ".demvv";
constexpr const char *lock_file = ".demvv.lock";

/// The entries a directory holding `what` ("run", "sweep", "calibration",
/// "report")
/// may have demvv write (for a run, of any kind): names or shell patterns
/// (fnmatch: "*.??????.tmp", "level_[0-9]*").
const std::vector<std::string> &output_entries(const std::string &what);
/// Whether `name` is one of `patterns`.
bool matches_entry(const std::string &name, const std::vector<std::string> &patterns);

/// Writes the marker that proves demvv made `dir`, holding `what`.
void mark_directory(const std::string &dir, const std::string &what);
/// Whether `dir` holds demvv's marker for `what` (a regular file, read within limits).
bool marked_as(const std::string &dir, const std::string &what);
/// Why `dir` is not marked as holding `what` ("it lacks demvv's marker
/// .demvv", "its marker ... says it holds a sweep, not a run", ...); "" when
/// it is.
std::string marker_problem(const std::string &dir, const std::string &what);

/// An exclusive lock on a directory for as long as the object lives (made
/// when absent).  DeckError naming the directory and the process that
/// holds it when another process does.
class DirectoryLock
{
public:
  DirectoryLock(const std::string &dir, const std::string &what);
  ~DirectoryLock();
  DirectoryLock(const DirectoryLock &) = delete;
  DirectoryLock &operator=(const DirectoryLock &) = delete;

private:
  int fd_ = -1;
  std::string dir_;      ///< the directory locked
  std::string path_;     ///< the lock file
  bool created_ = false; ///< this process made the lock file
};

/// Makes `dir` ready for a new run, before anything is written into it: a
/// directory that does not exist yet or is empty is taken as it is; a
/// non-empty one is refused (DeckError naming the directory and --replace),
/// so that a run's files never mix with an earlier run's (old ParaView
/// frames, gauge studies, level folders).  With `replace`, a run directory
/// (one that holds demvv's marker for a run) has the entries a run writes
/// removed, after `validate` (the deck's parse, every input file read and
/// checked) has passed, so a bad deck loses nothing; a non-empty directory
/// without the marker is never emptied (a folder holding a copied deck.prm
/// is no run directory).  A path that is no directory is refused.
/// OutputError when an entry cannot be removed.
/// `inputs` (absolute, as Deck::input_files) are never removed, whatever
/// their names: a deck run in its own folder keeps itself and its CSVs.
void claim_run_directory(const std::string &dir, bool replace, const std::function<void()> &validate,
                         const std::vector<std::string> &inputs = {});
/// True when `dir` exists and holds entries (the lock file aside), false
/// when it is absent or empty; DeckError when it is no directory or cannot
/// be read.  `named` names it in errors ("run directory 'x'"), `holding`
/// says what it is for.
bool holds_entries(const std::string &dir, const std::string &named, const std::string &holding);
/// Removes the entries of `dir` that a directory holding `what` writes
/// (output_entries; for a run whose summary names its kind, what that kind
/// writes), but none of `keep` (absolute paths); OutputError naming the
/// entry that would not go.
void remove_outputs(const std::string &dir, const std::string &what, const std::vector<std::string> &keep = {});
/// Takes the output directory of a command that resumes (a sweep, a
/// calibration: `what`), recognised by demvv's marker for `what` and the
/// file `record` inside it: false when it is absent or empty, or when
/// `replace` has emptied it; true when it holds an earlier one to resume.
/// DeckError when it holds something else (never emptied).
bool claim_resumable_directory(const std::string &dir, bool replace, const std::string &what,
                               const std::string &record);

/// The command that continues a stopped run of `deck` in options.out_dir:
/// the deck file, its --set values (a resume with others is refused), the
/// thread ceiling when one was given, each word quoted for a POSIX shell.
std::string resume_command(const DeckRecord &deck, const RunOptions &options);

/// Records a fault into a status (from a NumericalFault).
void record_fault(RunStatus &status, const dem::NumericalFault &fault);
/// Records a continuum run's failure into a status: its step (time step or
/// ODE output), simulated time [s] and message; no particle.
void record_failure(RunStatus &status, const continuum::NumericalFailure &failure);

/// "SIGINT", "SIGTERM" or "a signal".
const char *signal_name(int signal);

/// A signal stopped work that has no checkpoint (a sample's preparation
/// before the run that needs it): the command ends with 128 + signal.
class Interrupted : public std::runtime_error
{
public:
  Interrupted(const std::string &what, int signal) : std::runtime_error(what), signal(signal) {}
  int signal; ///< SIGINT or SIGTERM
};

/// SIGINT, SIGTERM and SIGHUP (a closed terminal or ssh connection, taken as
/// SIGTERM) only raise a flag while one of these lives: the DEM loop looks
/// at it after every step, so a run stops between two whole steps, and a
/// command looks at it after drawing figures.  The previous handlers come
/// back when it ends (checks and tests run many runs in one process).
class StopSignals
{
public:
  StopSignals();
  ~StopSignals();
  StopSignals(const StopSignals &) = delete;
  StopSignals &operator=(const StopSignals &) = delete;
  /// The signal received since construction (SIGINT or SIGTERM), 0 if none.
  int received() const;

private:
  void (*previous_int_)(int);
  void (*previous_term_)(int);
  void (*previous_hup_)(int);
};

/// The cores no other process is running on as this is called: every core
/// less the other runnable tasks (the fourth field of /proc/loadavg), at
/// least one.  Results do not depend on the thread count, only speed does:
/// beside one CPU-bound process on two cores, one thread ran 1.27 times
/// faster than two.
int idle_cores();
/// The machine's cores less the tasks running or ready to run as this is
/// called, the caller's running threads included (the fourth field of
/// /proc/loadavg); negative when tasks wait for a core, empty where the
/// file cannot be read.
std::optional<int> spare_cores();

/// Sets and returns the OpenMP threads: options.threads (at most the
/// machine's cores; with a ceiling, at most idle_cores() too), else
/// OMP_NUM_THREADS when set, else idle_cores().
int apply_threads(const RunOptions &options);

/// Whether a run may change its thread count while it goes (results never
/// depend on it): always, unless the count is exact: `threads` > 0 without
/// `most_threads`, or neither with OMP_NUM_THREADS set.
bool threads_are_ours(const RunOptions &options);
/// The most threads a run whose count is ours may use: `most_threads`
/// (--threads, a sweep's share; at most the cores), else every core.
int thread_ceiling(const RunOptions &options);

/// The thread count of a DEM run while it goes.  idle_cores() sees the load
/// at the start only; a process that starts later holds back every step of
/// a run whose threads wait for one another (two threads beside one busy
/// process ran slower than one).  Results do not depend on the thread count,
/// so the count may change between any two steps: every so often the
/// governor times a window of steps on one thread fewer (or, after one was
/// given up, one more) and keeps that count if it ran faster by 10 % than
/// the better of the windows just before and just after it (one window
/// slowed by something else does not decide).  A window lasts about 0.2 s
/// of wall time, a trial as many steps as the window before it; after a
/// trial that changed nothing the next comes twice as late (2 s at first,
/// at most 32 s), so on an idle machine trials cost well under 1 %.  A
/// trial ends early once its time exceeds what its whole window may take
/// to win (90 % of the window before it): it can no longer win, so this
/// decides nothing differently, but a count that runs many times slower
/// (two threads while a load holds one of two cores) costs at most about
/// 0.2 s a trial instead of its whole window of steps.  The trial is that
/// long so that a load that comes and goes (a core busy 50 ms of every
/// 100) is seen at both its phases, not at one of them.
/// A run that starts below its ceiling (the load at its start held it back)
/// has its first trial of one more thread after 0.5 s: a load that comes
/// and goes (half a core) can hold back the start of a run that two
/// threads serve better, and a short run would otherwise spend its first
/// 2 s on one.
/// A trial is taken when the machine shows a reason for it: one thread
/// fewer when more tasks are runnable than there are cores (another
/// process competes for ours), one more when fewer are (a core is free),
/// in at least a quarter of the looks at the machine over the window just
/// ended (one every 10 ms; its cost is in BENCHMARKS.md).  One look at the window's end
/// would see a load that holds a core 50 ms of every 100 at the same
/// phase each time, since windows of 0.2 s span whole periods of it: a run
/// started on one thread in the load's busy half never saw the free core
/// of its idle half.  A process that only passes by shows in few looks.
/// Without a reason it is looked at again 0.25 s later, and taken anyway
/// once 32 s have passed since the last, for a competitor the count of
/// runnable tasks does not show (another machine's load on the host's
/// cores); such a trial, lost, leaves the spacing as it was, so a load
/// that arrives later is still met within seconds.  So on an idle machine
/// a run of a few seconds has no trial (its first, of one thread fewer,
/// cost 3 % of a 2.5 s run), and beside a process that holds a core a run
/// on one thread does not try two every few seconds.
class ThreadGovernor
{
public:
  /// What the governor reads of the machine; empty members read the real
  /// one (tests pass their own).
  struct Probes
  {
    std::function<double()> now;                     ///< s, a steady clock
    std::function<std::optional<int>()> spare_cores; ///< as demvv::spare_cores()
  };
  /// `start`: the threads the run starts with; `most`: never exceeded
  /// (thread_ceiling()); `active`: whether the count may change
  /// (threads_are_ours()), else `start` is kept as it is.
  ThreadGovernor(int start, int most, bool active, Probes probes = {});
  /// Called after every step.
  void after_step();
  int threads() const { return phase_ == Phase::trial ? trial_ : current_; }
  /// How often the count changed so far.
  int changes() const { return changes_; }
  /// How many trials were taken so far (won or lost).
  int trials() const { return trials_; }
  /// For a run's summary: whether the count was governed (could change),
  /// up to how many threads, how many trials it took and how often the
  /// count changed, the count at the end.
  nlohmann::json to_json() const;

private:
  enum class Phase
  {
    settled, ///< running at current_
    trial,   ///< running at trial_
    confirm, ///< back at current_, the window that decides
  };
  void begin_window();
  void use(int threads);
  /// Steps of a window of about window_seconds at `per_step` [s].
  static long steps_in_window(double per_step);
  /// Ends a trial (at time `end` [s]): its count kept if it won, else the
  /// next trial comes twice as late (if the machine gave a reason for it).
  void settle(double end, bool trial_won);
  /// Whether a trial of trial_ threads is taken at time `end` [s]; sets
  /// trial_had_reason_.
  bool worth_trying(double end);
  /// Probes the machine once (spare_cores_) and counts what it showed.
  void look_at_machine();
  static constexpr double window_seconds = 0.2, gain = 0.1, longest_spacing = 32; // s, 1, s
  static constexpr double recheck = 0.25, probe_spacing = 0.01;                   // s, s
  Phase phase_ = Phase::settled;
  double trial_per_step_ = 0; ///< s, at trial_
  double trial_deadline_ = 0; ///< s, the longest a trial's window may take and still win
  std::function<double()> now_;
  std::function<std::optional<int>()> spare_cores_;
  int most_, current_, trial_ = 0, changes_ = 0, trials_ = 0;
  bool ours_;                    ///< governed: the count is demvv's to change, up to most_
  bool try_fewer_ = true;        ///< the direction of the next trial
  bool trial_had_reason_ = true; ///< the machine showed one (or could not be probed); else taken after 32 s without
  long window_steps_ = 16;       ///< steps in a window, fitted to about 0.2 s
  long steps_ = 0;               ///< steps taken in this window
  double window_start_ = 0;      ///< s
  double settled_per_step_ = 0;  ///< s, at current_ in the last window
  double next_trial_ = 0;        ///< s, when the next trial begins
  double last_trial_ = 0;        ///< s, when the last trial ended (the start before the first)
  double trial_spacing_ = 2;     ///< s
  double next_probe_ = 0;        ///< s, when the machine is looked at next
  long looks_ = 0, blind_looks_ = 0, free_looks_ = 0, crowded_looks_ = 0; ///< since the window began
};
} // namespace demvv
