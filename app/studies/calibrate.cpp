#include "app/studies/calibrate.h"

#include "app/decks/deck.h"
#include "app/io/output.h"
#include "app/kinds/deck_kinds.h"
#include "app/run/input_uncertainty.h"
#include "app/run/run.h"
#include "app/studies/ranks.h"

#include "continuum/cylinder.h"

#include <gsl/gsl_blas.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_matrix.h>
#include <gsl/gsl_multifit_nlinear.h>
#include <gsl/gsl_vector.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <limits>
#include <map>
#include <memory>
#include <set>
#include <sstream>

namespace demvv
{
namespace
{
namespace fs = std::filesystem;
constexpr double largest_step = 0.4;    ///< finite-difference step in ln(value), at most
constexpr double converged_step = 1e-4; ///< a step in every ln(value) below this ends the fit

/// A fitted parameter: deck entries that take one value.
struct Parameter
{
  std::string name; ///< the entries joined by '+'
  std::vector<std::string> keys;
  double start = 0;
};

/// A quantity of a uniaxial run, its target value and that value's
/// standard uncertainty.
struct Target
{
  std::string quantity;
  double SweepRow::*field = nullptr;
  double value = 0;
  double uncertainty = 0;
};

const std::vector<std::pair<std::string, double SweepRow::*>> &target_quantities()
{
  static const std::vector<std::pair<std::string, double SweepRow::*>> q = {{"peak_stress_pa", &SweepRow::peak},
                                                                            {"strain_at_peak", &SweepRow::strain},
                                                                            {"initial_modulus_pa", &SweepRow::modulus},
                                                                            {"poisson_ratio", &SweepRow::poisson}};
  return q;
}

/// The targets' values at one set of parameter values, over the seeds.
struct Point
{
  std::vector<std::string> values;          ///< per parameter, as set in the deck
  std::vector<std::vector<double>> by_seed; ///< [target][seed]
  std::vector<double> mean, se;             ///< per target: mean and its standard error over seeds
};

/// One evaluation: a centre and, per parameter, the centre with that
/// parameter stepped (one sweep).
struct Evaluation
{
  std::size_t index = 0;
  int iteration = 0;
  Point centre;
  std::vector<Point> stepped;
  std::vector<double> dx;                    ///< the step taken in each ln(value)
  std::vector<std::vector<double>> slope;    ///< [target][parameter] d mean / d ln(value)
  std::vector<std::vector<double>> slope_se; ///< its standard error over seeds
};

double number_in(const std::string &text, const std::string &option, const std::string &expected)
{
  std::size_t used = 0;
  double v = nan;
  try
  {
    v = std::stod(text, &used);
  }
  catch (const std::exception &)
  {
    used = 0;
  }
  if (used == 0 || trimmed(text.substr(used)) != "" || !std::isfinite(v))
    throw DeckError(option + ": '" + text + "' is not a number: expected " + expected);
  return v;
}

class Calibration
{
public:
  explicit Calibration(const CalibrationOptions &o);

  int run();

private:
  const CalibrationOptions &o_;
  continuum::ParallelInfo mpi_;
  std::vector<Parameter> parameters_;
  std::vector<Target> targets_;
  std::vector<std::string> condition_; ///< the --at entries, "KEY=VALUE"
  /// "calibration/record=" when the base deck names a calibration (a fitted
  /// deck calibrated again): its evaluations vary the fitted entries, which
  /// that record would refuse.
  std::vector<std::string> clear_record_;
  std::vector<double> steps_; ///< the next finite-difference steps in ln(value)
  std::vector<Evaluation> history_;
  int iteration_ = 0;
  int exit_code_ = 0; ///< of the evaluation that stopped the fit
  std::string stop_message_;

  static int residuals(const gsl_vector *x, void *self, gsl_vector *f);
  static int jacobian(const gsl_vector *x, void *self, gsl_matrix *J);

