#include "app/run/run.h"

#include "app/io/input.h"
#include "app/io/output.h"
#include "app/io/paraview.h"

#include <fcntl.h>
#include <fnmatch.h>
#include <omp.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

namespace demvv
{
const char *signal_name(int signal) { return signal == SIGINT ? "SIGINT" : signal == SIGTERM ? "SIGTERM" : "a signal"; }

nlohmann::json RunStatus::to_json() const
{
  const char *state = fault ? "numerical fault" : interrupted_by ? "interrupted" : paused ? "paused" : "completed";
  nlohmann::json j = {
    {"state", state}, {"interrupted", interrupted_by != 0 || paused}, {"steps", steps}, {"wall_seconds", wall_seconds}};
  if (interrupted_by)
    j["signal"] = signal_name(interrupted_by);
  if (interrupted_by && !message.empty())
    j["message"] = message;
  if (fault)
    j["fault"] = {{"step", step}, {"time_s", time}, {"particle", particle}, {"message", message}};
  return j;
}

std::string RunStatus::diagnostic() const
{
  std::ostringstream o;
  o << "numerical fault at step " << step << ", time " << time << " s";
  if (particle >= 0)
    o << ", particle " << particle;
  o << ": " << message;
  return o.str();
}

int RunStatus::exit_code() const
{
  if (fault)
    return 3;
  return interrupted_by ? 128 + interrupted_by : 0;
}

namespace
{
/// What a run of each kind writes beside the entries every run may have
/// (deck.prm, summary.json, plots, paraview, checkpoint): `--replace` of a
/// run directory whose summary names its kind removes these alone, so a
/// user's file that shares a name with another kind's output stays.
const std::map<std::string, std::vector<std::string>> &run_outputs_by_kind()
{
  static const std::map<std::string, std::vector<std::string>> kinds = {
    {"scene", {"series.csv", "bond_breaks.csv", "particles.csv", "contacts.csv"}},
    {"uniaxial", {"series.csv", "bond_breaks.csv", "gauge_study.csv", "section.csv"}},
    {"prepare", {"sample.json", "preparation_sections.csv"}},
    {"burgers_ode", {"series.csv"}},
    {"cylinder", {"series.csv", "mesh.csv", "level_[0-9]*"}},
    {"mms", {"convergence.csv", "convergence.txt"}},
    {"compare", {"compare.csv", "calibration", "dem", "dem_half_time_step"}},
  };
  return kinds;
}

/// demvv's temporary files: write_atomically's "NAME.XXXXXX.tmp".
constexpr const char *temporary_files = "*.??????.tmp";

/// A JSON object demvv wrote into a directory, read as any input is (a
/// regular file within `limit`, never through a link); an empty object
/// when it is absent, a link, unreadable or no object.
nlohmann::json json_object_in(const std::string &path, const std::string &what, std::uintmax_t limit)
{
  struct stat st
  {
  };
  if (::lstat(path.c_str(), &st) != 0 || !S_ISREG(st.st_mode))
    return nlohmann::json::object();
  try
  {
    nlohmann::json doc = parse_json_input(read_input(path, what, limit), path, what);
    return doc.is_object() ? doc : nlohmann::json::object();
  }
  catch (const std::exception &)
  {
    return nlohmann::json::object();
  }
}

/// The kind a run directory's summary.json names; "" when it names none
/// (a run stopped before its summary, a summary not demvv's).
std::string summary_kind(const std::string &dir)
{
  const nlohmann::json kind =
    json_object_in(dir + "/summary.json", "summary", max_summary_bytes).value("kind", nlohmann::json());
  return kind.is_string() && run_outputs_by_kind().count(kind.get<std::string>()) ? kind.get<std::string>() : "";
}

/// The entries of a run of `kind` ("": of any kind).
std::vector<std::string> run_entries(const std::string &kind)
{
  std::vector<std::string> names = {ownership_marker, "deck.prm",   "summary.json", "plots",
                                    "paraview",       "checkpoint", temporary_files};
  for (const auto &[name, files] : run_outputs_by_kind())
    if (kind.empty() || name == kind)
      for (const std::string &f : files)
        if (std::find(names.begin(), names.end(), f) == names.end())
          names.push_back(f);
  return names;
}
} // namespace

const std::vector<std::string> &output_entries(const std::string &what)
{
  static const std::vector<std::string> run = run_entries("");
  static const std::vector<std::string> sweep = {
    ownership_marker,      "sweep.json",           "sweep.csv",    "stats.csv", "members", "plots",
    "time_step_study.csv", "time_step_study.json", temporary_files};
  static const std::vector<std::string> calibration = {
    ownership_marker, "calibration.json", "evaluations.csv", "fitted.prm", "evaluations", "plots", temporary_files};
  static const std::vector<std::string> report = {ownership_marker, "report.json", "report.md",
                                                  "report.html",    "figures",     temporary_files};
  if (what == "run")
    return run;
  if (what == "report")
    return report;
  if (what == "sweep")
    return sweep;
  if (what == "calibration")
    return calibration;
  throw std::logic_error("demvv bug: no output entries for '" + what + "'");
}

bool matches_entry(const std::string &name, const std::vector<std::string> &patterns)
{
  for (const std::string &p : patterns)
    if (::fnmatch(p.c_str(), name.c_str(), 0) == 0)
      return true;
  return false;
}

void mark_directory(const std::string &dir, const std::string &what)
{
  write_atomically(dir + "/" + ownership_marker,
                   json_text({{"made_by", "demvv"},
                              {"holds", what},
                              {"outputs", output_entries(what)},
                              {"note", "demvv resumes, replaces or empties only directories holding this file, and "
                                       "removes only entries named in outputs"}},
                             2) +
                     "\n");
}

bool marked_as(const std::string &dir, const std::string &what) { return marker_problem(dir, what).empty(); }

std::string marker_problem(const std::string &dir, const std::string &what)
{
  const std::string path = dir + "/" + ownership_marker;
  struct stat st
  {
  };
  if (::lstat(path.c_str(), &st) != 0)
    return std::string("it lacks demvv's marker ") + ownership_marker;
  const nlohmann::json doc = json_object_in(path, "demvv marker", 1 << 16);
  if (doc.empty())
    return std::string("its marker ") + ownership_marker +
           " cannot be read: a link, not JSON or over 64 kB, damaged or edited";
  if (doc.value("made_by", nlohmann::json()) != "demvv")
    return std::string("its marker ") + ownership_marker + " does not say demvv made it (edited)";
  const nlohmann::json holds = doc.value("holds", nlohmann::json());
  if (holds != what)
    return std::string("its marker ") + ownership_marker + " says it holds a " +
           (holds.is_string() ? one_line(holds.get<std::string>().substr(0, 20), '?') : std::string("(nothing)")) +
           ", not a " + what;
  return "";
}

DirectoryLock::DirectoryLock(const std::string &dir, const std::string &what)
{
  std::error_code ec;
  const std::filesystem::file_status status = std::filesystem::status(dir, ec);
  if (std::filesystem::exists(status) && !std::filesystem::is_directory(status))
    throw DeckError(what + " directory '" + dir + "' exists and is not a directory: expected a directory for the " +
                    what + "'s files (--out)");
  make_directories(dir);
  const std::string path = dir + "/" + lock_file;
  dir_ = dir;
  path_ = path;
  // A lock file can be removed by a refused process (below) between our
  // open and our flock: the lock then holds a file no one else can find.
  // So the file locked must still be the one at the path; else try again.
  bool locked = false;
  for (int attempt = 0; attempt < 100 && !locked; ++attempt)
  {
    if (fd_ >= 0)
      ::close(fd_);
    fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0644);
    created_ = fd_ >= 0;
    if (fd_ < 0 && errno == EEXIST)
      fd_ = ::open(path.c_str(), O_RDWR | O_NOFOLLOW | O_CLOEXEC);
    if (fd_ < 0)
      throw DeckError(what + " directory '" + dir + "': cannot open its lock file " + lock_file + " (" +
                      std::strerror(errno) + "): expected a directory demvv may write, holding no link of that name");
    if (::flock(fd_, LOCK_EX | LOCK_NB) != 0)
      break;
    struct stat held
    {
    }, named{};
    locked = ::fstat(fd_, &held) == 0 && ::lstat(path.c_str(), &named) == 0 && held.st_dev == named.st_dev &&
             held.st_ino == named.st_ino;
  }
  if (!locked)
  {
    char holder[32] = {0};
    const ssize_t n = ::pread(fd_, holder, sizeof holder - 1, 0);
    ::close(fd_);
    fd_ = -1;
    std::string pid = n > 0 ? std::string(holder, std::size_t(n)) : std::string();
    pid.erase(pid.find_last_not_of(" \n") + 1);
    throw DeckError(what + " directory '" + dir + "' is in use by another demvv process" +
                    (pid.empty() ? std::string() : " (pid " + pid + ")") +
                    ": expected it to finish first, or another --out");
  }
  // The pid is a courtesy for a second process's message; the lock holds without it.
  const std::string pid = std::to_string(::getpid()) + "\n";
  [[maybe_unused]] const bool noted =
    ::ftruncate(fd_, 0) == 0 && ::pwrite(fd_, pid.data(), pid.size(), 0) == static_cast<ssize_t>(pid.size());
}

