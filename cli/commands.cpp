#include "cli/commands.h"

#include "app/decks/deck.h"
#include "app/io/input.h"
#include "app/io/output.h"
#include "app/kinds/deck_kinds.h"
#include "app/plot/run_figures.h"
#include "app/run/dem_driver.h"
#include "app/studies/ranks.h"
#include "verify/checks/catalogue.h"
#include "verify/checks/check.h"
#include "verify/report/report.h"

#include "continuum/cylinder.h"

#include <mpi.h>

#include <algorithm>
#include <csignal>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>

namespace demvv
{
namespace
{

/// The one line a finished run leaves on stderr.
void tell(const DeckRecord &deck, const RunOptions &o, const RunStatus &status)
{
  if (status.fault)
  {
    std::cerr << "demvv: " << status.diagnostic() << "; outputs up to that point are in " << o.out_dir << "\n";
    return;
  }
  if (!status.interrupted_by && !status.paused)
  {
    std::cerr << "demvv: done in " << status.wall_seconds << " s (" << status.steps << " steps); results in "
              << o.out_dir << (status.verdict.empty() ? "" : "; " + status.verdict) << "\n";
    return;
  }
  const std::string stopped =
    status.paused ? std::string("paused") : std::string("interrupted by ") + signal_name(status.interrupted_by);
  if (std::filesystem::exists(checkpoint_state_file(o.out_dir)))
    std::cerr << "demvv: " << stopped << " after step " << status.steps
              << "; outputs up to that point and a checkpoint are in " << o.out_dir
              << "; continue with: " << resume_command(deck, o) << "\n";
  else
    std::cerr << "demvv: " << stopped << "; outputs up to that point are in " << o.out_dir
              << "; this kind of run cannot be resumed: run it again with --replace\n";
}

/// Sets one entry of a run's summary.json after the run wrote it; `unsaid`
/// goes to stderr when the summary cannot be rewritten (the disk may be full).
void amend_summary(const std::string &run_dir, const std::string &key, const nlohmann::json &value,
                   const std::string &unsaid)
{
  const std::string path = run_dir + "/summary.json";
  try
  {
    nlohmann::json summary = nlohmann::json::parse(read_file(path));
    summary[key] = value;
    write_atomically(path, json_text(summary, 2) + "\n");
  }
  catch (const std::exception &)
  {
    std::cerr << "demvv: " << path << " " << unsaid << "\n";
  }
}

/// A signal stopped the drawing of a finished run's figures: summary.json
/// keeps its state and says which figures may be missing and how to draw them.
void mark_figures_interrupted(const std::string &run_dir, int signal)
{
  amend_summary(run_dir, "figures",
                {{"interrupted_by", signal_name(signal)},
                 {"note", "the drawing of the figures was stopped: some may be missing"},
                 {"draw_with", "demvv plot " + run_dir}},
                "could not say that its figures were interrupted");
}

/// After an output could not be written, summary.json says so instead of
/// "running" (if the disk still takes that much; otherwise stderr says it).
void mark_output_failure(const std::string &run_dir, const std::string &why)
{
  amend_summary(run_dir, "status", {{"state", "output failed"}, {"message", why}},
                "could not be marked as failed either: it may still say \"running\"");
}

/// Draws a run's figures; one line for what could not be drawn.
void draw_run_figures(const std::string &run_dir, bool list_drawn)
{
  const std::vector<DrawnFigure> figures = plot_run(run_dir, deck_kinds());
  const auto drawn = std::count_if(figures.begin(), figures.end(), [](const DrawnFigure &f) { return f.drawn(); });
  const std::string missing = undrawn(figures);
  if (list_drawn)
    std::cerr << "demvv: " << drawn << " figure" << (drawn == 1 ? "" : "s") << " in " << run_dir << "/plots\n";
  if (!missing.empty())
    std::cerr << "demvv: figures not drawn: " << missing << "\n";
}
} // namespace

int command_run(const std::string &deck_path, const std::vector<std::string> &overrides, const RunOptions &options)
{
  // A deck refuses a key set twice; so does the command line.
  refuse_repeated_overrides(overrides);
  const Deck deck = Deck::from_file(deck_kinds(), deck_path, overrides);
  RunOptions o = options;
  if (o.out_dir.empty())
    o.out_dir = "runs/" + deck.name();
  const DeckKind *kind = &deck.kind_row();
  if (!kind->pauses && (o.pause_after > 0 || o.resume))
    throw DeckError(std::string(o.resume ? "--resume" : "--pause-after " + std::to_string(o.pause_after)) + ": a " +
                    deck.kind() +
                    " run has no checkpoint to pause at or resume from: expected it only "
                    "for scene and uniaxial decks (or a run without it)");
  std::unique_ptr<DirectoryLock> lock; // held until the run, its figures and its summary are done
  ParsedRun parsed;                    // the claim's parse, run below (parsed once)
  on_rank_zero_for_all(kind->on_every_mpi_rank,
                       [&]
                       {
                         lock = std::make_unique<DirectoryLock>(o.out_dir, "run");
                         if (!o.resume)
                         {
                           std::vector<std::string> inputs = deck.input_files();
                           if (!deck.path().empty())
                             inputs.push_back(
                               std::filesystem::weakly_canonical(std::filesystem::absolute(deck.path())).string());
                           claim_run_directory(
                             o.out_dir, o.replace, [&] { parsed = kind->parse(deck); }, inputs);
                         }
                         else if (const std::string problem = marker_problem(o.out_dir, "run"); !problem.empty())
                           throw DeckError("--resume '" + o.out_dir + "': no run directory demvv made (" + problem +
                                           "): expected the directory of a paused or interrupted run");
                       });
  if (o.resume)
    check_resumable(o.out_dir, deck);
  RunStatus status;
  try
  {
    if (!parsed) // resumed, or a rank that left the claim to rank 0
      parsed = kind->parse(deck);
    status = parsed(o);
  }
  catch (const OutputError &e)
  {
    mark_output_failure(o.out_dir, e.what());
    throw;
  }
  catch (const Interrupted &e)
  {
    // A run stopped before its first step (preparing its sample) may have
    // written no summary yet: then there is nothing that says "running".
    if (std::filesystem::exists(o.out_dir + "/summary.json"))
      amend_summary(o.out_dir, "status",
                    {{"state", "interrupted"}, {"signal", signal_name(e.signal)}, {"message", e.what()}},
                    "could not be marked as interrupted: it may still say \"running\"");
    throw;
  }
  int stopped_while_drawing = 0;
  if (status.writes_run_directory)
  {
    // A signal while gnuplot draws reaches it too (one process group): the
    // run's results are whole, its figures are not, and both are said.
    const StopSignals signals;
    draw_run_figures(o.out_dir, false);
    stopped_while_drawing = signals.received();
    if (stopped_while_drawing)
      mark_figures_interrupted(o.out_dir, stopped_while_drawing);
  }
  tell(deck, o, status);
  if (stopped_while_drawing)
  {
    // The results are complete only if the run itself was not stopped
    // (a second signal may come while the figures of a stopped run are drawn).
    std::cerr << "demvv: " << signal_name(stopped_while_drawing) << " while drawing the figures: the run's results in "
              << o.out_dir << (status.exit_code() == 0 ? " are complete" : " are as the line above says")
              << ", some figures may be missing; draw them with: demvv plot " << o.out_dir << "\n";
    return 128 + stopped_while_drawing;
  }
  return status.exit_code();
}

int command_plot(const std::string &run_dir)
{
  const StopSignals signals;
  draw_run_figures(run_dir, true);
  if (const int stopped = signals.received())
  {
    mark_figures_interrupted(run_dir, stopped);
    return 128 + stopped;
  }
  // Drawn whole: a summary that said a drawing was interrupted says so no more.
  const std::string path = run_dir + "/summary.json";
  try
  {
    const nlohmann::json summary =
      parse_json_input(read_input(path, "run summary", max_summary_bytes), path, "run summary");
    if (summary.contains("figures") && summary.at("figures").contains("interrupted_by"))
      amend_summary(run_dir, "figures", {{"drawn_by", "demvv plot " + run_dir}},
                    "could not say that its figures are drawn");
  }
  catch (const std::exception &)
  {
    // The figures were drawn; a summary that cannot be read again keeps what it said.
  }
  return 0;
}

int command_defaults(const std::string &kind)
{
  std::cout << Deck::defaults(deck_kinds(), kind).documented();
  return 0;
}

int command_verify(bool full, const std::string &only, const std::string &out_dir, const std::string &cases_dir,
                   int threads)
{
  if (!cases_dir.empty() && !std::filesystem::is_directory(cases_dir))
    throw DeckError("--cases '" + cases_dir +
                    "': not a directory: expected the folder of the case decks (default: " + default_cases_dir() + ")");
  // The report's folder, taken before any check runs: new, empty, or a
  // report folder demvv made (its report replaced); a user's own folder is
  // never written into.
  make_directories(out_dir);
  const DirectoryLock lock(out_dir, "report");
  claim_resumable_directory(out_dir, true, "report", ownership_marker);
  const int used = apply_threads({"", threads, false});
  CheckContext ctx{cases_dir.empty() ? default_cases_dir() : cases_dir, !full, threads, {}};
  std::vector<CheckRecord> records;
  try
  {
    records = run_checks(ctx, only, true);
  }
  catch (const MissingCaseDeck &e)
  {
    throw DeckError(std::string("--cases: ") + e.what() +
                    ": expected the folder of the case decks (default: " + default_cases_dir() + ")");
  }
  if (records.empty())
    throw DeckError("--only '" + only + "': no check id or title contains it");
  nlohmann::json prov = provenance(used, 0, "");
  prov.erase("deck_fnv1a64"); // a verification runs many case decks, not one
  prov["mode"] = full ? "full" : "quick";
  prov["cases_dir"] = ctx.cases_dir;
  write_reports(records, prov, out_dir);
  // A validation check that fails is a finding about the model, reported
  // with its verdict; it does not fail the run (a check that throws does).
  const Headline head = headline(records);
  std::cerr << "demvv: " << head.text() << "; report in " << out_dir << "/report.html (and report.md, report.json)\n";
  return head.code_failures ? 1 : 0;
}

int command_catalogue(const std::string &out_file)
{
  const std::string text = verification_catalogue();
  write_named_output(out_file.empty() ? "-" : out_file, text);
  return 0;
}
} // namespace demvv
