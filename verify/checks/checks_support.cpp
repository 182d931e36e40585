#include "verify/checks/checks_support.h"
#include "app/io/text.h"
#include "app/kinds/deck_kinds.h"

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <sstream>
#include <stdexcept>

namespace demvv
{
Deck load_case(const CheckContext &ctx, const std::string &name, const std::vector<std::string> &overrides)
{
  return Deck::from_file(deck_kinds(), ctx.case_deck(name), overrides);
}

RunOptions run_options(const CheckContext &ctx)
{
  RunOptions o = RunOptions::at_most(ctx.threads);
  o.progress = false;
  return o;
}

SceneResult run_case(const CheckContext &ctx, const std::string &name, const std::vector<std::string> &overrides)
{
  return completed(name, run_scene(load_case(ctx, name, overrides), run_options(ctx)));
}

SceneResult completed(const std::string &name, SceneResult r)
{
  if (r.status.fault)
    throw std::runtime_error(name + ": " + r.status.diagnostic());
  if (r.series.rows() == 0)
    throw std::runtime_error(name + ": the run produced no output rows");
  return r;
}

double first_crossing(const std::vector<double> &time, const std::vector<double> &values, double level)
{
  for (std::size_t k = 1; k < values.size(); ++k)
    if (values[k - 1] < level && values[k] >= level)
      return time[k - 1] + (level - values[k - 1]) / (values[k] - values[k - 1]) * (time[k] - time[k - 1]);
  return std::nan("");
}

ScratchDirectory::ScratchDirectory()
{
  static int count = 0;
  path_ = (std::filesystem::temp_directory_path() /
           ("demvv-check-" + std::to_string(::getpid()) + "-" + std::to_string(++count)))
            .string();
  std::filesystem::remove_all(path_);
}

ScratchDirectory::~ScratchDirectory()
{
  std::error_code ec;
  std::filesystem::remove_all(path_, ec);
}

std::vector<std::string> fix_entries(SweepPlan &plan, const std::vector<std::string> &entries)
{
  std::vector<std::string> values;
  for (const std::string &e : entries)
  {
    const std::size_t eq = e.find('=');
    plan.keys.push_back(e.substr(0, eq));
    values.push_back(e.substr(eq + 1));
  }
  return values;
}

SweepOutcome run_sweep_in(const CheckContext &ctx, const ScratchDirectory &scratch, const SweepPlan &plan)
{
  SweepSettings settings;
  settings.threads = ctx.threads;
  settings.out_dir = scratch.path() + "/sweep";
  settings.progress = false;
  settings.figures = false; // a check draws its own figures
  return run_sweep(plan, settings);
}

const SweepRow &completed_member(const SweepOutcome &outcome, std::size_t index, const std::string &what)
{
  const SweepRow &row = outcome.rows.at(index);
  if (row.status != "completed")
    throw std::runtime_error(what + ": " + row.status + ": " + row.message);
  return row;
}

std::string num(double v) { return format_number(v, 6); }
} // namespace demvv
