// Helpers shared by the check implementations (checks_*.cpp).
#pragma once

#include "app/run/analysis.h"

#include "app/decks/deck.h"
#include "app/io/series.h"
#include "app/kinds/scene.h"
#include "app/studies/sweep.h"
#include "verify/checks/check.h"

#include "dem/simulation.h"
#include "dem/small_systems.h"

#include <string>
#include <vector>

namespace demvv
{
/// Loads cases/<name>/case.prm with overrides and runs it in memory.
SceneResult run_case(const CheckContext &ctx, const std::string &name, const std::vector<std::string> &overrides = {});
/// Returns r, or throws (failing the check) if the run faulted or wrote nothing.
SceneResult completed(const std::string &name, SceneResult r);
Deck load_case(const CheckContext &ctx, const std::string &name, const std::vector<std::string> &overrides = {});

/// How a check runs a deck: in memory, quietly, on at most ctx.threads.
RunOptions run_options(const CheckContext &ctx);

/// First time at which `values` crosses `level` upwards, linearly
/// interpolated between rows; NaN if it never does.
double first_crossing(const std::vector<double> &time, const std::vector<double> &values, double level);

/// A directory under the system's temporary folder, removed with its
/// contents when this goes out of scope: where a check runs a sweep.
class ScratchDirectory
{
public:
  ScratchDirectory();
  ~ScratchDirectory();
  ScratchDirectory(const ScratchDirectory &) = delete;
  ScratchDirectory &operator=(const ScratchDirectory &) = delete;
  const std::string &path() const { return path_; }

private:
  std::string path_;
};

/// Sets the same entries ("SECTION/KEY=value", as --set) in every point of
/// a sweep: appends their keys to plan.keys and returns their values, with
/// which each point of the plan then begins.
std::vector<std::string> fix_entries(SweepPlan &plan, const std::vector<std::string> &entries);

/// Runs (or resumes) a sweep without progress output in a scratch
/// directory, which holds the members' run directories while it lives;
/// each member on at most ctx.threads.
SweepOutcome run_sweep_in(const CheckContext &ctx, const ScratchDirectory &scratch, const SweepPlan &plan);

/// Member `index` of a sweep, or throws (failing the check) naming `what`
/// when that member did not complete.
const SweepRow &completed_member(const SweepOutcome &outcome, std::size_t index, const std::string &what);

/// A number in a check's notes: format_number at six significant digits.
std::string num(double v);

/// Small systems in a line or three (dem/small_systems.h).
using dem::small_systems::ball;
using dem::small_systems::undamped;
} // namespace demvv
