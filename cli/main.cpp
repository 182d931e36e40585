// demvv: the command-line entry point.
//
//   demvv run DECK [--out DIR [--replace]] [--set SECTION/KEY=VALUE]... [--threads N] [--quiet] [--resume RUN_DIR]
//   demvv sweep BASE_DECK --vary SECTION/KEY[+KEY...]=v1,v2,... [--vary ...] [--seeds N [--first-seed K]]
//               --out DIR [--replace] [--threads N] [--quiet]
//   demvv time-step BASE_DECK [--safety s1,s2,s3,...] [--seeds N] [--set SECTION/KEY=VALUE]... --out DIR
//   demvv calibrate BASE_DECK --fit KEY[+KEY...]=START --target QUANTITY=VALUE[,U] [--at KEY=VALUE] [--seeds N] --out DIR
//   demvv defaults KIND
//   demvv verify [--quick|--full] [--only PATTERN] [--out DIR] [--cases DIR] [--threads N]
//   demvv bench [--particles N] [--steps N] [--threads N]
//   demvv catalogue [--out FILE]
//   demvv plot RUN_DIR
//
// Exit codes: 0 success; 1 a verification check failed; 2 bad input or
// usage, including input that needs more memory than the machine has (most
// refused before allocating, any other allocation failure caught here);
// 3 the simulation stopped on a numerical fault (or a calibration did not
// reach its targets); 4 an output could not be
// written (a full disk: file and system reason named, rows before it whole);
// 130 / 143 the run was interrupted by SIGINT / SIGTERM (outputs kept,
// checkpoint written).
#include "app/decks/deck.h"
#include "app/io/input.h"
#include "app/io/output.h"
#include "app/kinds/deck_kinds.h"
#include "app/studies/calibrate.h"
#include "app/studies/sweep.h"
#include "app/studies/time_step_study.h"
#include "cli/bench.h"
#include "cli/commands.h"

#include <CLI/CLI.hpp>
#include <omp.h>

#include <csignal>
#include <cstdio>
#include <iostream>
#include <new>
#include <stdexcept>
#include <string>

namespace
{
/// Writes "demvv: WHY" to stderr in one piece, so that the lines of several
/// MPI ranks refusing at once never run into each other, and returns `code`.
int refuse(const std::string &why, int code)
{
  std::cerr << "demvv: " + demvv::readable_length(why) + "\n";
  return code;
}

/// `code`, or exit 4 when standard output could not be written (a full
/// disk, /dev/full): a report or catalogue that was not written is no
/// success.
int finish(int code)
{
  std::cout.flush();
  if (std::fflush(stdout) == 0 && std::cout && !std::ferror(stdout))
    return code;
  return refuse("standard output cannot be written (a full disk or device, or a closed pipe): what this command "
                "printed is incomplete",
                code == 0 ? 4 : code);
}

/// A directory option (--out) must name one: '' would fall back to a
/// default, and a control character (a newline) would be echoed into the
/// run's messages and records.
const CLI::Validator directory_name(
  [](std::string &value)
  {
    if (value.empty())
      return std::string("expected a directory name, found ''");
    if (const std::size_t bad = demvv::control_character(value); bad != std::string::npos)
      return "found '" + demvv::escaped(value) +
             "' with a control character: expected a directory name of printable "
             "text";
    return std::string();
  },
  "DIR");

/// A count option takes digits: CLI11 reads '1e3' as no integer and would
/// call it out of range.
const CLI::Validator whole_number(
  [](std::string &value)
  {
    const std::size_t digits = value.find_first_not_of("0123456789", value.rfind('+', 0) == 0 ? 1 : 0);
    if (value.empty() || digits != std::string::npos || value == "+")
      return "found '" + demvv::escaped(value) + "': expected a whole number written in digits (1000, not 1e3)";
    return std::string();
  },
  "");
} // namespace

