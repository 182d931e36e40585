#include "verify/cli/commands.h"

#include "verify/checks/catalogue.h"
#include "verify/checks/check.h"
#include "verify/kinds/continuum_cylinder.h"
#include "verify/kinds/continuum_mms.h"
#include "verify/kinds/continuum_ode.h"
#include "verify/decks/deck.h"
#include "verify/kinds/prepare.h"
#include "verify/io/output.h"
#include "verify/report/report.h"
#include "verify/kinds/scene.h"
#include "verify/kinds/uniaxial.h"

#include <iostream>

namespace verify
{
namespace
{
int report(const std::string &out_dir, const RunStatus &status)
{
  if (status.fault)
  {
    std::cerr << "demvv: " << status.diagnostic() << "; outputs up to that point are in " << out_dir << "\n";
    return 3;
  }
  std::cerr << "demvv: done in " << status.wall_seconds << " s (" << status.steps << " steps); results in "
            << out_dir << "\n";
  return 0;
}

int run_scene_deck(const Deck &deck, const RunOptions &o) { return report(o.out_dir, run_scene(deck, o).status); }
int run_uniaxial_deck(const Deck &deck, const RunOptions &o) { return report(o.out_dir, run_uniaxial(deck, o).status); }
int run_prepare_deck(const Deck &deck, const RunOptions &o) { return report(o.out_dir, run_prepare(deck, o).status); }
int run_ode_deck(const Deck &deck, const RunOptions &o) { return report(o.out_dir, run_burgers_ode(deck, o).status); }
int run_cylinder_deck(const Deck &deck, const RunOptions &o) { return report(o.out_dir, run_cylinder(deck, o).status); }
int run_study_deck(const Deck &deck, const RunOptions &o) { return report(o.out_dir, run_mms_deck(deck, o).status); }

struct Runner
{
  const char *kind;
  int (*run)(const Deck &, const RunOptions &);
};

const Runner runners[] = {
  {"scene", &run_scene_deck},
  {"uniaxial", &run_uniaxial_deck},
  {"prepare", &run_prepare_deck},
  {"burgers_ode", &run_ode_deck},
  {"cylinder", &run_cylinder_deck},
  {"mms", &run_study_deck},
};
} // namespace

int command_run(const std::string &deck_path, const std::vector<std::string> &overrides, const RunOptions &options)
{
  const Deck deck = Deck::from_file(deck_path, overrides);
  RunOptions o = options;
  if (o.out_dir.empty())
    o.out_dir = "runs/" + deck.name();
  for (const Runner &r : runners)
    if (deck.kind() == r.kind)
      return r.run(deck, o);
  throw DeckError(deck_path + ": decks of kind '" + deck.kind() + "' cannot be run yet");
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
  write_atomically(out_dir + "/report.json", report_json(records, prov).dump(2) + "\n");
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
