#include "app/studies/sweep.h"

#include "app/decks/csv_input.h"
#include "app/decks/deck.h"
#include "app/io/input.h"
#include "app/io/output.h"
#include "app/kinds/deck_kinds.h"
#include "app/kinds/prepare.h"
#include "app/plot/gnuplot.h"
#include "app/plot/studies.h"
#include "app/run/analysis.h"
#include "app/run/run.h"
#include "app/studies/ranks.h"

#include "continuum/cylinder.h"

#include <gsl/gsl_cdf.h>
#include <omp.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <sstream>

namespace demvv
{
namespace
{
namespace fs = std::filesystem;

/// The quantities of stats.csv's budget, in StatedUncertainty's order.
constexpr const char *budget_quantities[] = {"peak_stress_pa", "strain_at_peak", "initial_modulus_pa"};

/// The stated parts of one point's budget (members first .. last - 1) for
/// quantity q: the largest any completed member states (they share the
/// sample size, step and deck; NaN when one states none).
StatedUncertainty point_stated(const std::vector<SweepRow> &rows, std::size_t first, std::size_t last, std::size_t q)
{
  StatedUncertainty u{0, 0};
  const auto largest = [](double &part, double member) { part = std::isnan(member) ? member : std::max(part, member); };
  bool any = false;
  for (std::size_t i = first; i < last; ++i)
    if (rows[i].status == "completed")
    {
      any = true;
      largest(u.num, rows[i].stated[q].num);
      largest(u.input, rows[i].stated[q].input);
    }
  return any ? u : StatedUncertainty{};
}

/// One --vary: its entries (several, tied: each set to the same value)
/// and their values.
struct Varied
{
  std::vector<std::string> keys;
  std::vector<std::string> values;
};

struct Member
{
  std::size_t index = 0;
  std::vector<std::string> values; ///< one per varied key
  int seed = 0;                    ///< 0: the deck's own
  std::string label;               ///< folder name under members/
  std::vector<std::string> overrides;
  std::string prepare_deck; ///< the prepare deck its sample comes from when a seed re-prepares it
  std::vector<std::string> prepare_overrides;
  std::string resolved;     ///< the member's resolved deck ("" when refused before it runs)
  std::string refusal;      ///< why the member cannot run
  std::string refused_deck; ///< a refused member's identity: the base deck's hash and the overrides
};

std::vector<std::string> split(const std::string &text, char by)
{
  std::vector<std::string> parts;
  std::string part;
  std::istringstream in(text);
  while (std::getline(in, part, by))
    parts.push_back(part);
  if (!text.empty() && text.back() == by)
    parts.emplace_back();
  return parts;
}

/// "SECTION/KEY[+SECTION/KEY...]=v1,v2,...", checked against the base deck.
Varied parse_vary(const std::string &arg, const Deck &base)
{
  const auto eq = arg.find('=');
  Varied v;
  for (const std::string &part : split(eq == std::string::npos ? "" : arg.substr(0, eq), '+'))
  {
    const std::string key = trimmed(part);
    if (key.empty() || key.find('/') == std::string::npos)
      throw DeckError("--vary '" + arg +
                      "': expected SECTION/KEY[+SECTION/KEY...]=v1,v2,... (deck entries and their values)");
    if (!deck_declares(base, key))
      throw DeckError("--vary '" + arg + "': " + base.path() + " (kind " + base.kind() + ") has no entry '" + key +
                      "': expected an entry that `demvv defaults " + base.kind() + "` lists");
    if (base.holds_list(key))
      throw DeckError("--vary '" + escaped(arg) + "': '" + key +
                      "' holds a comma-separated vector or list, and --vary separates its values by commas: "
                      "expected a single-number entry (run one deck per vector instead)");
    v.keys.push_back(key);
  }
  if (v.keys.empty())
    throw DeckError("--vary '" + arg +
                    "': expected SECTION/KEY[+SECTION/KEY...]=v1,v2,... (deck entries and their values)");
  for (const std::string &value : split(arg.substr(eq + 1), ','))
  {
    const std::string t = trimmed(value);
    if (t.empty())
      throw DeckError("--vary '" + escaped(arg) + "': an empty value: expected comma-separated values, none empty");
    if (control_character(t) != std::string::npos)
      throw DeckError("--vary '" + escaped(arg) + "': the value '" + escaped(t) +
                      "' holds a control character: expected printable text (it is written into sweep.csv and the "
                      "members' decks)");
    // A value given twice (as text, or as the same number: 0.1 and 1e-1)
    // would run the same member twice.
    const auto same = [&t](const std::string &other)
    {
      char *end_a = nullptr, *end_b = nullptr;
      const double a = std::strtod(t.c_str(), &end_a), b = std::strtod(other.c_str(), &end_b);
      return other == t || (*end_a == '\0' && *end_b == '\0' && a == b);
    };
    if (std::any_of(v.values.begin(), v.values.end(), same))
      throw DeckError("--vary '" + arg + "': the value '" + t +
                      "' is given twice: expected distinct values (a repeated value runs the same member twice)");
    v.values.push_back(t);
  }
  if (v.values.empty())
    throw DeckError("--vary '" + arg + "': no values: expected comma-separated values after '='");
  return v;
}

/// A value as part of a folder name: a file by its name (a case.prm by its
/// folder's), without its extension; letters, digits, '.', '+', '-' kept.
std::string folder_part(const std::string &value)
{
  std::string name = value;
  if (value.find('/') != std::string::npos)
  {
    const fs::path file(value);
    name = (file.filename() == "case.prm" ? file.parent_path().filename() : file.filename()).stem().string();
  }
  std::string out;
  for (const char c : name.substr(0, 16))
    out += std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '+' || c == '-' ? c : '-';
  return out;
}

bool is_prepare_deck(const std::string &file)
{
  return file.size() > 4 && file.compare(file.size() - 4, 4, ".prm") == 0;
}

/// The members, point after point and seed innermost, each with its
/// overrides; the sample a seed re-prepares is named, not yet prepared.
std::vector<Member> plan_members(const SweepPlan &plan)
{
  const std::string &base_path = plan.base_deck;
  const int seeds = plan.seeds;
  const std::size_t count = std::max(seeds, 1) * plan.points.size();
  const std::size_t width = std::to_string(count == 0 ? 0 : count - 1).size();
  std::vector<Member> members(count);
  for (std::size_t i = 0; i < count; ++i)
  {
    Member &m = members[i];
    m.index = i;
    m.seed = seeds > 0 ? int(i % std::size_t(seeds)) + plan.first_seed : 0;
    m.values = plan.points[i / std::size_t(std::max(seeds, 1))];
    const std::string number = std::to_string(i);
    m.label = std::string(width - number.size(), '0') + number;
    for (std::size_t k = 0; k < plan.keys.size(); ++k)
    {
      m.label += "_" + folder_part(m.values[k]);
      m.overrides.push_back(plan.keys[k] + "=" + m.values[k]);
    }
    if (m.seed > 0)
      m.label += "_s" + std::to_string(m.seed);
    if (m.seed == 0)
      continue;
    // The seed keys of this member's deck (its kind and sample source).
    try
    {
      const Deck deck = Deck::from_file(deck_kinds(), base_path, m.overrides);
      const std::string s = std::to_string(m.seed);
      if (deck_declares(deck, "bonds/seed"))
        m.overrides.push_back("bonds/seed=" + s);
      if (deck_declares(deck, "sample/seed"))
        m.overrides.push_back("sample/seed=" + s);
      const bool from_file = !deck_declares(deck, "sample/source") || deck.text("sample/source") == "file";
      if (from_file && deck_declares(deck, "sample/file") && is_prepare_deck(deck.text("sample/file")))
      {
        m.prepare_deck = deck.file("sample/file");
        const Deck prepare = Deck::from_file(deck_kinds(), m.prepare_deck);
        m.prepare_overrides = {"sample/seed=" + s};
        if (deck_declares(prepare, "bonds/seed"))
          m.prepare_overrides.push_back("bonds/seed=" + s);
      }
    }
    catch (const DeckError &e)
    {
      m.refusal = e.what();
    }
  }
  return members;
}

/// Prepares the samples the seeds call for, each distinct one on one rank
/// (round-robin); a preparation that fails refuses its members.
void prepare_samples(std::vector<Member> &members, int rank, int ranks, bool progress)
{
  std::map<std::pair<std::string, std::vector<std::string>>, std::size_t> order;
  for (const Member &m : members)
    if (!m.prepare_deck.empty() && m.refusal.empty())
      order.emplace(std::make_pair(m.prepare_deck, m.prepare_overrides), order.size());
  for (const auto &[sample, n] : order)
    if (int(n % std::size_t(ranks)) == rank)
      try
      {
        cached_sample_file(sample.first, sample.second, progress && rank == 0);
      }
      catch (const std::runtime_error &e)
      {
        std::cerr << "demvv: " << e.what() << "\n";
      }
  wait_for_all_ranks();
}

/// Completes each member's overrides with its prepared sample and resolves
/// its deck; what its deck refuses is kept as the member's refusal.
void resolve_members(std::vector<Member> &members, const std::string &base_path, const std::string &base_hash)
{
  for (Member &m : members)
  {
    m.refused_deck = base_path + " (resolved deck " + base_hash + ")";
    for (const std::string &o : m.overrides)
      m.refused_deck += " --set " + o;
    if (!m.refusal.empty())
      continue;
    try
    {
      if (!m.prepare_deck.empty())
      {
        const std::string sample = cached_sample_file_name(m.prepare_deck, m.prepare_overrides);
        if (!fs::exists(sample))
          throw DeckError(m.prepare_deck + ": its sample for seed " + std::to_string(m.seed) +
                          " could not be prepared (see " + fs::path(sample).parent_path().string() +
                          "/summary.json): expected a prepare deck that prepares");
        // Absolute: an override's file is read relative to the deck.
        m.overrides.push_back("sample/file=" + fs::absolute(sample).lexically_normal().string());
      }
      m.resolved = Deck::from_file(deck_kinds(), base_path, m.overrides).resolved();
    }
    catch (const DeckError &e)
    {
      m.refusal = e.what();
    }
  }
}

/// The status word of a run directory's summary.json.
std::string status_word(const std::string &state)
{
  if (state == "numerical fault")
    return "fault";
  if (state == "paused")
    return "interrupted";
  return state;
}

/// Bond breakage at the peak stress, from the member's series.csv (the row
/// of the peak), else the final breakage from summary.json.
double broken_at_peak(const std::string &dir, const nlohmann::json &summary)
{
  try
  {
    const CsvTable t = CsvTable::read(dir + "/series.csv", CsvTable::Values::any_number);
    if (t.has("axial_strain") && t.has("axial_stress_pa") && t.has("bonds_broken_fraction") && t.rows() > 0)
    {
      std::vector<double> eps, sig;
      for (std::size_t r = 0; r < t.rows(); ++r)
      {
        eps.push_back(t.get(r, "axial_strain"));
        sig.push_back(t.get(r, "axial_stress_pa"));
      }
      return t.get(peak(eps, sig).index, "bonds_broken_fraction");
    }
  }
  catch (const std::runtime_error &)
  {
  }
  if (!summary.contains("bonds") || !summary.at("bonds").is_object())
    return nan;
  const nlohmann::json &b = summary.at("bonds");
  const double installed = json_number(b, "installed");
  const double broken =
    json_number(b, "broken_tension") + json_number(b, "broken_shear") + json_number(b, "broken_displacement");
  return installed > 0 ? broken / installed : nan;
}

/// A member's row from its run directory: pending while the directory
/// holds no summary of this member's deck made by this build (a member
/// another build ran is run again: one sweep, one build).
SweepRow read_row(const std::string &dir, const Member &m)
{
  SweepRow row;
  row.directory = dir;
  nlohmann::json summary;
  try
  {
    summary = nlohmann::json::parse(read_file(dir + "/summary.json"));
  }
  catch (const std::exception &)
  {
    return row;
  }
  if (!made_by_this_build(summary.value("provenance", nlohmann::json())))
    return row;
  const nlohmann::json status = summary.value("status", nlohmann::json::object());
  const std::string state = status.value("state", "");
  if (state == "refused" && !summary.contains("kind"))
  {
    // Refused before a run directory was made: the sweep wrote it, with
    // the refused deck's identity.
    if (summary.value("refused_deck", "") != m.refused_deck)
      return row;
  }
  else
  {
    std::string deck;
    try
    {
      deck = read_file(dir + "/deck.prm");
    }
    catch (const std::exception &)
    {
      return row;
    }
    if (deck != m.resolved || state.empty() || state == "running")
      return row;
  }
  row.status = status_word(state);
  if (status.contains("fault"))
    row.message = status.at("fault").value("message", "");
  else
    row.message = status.value("message", "");
  row.seconds = json_number(status, "wall_seconds");
  if (!std::isfinite(row.seconds))
    row.seconds = json_number(summary, "wall_seconds");
  if (row.status != "completed")
    return row;
  row.peak = json_number(summary, "peak_stress_pa");
  row.strain = json_number(summary, "strain_at_peak");
  row.modulus = json_number(summary, "initial_modulus_pa");
  row.poisson = json_number(summary, "poisson_ratio");
  row.broken = broken_at_peak(dir, summary);
  if (summary.contains("sample") && summary.at("sample").is_object())
    row.particles = json_number(summary.at("sample"), "particles");
  // The budget's parts the run states (a summary without them, or damaged,
  // states none).
  const auto stated = [&](const char *block, const char *field, double StatedUncertainty::*part)
  {
    try
    {
      const nlohmann::json &u = summary.at("uncertainty").at(block);
      if (u.value("estimated", false))
        for (std::size_t q = 0; q < row.stated.size(); ++q)
          row.stated[q].*part = json_number(u.at(budget_quantities[q]), field);
    }
    catch (const nlohmann::json::exception &)
    {
    }
  };
  stated("numerical_time_step", "u_num_relative", &StatedUncertainty::num);
  stated("input_calibration", "u_input_relative", &StatedUncertainty::input);
  return row;
}

/// True when a member's directory holds its completed run, or its deck's
/// refusal (the same deck is refused again): resume keeps it.
bool finished(const std::string &dir, const Member &m)
{
  const std::string status = read_row(dir, m).status;
  return status == "completed" || status == "refused";
}

/// A varied value as a number; NaN when it is not one.
double as_number(const std::string &text)
{
  char *end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  return end != text.c_str() && *end == '\0' && std::isfinite(v) ? v : nan;
}

std::string quoted(std::string text)
{
  std::replace(text.begin(), text.end(), '\n', ' ');
  std::string out = "\"";
  for (const char c : text)
    out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

/// A varied value as a CSV cell: a number as it is; any other text quoted,
/// and text a spreadsheet would take for a formula (starting with =, +, -
/// or @) behind a "'" that keeps it text.
std::string value_cell(const std::string &value)
{
  if (std::isfinite(as_number(value)))
    return value;
  const bool formula = !value.empty() && std::string("=+-@").find(value.front()) != std::string::npos;
  return quoted((formula ? "'" : "") + value);
}

/// Writes sweep.csv and stats.csv from the members' directories; returns
/// the rows.
std::vector<SweepRow> write_tables(const std::string &out, const SweepPlan &plan, const std::vector<Member> &members)
{
  std::vector<SweepRow> rows;
  for (const Member &m : members)
    rows.push_back(read_row(out + "/members/" + m.label, m));
  const std::string &base_path = plan.base_deck;
  std::string keys;
  for (const std::string &k : plan.keys)
    keys += k + ",";
  std::ostringstream t;
  t << "# demvv sweep of " << base_path
    << ": one row per member; units: peak_stress_pa [Pa], strain_at_peak [-], initial_modulus_pa [Pa], "
       "poisson_ratio [-], bonds_broken_fraction_at_peak [-] (at the peak stress; the final breakage where the "
       "run has no series), particles [-] (balls in the sample), run_time_s [s]; compression positive; seed empty: "
       "the deck's own seeds\n"
    << "member," << keys
    << "seed,status,peak_stress_pa,strain_at_peak,initial_modulus_pa,poisson_ratio,bonds_broken_fraction_at_peak,"
       "particles,run_time_s,message\n";
  for (std::size_t i = 0; i < members.size(); ++i)
  {
    const Member &m = members[i];
    const SweepRow &r = rows[i];
    t << m.index << ",";
    for (const std::string &v : m.values)
      t << value_cell(v) << ",";
    t << (m.seed > 0 ? std::to_string(m.seed) : "") << "," << r.status << "," << csv_cell(r.peak) << ","
      << csv_cell(r.strain) << "," << csv_cell(r.modulus) << "," << csv_cell(r.poisson) << "," << csv_cell(r.broken)
      << "," << csv_cell(r.particles) << "," << csv_cell(r.seconds) << ","
      << (r.message.empty() ? "" : quoted(r.message)) << "\n";
  }
  write_atomically(out + "/sweep.csv", t.str());

  std::ostringstream s;
  s << "# demvv sweep of " << base_path
    << ": per set of varied values, over the completed seeds: n, mean, sample standard deviation (sd) and the "
       "95 % confidence half-width of the mean (ci95, Student t with n - 1 degrees of freedom; sd and ci95 need n "
       ">= 2); the budget of each mean as standard uncertainties: u_seed (the standard error of the mean), "
       "u_num (the time-step study's, for the members' sample size and step; empty: not estimated, no study "
       "applies) and u_input (the fitted inputs' standard errors through the model's sensitivity, where the deck "
       "names the calibration that fitted it; empty: not estimated); units: *_pa [Pa], strain [-]\n"
    << "group," << keys
    << "n,peak_stress_mean_pa,peak_stress_sd_pa,peak_stress_ci95_pa,strain_at_peak_mean,strain_at_peak_sd,"
       "strain_at_peak_ci95,initial_modulus_mean_pa,initial_modulus_sd_pa,initial_modulus_ci95_pa,"
       "peak_stress_u_seed_pa,peak_stress_u_num_pa,peak_stress_u_input_pa,strain_at_peak_u_seed,"
       "strain_at_peak_u_num,strain_at_peak_u_input,initial_modulus_u_seed_pa,initial_modulus_u_num_pa,"
       "initial_modulus_u_input_pa\n";
  std::size_t group = 0;
  for (std::size_t first = 0; first < members.size(); ++group)
  {
    std::size_t last = first;
    while (last < members.size() && members[last].values == members[first].values)
      ++last;
    std::vector<double> peak, strain, modulus;
    std::size_t n = 0;
    for (std::size_t i = first; i < last; ++i)
      if (rows[i].status == "completed")
      {
        ++n;
        peak.push_back(rows[i].peak);
        strain.push_back(rows[i].strain);
        modulus.push_back(rows[i].modulus);
      }
    s << group << ",";
    for (const std::string &v : members[first].values)
      s << value_cell(v) << ",";
    s << n;
    const EnsembleStatistics stats[3] = {ensemble_statistics(peak), ensemble_statistics(strain),
                                         ensemble_statistics(modulus)};
    for (const EnsembleStatistics &st : stats)
      s << "," << csv_cell(st.mean) << "," << csv_cell(st.sd) << "," << csv_cell(st.ci95);
    for (std::size_t q = 0; q < std::size(budget_quantities); ++q)
    {
      const StatedUncertainty u = point_stated(rows, first, last, q);
      const double scale = std::abs(stats[q].mean);
      s << "," << csv_cell(stats[q].se) << "," << csv_cell(u.num * scale) << "," << csv_cell(u.input * scale);
    }
    s << "\n";
    first = last;
  }
  write_atomically(out + "/stats.csv", s.str());
  return rows;
}

/// What a sweep's figures are drawn against (the header says how it is
/// chosen): x of each point, the axis label, the series each point is in.
struct StudyAbscissa
{
  std::vector<double> x;
  std::string label;
  bool log = false;
  std::vector<std::string> series; ///< title of each point's series
  std::string caption;
};

StudyAbscissa study_abscissa(const SweepPlan &plan, const Deck &base, const std::vector<SweepRow> &rows)
{
  const std::size_t points = plan.points.size();
  const std::size_t per_point = rows.size() / std::max<std::size_t>(points, 1);
  const auto distinct = [](const std::vector<double> &x) { return std::set<double>(x.begin(), x.end()).size(); };
  const auto finite = [](const std::vector<double> &x)
  { return std::all_of(x.begin(), x.end(), [](double v) { return std::isfinite(v); }); };
  // "KEY = VALUE, ..." of point p's entries from the `from`-th on.
  const auto entries = [&](std::size_t p, std::size_t from)
  {
    std::string text;
    for (std::size_t j = from; j < plan.keys.size(); ++j)
      text += (text.empty() ? "" : ", ") + plan.keys[j] + " = " + plan.points[p][j];
    return text;
  };
  StudyAbscissa a;
  a.series.assign(points, "");
  if (!plan.keys.empty())
  {
    std::vector<double> values, balls;
    std::set<std::string> names;
    for (std::size_t p = 0; p < points; ++p)
    {
      values.push_back(as_number(plan.points[p][0]));
      names.insert(plan.points[p][0]);
      std::vector<double> counts;
      for (std::size_t i = p * per_point; i < (p + 1) * per_point; ++i)
        counts.push_back(rows[i].particles);
      balls.push_back(ensemble_statistics(counts).mean);
    }
    const std::string unit = base.unit(plan.keys[0]);
    std::string factor;
    for (std::size_t j = 0; j < plan.first_factor_keys; ++j)
      factor += (j == 0 ? "" : " + ") + plan.keys[j];
    if (finite(values) && distinct(values) > 1)
    {
      a.x = values;
      a.label = factor + (unit.empty() ? "" : " [" + unit + "]");
    }
    else if (finite(balls) && distinct(balls) == names.size() && names.size() > 1)
    {
      a.x = balls;
      a.label = "balls in the sample [-] (" + factor + ")";
    }
  }
  if (!a.x.empty())
  {
    for (std::size_t p = 0; p < points; ++p)
      a.series[p] = entries(p, plan.first_factor_keys);
    const double lo = *std::min_element(a.x.begin(), a.x.end()), hi = *std::max_element(a.x.begin(), a.x.end());
    a.log = lo > 0 && hi >= 20 * lo;
    return a;
  }
  a.label = "point of the sweep [-]";
  for (std::size_t p = 0; p < points; ++p)
  {
    a.x.push_back(double(p + 1));
    a.caption += (a.caption.empty() ? "Points: " : "; ") + std::to_string(p + 1) + ": " + entries(p, 0);
  }
  return a;
}

struct StudyQuantity
{
  std::string name, title, axis;
  double scale;
  double SweepRow::*value;
};

/// The uncertainty budget of one quantity's means, part by part in per cent
/// of the mean at each point: u_seed (the seeds' standard error), u_num and
/// u_input where the members state them.
struct BudgetParts
{
  static constexpr const char *titles[3] = {"u_seed (seeds' standard error)", "u_num (time step)",
                                            "u_input (fitted inputs)"};
  std::vector<double> x[3], y[3];

  void add(double at, const EnsembleStatistics &st, const StatedUncertainty &u)
  {
    const double share[3] = {100 * st.se / std::abs(st.mean), 100 * u.num, 100 * u.input};
    for (int k = 0; k < 3; ++k)
      if (std::isfinite(share[k]))
      {
        x[k].push_back(at);
        y[k].push_back(share[k]);
      }
  }
};

/// The budget's figure; a part no point has is named in the caption as not
/// estimated (none at all: no figure).
std::optional<Figure> budget_figure(const StudyQuantity &q, const StudyAbscissa &a, bool by_seed,
                                    const BudgetParts &parts)
{
  std::vector<Curve> curves;
  std::string absent;
  for (int k = 0; k < 3; ++k)
  {
    const std::string title = BudgetParts::titles[k];
    if (parts.x[k].empty())
      absent += (absent.empty() ? "" : ", ") + title.substr(0, title.find(' '));
    else
      curves.push_back(curve(title, parts.x[k], parts.y[k], CurveStyle::points));
  }
  if (curves.empty())
    return std::nullopt;
  Figure f = make_figure("budget_" + q.name, q.title + ": the uncertainty budget of the means",
                         by_seed ? "point [-]" : a.label, "standard uncertainty [% of the mean]", curves,
                         "The standard uncertainties of each point's mean over seeds, part by part (stats.csv): "
                         "u_seed the seeds' standard error, u_num the time-step study's, u_input the fitted "
                         "inputs' through the model's sensitivity." +
                           (absent.empty() ? std::string() : " Not estimated for these members: " + absent + "."));
  f.log_x = !by_seed && a.log;
  f.x_margins = true;
  return f;
}

/// The study's figures (peak stress, strain at peak, initial modulus, and
/// the budget of each) into DIR/plots; a figure gnuplot could not draw is
/// one line, never fatal.
void draw_sweep_figures(const std::string &out, const SweepPlan &plan, const Deck &base,
                        const std::vector<SweepRow> &rows)
{
  const StudyAbscissa a = study_abscissa(plan, base, rows);
  const std::size_t per_point = rows.size() / std::max<std::size_t>(plan.points.size(), 1);
  const bool by_seed = plan.points.size() == 1 && plan.seeds > 1;
  const std::vector<StudyQuantity> quantities = {
    {"peak_stress", "Peak stress", "peak axial stress [MPa]", 1e-6, &SweepRow::peak},
    {"strain_at_peak", "Strain at peak stress", "axial strain at peak [%]", 100, &SweepRow::strain},
    {"initial_modulus", "Initial modulus", "initial modulus [GPa]", 1e-9, &SweepRow::modulus},
  };
  std::vector<Figure> figures;
  for (std::size_t qi = 0; qi < quantities.size(); ++qi)
  {
    const StudyQuantity &q = quantities[qi];
    std::vector<StudySeries> series;
    BudgetParts budget;
    for (std::size_t p = 0; p < plan.points.size(); ++p)
    {
      auto s = std::find_if(series.begin(), series.end(), [&](const StudySeries &t) { return t.title == a.series[p]; });
      if (s == series.end())
        s = series.insert(series.end(), StudySeries{a.series[p], {}, {}, {}, {}, {}});
      std::vector<double> values;
      for (std::size_t i = p * per_point; i < (p + 1) * per_point; ++i)
        if (rows[i].status == "completed" && std::isfinite(rows[i].*q.value))
        {
          values.push_back(rows[i].*q.value);
          s->member_x.push_back(by_seed ? double(plan.first_seed + int(i)) : a.x[p]);
          s->member_y.push_back(rows[i].*q.value);
        }
      const EnsembleStatistics st = ensemble_statistics(values);
      budget.add(by_seed ? double(p + 1) : a.x[p], st, point_stated(rows, p * per_point, (p + 1) * per_point, qi));
      if (st.n == 0)
        continue;
      const std::vector<double> at =
        by_seed ? std::vector<double>{double(plan.first_seed), double(plan.first_seed + plan.seeds - 1)}
                : std::vector<double>{a.x[p]};
      for (const double x : at)
      {
        s->x.push_back(x);
        s->mean.push_back(st.mean);
        s->ci95.push_back(st.ci95);
      }
    }
    // A quantity no member has (a sweep of a kind without a peak stress)
    // gets no figure, rather than one gnuplot refuses.
    if (std::none_of(series.begin(), series.end(), [](const StudySeries &s) { return !s.x.empty(); }))
      continue;
    StudyAxes axes{q.name,           q.title + " over the sweep", by_seed ? "seed [-]" : a.label, q.axis, 1, q.scale,
                   !by_seed && a.log};
    for (StudySeries &s : series)
      if (s.title.empty())
        s.title = "mean over seeds";
    Figure f = parameter_study_figure(axes, series);
    if (!a.caption.empty() && !by_seed)
      f.caption += " " + a.caption + ".";
    figures.push_back(std::move(f));
    if (std::optional<Figure> f_budget = budget_figure(q, a, by_seed, budget))
      figures.push_back(std::move(*f_budget));
  }
  const std::string missing = undrawn(draw_figures(figures, out + "/plots"));
  if (!missing.empty())
    std::cerr << "demvv: sweep figures not drawn: " << missing << "\n";
}

/// Takes the sweep directory on rank 0: new or empty, or the same sweep's
/// (resumed), or with --replace a sweep directory emptied.
void claim_sweep_directory(const std::string &dir, bool replace, const std::vector<Member> &members)
{
  if (!claim_resumable_directory(dir, replace, "sweep", "sweep.json"))
    return;
  const std::string named = "sweep directory '" + dir + "'";
  std::vector<std::string> labels, before;
  for (const Member &m : members)
    labels.push_back(m.label);
  try
  {
    before = nlohmann::json::parse(read_file(dir + "/sweep.json")).at("members").get<std::vector<std::string>>();
  }
  catch (const std::exception &)
  {
    throw DeckError(named + ": its sweep.json cannot be read as a sweep's record (damaged or edited): expected the "
                            "file demvv wrote, or --replace to start the sweep over");
  }
  if (before != labels)
    throw DeckError(
      named + " holds another sweep (other members): expected the same --vary, --seeds and --first-seed to resume "
              "it, or --replace to start it over");
  // A link planted in a shared sweep directory would send the members'
  // runs, and the removal of a member's folder before it runs again,
  // elsewhere.
  const fs::path folder = fs::path(dir) / "members";
  std::error_code ec;
  const fs::file_status st = fs::symlink_status(folder, ec);
  if (ec || !fs::exists(st))
    return;
  if (!fs::is_directory(st))
    throw DeckError(folder.string() + ": a link or a special file, not the sweep's members folder: expected a folder "
                                      "(or --replace to start the sweep over)");
  for (const fs::directory_entry &entry : fs::directory_iterator(folder, ec))
    if (!fs::is_directory(entry.symlink_status(ec)))
      throw DeckError(entry.path().string() + ": a link or a special file, not a member's run directory: expected "
                                              "the folders the sweep made (or --replace to start the sweep over)");
}

/// Each member's threads (RunOptions::threads and most_threads), applied:
/// --threads N: each member starts on N (fewer if fewer cores are idle) and may use up to N; else
/// OMP_NUM_THREADS, kept exactly; else demvv's choice: one rank starts on
/// the idle cores and may use them all, several share the cores out.  A
/// DEM member's count is governed during its run, as a run's is.
RunOptions member_threads(int requested, int ranks)
{
  RunOptions o = RunOptions::at_most(requested);
  if (requested <= 0 && !std::getenv("OMP_NUM_THREADS"))
  {
    o.most_threads = ranks == 1 ? omp_get_num_procs() : std::max(1, omp_get_num_procs() / ranks);
    if (ranks > 1)
      o.threads = o.most_threads;
  }
  o.threads = apply_threads(o);
  return o;
}
} // namespace

EnsembleStatistics ensemble_statistics(const std::vector<double> &values)
{
  std::vector<double> v;
  for (const double x : values)
    if (std::isfinite(x))
      v.push_back(x);
  EnsembleStatistics s;
  s.n = v.size();
  if (v.empty())
    return s;
  double sum = 0;
  for (const double x : v)
    sum += x;
  s.mean = sum / double(v.size());
  if (v.size() < 2)
    return s;
  double squares = 0;
  for (const double x : v)
    squares += (x - s.mean) * (x - s.mean);
  s.sd = std::sqrt(squares / double(v.size() - 1));
  s.se = std::sqrt(squares / double(v.size() - 1) / double(v.size()));
  s.ci95 = gsl_cdf_tdist_Pinv(0.975, double(v.size() - 1)) * s.sd / std::sqrt(double(v.size()));
  return s;
}

std::string csv_cell(double v) { return std::isfinite(v) ? format_number(v) : ""; }

nlohmann::json finite_or_null(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(); }

/// Parses the deck of every point (its kind's parse reads the entries it
/// uses, runs nothing).  A point refused beside others that run is a finding
/// of the sweep (its row says why); a sweep whose every point is refused
/// would run nothing, and a varied entry that no point's deck reads would run
/// the same member under different labels: both are refused.
void refuse_idle_factors(const SweepPlan &plan)
{
  if (plan.keys.empty())
    return;
  std::string first_refusal;
  std::vector<bool> read(plan.keys.size(), false);
  bool any_accepted = false;
  for (const auto &point : plan.points)
  {
    std::vector<std::string> overrides;
    for (std::size_t k = 0; k < plan.keys.size(); ++k)
      overrides.push_back(plan.keys[k] + "=" + point[k]);
    try
    {
      const Deck deck = Deck::from_file(deck_kinds(), plan.base_deck, overrides);
      deck.kind_row().parse(deck);
      any_accepted = true;
      for (std::size_t k = 0; k < plan.keys.size(); ++k)
        read[k] = read[k] || deck.was_read(plan.keys[k]);
    }
    catch (const DeckError &e)
    {
      if (first_refusal.empty())
        first_refusal = e.what();
    }
  }
  if (!any_accepted)
    throw DeckError("sweep of " + plan.base_deck + ": the deck refuses every point (the first: " + first_refusal +
                    "): expected values the deck accepts");
  for (std::size_t k = 0; k < plan.keys.size(); ++k)
    if (!read[k])
      throw DeckError("sweep of " + plan.base_deck + ": no point's deck reads '" + plan.keys[k] +
                      "' (its other entries make the run ignore it: another contact law, sample source or "
                      "history): expected an entry the members use (varying it would run identical members)");
}

SweepOutcome run_sweep(const SweepPlan &plan, const SweepSettings &o)
{
  const continuum::ParallelInfo mpi = study_ranks();
  const Deck base = Deck::from_file(deck_kinds(), plan.base_deck);
  const DeckKind *kind = &base.kind_row();
  if (kind->on_every_mpi_rank && mpi.ranks > 1)
    throw DeckError(plan.base_deck + ": a " + base.kind() +
                    " deck runs on every MPI rank, so its members cannot be "
                    "shared among ranks: expected a sweep without mpirun (its members then run one after another)");
  if (o.out_dir.empty())
    throw DeckError("sweep of " + plan.base_deck + ": no --out: expected the sweep directory");

  const std::size_t count = plan.points.size() * std::size_t(std::max(plan.seeds, 1));
  if (count > o.max_members)
    throw DeckError("sweep of " + plan.base_deck + ": " + std::to_string(plan.points.size()) + " point(s) x " +
                    std::to_string(std::max(plan.seeds, 1)) + " seed(s) = " + std::to_string(count) +
                    " members: expected at most " + std::to_string(o.max_members) +
                    " (--max-members N to allow more, knowing each member is a run)");
  refuse_idle_factors(plan);
  std::vector<Member> members = plan_members(plan);
  std::unique_ptr<DirectoryLock> lock; // rank 0's, for the whole sweep
  on_rank_zero_for_all(true,
                       [&]
                       {
                         lock = std::make_unique<DirectoryLock>(o.out_dir, "sweep");
                         claim_sweep_directory(o.out_dir, o.replace, members);
                       });
  const RunOptions member_options = member_threads(o.threads, mpi.ranks);
  const int threads = member_options.threads;
  prepare_samples(members, int(mpi.rank), int(mpi.ranks), o.progress);
  resolve_members(members, plan.base_deck, fnv1a_hex(base.resolved()));

  std::vector<bool> kept(members.size());
  std::size_t n_kept = 0;
  for (std::size_t i = 0; i < members.size(); ++i)
    n_kept += (kept[i] = finished(o.out_dir + "/members/" + members[i].label, members[i])) ? 1 : 0;

  nlohmann::json record = {{"command_line", o.command_line},
                           {"base_deck", plan.base_deck},
                           {"base_deck_hash", fnv1a_hex(base.resolved())},
                           {"kind", base.kind()},
                           {"seeds", plan.seeds},
                           {"first_seed", plan.first_seed},
                           {"seed_keys", "bonds/seed; sample/seed of a prepare deck; the sample of a prepare deck "
                                         "named by sample/file prepared with sample/seed and bonds/seed"},
                           {"ranks", mpi.ranks},
                           {"threads_per_rank", threads},
                           {"keys", plan.keys},
                           {"points", plan.points},
                           {"provenance", provenance(threads, 0, base.resolved())}};
  for (const Member &m : members)
    record["members"].push_back(m.label);
  const auto write_record = [&](const std::string &state)
  {
    record["status"] = state;
    write_atomically(o.out_dir + "/sweep.json", json_text(record, 2) + "\n");
  };
  if (mpi.rank == 0)
  {
    make_directories(o.out_dir + "/members");
    write_record("running");
    write_tables(o.out_dir, plan, members);
    if (o.progress)
      std::cerr << "demvv: sweep of " << members.size() << " members: " << n_kept << " kept from an earlier run, "
                << members.size() - n_kept << " to run on " << mpi.ranks << " rank" << (mpi.ranks > 1 ? "s" : "")
                << " x " << threads << " thread" << (threads > 1 ? "s" : "") << "\n";
  }
  wait_for_all_ranks();
  Progress progress("sweep", o.progress && mpi.rank == 0, double(n_kept) / double(members.size()));
  int interrupted = 0;
  for (std::size_t i = mpi.rank; i < members.size() && !interrupted; i += mpi.ranks)
  {
    const Member &m = members[i];
    if (kept[i])
      continue;
    const std::string dir = o.out_dir + "/members/" + m.label;
    std::error_code ec;
    fs::remove_all(dir, ec);
    std::string refusal = m.refusal;
    if (refusal.empty())
      try
      {
        RunOptions member_run = member_options;
        member_run.out_dir = dir;
        member_run.progress = false;
        member_run.resumable_alone = false;
        const RunStatus status = kind->parse(Deck::from_file(deck_kinds(), plan.base_deck, m.overrides))(member_run);
        interrupted = status.interrupted_by;
        if (status.fault)
          std::cerr << "demvv: member " << m.label << ": " << status.diagnostic() << "\n";
      }
      catch (const OutputError &)
      {
        throw;
      }
      catch (const std::runtime_error &e)
      {
        refusal = e.what();
      }
    if (!refusal.empty())
    {
      std::cerr << "demvv: member " << m.label << " refused: " << refusal << "\n";
      make_directories(dir);
      write_atomically(dir + "/summary.json", json_text({{"status", {{"state", "refused"}, {"message", refusal}}},
                                                         {"refused_deck", m.refused_deck},
                                                         {"provenance", provenance(threads, m.seed, m.resolved)}},
                                                        2) +
                                                "\n");
      if (!m.resolved.empty())
        write_atomically(dir + "/deck.prm", m.resolved);
    }
    if (mpi.rank == 0)
    {
      const std::vector<SweepRow> rows = write_tables(o.out_dir, plan, members);
      const auto done =
        std::count_if(rows.begin(), rows.end(), [](const SweepRow &r) { return r.status != "pending"; });
      progress.update(double(done) / double(members.size()),
                      std::to_string(done) + " of " + std::to_string(members.size()) + " members");
    }
  }
  interrupted = largest_over_ranks(interrupted);
  SweepOutcome outcome;
  outcome.exit_code = interrupted ? 128 + interrupted : 0;
  if (mpi.rank != 0)
  {
    for (const Member &m : members)
      outcome.rows.push_back(read_row(o.out_dir + "/members/" + m.label, m));
    return outcome;
  }
  progress.finish();
  outcome.rows = write_tables(o.out_dir, plan, members);
  if (o.figures)
    draw_sweep_figures(o.out_dir, plan, base, outcome.rows);
  std::map<std::string, std::size_t> counts;
  for (const SweepRow &r : outcome.rows)
    ++counts[r.status];
  nlohmann::json tally = nlohmann::json::object();
  std::string said;
  for (const auto &[status, n] : counts)
  {
    tally[status] = n;
    said += (said.empty() ? "" : ", ") + std::to_string(n) + " " + status;
  }
  record["members_by_status"] = tally;
  write_record(interrupted ? "interrupted" : "completed");
  outcome.summary = std::string("sweep ") + (interrupted ? "interrupted" : "done") + ": " + said + " of " +
                    std::to_string(members.size()) + " members; table in " + o.out_dir + "/sweep.csv" +
                    (interrupted ? "; rerun the same command to resume" : "");
  return outcome;
}

int command_sweep(const SweepOptions &o)
{
  const Deck base = Deck::from_file(deck_kinds(), o.base_deck);
  if (o.vary.empty() && o.seeds == 0)
    throw DeckError("sweep of " + o.base_deck + ": nothing varies: expected --vary SECTION/KEY=v1,v2,... or --seeds N");
  SweepPlan plan{o.base_deck, {}, {{}}, o.seeds, o.first_seed};
  for (const std::string &arg : o.vary)
  {
    const Varied v = parse_vary(arg, base);
    for (const std::string &key : v.keys)
    {
      if (std::find(plan.keys.begin(), plan.keys.end(), key) != plan.keys.end())
        throw DeckError("--vary '" + arg + "': '" + key + "' is varied twice: expected each key once");
      if (o.seeds > 0 && key.size() >= 5 && key.compare(key.size() - 5, 5, "/seed") == 0)
        throw DeckError("--vary '" + arg + "' with --seeds " + std::to_string(o.seeds) +
                        ": --seeds sets the seeds: expected one of them");
      plan.keys.push_back(key);
    }
    if (&arg == &o.vary.front())
      plan.first_factor_keys = v.keys.size();
    // The product, the first --vary outermost; tied entries take one value.
    std::vector<std::vector<std::string>> points;
    for (const std::vector<std::string> &point : plan.points)
      for (const std::string &value : v.values)
      {
        points.push_back(point);
        points.back().insert(points.back().end(), v.keys.size(), value);
      }
    plan.points = points;
  }
  const SweepOutcome outcome = run_sweep(plan, o.settings);
  if (!outcome.summary.empty())
    std::cerr << "demvv: " << outcome.summary << "\n";
  return outcome.exit_code;
}
} // namespace demvv