DirectoryLock::~DirectoryLock()
{
  if (fd_ < 0)
    return;
  // A lock file this process made in a directory that never became demvv's
  // (no marker: the directory was refused) goes, so that a refusal leaves
  // a foreign folder as it found it; a process that opened it meanwhile
  // finds it gone after its flock and opens a new one (constructor).
  // Otherwise the file stays.
  struct stat st
  {
  };
  if (created_ && ::lstat((dir_ + "/" + ownership_marker).c_str(), &st) != 0)
    ::unlink(path_.c_str());
  ::close(fd_); // releases the lock
}

bool holds_entries(const std::string &dir, const std::string &named, const std::string &holding)
{
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status status = fs::status(dir, ec);
  if (!fs::exists(status))
    return false;
  if (!fs::is_directory(status))
    throw DeckError(named + " exists and is not a directory: expected a directory for " + holding + " (--out)");
  fs::directory_iterator entries(dir, ec);
  if (ec)
    throw DeckError(named + " cannot be read (" + ec.message() + "): expected a directory demvv may write (--out)");
  for (const fs::directory_entry &entry : entries)
    if (entry.path().filename() != lock_file)
      return true;
  return false;
}

void remove_outputs(const std::string &dir, const std::string &what, const std::vector<std::string> &keep)
{
  namespace fs = std::filesystem;
  // A run removes what its kind writes, when its summary says which.
  const std::string kind = what == "run" ? summary_kind(dir) : "";
  const std::vector<std::string> names = kind.empty() ? output_entries(what) : run_entries(kind);
  std::vector<fs::path> old;
  std::error_code ec;
  for (const fs::directory_entry &entry : fs::directory_iterator(dir))
  {
    const fs::path canonical = fs::weakly_canonical(fs::absolute(entry.path(), ec), ec);
    const bool input = std::find(keep.begin(), keep.end(), canonical.string()) != keep.end();
    if (!input && matches_entry(entry.path().filename().string(), names) && entry.path().filename() != ownership_marker)
      old.push_back(entry.path());
  }
  // remove_all does not follow links: a link among the entries goes, its target stays.
  for (const fs::path &entry : old)
    if (fs::remove_all(entry, ec) == static_cast<std::uintmax_t>(-1) || ec)
      throw OutputError(entry.string() + ": cannot be removed to replace the " + what + " in " + dir + " (" +
                        ec.message() + ")");
}

