#include "app/run/dem_driver.h"

#include "app/io/input.h"
#include "app/io/output.h"
#include "app/io/paraview.h"
#include "app/io/sample_file.h"

#include "dem/stability.h"
#include "dem/types.h"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <iostream>

namespace demvv
{
namespace
{
/// JSON has no NaN or infinity: such values are written as strings, so a
/// checkpoint gives back every double exactly.
nlohmann::json exact(double v)
{
  if (std::isfinite(v))
    return v;
  return std::isnan(v) ? "nan" : v > 0 ? "inf" : "-inf";
}

double exact_value(const nlohmann::json &j)
{
  if (j.is_number())
    return j.get<double>();
  const std::string s = j.get<std::string>();
  if (s == "nan")
    return std::nan("");
  return s == "inf" ? INFINITY : -INFINITY;
}

nlohmann::json exact_values(const std::vector<double> &values)
{
  nlohmann::json out = nlohmann::json::array();
  for (double v : values)
    out.push_back(exact(v));
  return out;
}

/// The driver's part of a step: the output cadence, ParaView frames and the
/// bond-break log, around the protocol's own hooks.
class Cadence final : public dem::StepHooks
{
public:
  Cadence(DemProtocol &protocol, RunFiles &files, const DemOutputSpec &output)
    : protocol_(protocol), files_(files), output_(output)
  {
  }

  void before_forces(dem::Simulation &sim) override { protocol_.before_forces(sim); }

  dem::ForceTimeAction at_force_time(dem::Simulation &sim) override
  {
    dem::ForceTimeAction action = protocol_.at_force_time(sim);
    resolution_.observe(sim);
    protocol_.observe_breaks(sim, files_.drain_breaks(sim));
    last_ = protocol_.finished(sim);
    const double clock = protocol_.clock(sim);
    due_ = last_ || clock >= next_row_;
    if (due_)
    {
      protocol_.measure(sim);
      next_row_ = clock + output_.interval;
      ParaviewWriter *paraview = files_.paraview();
      if (paraview && (last_ || clock >= next_frame_))
      {
        paraview->write_frame(sim, sim.time());
        next_frame_ = clock + (output_.paraview_interval > 0 ? output_.paraview_interval : output_.interval);
      }
    }
    action.measure_kinetic = action.measure_kinetic || due_;
    return action;
  }

  void after_integration(dem::Simulation &sim) override
  {
    protocol_.after_integration(sim);
    if (!due_)
      return;
    protocol_.record(sim);
    sim.check_energy_ledger(dem::LedgerLimits{});
    sim.check_contact_overlaps(0.5);
  }

  bool last() const { return last_; }
  const ContactResolution &resolution() const { return resolution_; }

