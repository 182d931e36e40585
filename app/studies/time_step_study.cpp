#include "app/studies/time_step_study.h"

#include "app/decks/deck.h"
#include "app/io/output.h"
#include "app/kinds/deck_kinds.h"
#include "app/plot/gnuplot.h"
#include "app/plot/studies.h"

#include <gsl/gsl_cdf.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <sstream>

namespace demvv
{
namespace
{
const std::string safety_key = "motion/time step safety";
const std::string fixed_step_key = "motion/fixed time step";

/// A bulk quantity every uniaxial run writes, as a sweep reads it.
struct Quantity
{
  const char *name, *title, *axis;
  double scale; ///< display unit
  double SweepRow::*value;
};

const std::vector<Quantity> &quantities()
{
  static const std::vector<Quantity> q = {
    {"peak_stress_pa", "Peak stress", "peak stress [MPa]", 1e-6, &SweepRow::peak},
    {"strain_at_peak", "Strain at the peak", "strain at the peak [%]", 100, &SweepRow::strain},
    {"initial_modulus_pa", "Initial modulus", "initial modulus [GPa]", 1e-9, &SweepRow::modulus},
  };
  return q;
}

double t95(std::size_t n) { return n >= 2 ? gsl_cdf_tdist_Pinv(0.975, double(n - 1)) : std::nan(""); }

/// Seed-by-seed differences b - a where both are finite.
std::vector<double> paired(const std::vector<double> &a, const std::vector<double> &b)
{
  std::vector<double> d;
  for (std::size_t j = 0; j < a.size() && j < b.size(); ++j)
    if (std::isfinite(a[j]) && std::isfinite(b[j]))
      d.push_back(b[j] - a[j]);
  return d;
}

/// The order from the paired changes d1 (coarse to middle) and d2 (middle
/// to fine), levels in the ratio r; the delta method's 95 % interval.
ObservedOrder observed_order(const std::vector<double> &coarse, const std::vector<double> &middle,
                             const std::vector<double> &fine, const LevelChange &c1, const LevelChange &c2, double r)
{
  ObservedOrder o;
  const double d1 = c1.difference.mean, d2 = c2.difference.mean;
  if (!c1.resolved || !c2.resolved || d1 * d2 <= 0)
    return o;
  o.resolved = true;
  o.order = std::log(d1 / d2) / std::log(r);
  // Covariance of the two changes' means, over the seeds where all three levels have values.
  std::vector<double> x, y;
  for (std::size_t j = 0; j < coarse.size(); ++j)
    if (std::isfinite(coarse[j]) && std::isfinite(middle[j]) && std::isfinite(fine[j]))
    {
      x.push_back(middle[j] - coarse[j]);
      y.push_back(fine[j] - middle[j]);
    }
  double cov = 0;
  if (x.size() >= 2)
  {
    const double mx = ensemble_statistics(x).mean, my = ensemble_statistics(y).mean;
    for (std::size_t k = 0; k < x.size(); ++k)
      cov += (x[k] - mx) * (y[k] - my);
    cov /= double(x.size() - 1) * double(x.size());
  }
  const double se1 = c1.difference.se, se2 = c2.difference.se;
  const double var = std::max(0.0, se1 * se1 / (d1 * d1) + se2 * se2 / (d2 * d2) - 2 * cov / (d1 * d2));
  const std::size_t n = std::min(c1.difference.n, c2.difference.n);
  const double half = t95(n) * std::sqrt(var) / std::log(r);
  o.low = o.order - half;
  o.high = o.order + half;
  return o;
}

bool constant_ratio(const std::vector<double> &s)
{
  for (std::size_t i = 2; i < s.size(); ++i)
    if (std::abs(s[i - 2] / s[i - 1] - s[i - 1] / s[i]) > 1e-9 * (s[i - 2] / s[i - 1]))
      return false;
  return true;
}
} // namespace

double LevelChange::bound() const { return std::abs(difference.mean) + difference.ci95; }

TimeStepAnalysis analyse_time_step(const std::vector<double> &safety, const std::vector<std::vector<double>> &values)
{
  TimeStepAnalysis a;
  a.safety = safety;
  const std::size_t L = safety.size();
  for (const std::vector<double> &v : values)
    a.level.push_back(ensemble_statistics(v));
  for (std::size_t i = 0; i + 1 < L; ++i)
  {
    LevelChange c;
    c.difference = ensemble_statistics(paired(values[i], values[i + 1]));
    c.resolved =
      c.difference.n >= 2 && std::isfinite(c.difference.ci95) && std::abs(c.difference.mean) > c.difference.ci95;
    a.change.push_back(c);
  }
  if (constant_ratio(safety))
    for (std::size_t i = 0; i + 2 < L; ++i)
      a.order.push_back(observed_order(values[i], values[i + 1], values[i + 2], a.change[i], a.change[i + 1],
                                       safety[i] / safety[i + 1]));
  // The finest level's own error: Richardson where the finest order is
  // resolved (and positive), else the bound of the last change for p >= 1.
  const LevelChange &last = a.change.back();
  const double r = safety[L - 2] / safety[L - 1];
  double finest_error = last.bound() / (r - 1);
  if (!a.order.empty() && a.order.back().resolved && a.order.back().order > 0)
  {
    const double factor = std::pow(r, a.order.back().order) - 1;
    a.extrapolated = a.level.back().mean + last.difference.mean / factor;
    finest_error = 1.25 * std::abs(last.difference.mean) / factor;
  }
  for (std::size_t i = 0; i < L; ++i)
  {
    const double to_finest = i + 1 == L ? 0.0
                                        : [&]
    {
      const EnsembleStatistics d = ensemble_statistics(paired(values[i], values[L - 1]));
      return std::abs(d.mean) + (std::isfinite(d.ci95) ? d.ci95 : std::abs(d.mean));
    }();
    a.error_bound.push_back(to_finest + finest_error);
  }
  return a;
}

namespace
{
/// Refuses what the study cannot measure, before any member runs.
void check_options(const TimeStepStudyOptions &o, const std::vector<double> &safety)
{
  const std::string where = "time-step study of " + o.base_deck;
  if (o.seeds < 2)
    throw DeckError(where + ": --seeds " + std::to_string(o.seeds) +
                    ": an ensemble needs a scatter to tell a change from it: expected at least 2 seeds (5 or more "
                    "for a usable interval)");
  if (safety.size() < 3)
    throw DeckError(where + ": --safety with " + std::to_string(safety.size()) +
                    " level(s): an observed order needs three: expected at least 3 safeties, e.g. 0.8,0.4,0.2");
  for (std::size_t i = 0; i < safety.size(); ++i)
  {
    if (!(safety[i] > 0 && safety[i] <= 1))
      throw DeckError(where + ": --safety value '" + o.safety_text[i] +
                      "': a fraction of the critical time step: expected a number in (0, 1]");
    if (i > 0 && !(safety[i] < safety[i - 1]))
      throw DeckError(where + ": --safety '" + o.safety_text[i] + "' after '" + o.safety_text[i - 1] +
                      "': expected the levels coarse to fine, each safety smaller than the one before");
    // The error estimate divides by r - 1 and by ln r: levels a hair apart
    // give a change of rounding size over a near-zero step ratio.  Celik et
    // al. (2008, J. Fluids Eng. 130) ask for r > 1.3; 1.1 is the least any
    // grid-convergence practice uses.
    if (i > 0 && !(safety[i - 1] >= 1.1 * safety[i]))
      throw DeckError(where + ": --safety '" + o.safety_text[i] + "' after '" + o.safety_text[i - 1] +
                      "': a step ratio of " + format_number(safety[i - 1] / safety[i], 4) +
                      ": expected each safety at most 1/1.1 of the one before (the change between levels would be "
                      "rounding, and the error estimate divides by the ratio - 1; 2 is usual)");
  }
}

void write_study_files(const std::string &dir, const std::vector<TimeStepAnalysis> &analyses, double default_safety,
                       const nlohmann::json &record)
{
  std::ostringstream t;
  t << "# demvv time-step study: per quantity and time-step safety, over the seeds (common random numbers "
       "across levels): n, mean, sd, se, ci95 (95 % Student-t half-width); change_to_finer = the paired mean "
       "change to the next finer level with its ci95 and verdict; observed_order (three levels from this one) "
       "with its 95 % interval; u_num_bound = U_num, a 95 % bound on the time-step error at this level, and "
       "relative to the mean; units: *_pa [Pa], strain [-]\n"
       "quantity,safety,n,mean,sd,se,ci95,change_to_finer,change_to_finer_ci95,change_verdict,observed_order,"
       "order_low,order_high,u_num_bound,u_num_bound_relative\n";
  for (std::size_t q = 0; q < analyses.size(); ++q)
  {
    const TimeStepAnalysis &a = analyses[q];
    for (std::size_t i = 0; i < a.safety.size(); ++i)
    {
      const EnsembleStatistics &s = a.level[i];
      t << quantities()[q].name << "," << format_number(a.safety[i]) << "," << s.n << "," << csv_cell(s.mean) << ","
        << csv_cell(s.sd) << "," << csv_cell(s.se) << "," << csv_cell(s.ci95) << ",";
      if (i < a.change.size())
        t << csv_cell(a.change[i].difference.mean) << "," << csv_cell(a.change[i].difference.ci95) << ","
          << (a.change[i].resolved ? "resolved" : "not resolved");
      else
        t << ",,";
      t << ",";
      if (i < a.order.size() && a.order[i].resolved)
        t << csv_cell(a.order[i].order) << "," << csv_cell(a.order[i].low) << "," << csv_cell(a.order[i].high);
      else
        t << ",,";
      t << "," << csv_cell(a.error_bound[i]) << "," << csv_cell(a.error_bound[i] / std::abs(s.mean)) << "\n";
    }
  }
  write_atomically(dir + "/time_step_study.csv", t.str());

  nlohmann::json doc = record;
  for (std::size_t q = 0; q < analyses.size(); ++q)
  {
    const TimeStepAnalysis &a = analyses[q];
    nlohmann::json levels = nlohmann::json::array();
    for (std::size_t i = 0; i < a.safety.size(); ++i)
    {
      nlohmann::json l = {{"safety", a.safety[i]},
                          {"n", a.level[i].n},
                          {"mean", finite_or_null(a.level[i].mean)},
                          {"se", finite_or_null(a.level[i].se)},
                          {"ci95", finite_or_null(a.level[i].ci95)},
                          {"u_num_bound", finite_or_null(a.error_bound[i])},
                          {"u_num_bound_relative", finite_or_null(a.error_bound[i] / std::abs(a.level[i].mean))}};
      if (i < a.change.size())
        l["change_to_finer"] = {{"mean", finite_or_null(a.change[i].difference.mean)},
                                {"ci95", finite_or_null(a.change[i].difference.ci95)},
                                {"verdict", a.change[i].resolved ? "resolved" : "not resolved"},
                                {"bound", finite_or_null(a.change[i].bound())}};
      if (i < a.order.size())
        l["observed_order"] = a.order[i].resolved ? nlohmann::json{{"order", a.order[i].order},
                                                                   {"low", finite_or_null(a.order[i].low)},
                                                                   {"high", finite_or_null(a.order[i].high)}}
                                                  : nlohmann::json("not resolved");
      levels.push_back(l);
    }
    doc["quantities"][quantities()[q].name] = {{"levels", levels}, {"extrapolated", finite_or_null(a.extrapolated)}};
  }
  doc["default_safety"] = default_safety;
  doc["method"] = "paired changes over common-random-number seeds; U_num(s) = 95 % bound on |q(finest) - q(s)| "
                  "plus the finest level's error (Richardson with factor of safety 1.25 where the order is "
                  "resolved, else the last change's bound / (r - 1), valid for order >= 1); u_num = U_num / 2";
  write_atomically(dir + "/time_step_study.json", json_text(doc, 2) + "\n");
}

void draw_study_figures(const std::string &dir, const std::vector<TimeStepAnalysis> &analyses,
                        const std::vector<SweepRow> &rows, int seeds)
{
  std::vector<Figure> figures;
  for (std::size_t q = 0; q < analyses.size(); ++q)
  {
    const Quantity &quantity = quantities()[q];
    const TimeStepAnalysis &a = analyses[q];
    StudySeries s{"mean over seeds", {}, {}, {}, {}, {}};
    for (std::size_t i = 0; i < a.safety.size(); ++i)
    {
      if (a.level[i].n == 0)
        continue;
      s.x.push_back(a.safety[i]);
      s.mean.push_back(a.level[i].mean);
      s.ci95.push_back(a.level[i].ci95);
      for (int j = 0; j < seeds; ++j)
      {
        const SweepRow &r = rows[i * std::size_t(seeds) + std::size_t(j)];
        if (r.status == "completed")
        {
          s.member_x.push_back(a.safety[i]);
          s.member_y.push_back(r.*quantity.value);
        }
      }
    }
    Figure f = parameter_study_figure(
      {std::string("time_step_") + quantity.name, std::string(quantity.title) + " against the time-step safety",
       "time-step safety (fraction of the critical step) [-]", quantity.axis, 1, quantity.scale, true},
      {s});
    f.caption += " Each seed is one packing and one set of bond strengths, the same at every level.";
    figures.push_back(std::move(f));
  }
  const std::string missing = undrawn(draw_figures(figures, dir + "/plots"));
  if (!missing.empty())
    std::cerr << "demvv: time-step study figures not drawn: " << missing << "\n";
}

std::string percent(double v)
{
  char b[32];
  std::snprintf(b, sizeof b, "%.2f %%", 100 * v);
  return b;
}

void print_table(std::ostream &out, const std::vector<TimeStepAnalysis> &analyses)
{
  for (std::size_t q = 0; q < analyses.size(); ++q)
  {
    const TimeStepAnalysis &a = analyses[q];
    out << quantities()[q].name << "\n  safety  n  mean  u_seed(se)  change to finer [95 %]  verdict  U_num\n";
    for (std::size_t i = 0; i < a.safety.size(); ++i)
    {
      out << "  " << format_number(a.safety[i]) << "  " << a.level[i].n << "  " << csv_cell(a.level[i].mean) << "  "
          << csv_cell(a.level[i].se) << "  ";
      if (i < a.change.size())
        out << csv_cell(a.change[i].difference.mean) << " +- " << csv_cell(a.change[i].difference.ci95) << "  "
            << (a.change[i].resolved ? "resolved" : "not resolved");
      else
        out << "-  -";
      out << "  " << percent(a.error_bound[i] / std::abs(a.level[i].mean)) << "\n";
    }
    for (std::size_t i = 0; i < a.order.size(); ++i)
      out << "  observed order from safety " << format_number(a.safety[i]) << ": "
          << (a.order[i].resolved ? format_number(a.order[i].order) + " [" + format_number(a.order[i].low) + ", " +
                                      format_number(a.order[i].high) + "]"
                                  : std::string("not resolved (a change within the seed noise, or changes of "
                                                "opposite sign)"))
          << "\n";
  }
}
} // namespace

int command_time_step(const TimeStepStudyOptions &o)
{
  std::vector<double> safety;
  for (const std::string &s : o.safety_text)
  {
    std::size_t used = 0;
    double v = std::nan("");
    try
    {
      v = std::stod(s, &used);
    }
    catch (const std::exception &)
    {
    }
    if (used != s.size())
      v = std::nan("");
    safety.push_back(v);
  }
  check_options(o, safety);
  const Deck base = Deck::from_file(deck_kinds(), o.base_deck);
  if (base.kind() != "uniaxial")
    throw DeckError(o.base_deck + ": kind '" + base.kind() +
                    "': a time-step study measures peak stress, strain at peak and initial modulus, which only "
                    "uniaxial runs write: expected a uniaxial deck");
  if (!deck_declares(base, safety_key))
    throw DeckError(o.base_deck + ": declares no " + safety_key + ": expected a deck with an automatic time step");
  // A fixed step would make every level the same run: the study would
  // report an error of zero it never measured.
  if (Deck::from_file(deck_kinds(), o.base_deck, o.sets).real(fixed_step_key) > 0)
    throw DeckError(o.base_deck + ": " + fixed_step_key +
                    " is set (in the deck or by --set), so every safety would run the same step: expected the "
                    "automatic step (" +
                    fixed_step_key + " = 0)");
  SweepPlan plan{o.base_deck, {safety_key}, {}, o.seeds, 1};
  std::vector<std::string> set_values;
  refuse_repeated_overrides(o.sets);
  for (const std::string &set : o.sets)
  {
    const std::size_t eq = set.find('=');
    if (eq == std::string::npos || eq == 0)
      throw DeckError("--set '" + set + "': expected SECTION/KEY=VALUE");
    const std::string key = set.substr(0, eq);
    if (key == safety_key || (key.size() >= 5 && key.compare(key.size() - 5, 5, "/seed") == 0))
      throw DeckError("--set '" + set + "': the study sets " + key + " itself: expected another entry");
    plan.keys.push_back(key);
    set_values.push_back(set.substr(eq + 1));
  }
  Deck::from_file(deck_kinds(), o.base_deck, o.sets); // every --set checked before a member runs
  for (const std::string &s : o.safety_text)
  {
    plan.points.push_back({s});
    plan.points.back().insert(plan.points.back().end(), set_values.begin(), set_values.end());
  }

  const auto start = std::chrono::steady_clock::now();
  const SweepOutcome outcome = run_sweep(plan, o.settings);
  if (outcome.rows.empty() || outcome.summary.empty())
    return outcome.exit_code; // another MPI rank: rank 0 writes the tables
  std::vector<TimeStepAnalysis> analyses;
  for (const Quantity &q : quantities())
  {
    std::vector<std::vector<double>> values(safety.size());
    for (std::size_t i = 0; i < safety.size(); ++i)
      for (int j = 0; j < o.seeds; ++j)
      {
        const SweepRow &r = outcome.rows[i * std::size_t(o.seeds) + std::size_t(j)];
        values[i].push_back(r.status == "completed" ? r.*q.value : std::nan(""));
      }
    analyses.push_back(analyse_time_step(safety, values));
  }
  const Deck base_deck = Deck::from_file(deck_kinds(), o.base_deck, o.sets);
  const double default_safety = base_deck.real(safety_key);
  nlohmann::json record = {
    {"safety_bound", "damped"},
    {"local_damping", base_deck.real("motion/local damping")},
    {"base_deck", o.base_deck},
    {"sets", o.sets},
    {"seeds", o.seeds},
    {"safeties", safety},
    {"complete", outcome.exit_code == 0},
    {"wall_seconds_this_leg", std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()},
    {"command_line", o.settings.command_line},
    {"provenance", provenance(0, 0, base.resolved())}};
  double member_seconds = 0;
  for (const SweepRow &r : outcome.rows)
    if (std::isfinite(r.seconds))
      member_seconds += r.seconds;
  record["member_run_seconds"] = member_seconds;
  write_study_files(o.settings.out_dir, analyses, default_safety, record);
  if (o.settings.figures)
    draw_study_figures(o.settings.out_dir, analyses, outcome.rows, o.seeds);
  print_table(std::cout, analyses);
  std::cerr << "demvv: " << outcome.summary << "; study in " << o.settings.out_dir << "/time_step_study.csv\n";
  return outcome.exit_code;
}
} // namespace demvv