int main(int argc, char **argv)
{
  // A file-size limit (ulimit -f) or a closed pipe makes write(2) fail with
  // EFBIG or EPIPE instead of killing the process mid-row: the output
  // error path (exit 4, rows before it whole, summary marked) handles it.
  std::signal(SIGXFSZ, SIG_IGN);
  std::signal(SIGPIPE, SIG_IGN);
  // OMP_NUM_THREADS above the cores is clamped as --threads is (results do
  // not depend on the count; 100 000 threads crashed the runtime).
  if (omp_get_max_threads() > omp_get_num_procs())
    omp_set_num_threads(omp_get_num_procs());

  CLI::App app{"demvv: DEM verification workbench (SI units, compression positive)"};
  app.require_subcommand(1);

  std::string deck_path, out_dir, kind;
  std::vector<std::string> overrides;
  int threads = 0;

  std::string kinds_help = "Deck kinds:";
  for (const demvv::DeckKind &k : demvv::deck_kinds())
    kinds_help += "\n  " + std::string(k.name) + ": " + std::string(k.summary);
  app.footer(kinds_help);

  bool quiet = false;
  std::string resume_dir;
  auto *run = app.add_subcommand("run", "Run a deck and write its run directory");
  run->add_option("DECK", deck_path, "Deck file (.prm or .json)")->required();
  run->add_option("--out", out_dir, "Run directory (default runs/<deck-name>): a new or empty directory")
    ->check(directory_name);
  bool replace = false;
  run->add_flag("--replace", replace,
                "Replace the run in a non-empty run directory whole (its old files removed once the deck is read "
                "and checked)");
  run->add_option("--set", overrides, "Override a deck entry: SECTION/KEY=VALUE (repeatable)");
  run
    ->add_option("--threads", threads,
                 "OpenMP threads, at most: a DEM run starts on N or the idle cores if fewer, and moves between one and "
                 "N as the load does (a busy machine); results never depend on it (default: OMP_NUM_THREADS, kept "
                 "exactly, else the cores no other process is busy on, then up to every core)")
    ->check(whole_number)
    ->check(CLI::Range(1, 1024));
  run->add_flag("--quiet", quiet, "No progress line (it is shown only when standard output is a terminal)");
  run
    ->add_option("--resume", resume_dir,
                 "Continue the interrupted run in RUN_DIR from its checkpoint, bit for bit; the deck and --set "
                 "values must be those it started with")
    ->check(directory_name);
  long pause_after = 0;
  run
    ->add_option("--pause-after", pause_after,
                 "Stop after this many steps as an interruption would (outputs flushed, checkpoint written, "
                 "exit 0), e.g. to fit a long run into batch-queue jobs; continue with --resume")
    ->check(whole_number)
    ->check(CLI::Range(1L, 1000000000000L));
  run->footer(kinds_help);

  demvv::SweepOptions sweep;
  auto *sweep_cmd = app.add_subcommand(
    "sweep", "Run a deck over every combination of varied entries and seeds; sweep.csv and stats.csv in --out "
             "(rerun to resume; under mpirun the ranks share the members)");
  sweep_cmd->add_option("BASE_DECK", sweep.base_deck, "The deck every member starts from")->required();
  sweep_cmd->add_option("--vary", sweep.vary,
                        "SECTION/KEY=v1,v2,...: the values of one deck entry (repeatable; members are the "
                        "product); SECTION/KEY+SECTION/KEY=v1,...: entries tied to one value each");
  auto *sweep_seeds =
    sweep_cmd
      ->add_option("--seeds", sweep.seeds,
                   "Run each combination with seeds K..K+N-1 (bond strengths and, for a sample from a prepare "
                   "deck, the packing); default: the deck's own seeds")
      ->check(whole_number)
      ->check(CLI::Range(1, 100000));
  sweep_cmd
    ->add_option("--first-seed", sweep.first_seed,
                 "K, the first of the --seeds (default 1; another K: another seed set, e.g. packings a "
                 "calibration never saw)")
    ->needs(sweep_seeds)
    ->check(whole_number)
    ->check(CLI::Range(1, 1000000));
  sweep_cmd->add_option("--out", sweep.settings.out_dir, "Sweep directory: new, empty, or this sweep's (resumed)")
    ->required()
    ->check(directory_name);
  sweep_cmd->add_flag("--replace", sweep.settings.replace,
                      "Start the sweep in --out over (only a sweep directory is emptied)");
  sweep_cmd
    ->add_option("--threads", sweep.settings.threads,
                 "OpenMP threads per member, at most, changed during a DEM member as the load does (default: "
                 "OMP_NUM_THREADS, kept exactly, else the idle cores, shared among MPI ranks)")
    ->check(whole_number)
    ->check(CLI::Range(1, 1024));
  sweep_cmd
    ->add_option("--max-members", sweep.settings.max_members,
                 "The most members the sweep may have (default 10000); more are refused before planning")
    ->check(whole_number)
    ->check(CLI::Range(std::size_t{1}, std::size_t{100000000}));
  bool sweep_quiet = false;
  sweep_cmd->add_flag("--quiet", sweep_quiet, "No progress line and no opening line");
  sweep_cmd->footer(kinds_help);

  demvv::TimeStepStudyOptions time_step;
  auto *time_step_cmd = app.add_subcommand(
    "time-step", "Measure the time-step error of a uniaxial deck's bulk results on seed ensembles (the same seeds at "
                 "every time-step safety); time_step_study.csv/.json in --out (rerun to resume)");
  time_step_cmd->add_option("BASE_DECK", time_step.base_deck, "The uniaxial deck every member starts from")->required();
  time_step_cmd
    ->add_option("--safety", time_step.safety_text,
                 "Time-step safeties (fractions of the critical step bound), coarse to fine, at least "
                 "three in (0, 1] (default 0.8,0.4,0.2)")
    ->delimiter(',');
  time_step_cmd->add_option("--seeds", time_step.seeds, "Seeds per level, at least 2 (default 5)")->check(whole_number);
  time_step_cmd->add_option("--set", time_step.sets,
                            "Set a deck entry in every member: SECTION/KEY=VALUE (repeatable)");
  time_step_cmd
    ->add_option("--out", time_step.settings.out_dir, "Study directory: new, empty, or this study's (resumed)")
    ->required()
    ->check(directory_name);
  time_step_cmd->add_flag("--replace", time_step.settings.replace, "Start the study in --out over");
  time_step_cmd->add_option("--threads", time_step.settings.threads, "OpenMP threads per member, at most")
    ->check(whole_number)
    ->check(CLI::Range(1, 1024));
  bool time_step_quiet = false;
  time_step_cmd->add_flag("--quiet", time_step_quiet, "No progress line and no opening line");

  demvv::CalibrationOptions calibration;
  auto *calibrate_cmd = app.add_subcommand(
    "calibrate", "Fit deck parameters to target quantities of uniaxial runs at one condition (GSL nonlinear least "
                 "squares over seed ensembles); calibration.json, evaluations.csv and fitted.prm in --out (rerun to "
                 "resume)");
  calibrate_cmd->add_option("BASE_DECK", calibration.base_deck, "The uniaxial deck every evaluation starts from")
    ->required();
  calibrate_cmd
    ->add_option("--fit", calibration.fit,
                 "KEY[+KEY...]=START: deck entries that take one fitted positive value, and its start "
                 "(repeatable)")
    ->required();
  calibrate_cmd
    ->add_option("--target", calibration.targets,
                 "QUANTITY=VALUE[,UNCERTAINTY]: peak_stress_pa [Pa], strain_at_peak [-], "
                 "initial_modulus_pa [Pa] or poisson_ratio [-], its target and the target's standard "
                 "uncertainty (repeatable)")
    ->required();
  calibrate_cmd->add_option("--at", calibration.at,
                            "KEY=VALUE: the calibration condition, set in every evaluation as --set would "
                            "(repeatable)");
  calibrate_cmd->add_option("--seeds", calibration.seeds, "Seeds per evaluation (default 3)")
    ->check(whole_number)
    ->check(CLI::Range(2, 100000));
  calibrate_cmd
    ->add_option("--first-seed", calibration.first_seed,
                 "The seeds are K ... K + N - 1 (default 1; another K: another seed set)")
    ->check(whole_number)
    ->check(CLI::Range(1, 1000000));
  calibrate_cmd->add_option("--step", calibration.step,
                            "Finite-difference step in ln(value) for the Jacobian (default 0.05; doubled where the "
                            "slope is lost in the seed noise)");
  calibrate_cmd->add_option("--tolerance", calibration.tolerance,
                            "Relative residual that meets a target even when the seed noise is smaller (default "
                            "0.005)");
  calibrate_cmd->add_option("--max-iterations", calibration.max_iterations, "Iterations at most (default 10)");
  calibrate_cmd
    ->add_option("--out", calibration.settings.out_dir,
                 "Calibration directory: new, empty, or this calibration's (resumed)")
    ->required()
    ->check(directory_name);
  calibrate_cmd->add_flag("--replace", calibration.settings.replace,
                          "Start the calibration in --out over (only a calibration directory is emptied)");
  calibrate_cmd
    ->add_option("--threads", calibration.settings.threads,
                 "OpenMP threads per run, at most, changed during a run as the load does (default: "
                 "OMP_NUM_THREADS, kept exactly, else the idle cores, shared among MPI ranks)")
    ->check(whole_number)
    ->check(CLI::Range(1, 1024));
  bool calibrate_quiet = false;
  calibrate_cmd->add_flag("--quiet", calibrate_quiet, "No progress lines (the evaluations and their members)");

  auto *defaults = app.add_subcommand("defaults", "Print a complete, documented deck of a kind");
  defaults->add_option("KIND", kind, "Deck kind")->required();
  defaults->footer(kinds_help);

  bool quick = false, full = false;
  std::string only, cases_dir;
  auto *verify_cmd = app.add_subcommand("verify", "Run the verification checks and write report.md / report.json");
  verify_cmd->add_flag("--quick", quick, "Short versions of the long checks (default)");
  verify_cmd->add_flag("--full", full, "Full versions of the long checks");
  verify_cmd->add_option("--only", only, "Run only checks whose id or title contains PATTERN");
  verify_cmd->add_option("--out", out_dir, "Report directory (default runs/verify)")->check(directory_name);
  verify_cmd->add_option("--cases", cases_dir, "Case decks directory (default: the source tree's cases/)");
  verify_cmd
    ->add_option("--threads", threads,
                 "OpenMP threads, at most, for each run of a check (default: OMP_NUM_THREADS, kept exactly, "
                 "else the cores no other process is busy on)")
    ->check(whole_number)
    ->check(CLI::Range(1, 1024));

  demvv::BenchOptions bench;
  auto *bench_cmd = app.add_subcommand("bench", "Time the engine on a bonded sample and print one line");
  bench_cmd->add_option("--particles", bench.particles, "Number of balls, at least 100 (default 6000)")
    ->check(whole_number)
    ->check(CLI::Range(100L, 100000000L));
  bench_cmd->add_option("--steps", bench.steps, "Timed steps (default 2000)")
    ->check(whole_number)
    ->check(CLI::Range(1L, 1000000000L));
  bench_cmd->add_option("--threads", bench.threads, "OpenMP threads")->check(whole_number)->check(CLI::Range(1, 1024));
  bench_cmd->add_option("--repeat", bench.repeat, "Timings to take; the fastest is reported (default 3)")
    ->check(whole_number)
    ->check(CLI::Range(1, 100));
  bench_cmd->add_option("--lattice", bench.lattice, "Sample lattice: sc (coordination 6) or fcc (12)");
  bench_cmd->add_option("--law", bench.law, "Contact law keyword");
  bench_cmd->add_option("--sample", bench.sample,
                        "A prepared sample (sample.json or a prepare deck, prepared once and cached) instead of the "
                        "lattice; --particles is then ignored");

  std::string plot_dir;
  auto *plot_cmd =
    app.add_subcommand("plot", "Draw (again) the figures of a run directory into RUN_DIR/plots (gnuplot, SVG)");
  plot_cmd->add_option("RUN_DIR", plot_dir, "A run directory (it holds summary.json)")->required();

  std::string catalogue_out;
  auto *catalogue_cmd =
    app.add_subcommand("catalogue", "Write the verification catalogue (Markdown) generated from the check registry");
  catalogue_cmd->add_option(
    "--out", catalogue_out,
    "File to write (default or -: standard output; a device such as /dev/null is written through)");

  try
  {
    app.parse(argc, argv);
  }
  catch (const CLI::CallForHelp &e)
  {
    return finish(app.exit(e));
  }
  catch (const CLI::CallForAllHelp &e)
  {
    return finish(app.exit(e));
  }
  catch (const CLI::ParseError &e)
  {
    return refuse(std::string(e.what()) + " (see demvv --help)", 2);
  }

  try
  {
    if (run->parsed())
    {
      if (!resume_dir.empty() && !out_dir.empty() && out_dir != resume_dir)
        throw demvv::DeckError("--resume '" + resume_dir + "' and --out '" + out_dir +
                               "': a resumed run continues in its own directory: expected no --out");
      if (!resume_dir.empty() && replace)
        throw demvv::DeckError("--resume '" + resume_dir +
                               "' and --replace: a resumed run continues the files in its directory: expected one "
                               "of them");
      demvv::RunOptions options = demvv::RunOptions::at_most(threads);
      options.out_dir = resume_dir.empty() ? out_dir : resume_dir;
      options.progress = !quiet;
      options.resume = !resume_dir.empty();
      options.pause_after = pause_after;
      options.replace = replace;
      return finish(demvv::command_run(deck_path, overrides, options));
    }
    if (sweep_cmd->parsed())
    {
      sweep.settings.progress = !sweep_quiet;
      for (int i = 0; i < argc; ++i)
        sweep.settings.command_line += (i ? " " : "") + std::string(argv[i]);
      return finish(demvv::command_sweep(sweep));
    }
    if (time_step_cmd->parsed())
    {
      time_step.settings.progress = !time_step_quiet;
      for (int i = 0; i < argc; ++i)
        time_step.settings.command_line += (i ? " " : "") + std::string(argv[i]);
      return finish(demvv::command_time_step(time_step));
    }
    if (calibrate_cmd->parsed())
    {
      calibration.settings.progress = !calibrate_quiet;
      for (int i = 0; i < argc; ++i)
        calibration.settings.command_line += (i ? " " : "") + std::string(argv[i]);
      return finish(demvv::command_calibrate(calibration));
    }
    if (defaults->parsed())
      return finish(demvv::command_defaults(kind));
    if (bench_cmd->parsed())
      return finish(demvv::command_bench(bench));
    if (verify_cmd->parsed())
    {
      if (quick && full)
        throw demvv::DeckError("--quick and --full exclude each other");
      return finish(demvv::command_verify(full, only, out_dir.empty() ? "runs/verify" : out_dir, cases_dir, threads));
    }
    if (plot_cmd->parsed())
      return finish(demvv::command_plot(plot_dir));
    if (catalogue_cmd->parsed())
      return finish(demvv::command_catalogue(catalogue_out));
  }
  catch (const demvv::DeckError &e)
  {
    return refuse(e.what(), 2);
  }
  catch (const demvv::OutputError &e)
  {
    return refuse(std::string(e.what()) + "; every row and file written before is complete", 4);
  }
  catch (const demvv::Interrupted &e)
  {
    return refuse(e.what(), 128 + e.signal);
  }
  catch (const std::runtime_error &e)
  {
    return refuse(e.what(), 2);
  }
  catch (const std::bad_alloc &)
  {
    // One literal, one write, nothing allocated.
    std::cerr << "demvv: out of memory: the input needs more memory than this process may have (the machine's, or "
                 "a limit such as ulimit -v): expected fewer balls or a smaller input\n";
    return 2;
  }
  catch (const std::length_error &e)
  {
    return refuse("out of memory (" + std::string(e.what()) + "): expected fewer balls or a smaller input", 2);
  }
  return 0;
}
