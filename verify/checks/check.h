// Verification checks: requirement, reference, metric, tolerance, verdict.
//
// A check is one row of the registry (checks_registry.cpp): an id, a title,
// the family of checks it belongs to, one sentence of requirement ("demvv
// shall ..."), its V&V category (thesis §2.5: code verification, solution
// verification, calibration, validation; and model comparison, DEM against
// the continuum of the same contacts), the tolerance classes its metrics
// use, the reference it is measured against, and the function that runs it.
// The function returns metrics; each metric carries its value, its
// tolerance, the class of that tolerance and the reason for it.  A metric
// whose value or reference is NaN or missing fails: nothing passes by
// default.
//
// The class belongs to the metric, not to the check, because one check can
// measure things limited by different causes: an impact's peak force is
// limited by the step's truncation error (B) and its duration by where the
// contact starts inside a step (C).  The registry row declares the classes
// so that the catalogue can list them without running the check; the tests
// hold every returned metric to its row's declaration.
//
// `demvv verify` runs the registry and writes report.md and report.json; the
// Catch2 tests run the same checks, so a test and a report can never
// disagree.
#pragma once

#include "app/plot/figure.h"
#include "app/reference/convergence.h"

#include <map>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace demvv
{
/// The kind of evidence a check gives (catalogue.cpp defines each).
enum class Category
{
  code_verification,
  solution_verification,
  model_comparison,
  calibration,
  validation,
};

/// Every category, in the order the catalogue and the report list them.
inline constexpr Category all_categories[] = {Category::code_verification, Category::solution_verification,
                                              Category::model_comparison, Category::calibration, Category::validation};

std::string_view category_name(Category c);

/// What limits the accuracy of a metric, and so how its tolerance is set
/// (the catalogue, catalogue.cpp, gives each class's pass rule and reasoning).
enum class ToleranceClass
{
  A, ///< algebraic or one exact step: round-off only
  B, ///< time- or mesh-discretised, smooth: truncation error and its order
  C, ///< event-resolved: an event inside a step, one step's worth
  D, ///< statistical: scatter between random samples
};

char tolerance_class_letter(ToleranceClass t);
/// "algebraic", "time-discretised", "event-resolved", "statistical".
std::string_view tolerance_class_name(ToleranceClass t);
/// The letters in order, comma-separated: "B, C".
std::string tolerance_class_list(const std::vector<ToleranceClass> &classes);

struct Metric
{
  std::string name;                                   ///< what is measured, with its unit
  double value = 0;                                   ///< measured
  double tolerance = 0;                               ///< pass when value <= tolerance (or >= for at_least)
  bool at_least = false;                              ///< pass when value >= tolerance instead
  ToleranceClass tolerance_class = ToleranceClass::A; ///< what limits the value's accuracy
  std::string reason;                                 ///< why this tolerance
  bool pass = false;
};

/// |measured - expected| / |expected|, passing when <= tolerance; fails on
/// NaN, infinity or a zero reference.
Metric relative_error(std::string name, double measured, double expected, double tolerance, ToleranceClass tc,
                      std::string reason);
/// |measured - expected|, passing when <= tolerance; fails on NaN.
Metric absolute_error(std::string name, double measured, double expected, double tolerance, ToleranceClass tc,
                      std::string reason);
/// value <= limit (or >= when at_least); fails on NaN.
Metric bound(std::string name, double value, double limit, bool at_least, ToleranceClass tc, std::string reason);

struct CheckOutcome
{
  std::vector<Metric> metrics;
  std::vector<ConvergenceTable> tables;
  /// Measured curves beside their reference (closed form, law, continuum),
  /// drawn in report.html; convergence tables get their figure there too.
  std::vector<Figure> figures;
  std::vector<std::string> notes;
  bool pass() const;
};

struct CheckContext
{
  std::string cases_dir; ///< where the case decks are
  bool quick = true;     ///< fewer levels / shorter runs
  int threads = 0;       ///< demvv verify --threads: the most each run of a check uses (0: demvv's choice)

  /// The case decks read while a check runs: the path under cases_dir and
  /// the standard FNV-1a 64 of the file's text, for the report's provenance
  /// (run_checks empties it before each check; decks a check writes in its
  /// own code are part of the build, whose sources_sha256 the report states).
  mutable std::map<std::string, std::string> decks_read;

  /// The deck of case `name` (cases_dir/name/case.prm), recorded in
  /// decks_read; throws MissingCaseDeck when the folder has none.
  std::string case_deck(const std::string &name) const;
};

/// A check's case deck is missing from the cases folder it was given: bad
/// input to demvv verify (exit 2), not a failure of the code.
struct MissingCaseDeck : std::runtime_error
{
  using std::runtime_error::runtime_error;
};

struct Check
{
  std::string_view id;
  std::string_view title;
  std::string_view family; ///< contact, engine, bulk, burgers or continuum: its test's tag
  std::string_view requirement;
  Category category;
  std::vector<ToleranceClass> tolerance_classes; ///< every class its metrics use, in order A to D
  std::string_view reference;
  CheckOutcome (*run)(const CheckContext &);
};

const std::vector<Check> &check_registry();
const Check *find_check(std::string_view id);

/// The case directory compiled in (the source tree's cases/).
std::string default_cases_dir();
} // namespace demvv
