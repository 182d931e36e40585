// The verification report: report.md for people, report.json for scripts.
//
// report.md has a requirements table (id, requirement, the tolerance classes
// its metrics use, V&V category, reference, verdict, runtime), a metrics
// table (metric, its tolerance class, value, tolerance, verdict, reason), a
// convergence table for every order study, the notes of each check, and
// provenance.  report.json holds the same, per check and per metric.
#pragma once

#include "verify/checks/check.h"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace verify
{
struct CheckRecord
{
  const Check *check = nullptr;
  CheckOutcome outcome;
  double seconds = 0;
  std::string error; ///< set when the check threw instead of returning
  bool pass() const { return error.empty() && outcome.pass(); }
};

nlohmann::json report_json(const std::vector<CheckRecord> &records, const nlohmann::json &provenance);
std::string report_markdown(const std::vector<CheckRecord> &records, const nlohmann::json &provenance);

/// Runs the checks whose id or title contains `only` (all if empty).
std::vector<CheckRecord> run_checks(const CheckContext &ctx, const std::string &only, bool verbose);
} // namespace verify