  std::vector<std::string> values_at(const gsl_vector *x) const;
  /// The evaluation of these values (run now, or found in the history);
  /// nullptr when it failed (exit_code_ and stop_message_ say why).
  const Evaluation *evaluate(const std::vector<std::string> &values);
  Point read_point(const std::vector<SweepRow> &rows, std::size_t first, const std::vector<std::string> &values,
                   const std::string &label);
  bool met(const Point &p) const;
  void write_outputs(const std::string &status, const Evaluation *final) const;
  std::vector<std::string> overrides(const std::vector<std::string> &values) const;
};

Calibration::Calibration(const CalibrationOptions &o) : o_(o), mpi_(study_ranks())
{
  const Deck base = Deck::from_file(deck_kinds(), o.base_deck);
  if (base.kind() != "uniaxial")
    throw DeckError(o.base_deck + ": a " + base.kind() +
                    " deck: expected a uniaxial deck (the targets are "
                    "quantities of a uniaxial run)");
  std::set<std::string> keys;
  const auto take_key = [&](const std::string &key, const std::string &option)
  {
    if (key.find('/') == std::string::npos || !deck_declares(base, key))
      throw DeckError(option + ": " + o.base_deck + " (kind uniaxial) has no entry '" + key +
                      "': expected an entry that `demvv defaults uniaxial` lists");
    if (key.size() >= 5 && key.compare(key.size() - 5, 5, "/seed") == 0)
      throw DeckError(option + ": '" + key +
                      "': the seeds are the calibration's (--seeds, --first-seed): expected "
                      "another entry");
    if (!keys.insert(key).second)
      throw DeckError(option + ": '" + key + "' is named twice (--fit, --at): expected each entry once");
  };
  for (const std::string &arg : o.fit)
  {
    const auto eq = arg.find('=');
    if (eq == std::string::npos)
      throw DeckError("--fit '" + arg + "': expected KEY[+KEY...]=START (deck entries and a start value)");
    Parameter p;
    p.name = trimmed(arg.substr(0, eq));
    std::istringstream in(p.name);
    for (std::string key; std::getline(in, key, '+');)
    {
      take_key(trimmed(key), "--fit '" + arg + "'");
      p.keys.push_back(trimmed(key));
    }
    if (p.keys.empty())
      throw DeckError("--fit '" + arg + "': no entry: expected KEY[+KEY...]=START (deck entries and a start value)");
    p.start = number_in(arg.substr(eq + 1), "--fit '" + arg + "'", "a positive start value");
    if (!(p.start > 0))
      throw DeckError("--fit '" + arg + "': start " + format_number(p.start) +
                      ": expected a positive value (the fit works on ln(value))");
    parameters_.push_back(p);
  }
  for (const std::string &arg : o.at)
  {
    const auto eq = arg.find('=');
    if (eq == std::string::npos)
      throw DeckError("--at '" + arg + "': expected KEY=VALUE (the calibration condition, as --set)");
    take_key(trimmed(arg.substr(0, eq)), "--at '" + arg + "'");
    condition_.push_back(trimmed(arg.substr(0, eq)) + "=" + trimmed(arg.substr(eq + 1)));
  }
  for (const std::string &arg : o.targets)
  {
    const auto eq = arg.find('=');
    Target t;
    t.quantity = trimmed(arg.substr(0, eq));
    for (const auto &[name, field] : target_quantities())
      if (name == t.quantity)
        t.field = field;
    if (eq == std::string::npos || t.field == nullptr)
    {
      std::string names;
      for (const auto &q : target_quantities())
        names += (names.empty() ? "" : ", ") + q.first;
      throw DeckError("--target '" + arg + "': expected QUANTITY=VALUE[,UNCERTAINTY] with QUANTITY one of " + names);
    }
    const std::string rest = arg.substr(eq + 1);
    const auto comma = rest.find(',');
    t.value = number_in(rest.substr(0, comma), "--target '" + arg + "'", "a target value");
    if (t.value == 0)
      throw DeckError("--target '" + arg + "': 0: expected a non-zero value (residuals are relative to it)");
    if (t.value < 0 && t.quantity != "poisson_ratio")
      throw DeckError("--target '" + arg + "': " + format_number(t.value) + ": expected a positive " + t.quantity +
                      " (compression is positive in demvv)");
    if (comma != std::string::npos)
      t.uncertainty = number_in(rest.substr(comma + 1), "--target '" + arg + "'", "a standard uncertainty >= 0");
    if (t.uncertainty < 0)
      throw DeckError("--target '" + arg + "': uncertainty " + format_number(t.uncertainty) + ": expected >= 0");
    for (const Target &other : targets_)
      if (other.quantity == t.quantity)
        throw DeckError("--target '" + arg + "': " + t.quantity + " is targeted twice: expected each quantity once");
    targets_.push_back(t);
  }
  if (parameters_.empty() || targets_.empty())
    throw DeckError("calibration of " + o.base_deck + ": expected at least one --fit and one --target");
  if (parameters_.size() > targets_.size())
    throw DeckError("calibration of " + o.base_deck + ": " + std::to_string(parameters_.size()) + " parameters for " +
                    std::to_string(targets_.size()) +
                    " targets: expected no more parameters than targets (the fit would not be determined)");
  if (o.seeds < 2)
    throw DeckError("--seeds " + std::to_string(o.seeds) +
                    ": expected at least 2 (the fit's uncertainty comes "
                    "from the seed ensemble)");
  if (o.first_seed < 1)
    throw DeckError("--first-seed " + std::to_string(o.first_seed) + ": expected a seed >= 1");
  if (!(o.step > 0 && o.step <= largest_step))
    throw DeckError("--step " + format_number(o.step) + ": expected a step in ln(value) in (0, " +
                    format_number(largest_step) + "]");
  if (!(o.tolerance >= 0 && o.tolerance < 1))
    throw DeckError("--tolerance " + format_number(o.tolerance) + ": expected a relative residual in [0, 1)");
  if (o.max_iterations < 1)
    throw DeckError("--max-iterations " + std::to_string(o.max_iterations) + ": expected at least 1");
  if (o.settings.out_dir.empty())
    throw DeckError("calibration of " + o.base_deck + ": no --out: expected the calibration directory");
  if (deck_declares(base, calibration_record_key) && !base.text(calibration_record_key).empty())
    clear_record_.push_back(std::string(calibration_record_key) + "=");
  std::vector<std::string> start;
  for (const Parameter &p : parameters_)
    start.push_back(format_number(p.start));
  Deck::from_file(deck_kinds(), o.base_deck, overrides(start));
  steps_.assign(parameters_.size(), o.step);
}

std::vector<std::string> Calibration::overrides(const std::vector<std::string> &values) const
{
  std::vector<std::string> out = condition_;
  out.insert(out.end(), clear_record_.begin(), clear_record_.end());
  for (std::size_t j = 0; j < parameters_.size(); ++j)
    for (const std::string &key : parameters_[j].keys)
      out.push_back(key + "=" + values[j]);
  return out;
}

std::vector<std::string> Calibration::values_at(const gsl_vector *x) const
{
  std::vector<std::string> values;
  for (std::size_t j = 0; j < parameters_.size(); ++j)
    values.push_back(format_number(std::exp(gsl_vector_get(x, j))));
  return values;
}

Point Calibration::read_point(const std::vector<SweepRow> &rows, std::size_t first,
                              const std::vector<std::string> &values, const std::string &label)
{
  Point p;
  p.values = values;
  p.by_seed.resize(targets_.size());
  for (int s = 0; s < o_.seeds; ++s)
  {
    const SweepRow &row = rows[first + std::size_t(s)];
    if (row.status != "completed" && exit_code_ == 0)
    {
      exit_code_ = row.status == "refused" ? 2 : 3;
      stop_message_ = label + ", seed " + std::to_string(o_.first_seed + s) + ": " + row.status +
                      (row.message.empty() ? "" : ": " + row.message);
    }
    for (std::size_t i = 0; i < targets_.size(); ++i)
      p.by_seed[i].push_back(row.*(targets_[i].field));
  }
  for (std::size_t i = 0; i < targets_.size(); ++i)
  {
    const EnsembleStatistics st = ensemble_statistics(p.by_seed[i]);
    p.mean.push_back(st.n == p.by_seed[i].size() ? st.mean : nan);
    p.se.push_back(st.n == p.by_seed[i].size() ? st.se : nan);
    if (!std::isfinite(p.mean.back()) && exit_code_ == 0)
    {
      exit_code_ = 3;
      stop_message_ = label + ": " + targets_[i].quantity + " was not measured (no value in the runs' summaries)";
    }
  }
  return p;
}

const Evaluation *Calibration::evaluate(const std::vector<std::string> &values)
{
  for (const Evaluation &e : history_)
    if (e.centre.values == values)
      return &e;
  Evaluation e;
  e.index = history_.size();
  e.iteration = iteration_;
  char name[16];
  std::snprintf(name, sizeof name, "%03zu", e.index);
  SweepPlan plan{o_.base_deck, {}, {}, o_.seeds, o_.first_seed};
  for (const std::string &o : overrides(values))
    plan.keys.push_back(o.substr(0, o.find('=')));
  const auto point = [&](const std::vector<std::string> &v)
  {
    std::vector<std::string> p;
    for (const std::string &o : overrides(v))
      p.push_back(o.substr(o.find('=') + 1));
    return p;
  };
  std::vector<std::vector<std::string>> stepped_values;
  plan.points.push_back(point(values));
  for (std::size_t j = 0; j < parameters_.size(); ++j)
  {
    std::vector<std::string> v = values;
    v[j] = format_number(std::stod(values[j]) * std::exp(steps_[j]));
    stepped_values.push_back(v);
    plan.points.push_back(point(v));
  }
  SweepSettings settings = o_.settings;
  settings.out_dir = o_.settings.out_dir + "/evaluations/" + name;
  settings.replace = false;
  settings.figures = false;
  SweepOutcome outcome;
  try
  {
    outcome = run_sweep(plan, settings);
  }
  catch (const DeckError &e)
  {
    // The start is the user's: its refusal is bad input.  A point the fit
    // stepped to is the fit's: the targets lie beyond what the deck accepts.
    if (history_.empty())
      throw;
    stop_message_ = std::string("the fit stepped to values the deck refuses (") + e.what() +
                    "): the targets cannot be reached within them";
    return nullptr;
  }
  if (outcome.exit_code != 0)
  {
    exit_code_ = outcome.exit_code;
    stop_message_ = std::string("evaluation ") + name + " interrupted";
    return nullptr;
  }
  const std::string label = std::string("evaluation ") + name;
  e.centre = read_point(outcome.rows, 0, values, label + " (centre)");
  for (std::size_t j = 0; j < parameters_.size(); ++j)
  {
    e.stepped.push_back(read_point(outcome.rows, (j + 1) * std::size_t(o_.seeds), stepped_values[j],
                                   label + " (" + parameters_[j].name + " stepped)"));
    e.dx.push_back(std::log(std::stod(stepped_values[j][j]) / std::stod(values[j])));
  }
  e.slope.assign(targets_.size(), std::vector<double>(parameters_.size(), nan));
  e.slope_se = e.slope;
  for (std::size_t i = 0; i < targets_.size(); ++i)
    for (std::size_t j = 0; j < parameters_.size(); ++j)
    {
      std::vector<double> per_seed;
      for (int s = 0; s < o_.seeds; ++s)
        per_seed.push_back((e.stepped[j].by_seed[i][std::size_t(s)] - e.centre.by_seed[i][std::size_t(s)]) / e.dx[j]);
      const EnsembleStatistics st = ensemble_statistics(per_seed);
      e.slope[i][j] = st.n == per_seed.size() ? st.mean : nan;
      e.slope_se[i][j] = st.n == per_seed.size() ? st.se : nan;
    }
  // A step whose slope is lost in the seed noise is doubled for the next
  // Jacobian.
  for (std::size_t j = 0; j < parameters_.size(); ++j)
  {
    bool resolved = false;
    for (std::size_t i = 0; i < targets_.size(); ++i)
      resolved = resolved || std::abs(e.slope[i][j]) > 2 * e.slope_se[i][j];
    if (!resolved)
      steps_[j] = std::min(largest_step, 2 * steps_[j]);
  }
  history_.push_back(e);
  if (mpi_.rank == 0 && o_.settings.progress)
  {
    std::ostringstream line;
    line << "demvv: calibration evaluation " << name << " (iteration " << iteration_ << "):";
    for (std::size_t j = 0; j < parameters_.size(); ++j)
      line << " " << parameters_[j].name << " = " << values[j];
    for (std::size_t i = 0; i < targets_.size(); ++i)
      line << "; " << targets_[i].quantity << " " << format_number(e.centre.mean[i]) << " +- "
           << format_number(e.centre.se[i]) << " (target " << format_number(targets_[i].value) << ")";
    std::cerr << line.str() << "\n";
  }
  write_outputs("running", nullptr);
  return exit_code_ == 0 ? &history_.back() : nullptr;
}

int Calibration::residuals(const gsl_vector *x, void *self, gsl_vector *f)
{
  auto *c = static_cast<Calibration *>(self);
  const Evaluation *e = c->evaluate(c->values_at(x));
  if (e == nullptr)
    return GSL_EFAILED;
  for (std::size_t i = 0; i < c->targets_.size(); ++i)
    gsl_vector_set(f, i, (e->centre.mean[i] - c->targets_[i].value) / std::abs(c->targets_[i].value));
  return GSL_SUCCESS;
}

int Calibration::jacobian(const gsl_vector *x, void *self, gsl_matrix *J)
{
  auto *c = static_cast<Calibration *>(self);
  const Evaluation *e = c->evaluate(c->values_at(x));
  if (e == nullptr)
    return GSL_EFAILED;
  for (std::size_t i = 0; i < c->targets_.size(); ++i)
    for (std::size_t j = 0; j < c->parameters_.size(); ++j)
      gsl_matrix_set(J, i, j, e->slope[i][j] / std::abs(c->targets_[i].value));
  return GSL_SUCCESS;
}

bool Calibration::met(const Point &p) const
{
  for (std::size_t i = 0; i < targets_.size(); ++i)
  {
    const double miss = std::abs(p.mean[i] - targets_[i].value);
    if (!(miss <= p.se[i] || miss <= o_.tolerance * std::abs(targets_[i].value)))
      return false;
  }
  return true;
}

/// Whether parameter j moves no target at evaluation e (every slope exactly
/// 0: with the same seeds at every point, its runs were identical).
bool moves_no_target(const Evaluation &e, std::size_t j)
{
  return std::all_of(e.slope.begin(), e.slope.end(), [j](const std::vector<double> &row) { return row[j] == 0; });
}

/// (A^T S^-1 A)^-1 for a Jacobian A [target][parameter] and variances S;
/// empty when singular.
std::vector<std::vector<double>> covariance(const std::vector<std::vector<double>> &A,
                                            const std::vector<double> &variance)
{
  const std::size_t n = A.size(), p = A.front().size();
  std::unique_ptr<gsl_matrix, decltype(&gsl_matrix_free)> Aw(gsl_matrix_alloc(n, p), gsl_matrix_free);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < p; ++j)
      gsl_matrix_set(Aw.get(), i, j, A[i][j] / std::sqrt(variance[i]));
  std::unique_ptr<gsl_matrix, decltype(&gsl_matrix_free)> C(gsl_matrix_alloc(p, p), gsl_matrix_free);
  if (gsl_multifit_nlinear_covar(Aw.get(), 0.0, C.get()) != GSL_SUCCESS)
    return {};
  std::vector<std::vector<double>> out(p, std::vector<double>(p));
  for (std::size_t j = 0; j < p; ++j)
    for (std::size_t k = 0; k < p; ++k)
      out[j][k] = gsl_matrix_get(C.get(), j, k);
  return out;
}

void Calibration::write_outputs(const std::string &status, const Evaluation *final) const
{
  if (mpi_.rank != 0)
    return;
  const std::string &dir = o_.settings.out_dir;
  // The history: one row per point evaluated.
  std::ostringstream csv;
  csv << "# demvv calibrate of " << o_.base_deck
      << ": one row per point evaluated (centre: the trial point; step: the centre with one parameter stepped for "
         "the Jacobian); the parameters in deck units; per target the mean over seeds, its standard error (se) "
         "and, for centres, the relative residual (mean - target) / |target|; units: *_pa [Pa], strain [-]\n"
      << "evaluation,iteration,point";
  for (const Parameter &p : parameters_)
    csv << ",\"" << p.name << "\"";
  for (const Target &t : targets_)
    csv << "," << t.quantity << "_mean," << t.quantity << "_se," << t.quantity << "_relative_residual";
  csv << "\n";
  const auto row = [&](const Evaluation &e, const Point &p, const std::string &what, bool centre)
  {
    csv << e.index << "," << e.iteration << "," << what;
    for (const std::string &v : p.values)
      csv << "," << v;
    for (std::size_t i = 0; i < targets_.size(); ++i)
    {
      csv << "," << format_number(p.mean[i]) << "," << (std::isfinite(p.se[i]) ? format_number(p.se[i]) : "") << ",";
      if (centre)
        csv << format_number((p.mean[i] - targets_[i].value) / std::abs(targets_[i].value));
    }
    csv << "\n";
  };
  for (const Evaluation &e : history_)
  {
    row(e, e.centre, "centre", true);
    for (std::size_t j = 0; j < e.stepped.size(); ++j)
      row(e, e.stepped[j], "\"step " + parameters_[j].name + "\"", false);
  }
  write_atomically(dir + "/evaluations.csv", csv.str());

  nlohmann::json doc = {{"command_line", o_.settings.command_line},
                        {"base_deck", o_.base_deck},
                        {"condition", condition_},
                        {"seeds", o_.seeds},
                        {"first_seed", o_.first_seed},
                        {"finite_difference_step", o_.step},
                        {"tolerance", o_.tolerance},
                        {"max_iterations", o_.max_iterations},
                        {"status", status},
                        {"message", stop_message_},
                        {"iterations", iteration_},
                        {"evaluations", history_.size()},
                        {"provenance", provenance(0, o_.first_seed, read_file(o_.base_deck))}};
  const Evaluation *e = final != nullptr ? final : (history_.empty() ? nullptr : &history_.back());
  std::vector<std::vector<double>> cov_seeds, cov_all;
  if (e != nullptr)
  {
    std::vector<double> seeds_only, all;
    for (std::size_t i = 0; i < targets_.size(); ++i)
    {
      // A quantity the seeds do not move (no random draw reaches it) has
      // no scatter: its variance is floored at round-off.
      const double floor = 1e-12 * std::abs(targets_[i].value);
      seeds_only.push_back(std::max(e->centre.se[i] * e->centre.se[i], floor * floor));
      all.push_back(seeds_only.back() + targets_[i].uncertainty * targets_[i].uncertainty);
    }
    cov_seeds = covariance(e->slope, seeds_only);
    cov_all = covariance(e->slope, all);
  }
  for (std::size_t j = 0; j < parameters_.size(); ++j)
  {
    nlohmann::json p = {{"name", parameters_[j].name}, {"keys", parameters_[j].keys}, {"start", parameters_[j].start}};
    if (e != nullptr)
    {
      const double value = std::stod(e->centre.values[j]);
      p["value"] = value;
      p["deck_value"] = e->centre.values[j];
      if (!cov_all.empty() && !moves_no_target(*e, j))
      {
        p["standard_error"] = finite_or_null(value * std::sqrt(cov_all[j][j]));
        p["standard_error_seeds"] = finite_or_null(value * std::sqrt(cov_seeds[j][j]));
        p["relative_standard_error"] = finite_or_null(std::sqrt(cov_all[j][j]));
      }
      p["finite_difference_step"] = e->dx[j];
    }
    doc["parameters"].push_back(p);
  }
  // The path the fit took: each centre's parameters and target means.
  doc["path"] = nlohmann::json::array();
  for (const Evaluation &c : history_)
  {
    nlohmann::json values = nlohmann::json::array(), means = nlohmann::json::array(), ses = nlohmann::json::array();
    for (const std::string &v : c.centre.values)
      values.push_back(std::stod(v));
    for (std::size_t i = 0; i < targets_.size(); ++i)
    {
      means.push_back(finite_or_null(c.centre.mean[i]));
      ses.push_back(finite_or_null(c.centre.se[i]));
    }
    doc["path"].push_back({{"iteration", c.iteration}, {"values", values}, {"mean", means}, {"se", ses}});
  }
  if (!cov_all.empty())
    for (std::size_t j = 0; j < parameters_.size(); ++j)
    {
      nlohmann::json r = nlohmann::json::array();
      for (std::size_t k = 0; k < parameters_.size(); ++k)
        r.push_back(finite_or_null(cov_all[j][k] / std::sqrt(cov_all[j][j] * cov_all[k][k])));
      doc["correlation"].push_back(r);
    }
  for (std::size_t i = 0; i < targets_.size(); ++i)
  {
    nlohmann::json t = {
      {"quantity", targets_[i].quantity}, {"value", targets_[i].value}, {"uncertainty", targets_[i].uncertainty}};
    if (e != nullptr)
    {
      t["fitted_mean"] = finite_or_null(e->centre.mean[i]);
      t["standard_error_of_mean"] = finite_or_null(e->centre.se[i]);
      t["by_seed"] = e->centre.by_seed[i];
      t["residual"] = finite_or_null(e->centre.mean[i] - targets_[i].value);
      t["relative_residual"] = finite_or_null((e->centre.mean[i] - targets_[i].value) / std::abs(targets_[i].value));
      nlohmann::json slope = nlohmann::json::array(), slope_se = nlohmann::json::array();
      for (std::size_t j = 0; j < parameters_.size(); ++j)
      {
        slope.push_back(finite_or_null(e->slope[i][j]));
        slope_se.push_back(finite_or_null(e->slope_se[i][j]));
      }
      t["slope_per_ln_parameter"] = slope;
      t["slope_standard_error"] = slope_se;
    }
    doc["targets"].push_back(t);
  }
  write_atomically(dir + "/calibration.json", json_text(doc, 2) + "\n");
  if (e == nullptr || status != "converged")
    return;
  std::ostringstream deck;
  deck << "# Fitted by demvv calibrate, " << dir << "/calibration.json:\n";
  for (std::size_t j = 0; j < parameters_.size(); ++j)
    deck << "#   " << parameters_[j].name << " = " << e->centre.values[j]
         << (doc["parameters"][j].contains("standard_error") && doc["parameters"][j]["standard_error"].is_number()
               ? " +- " + format_number(doc["parameters"][j]["standard_error"].get<double>()) + " (standard error)"
               : "")
         << "\n";
  deck << "# at the calibration condition:";
  for (const std::string &c : condition_)
    deck << " " << c << ";";
  deck << " seeds " << o_.first_seed << " ... " << o_.first_seed + o_.seeds - 1 << ".\n";
  // The fitted deck names this record: its runs state u_input from it
  // (app/run/input_uncertainty.h).
  std::vector<std::string> fitted = overrides(e->centre.values);
  fitted.push_back(std::string(calibration_record_key) + "=" +
                   std::filesystem::absolute(dir + "/calibration.json").lexically_normal().string());
  deck << Deck::from_file(deck_kinds(), o_.base_deck, fitted).resolved();
  write_atomically(dir + "/fitted.prm", deck.str());
}

int Calibration::run()
{
  std::unique_ptr<DirectoryLock> lock; // rank 0's, for the whole calibration
  on_rank_zero_for_all(
    true,
    [&]
    {
      lock = std::make_unique<DirectoryLock>(o_.settings.out_dir, "calibration");
      const std::string record = o_.settings.out_dir + "/calibration.json";
      if (!claim_resumable_directory(o_.settings.out_dir, o_.settings.replace, "calibration", "calibration.json"))
        return;
      // The fit's path is read back only where this build's arithmetic made it.
      nlohmann::json doc;
      try
      {
        doc = nlohmann::json::parse(read_file(record));
      }
      catch (const std::exception &)
      {
      }
      if (doc.is_object() && !made_by_this_build(doc.value("provenance", nlohmann::json())))
        throw DeckError("calibration directory '" + o_.settings.out_dir + "' was begun by another build of demvv (" +
                        record + "): expected the build that began it, or --replace to start it over");
    });
  if (mpi_.rank == 0)
    make_directories(o_.settings.out_dir + "/evaluations");

  const std::size_t n = targets_.size(), p = parameters_.size();
  gsl_multifit_nlinear_fdf fdf;
  fdf.f = &Calibration::residuals;
  fdf.df = &Calibration::jacobian;
  fdf.fvv = nullptr;
  fdf.n = n;
  fdf.p = p;
  fdf.params = this;
  gsl_multifit_nlinear_parameters settings = gsl_multifit_nlinear_default_parameters();
  std::unique_ptr<gsl_multifit_nlinear_workspace, decltype(&gsl_multifit_nlinear_free)> w(
    gsl_multifit_nlinear_alloc(gsl_multifit_nlinear_trust, &settings, n, p), gsl_multifit_nlinear_free);
  std::unique_ptr<gsl_vector, decltype(&gsl_vector_free)> x(gsl_vector_alloc(p), gsl_vector_free);
  for (std::size_t j = 0; j < p; ++j)
    gsl_vector_set(x.get(), j, std::log(parameters_[j].start));

  gsl_error_handler_t *previous = gsl_set_error_handler_off();
  int status = gsl_multifit_nlinear_init(x.get(), &fdf, w.get());
  std::string outcome = "not converged";
  while (status == GSL_SUCCESS && exit_code_ == 0)
  {
    const Evaluation *here = evaluate(values_at(gsl_multifit_nlinear_position(w.get())));
    if (here == nullptr)
      break;
    if (met(here->centre))
    {
      outcome = "converged";
      stop_message_ = "every target met within its seed-ensemble standard error or the tolerance";
      break;
    }
    if (iteration_ >= o_.max_iterations)
    {
      stop_message_ = "after " + std::to_string(iteration_) + " iterations the targets are not met";
      break;
    }
    ++iteration_;
    status = gsl_multifit_nlinear_iterate(w.get());
    if (exit_code_ != 0)
      break;
    if (status == GSL_ENOPROG)
    {
      stop_message_ = "the trust region found no step that lowers the residuals (the fit sits at the seed noise, "
                      "or the targets cannot be reached)";
      break;
    }
    if (status != GSL_SUCCESS)
    {
      if (stop_message_.empty()) // else the evaluation said why
        stop_message_ = std::string("the fit stopped: ") + gsl_strerror(status);
      break;
    }
    int info = 0;
    if (gsl_multifit_nlinear_test(converged_step, 0, 0, &info, w.get()) == GSL_SUCCESS && info == 1)
    {
      const Evaluation *last = evaluate(values_at(gsl_multifit_nlinear_position(w.get())));
      if (last == nullptr)
        break;
      outcome = met(last->centre) ? "converged" : "not converged";
      stop_message_ = "the step in every ln(value) fell below " + format_number(converged_step) +
                      (outcome == "converged" ? "" : " with the targets not met");
      break;
    }
  }
  gsl_set_error_handler(previous);
  if (status != GSL_SUCCESS && exit_code_ == 0 && stop_message_.empty())
    stop_message_ = std::string("the fit could not start: ") + gsl_strerror(status);

  const Evaluation *final = history_.empty() ? nullptr : evaluate(values_at(gsl_multifit_nlinear_position(w.get())));
  // A parameter no target moves (every slope exactly 0: with the same seeds
  // at every point, the runs were identical) is not determined by the
  // targets, however well they are met: its standard error is unbounded.
  if (final != nullptr && outcome == "converged")
  {
    std::string idle;
    for (std::size_t j = 0; j < p; ++j)
      if (moves_no_target(*final, j))
        idle += (idle.empty() ? "" : ", ") + parameters_[j].name;
    if (!idle.empty())
    {
      outcome = "not determined";
      stop_message_ = "no target moves with " + idle +
                      " (every slope exactly 0 over the seeds): the targets do not determine it; expected a "
                      "parameter the targets depend on";
    }
  }
  if (exit_code_ != 0)
  {
    const bool interrupted = exit_code_ >= 128;
    write_outputs(interrupted ? "interrupted" : "failed", final);
    if (interrupted)
    {
      std::cerr << "demvv: calibration interrupted; rerun the same command to resume\n";
      return exit_code_;
    }
    if (exit_code_ == 2)
      throw DeckError("calibration of " + o_.base_deck + ": " + stop_message_);
    std::cerr << "demvv: calibration failed: " << stop_message_ << "; evaluations so far in " << o_.settings.out_dir
              << "\n";
    return 3;
  }
  write_outputs(outcome, final);
  if (mpi_.rank == 0 && !history_.empty())
  {
    const nlohmann::json doc = nlohmann::json::parse(read_file(o_.settings.out_dir + "/calibration.json"));
    std::cerr << "demvv: calibration " << outcome << " after " << iteration_ << " iterations, " << history_.size()
              << " evaluations:";
    for (const nlohmann::json &q : doc.at("parameters"))
      std::cerr << " " << q.at("name").get<std::string>() << " = " << q.at("deck_value").get<std::string>()
                << (q.contains("standard_error") && q["standard_error"].is_number()
                      ? " +- " + format_number(q["standard_error"].get<double>())
                      : "");
    std::cerr << "; " << stop_message_
              << (outcome == "converged" ? "; fitted deck " + o_.settings.out_dir + "/fitted.prm"
                                         : "; no fitted deck (calibration.json has the last point)")
              << "\n";
  }
  return outcome == "converged" ? 0 : 3;
}
} // namespace

int command_calibrate(const CalibrationOptions &options)
{
  Calibration calibration(options);
  return calibration.run();
}
} // namespace demvv
