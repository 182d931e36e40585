#include "verify/cli/commands.h"

#include "verify/checks/catalogue.h"
#include "verify/checks/check.h"
#include "verify/decks/deck.h"
#include "verify/io/output.h"
#include "verify/plot/run_figures.h"
#include "verify/report/report.h"
#include "verify/run/dem_driver.h"

#include "continuum/cylinder.h"

#include <mpi.h>

#include <algorithm>
#include <csignal>
#include <filesystem>
#include <iostream>
#include <memory>

namespace verify
{
namespace
{
const char *signal_name(int signal) { return signal == SIGINT ? "SIGINT" : signal == SIGTERM ? "SIGTERM" : "a signal"; }

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

/// After an output could not be written, summary.json says so instead of
/// "running" (if the disk still takes that much; otherwise stderr says it).
void mark_output_failure(const std::string &run_dir, const std::string &why)
{
  const std::string path = run_dir + "/summary.json";
  try
  {
    nlohmann::json summary = nlohmann::json::parse(read_file(path));
    summary["status"] = {{"state", "output failed"}, {"message", why}};
    write_atomically(path, json_text(summary, 2) + "\n");
  }
  catch (const std::exception &)
  {
    std::cerr << "demvv: " << path << " could not be marked as failed either: it may still say \"running\"\n";
  }
}

/// Draws a run's figures; one line for what could not be drawn.
void draw_run_figures(const std::string &run_dir, bool list_drawn)
{
  const std::vector<DrawnFigure> figures = plot_run(run_dir);
  const auto drawn = std::count_if(figures.begin(), figures.end(), [](const DrawnFigure &f) { return f.drawn(); });
  const std::string missing = undrawn(figures);
  if (list_drawn)
    std::cerr << "demvv: " << drawn << " figure" << (drawn == 1 ? "" : "s") << " in " << run_dir << "/plots\n";
  if (!missing.empty())
    std::cerr << "demvv: figures not drawn: " << missing << "\n";
}
} // namespace

/// Runs `claim` (which may throw a one-line error) on MPI rank 0 alone when
/// a kind runs on every rank, and gives every rank its verdict: all go on,
/// or all throw the same error (DeckError, exit 2; OutputError, exit 4).
/// No rank goes on before rank 0 is done, so none writes into a directory
/// that rank 0 is still emptying, and no rank waits for one that has quit.
void on_rank_zero_for_all(bool every_rank, const std::function<void()> &claim)
{
  if (!every_rank)
  {
    claim();
    return;
  }
  int code = 0;
  std::string message;
  if (continuum::parallel_info().rank == 0)
    try
    {
      claim();
    }
    catch (const OutputError &e)
    {
      code = 4;
      message = e.what();
    }
    catch (const std::exception &e)
    {
      code = 2;
      message = e.what();
    }
  int length = static_cast<int>(message.size());
  MPI_Bcast(&code, 1, MPI_INT, 0, MPI_COMM_WORLD);
  MPI_Bcast(&length, 1, MPI_INT, 0, MPI_COMM_WORLD);
  message.resize(static_cast<std::size_t>(length));
  MPI_Bcast(message.data(), length, MPI_CHAR, 0, MPI_COMM_WORLD);
  if (code == 4)
    throw OutputError(message);
  if (code != 0)
    throw DeckError(message);
}

int command_run(const std::string &deck_path, const std::vector<std::string> &overrides, const RunOptions &options)
{
  const Deck deck = Deck::from_file(deck_path, overrides);
  RunOptions o = options;
  if (o.out_dir.empty())
    o.out_dir = "runs/" + deck.name();
  const DeckKind *kind = find_deck_kind(deck.kind());
  if (!kind->pauses && (o.pause_after > 0 || o.resume))
    throw DeckError(std::string(o.resume ? "--resume" : "--pause-after " + std::to_string(o.pause_after)) +
                    ": a " + deck.kind() + " run has no checkpoint to pause at or resume from: expected it only "
                    "for scene and uniaxial decks (or a run without it)");
  std::unique_ptr<DirectoryLock> lock; // held until the run, its figures and its summary are done
  on_rank_zero_for_all(kind->on_every_mpi_rank, [&] {
    lock = std::make_unique<DirectoryLock>(o.out_dir, "run");
    if (!o.resume)
    {
      std::vector<std::string> inputs = deck.input_files();
      if (!deck.path().empty())
        inputs.push_back(std::filesystem::weakly_canonical(std::filesystem::absolute(deck.path())).string());
      claim_run_directory(o.out_dir, o.replace, [&] { kind->parse(deck); }, inputs);
    }
    else if (!marked_as(o.out_dir, "run"))
      throw DeckError("--resume '" + o.out_dir + "': holds no demvv marker (" + ownership_marker +
                      "), so it is no run directory demvv made: expected the directory of a paused or interrupted "
                      "run");
  });
  if (o.resume)
    check_resumable(o.out_dir, deck);
  RunStatus status;
  try
  {
    status = kind->run(deck, o);
  }
  catch (const OutputError &e)
  {
    mark_output_failure(o.out_dir, e.what());
    throw;
  }
  if (status.writes_run_directory)
    draw_run_figures(o.out_dir, false);
  tell(deck, o, status);
  return status.exit_code();
}

int command_plot(const std::string &run_dir)
{
  draw_run_figures(run_dir, true);
  return 0;
}

int command_defaults(const std::string &kind)
{
  std::cout << Deck::defaults(kind).documented();
  return 0;
}

int command_verify(bool full, const std::string &only, const std::string &out_dir, const std::string &cases_dir,
                   int threads)
{
  const int used = apply_threads({"", threads, false});
  CheckContext ctx{cases_dir.empty() ? default_cases_dir() : cases_dir, !full, threads};
  const std::vector<CheckRecord> records = run_checks(ctx, only, true);
  if (records.empty())
    throw DeckError("--only '" + only + "': no check id or title contains it");
  nlohmann::json prov = provenance(used, 0, "");
  prov["mode"] = full ? "full" : "quick";
  prov["cases_dir"] = ctx.cases_dir;
  write_reports(records, prov, out_dir);
  // A validation check that fails is a finding about the model, reported
  // with its verdict; it does not fail the run (a check that throws does).
  std::size_t failed = 0, passed = 0, model_errors = 0;
  for (const CheckRecord &r : records)
  {
    const bool validation = r.check->category == Category::validation && r.error.empty();
    passed += r.pass() ? 1 : 0;
    failed += r.pass() || validation ? 0 : 1;
    model_errors += !r.pass() && validation ? 1 : 0;
  }
  std::cerr << "demvv: " << passed << " of " << records.size() << " checks pass"
            << (model_errors ? "; " + std::to_string(model_errors) +
                                 " validation check(s) found a model error (reported, not a failure of the code)"
                             : "")
            << "; report in " << out_dir << "/report.html (and report.md, report.json)\n";
  return failed ? 1 : 0;
}

int command_catalogue(const std::string &out_file)
{
  const std::string text = verification_catalogue();
  write_named_output(out_file.empty() ? "-" : out_file, text);
  return 0;
}
} // namespace verify
