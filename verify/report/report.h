// The verification report: report.html and report.md for people,
// report.json for scripts.
//
// report.html is one self-contained page (figures inline as SVG data, no
// network): a verdict table, the definitions of the V&V categories and
// tolerance classes, then a section per check with its requirement,
// reference, category, run time, figures (each convergence study on log-log
// axes with the theoretical slope, the check's own curves beside their
// reference, and every metric's value against its tolerance), the metrics
// table and notes.  A small script marks any figure the browser could not
// render, which the browser test reads back.
//
// report.md has a requirements table (id, requirement, the tolerance classes
// its metrics use, V&V category, reference, verdict, runtime), a metrics
// table (metric, its tolerance class, value, tolerance, verdict, reason), a
// convergence table for every order study, the notes of each check, and
// provenance.  report.json holds the same, per check and per metric.
#pragma once

#include "app/plot/gnuplot.h"
#include "verify/checks/check.h"

#include <nlohmann/json.hpp>

#include <map>
#include <string>
#include <vector>

namespace demvv
{
struct CheckRecord
{
  const Check *check = nullptr;
  CheckOutcome outcome;
  double seconds = 0;
  std::string error;                        ///< set when the check threw instead of returning
  std::map<std::string, std::string> decks; ///< case decks it read: path under the cases folder -> FNV-1a 64
  bool pass() const { return error.empty() && outcome.pass(); }
};

/// The verdicts of a verification by V&V category (thesis §2.5): checks
/// passed of those run per category, validation checks that found a model
/// error (a finding about the model, reported with its verdict, not a
/// failure of the code) and checks that failed otherwise (a check that
/// stopped included).  The headline of every report and of `demvv verify`'s
/// last line, and its exit code.
struct Headline
{
  struct Tally
  {
    Category category;
    std::size_t passed = 0, run = 0;
  };
  std::vector<Tally> categories; ///< in the order of §2.5, those run only
  std::size_t model_errors = 0;
  std::size_t code_failures = 0;

  /// One line: "code verification 14/14 pass; ...; validation 3/4 pass (1 model
  /// error found: ...)".
  std::string text() const;
  /// "N of M checks pass", over every category.
  std::string counts() const;
};
Headline headline(const std::vector<CheckRecord> &records);

/// The line under the headline: the mode (quick: what it leaves out), the
/// date, the commit, the host and its CPU, from the report's provenance.
std::string banner(const nlohmann::json &provenance);

/// What the report covers and what a signature on it is for: the build and
/// decks, what is verified, the intended use, what is left out, and in
/// quick mode what the small lattices cannot show.  One paragraph each.
std::vector<std::string> report_scope(const nlohmann::json &provenance);
/// What a signature in the sign-off block attests, and its roles.
extern const char *const sign_off_statement;
extern const std::vector<const char *> sign_off_roles;
/// The case decks a check read with their FNV-1a 64, or what stands for them.
std::string case_decks_text(const CheckRecord &record);

nlohmann::json report_json(const std::vector<CheckRecord> &records, const nlohmann::json &provenance);
std::string report_markdown(const std::vector<CheckRecord> &records, const nlohmann::json &provenance);

/// A number as every report prints it: format_number at three significant digits.
std::string report_number(double v);
/// What a convergence table's expected order is, in words: "theoretical
/// order 2", "order 1.53 fitted to these points", "at least order 2", or
/// "no order: exact up to round-off (bound 1e-09)".
std::string reference_text(const ConvergenceTable &table);

/// The figures of one check in report.html (names start with the check's id).
std::vector<Figure> check_figures(const CheckRecord &record);
/// report.html, given each record's figures (check_figures) and each figure drawn (by name).
std::string report_html(const std::vector<CheckRecord> &records, const std::vector<std::vector<Figure>> &figures,
                        const nlohmann::json &provenance, const std::map<std::string, DrawnFigure> &drawn);
/// Writes report.json, report.md, figures/ (scripts, data, SVG) and report.html into out_dir.
void write_reports(const std::vector<CheckRecord> &records, const nlohmann::json &provenance,
                   const std::string &out_dir);

/// Runs the checks whose id or title contains `only` (all if empty).  A
/// check that throws is recorded as failed, except for MissingCaseDeck,
/// which is passed on (the cases folder given is bad input).
std::vector<CheckRecord> run_checks(const CheckContext &ctx, const std::string &only, bool verbose);
} // namespace demvv