bool claim_resumable_directory(const std::string &dir, bool replace, const std::string &what, const std::string &record)
{
  const std::string named = what + " directory '" + dir + "'";
  if (!holds_entries(dir, named, "the " + what))
  {
    mark_directory(dir, what);
    return false;
  }
  std::string problem = marker_problem(dir, what);
  if (problem.empty() && !std::filesystem::exists(std::filesystem::path(dir) / record))
    problem = "it lacks the " + what + "'s " + record;
  if (!problem.empty())
    throw DeckError(named + " is not empty and is no " + what + " directory demvv made (" + problem +
                    "): expected a new or empty directory (--out), or a " + what + "'s own to resume or replace");
  if (!replace)
    return true;
  remove_outputs(dir, what);
  mark_directory(dir, what);
  return false;
}

void claim_run_directory(const std::string &dir, bool replace, const std::function<void()> &validate,
                         const std::vector<std::string> &inputs)
{
  const std::string named = "run directory '" + dir + "'";
  if (!holds_entries(dir, named, "the run's files"))
    return;
  if (!replace)
    throw DeckError(named + " is not empty: expected a new or empty directory (--out), or --replace to replace "
                            "the run there whole");
  if (const std::string problem = marker_problem(dir, "run"); !problem.empty())
    throw DeckError(named + " is not empty and is no run directory demvv made (" + problem +
                    "): --replace replaces only those: expected a run directory or a new or empty one (--out)");
  validate();
  remove_outputs(dir, "run", inputs);
}

