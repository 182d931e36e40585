#include "verify/cli/commands.h"

#include "verify/checks/catalogue.h"
#include "verify/checks/check.h"
#include "verify/decks/deck.h"
#include "verify/io/output.h"
#include "verify/report/report.h"
#include "verify/run/dem_driver.h"

#include <csignal>
#include <iostream>

namespace verify
{
namespace
{
const char *signal_name(int signal) { return signal == SIGINT ? "SIGINT" : signal == SIGTERM ? "SIGTERM" : "a signal"; }

/// The one line a finished run leaves on stderr.
void tell(const std::string &deck_path, const std::string &out_dir, const RunStatus &status)
{
  if (status.fault)
    std::cerr << "demvv: " << status.diagnostic() << "; outputs up to that point are in " << out_dir << "\n";
  else if (status.interrupted_by || status.paused)
    std::cerr << "demvv: " << (status.paused ? "paused" : "interrupted by ") << (status.paused ? "" : signal_name(status.interrupted_by))
              << " after step " << status.steps << "; outputs up to that point and a checkpoint are in " << out_dir
              << "; continue with: demvv run " << deck_path << " --resume " << out_dir << "\n";
  else
    std::cerr << "demvv: done in " << status.wall_seconds << " s (" << status.steps << " steps); results in "
              << out_dir << "\n";
}
} // namespace

int command_run(const std::string &deck_path, const std::vector<std::string> &overrides, const RunOptions &options)
{
  const Deck deck = Deck::from_file(deck_path, overrides);
  RunOptions o = options;
  if (o.out_dir.empty())
    o.out_dir = "runs/" + deck.name();
  const DeckKind *kind = find_deck_kind(deck.kind());
  if (o.resume)
    check_resumable(o.out_dir, deck);
  const RunStatus status = kind->run(deck, o);
  tell(deck_path, o.out_dir, status);
  return status.exit_code();
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
  CheckContext ctx{cases_dir.empty() ? default_cases_dir() : cases_dir, !full};
  const std::vector<CheckRecord> records = run_checks(ctx, only, true);
  if (records.empty())
    throw DeckError("--only '" + only + "': no check id or title contains it");
  nlohmann::json prov = provenance(used, 0, "");
  prov["mode"] = full ? "full" : "quick";
  prov["cases_dir"] = ctx.cases_dir;
  make_directories(out_dir);
  write_atomically(out_dir + "/report.json", json_text(report_json(records, prov), 2) + "\n");
  write_atomically(out_dir + "/report.md", report_markdown(records, prov));
  std::size_t failed = 0;
  for (const CheckRecord &r : records)
    failed += r.pass() ? 0 : 1;
  std::cerr << "demvv: " << records.size() - failed << " of " << records.size() << " checks pass; report in "
            << out_dir << "/report.md\n";
  return failed ? 1 : 0;
}

int command_catalogue(const std::string &out_file)
{
  const std::string text = verification_catalogue();
  if (out_file.empty())
    std::cout << text;
  else
    write_atomically(out_file, text);
  return 0;
}
} // namespace verify