  nlohmann::json state() const
  {
    return {{"next_row", exact(next_row_)}, {"next_frame", exact(next_frame_)}, {"resolution", resolution_.state()}};
  }
  void restore(const nlohmann::json &s)
  {
    next_row_ = exact_value(s.at("next_row"));
    next_frame_ = exact_value(s.at("next_frame"));
    resolution_.restore(s.at("resolution"));
  }

private:
  DemProtocol &protocol_;
  RunFiles &files_;
  const DemOutputSpec &output_;
  double next_row_ = 0, next_frame_ = 0;
  bool due_ = false, last_ = false;
  ContactResolution resolution_;
};

std::string deck_hash(const Deck &deck) { return fnv1a_hex(deck.resolved()); }

/// Refuses a run whose steps cannot be counted in a lifetime (see the header note).
void check_reachable(const dem::Simulation &sim, const DemProtocol &protocol)
{
  const double steps = dem::least_steps(sim.particles(), sim.settings(), protocol.time_left(sim));
  // A generous speed for the estimate: 1e7 particle-steps per second.
  const double seconds = std::max(1.0, double(sim.particles().size())) * steps / 1e7;
  if (!(steps > max_run_steps))
  {
    // A run that can end but not soon (an hour even at a speed above the
    // engine's) starts with a word on what it asks.
    if (seconds > 3600)
    {
      char text[200];
      std::snprintf(text, sizeof text,
                    "demvv: note: this run needs at least %.3g steps, about %.3g hours at 1e7 particle-steps/s "
                    "(a stiffness, a duration or a rate far from the usual sets its step)\n",
                    steps, seconds / 3600);
      std::cerr << text;
    }
    return;
  }
  // Either side may be the mistake, the duration or the step: the message
  // gives the step and what sets it beside the duration's key.
  const double years = seconds / 3.15576e7;
  const dem::SimulationSettings &settings = sim.settings();
  char step[320];
  const dem::Index b = dem::stiffest_ball(sim.particles());
  if (settings.fixed_time_step > 0 || b < 0)
    std::snprintf(step, sizeof step, "the fixed step motion/fixed time step %.3g s", settings.fixed_time_step);
  else
  {
    const dem::ParticleStore &P = sim.particles();
    std::snprintf(step, sizeof step,
                  "a step of at most %.3g s, motion/time step safety %.3g of the critical step of particle %lld "
                  "(normal stiffness %.3g N/m, shear stiffness %.3g N/m, mass %.3g kg)",
                  protocol.time_left(sim) / steps, settings.time_step_safety, static_cast<long long>(b), P.kn[b],
                  P.ks[b], P.mass[b]);
  }
  char text[640];
  std::snprintf(text, sizeof text,
                "the run would need at least %.3g steps (about %.3g years at 1e7 particle-steps/s) at %s: expected a "
                "run of at most %.0e steps",
                steps, years, step, max_run_steps);
  protocol.refuse_duration(text);
}

void write_checkpoint(const dem::Simulation &sim, DemProtocol &protocol, const RunFiles &files, const Cadence &cadence,
                      const std::string &dir, const std::string &hash)
{
  make_directories(dir + "/checkpoint");
  SampleFile state;
  state.snapshot = sim.snapshot();
  state.contact_law = std::string(sim.model().name());
  state.title = "checkpoint of " + protocol.label();
  // Its hash ties the sample file to the state below: an edited sample
  // (a position changed by hand) is refused on resume, not continued.  It
  // is named by its step, so the state file written last names a sample
  // file that is whole: a run killed between the two keeps the checkpoint
  // before, whole (the older sample goes once the new state names its own).
  const std::string sample_file = checkpoint_sample_file(dir, sim.steps());
  const std::string sample_hash = fnv1a_hex(write_sample(sample_file, state));

  nlohmann::json series = nlohmann::json::array();
  for (const SeriesFile &f : protocol.series_files())
  {
    nlohmann::json rows = nlohmann::json::array();
    for (const std::vector<double> &r : f.series->all_rows())
      rows.push_back(exact_values(r));
    const std::string path = dir + "/" + f.file;
    sync_file(path); // the rows on disk before the checkpoint counts them
    series.push_back({{"file", f.file},
                      {"bytes", std::filesystem::exists(path) ? std::filesystem::file_size(path) : 0},
                      {"rows", std::move(rows)}});
  }
  const nlohmann::json doc = {
    {"format", "demvv-checkpoint"},
    {"format_version", 1},
    {"deck_hash", hash},
    {"build", build_identity()},
    {"steps", sim.steps()},
    {"time_s", sim.time()},
    {"cadence", cadence.state()},
    {"protocol", exact_values(protocol.checkpoint_values())},
    {"files", files.checkpoint_state()},
    {"inputs", files.directory() ? files.directory()->input_hashes() : nlohmann::json::object()},
    {"sample_fnv1a64", sample_hash},
    {"series", std::move(series)}};
  // The driver's state is written last: a checkpoint whose state file names
  // another step than its sample file is refused on resume.
  write_atomically(checkpoint_state_file(dir), json_text(doc) + "\n");
  std::error_code ec;
  for (const auto &entry : std::filesystem::directory_iterator(dir + "/checkpoint", ec))
  {
    const std::string name = entry.path().filename().string();
    if (name.rfind("state_", 0) == 0 && entry.path().string() != sample_file)
      std::filesystem::remove(entry.path(), ec);
  }
}

nlohmann::json read_checkpoint(const std::string &dir)
{
  const std::string path = checkpoint_state_file(dir);
  if (!std::filesystem::exists(path))
    throw DeckError(dir + ": no checkpoint to resume from (expected " + path +
                    ", written when a run is interrupted or at its checkpoint interval)");
  nlohmann::json doc = parse_json_input(read_input(path, "checkpoint", max_table_bytes), path, "demvv checkpoint");
  if (!doc.is_object() || doc.value("format", nlohmann::json()) != "demvv-checkpoint" ||
      doc.value("format_version", nlohmann::json()) != 1)
    throw DeckError(path + ": not a demvv checkpoint of format version 1");
  return doc;
}

/// The checkpoint's state into the simulation, the series and the files.
void resume_from_checkpoint_state(dem::Simulation &sim, DemProtocol &protocol, RunFiles &files, Cadence &cadence,
                                  const std::string &dir)
{
  const nlohmann::json doc = read_checkpoint(dir);
  if (!doc.contains("steps") || !doc.at("steps").is_number_integer())
    throw DeckError(checkpoint_state_file(dir) + ": no step count: expected the state file a checkpoint wrote");
  const std::string sample_path = checkpoint_sample_file(dir, doc.at("steps").get<long>());
  const std::string sample_text = read_input(sample_path, "checkpoint sample file", max_table_bytes);
  const std::string sample_hash = fnv1a_hex(sample_text);
  if (sample_hash != doc.at("sample_fnv1a64").get<std::string>())
    throw DeckError(sample_path + ": FNV-1a 64 " + sample_hash + ", the checkpoint recorded " +
                    doc.at("sample_fnv1a64").get<std::string>() +
                    ": expected the sample file the checkpoint wrote, unedited (a checkpoint cut short, or changed by "
                    "hand, cannot be resumed)");
  SampleFile state = parse_sample(sample_text, sample_path);
  if (state.snapshot.clock.steps != doc.at("steps").get<long>())
    throw DeckError(checkpoint_state_file(dir) + ": the checkpoint's state (step " +
                    std::to_string(doc.at("steps").get<long>()) + ") and its sample file (step " +
                    std::to_string(state.snapshot.clock.steps) + ") disagree: expected one checkpoint");
  sim.restore(std::move(state.snapshot));
  cadence.restore(doc.at("cadence"));
  std::vector<double> values;
  for (const nlohmann::json &v : doc.value("protocol", nlohmann::json::array()))
    values.push_back(exact_value(v));
  if (values.size() != protocol.checkpoint_values().size())
    throw DeckError(checkpoint_state_file(dir) + ": the checkpoint holds " + std::to_string(values.size()) +
                    " protocol values, the deck's test keeps " + std::to_string(protocol.checkpoint_values().size()) +
                    ": expected the same deck");
  protocol.restore_values(values);
  files.resume(doc.at("files"));
  const std::vector<SeriesFile> series = protocol.series_files();
  const nlohmann::json &saved = doc.at("series");
  if (saved.size() != series.size())
    throw DeckError(checkpoint_state_file(dir) + ": the checkpoint holds " + std::to_string(saved.size()) +
                    " series, the deck writes " + std::to_string(series.size()) + ": expected the same deck");
  for (std::size_t k = 0; k < series.size(); ++k)
  {
    std::vector<std::vector<double>> rows;
    for (const nlohmann::json &r : saved[k].at("rows"))
    {
      std::vector<double> row;
      for (const nlohmann::json &v : r)
        row.push_back(exact_value(v));
      rows.push_back(std::move(row));
    }
    series[k].series->restore_rows(std::move(rows));
    series[k].series->resume_stream(dir + "/" + series[k].file, saved[k].at("bytes").get<std::uintmax_t>());
  }
}

/// Continues the simulation, the series and the files from the checkpoint;
/// a checkpoint edited or damaged beyond its format is the one-line error.
void resume_from_checkpoint(dem::Simulation &sim, DemProtocol &protocol, RunFiles &files, Cadence &cadence,
                            const std::string &dir)
{
  try
  {
    resume_from_checkpoint_state(sim, protocol, files, cadence, dir);
  }
  catch (const nlohmann::json::exception &e)
  {
    throw DeckError(checkpoint_state_file(dir) + ": a field is missing or of the wrong type (" + e.what() +
                    "): expected a checkpoint written by demvv");
  }
}
} // namespace

void declare_checkpoint_interval(DeckSchema &s)
{
  s.real("checkpoint interval", 0, 0, inf, "s",
         "Wall-clock time between checkpoints (checkpoint/ in the run directory), from which `demvv run DECK "
         "--resume RUN_DIR` (with the run's --set values) continues a killed run bit for bit; 0: only when "
         "interrupted (SIGINT, SIGTERM).");
}

void ContactResolution::observe(const dem::Simulation &sim)
{
  const double bound = sim.critical_time_step();
  if (!std::isfinite(bound) || !(sim.time_step() > 0))
    return;
  // The bound carries local damping's stability factor (stability.h); the
  // contact's own period is that of its undamped stiffness.
  damping_factor_ = std::sqrt(1 + sim.settings().local_damping);
  smallest_bound_ = std::min(smallest_bound_, bound);
  steps_per_period_ = std::min(steps_per_period_, dem::pi * bound * damping_factor_ / sim.time_step());
}

double ContactResolution::period_error() const
{
  return std::isfinite(steps_per_period_) ? dem::centred_difference_frequency_error(steps_per_period_) : 0;
}

nlohmann::json ContactResolution::smallest_bound_json() const
{
  return std::isfinite(smallest_bound_) ? nlohmann::json(smallest_bound_) : nlohmann::json(nullptr);
}

nlohmann::json ContactResolution::to_json() const
{
  if (!std::isfinite(steps_per_period_))
    return {{"note", "no contact carried force during the run"}};
  nlohmann::json j = {{"smallest_critical_time_step_bound_s", smallest_bound_},
                      {"steps_per_shortest_contact_period", steps_per_period_},
                      {"estimated_period_error", period_error()},
                      {"note",
                       "the automatic step is a stability bound: centred differences shorten a contact period "
                       "resolved by N steps by (2/theta) asin(theta/2) - 1, theta = 2 pi / N (an upper estimate: "
                       "the bound over-estimates the fastest frequency; N is counted on the undamped bound, local "
                       "damping's factor sqrt(1 + alpha) in the step being one of stability); lower motion/time step "
                       "safety to resolve contact dynamics"}};
  if (!warning().empty())
    j["warning"] = warning();
  return j;
}

std::string ContactResolution::warning() const
{
  if (period_error() <= 0.01)
    return "";
  char text[640];
  std::snprintf(text, sizeof text,
                "the shortest contact period is resolved by %.3g steps: contact durations and peak forces may be "
                "off by up to %.2g %% (centred differences), and an impact's rebound energy by far more (where its "
                "first touch falls within a step decides: up to 3 %% at 16 steps, 1 %% at 31, over 100 %% at 4, "
                "undamped); for contact dynamics lower motion/time step safety (0.2 gives about %.0f steps, 0.1 "
                "about %.0f)",
                steps_per_period_, 100 * period_error(), dem::pi * damping_factor_ / 0.2,
                dem::pi * damping_factor_ / 0.1);
  return text;
}

nlohmann::json ContactResolution::state() const
{
  return {{"steps_per_period", exact(steps_per_period_)},
          {"smallest_bound_s", exact(smallest_bound_)},
          {"damping_factor", exact(damping_factor_)}};
}

void ContactResolution::restore(const nlohmann::json &state)
{
  steps_per_period_ = exact_value(state.at("steps_per_period"));
  smallest_bound_ = exact_value(state.at("smallest_bound_s"));
  damping_factor_ = exact_value(state.at("damping_factor"));
}

std::string checkpoint_state_file(const std::string &run_dir) { return run_dir + "/checkpoint/driver.json"; }
std::string checkpoint_sample_file(const std::string &run_dir, long step)
{
  return run_dir + "/checkpoint/state_" + std::to_string(step) + ".json";
}

void check_resumable(const std::string &run_dir, const Deck &deck)
{
  const nlohmann::json doc = read_checkpoint(run_dir);
  if (doc.value("deck_hash", "") != deck_hash(deck))
    throw DeckError(run_dir +
                    ": its checkpoint was written by another deck (or other --set values): expected "
                    "the deck the run started with, as recorded in " +
                    run_dir + "/deck.prm");
  // ... and with the files it read: a sample or particle file changed
  // between the pause and the resume would continue another run.
  const nlohmann::json recorded = doc.value("inputs", nlohmann::json::object());
  const nlohmann::json now = hash_input_files(deck.input_files());
  for (const auto &[path, hash] : recorded.items())
    if (!now.contains(path) || now.at(path) != hash)
      throw DeckError(run_dir + ": the input file " + path + (now.contains(path) ? " changed" : " is gone") +
                      " since the run began (its FNV-1a hash was " + hash.get<std::string>() +
                      "): expected the files the run started with, or the run from its start (--out " + run_dir +
                      " --replace)");
  // A run goes on bit for bit only with the arithmetic it started with.
  if (!made_by_this_build(doc.value("build", nlohmann::json())))
    throw DeckError(run_dir + ": its checkpoint was written by another build of demvv (its provenance is in " +
                    run_dir +
                    "/summary.json): expected the build the run started with, or the run from its start "
                    "(--out " +
                    run_dir + " --replace)");
}

DemOutcome run_dem(dem::Simulation &sim, DemProtocol &protocol, RunFiles &files, const DemOutputSpec &output,
                   const RunOptions &options)
{
  RunStatus status;
  Cadence cadence(protocol, files, output);
  RunDirectory *dir = files.directory();
  const std::string hash = dir ? dir->deck_hash() : "";
  if (!options.resume)
    try
    {
      check_reachable(sim, protocol);
    }
    catch (const DeckError &e)
    {
      if (dir)
        dir->write_summary({{"status", {{"state", "refused"}, {"message", e.what()}}}});
      throw;
    }
  if (dir && options.resume)
  {
    resume_from_checkpoint(sim, protocol, files, cadence, options.out_dir);
    dir->write_summary({{"status", {{"state", "running"}}}});
  }
  else if (dir)
  {
    const std::string cadence_note = output.interval > 0 ? "; a row every " + format_number(output.interval) + " of " +
                                                             protocol.clock_name() + " and at the last step"
                                                         : "; a row every step";
    for (const SeriesFile &f : protocol.series_files())
      f.series->stream_to(dir->path(f.file), f.comment + cadence_note);
  }

  const long steps_at_start = sim.steps();
  Progress progress(protocol.label(), options.progress, std::clamp(protocol.fraction_done(sim), 0.0, 1.0));
  StopSignals signals;
  ThreadGovernor governor(omp_get_max_threads(), thread_ceiling(options), threads_are_ours(options));
  const auto start = std::chrono::steady_clock::now();
  auto last_checkpoint = start;
  try
  {
    for (;;)
    {
      sim.step(cadence);
      if (cadence.last())
        break;
      governor.after_step();
      if (signals.received())
      {
        status.interrupted_by = signals.received();
        break;
      }
      if (options.pause_after > 0 && sim.steps() - steps_at_start >= options.pause_after)
      {
        status.paused = true;
        break;
      }
      if (dir && output.checkpoint_interval > 0)
      {
        const auto now = std::chrono::steady_clock::now();
        if (std::chrono::duration<double>(now - last_checkpoint).count() >= output.checkpoint_interval)
        {
          write_checkpoint(sim, protocol, files, cadence, options.out_dir, hash);
          last_checkpoint = now;
        }
      }
      if (progress.due())
      {
        const double rate = double(sim.particles().size()) * double(sim.steps() - steps_at_start) / progress.elapsed();
        const double done = std::clamp(protocol.fraction_done(sim), 0.0, 1.0);
        char speed[96];
        std::snprintf(speed, sizeof speed, "  step %ld of ~%.3g  %.3g particle-steps/s  %d thread%s", sim.steps(),
                      done > 0 ? double(sim.steps()) / done : double(sim.steps()), rate, governor.threads(),
                      governor.threads() == 1 ? "" : "s");
        progress.update(done, protocol.state_text(sim) + speed);
      }
    }
  }
  catch (const dem::NumericalFault &f)
  {
    record_fault(status, f);
    if (status.particle >= 0)
      status.particle = files.ball_id(status.particle);
  }
  progress.finish();
  const bool stopped_early = status.interrupted_by || status.paused;
  if (dir && stopped_early)
    write_checkpoint(sim, protocol, files, cadence, options.out_dir, hash);
  else if (dir)
    std::filesystem::remove_all(options.out_dir + "/checkpoint"); // a finished run has nothing to resume
  status.steps = sim.steps();
  status.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  nlohmann::json summary = protocol.summary(sim, status, cadence.resolution(), dir);
  const std::string warning = cadence.resolution().warning();
  if (protocol.resolves_contact_dynamics() && !warning.empty() && dir)
    std::cerr << "demvv: warning: " << warning << "\n";
  if (dir && summary.contains("warnings"))
    for (const auto &w : summary["warnings"])
      std::cerr << "demvv: warning: " << w.get<std::string>() << "\n";
  summary["status"] = status.to_json();
  summary["status"]["threads"] = governor.to_json();
  if (dir && stopped_early && options.resumable_alone)
    summary["status"]["resume"] = resume_command(dir->deck(), options);
  if (dir)
    dir->write_summary(summary);
  return {status, summary};
}
} // namespace demvv