void record_fault(RunStatus &status, const dem::NumericalFault &fault)
{
  status.fault = true;
  status.step = fault.step;
  status.time = fault.time;
  status.particle = fault.particle;
  status.message = fault.what();
}

void record_failure(RunStatus &status, const continuum::NumericalFailure &failure)
{
  status.fault = true;
  status.step = failure.step();
  status.time = failure.time();
  status.message = failure.what();
}

nlohmann::json hash_input_files(const std::vector<std::string> &paths)
{
  nlohmann::json hashes = nlohmann::json::object();
  for (const std::string &p : paths)
  {
    std::error_code ec;
    if (std::filesystem::is_regular_file(p, ec))
      hashes[p] = fnv1a_hex(read_input(p, "input file", max_table_bytes));
  }
  return hashes;
}

RunDirectory::RunDirectory(const std::string &dir, const DeckRecord &deck, int threads, long long seed, bool resuming)
  : dir_(dir), deck_hash_(fnv1a_hex(deck.resolved)), deck_(deck), input_hashes_(hash_input_files(deck.inputs))
{
  make_directories(dir);
  mark_directory(dir, "run");
  const std::string &resolved = deck.resolved;
  provenance_ = provenance(threads, seed, resolved);
  provenance_["deck_file"] = deck.path;
  provenance_["resolved_deck"] = "deck.prm";
  if (resuming)
    return;
  write_atomically(path("deck.prm"), resolved);
  write_summary({{"status", {{"state", "running"}}}});
}

namespace
{
/// `text` as one word of a POSIX shell's command line.
std::string shell_word(const std::string &text)
{
  static const std::string plain = "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789/._-=+,:@%";
  if (!text.empty() && text.find_first_not_of(plain) == std::string::npos)
    return text;
  std::string word = "'";
  for (const char c : text)
    word += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return word + "'";
}
} // namespace

std::string resume_command(const DeckRecord &deck, const RunOptions &options)
{
  std::string command = "demvv run " + (deck.path.empty() ? std::string("DECK") : shell_word(deck.path));
  for (const std::string &assignment : deck.overrides)
    command += " --set " + shell_word(assignment);
  if (options.most_threads > 0)
    command += " --threads " + std::to_string(options.most_threads);
  return command + " --resume " + shell_word(options.out_dir);
}

void RunDirectory::write_summary(nlohmann::json summary) const
{
  summary["provenance"] = provenance_;
  write_atomically(path("summary.json"), json_text(summary, 2) + "\n");
}

RunFiles::RunFiles(const RunOptions &options, const DeckRecord &deck, int threads, long long seed,
                   const std::string &convention, bool paraview)
{
  if (options.out_dir.empty())
    return;
  dir_ = std::make_unique<RunDirectory>(options.out_dir, deck, threads, seed, options.resume);
  if (!options.resume)
    breaks_ =
      std::make_unique<CsvSeries>(dir_->path("bond_breaks.csv"),
                                  convention + "; mode 1 tension, 2 shear, 3 displacement (appendix A); "
                                               "x, y, z: the point on the pair's line of centres at the break",
                                  std::vector<std::string>{"time_s", "first", "second", "mode", "x_m", "y_m", "z_m"});
  if (paraview)
    paraview_ = std::make_unique<ParaviewWriter>(dir_->path("paraview"));
}

RunFiles::~RunFiles() = default;

void RunFiles::set_ball_ids(std::vector<dem::Index> ids)
{
  ids_ = std::move(ids);
  if (paraview_)
    paraview_->set_ball_ids(ids_);
}

std::vector<dem::BondBreak> RunFiles::drain_breaks(dem::Simulation &sim)
{
  std::vector<dem::BondBreak> breaks = sim.take_breaks();
  if (breaks.empty())
    return breaks;
  if (breaks_)
    for (const dem::BondBreak &b : breaks)
    {
      const dem::Index a = ball_id(b.first), c = ball_id(b.second);
      breaks_->write({b.time, double(std::min(a, c)), double(std::max(a, c)), double(static_cast<int>(b.mode)),
                      b.point.x(), b.point.y(), b.point.z()});
    }
  if (paraview_)
    paraview_->add_breaks(breaks);
  return breaks;
}

nlohmann::json RunFiles::checkpoint_state() const
{
  nlohmann::json state = nlohmann::json::object();
  if (dir_)
  {
    sync_file(dir_->path("bond_breaks.csv"));
    state["bond_breaks_bytes"] = std::filesystem::file_size(dir_->path("bond_breaks.csv"));
  }
  if (paraview_)
    state["paraview"] = paraview_->state();
  return state;
}

void RunFiles::resume(const nlohmann::json &state)
{
  if (!dir_)
    return;
  breaks_ =
    std::make_unique<CsvSeries>(dir_->path("bond_breaks.csv"), 7, state.at("bond_breaks_bytes").get<std::uintmax_t>());
  if (paraview_ && state.contains("paraview"))
    paraview_->restore(state.at("paraview"));
}

std::optional<int> spare_cores()
{
  std::ifstream in("/proc/loadavg");
  double minute = 0, five = 0, fifteen = 0;
  std::string tasks;
  if (!(in >> minute >> five >> fifteen >> tasks))
    return std::nullopt;
  return omp_get_num_procs() - std::atoi(tasks.c_str()); // "runnable/total", this process included
}

int idle_cores()
{
  const int cores = omp_get_num_procs();
  const std::optional<int> spare = spare_cores(); // the caller's one running thread among the runnable
  return spare ? std::clamp(*spare + 1, 1, cores) : cores;
}

bool threads_are_ours(const RunOptions &options)
{
  return options.most_threads > 0 || (options.threads <= 0 && !std::getenv("OMP_NUM_THREADS"));
}

int thread_ceiling(const RunOptions &options)
{
  return options.most_threads > 0 ? std::min(options.most_threads, omp_get_num_procs()) : omp_get_num_procs();
}

namespace
{
volatile std::sig_atomic_t stop_signal = 0;

extern "C" void request_stop(int signal) { stop_signal = signal == SIGHUP ? SIGTERM : signal; }
} // namespace

StopSignals::StopSignals()
{
  stop_signal = 0;
  previous_int_ = std::signal(SIGINT, request_stop);
  previous_term_ = std::signal(SIGTERM, request_stop);
  previous_hup_ = std::signal(SIGHUP, request_stop);
}

StopSignals::~StopSignals()
{
  std::signal(SIGINT, previous_int_);
  std::signal(SIGTERM, previous_term_);
  std::signal(SIGHUP, previous_hup_);
}

int StopSignals::received() const { return stop_signal; }

int apply_threads(const RunOptions &options)
{
  // More threads than the machine has cores never run faster, and a few
  // hundred exhaust libgomp's address space under a memory cap: the count
  // asked for is clamped to the cores (results do not depend on it).  A
  // count with a ceiling (--threads N, a sweep's share) is the most a run
  // uses: it starts on the cores no other process is running on, as the
  // default does, and the governor tries more as they free up (started on
  // both cores beside a busy process, a short run spent its first seconds
  // at half speed before the governor's first trial).
  if (options.threads > 0)
  {
    const int asked = std::min(options.threads, omp_get_num_procs());
    omp_set_num_threads(threads_are_ours(options) ? std::min(asked, idle_cores()) : asked);
  }
  else if (threads_are_ours(options))
    omp_set_num_threads(idle_cores());
  return omp_get_max_threads();
}

ThreadGovernor::ThreadGovernor(int start, int most, bool active, Probes probes)
  : now_(std::move(probes.now)), spare_cores_(std::move(probes.spare_cores)), most_(std::max(most, 1)),
    current_(active ? std::clamp(start, 1, most_) : start), ours_(active)
{
  if (ours_ && current_ != start)
    use(current_);
  if (!now_)
    now_ = [start = std::chrono::steady_clock::now()]
    { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
  if (!spare_cores_)
    spare_cores_ = demvv::spare_cores;
  begin_window();
  last_trial_ = window_start_;
  // A run started below its ceiling (the load held it back) first tries one
  // more thread, and soon.
  constexpr double first_trial_up = 0.5; // s
  try_fewer_ = current_ == most_;
  next_trial_ = window_start_ + (try_fewer_ ? trial_spacing_ : first_trial_up);
}

nlohmann::json ThreadGovernor::to_json() const
{
  nlohmann::json j = {{"governed", ours_}, {"at_end", threads()}, {"changes", changes_}, {"trials", trials_}};
  if (ours_)
    j["most"] = most_;
  return j;
}

void ThreadGovernor::begin_window()
{
  steps_ = 0;
  window_start_ = now_();
  looks_ = blind_looks_ = free_looks_ = crowded_looks_ = 0;
}

void ThreadGovernor::use(int threads) { omp_set_num_threads(threads); }

long ThreadGovernor::steps_in_window(double per_step)
{
  return std::clamp(long(window_seconds / per_step), 4L, 100000L);
}

void ThreadGovernor::after_step()
{
  if (!ours_ || most_ == 1) // no trials where only one count is allowed
    return;
  ++steps_;
  const double now = now_(); // one clock read a step, for the looks, the trial's deadline and the window's end
  if (now >= next_probe_)
  {
    next_probe_ = now + probe_spacing;
    look_at_machine();
  }
  // A trial whose time already exceeds what its whole window may take to
  // win cannot win any more: its time per step over the window will be at
  // least the time spent so far over the window's steps, above 90 % of the
  // window before it and so of the better of that and the one after.  It
  // ends here, so that a count which runs many times slower (two threads
  // beside a load that holds one core) costs at most that much, not its
  // whole window of steps.
  if (phase_ == Phase::trial && steps_ < window_steps_ && now - window_start_ > trial_deadline_)
  {
    use(current_);
    window_steps_ = steps_in_window(settled_per_step_);
    settle(now, false);
    return;
  }
  if (steps_ < window_steps_)
    return;
  const double end = now;
  const double per_step = std::max((end - window_start_) / double(steps_), 1e-9);
  window_steps_ = steps_in_window(per_step);
  switch (phase_)
  {
  case Phase::settled:
    settled_per_step_ = per_step;
    if (end >= next_trial_)
    {
      if (current_ == 1)
        try_fewer_ = false;
      else if (current_ == most_)
        try_fewer_ = true;
      trial_ = try_fewer_ ? current_ - 1 : current_ + 1;
      if (!worth_trying(end))
      {
        next_trial_ = end + recheck;
        begin_window();
        break;
      }
      use(trial_);
      ++trials_;
      trial_deadline_ = (1 - gain) * settled_per_step_ * double(window_steps_);
      phase_ = Phase::trial;
    }
    begin_window();
    break;
  case Phase::trial:
    trial_per_step_ = per_step;
    use(current_);
    window_steps_ = steps_in_window(settled_per_step_);
    phase_ = Phase::confirm;
    begin_window();
    break;
  case Phase::confirm:
    // The trial against the better of the windows on either side of it, so
    // that one window slowed by something else does not decide.
    settle(end, trial_per_step_ < (1 - gain) * std::min(settled_per_step_, per_step));
    settled_per_step_ = per_step;
    break;
  }
}

void ThreadGovernor::look_at_machine()
{
  const std::optional<int> spare = spare_cores_();
  ++looks_;
  if (!spare)
    ++blind_looks_;
  else if (*spare > 0)
    ++free_looks_;
  else if (*spare < 0)
    ++crowded_looks_;
}

bool ThreadGovernor::worth_trying(double end)
{
  // A free core (one more thread) or a competitor (one fewer) in at least
  // a quarter of the window's looks; a window too short for one looks now.
  if (looks_ == 0)
    look_at_machine();
  const long seen = trial_ < current_ ? crowded_looks_ : free_looks_;
  trial_had_reason_ = blind_looks_ > 0 || 4 * seen >= looks_;
  return trial_had_reason_ || end - last_trial_ >= longest_spacing;
}

void ThreadGovernor::settle(double end, bool trial_won)
{
  last_trial_ = end;
  if (trial_won)
  {
    try_fewer_ = trial_ < current_;
    current_ = trial_;
    use(current_);
    ++changes_;
    trial_spacing_ = 2;
  }
  else
  {
    try_fewer_ = !try_fewer_;
    // A trial the machine gave no reason for, lost, says nothing about
    // the next reason it gives: the spacing stays.
    if (trial_had_reason_)
      trial_spacing_ = std::min(2 * trial_spacing_, longest_spacing);
  }
  next_trial_ = end + trial_spacing_;
  phase_ = Phase::settled;
  begin_window();
}
} // namespace demvv
