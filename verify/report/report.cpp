#include "verify/report/report.h"
#include "app/io/text.h"

#include "app/io/output.h"

#include <chrono>
#include <cstdio>
#include <iostream>
#include <sstream>

namespace demvv
{
std::string report_number(double v) { return format_number(v, 3); }

std::string reference_text(const ConvergenceTable &t)
{
  switch (t.reference)
  {
  case ConvergenceTable::Reference::fitted:
    return "order " + report_number(t.expected_order) + " fitted to these points, which no theory gives";
  case ConvergenceTable::Reference::least:
    return "at least order " + report_number(t.expected_order) + ", the slowest decay the check accepts";
  case ConvergenceTable::Reference::roundoff:
    return "no order: exact up to round-off, bound " + report_number(t.roundoff_bound);
  case ConvergenceTable::Reference::theory:
    break;
  }
  if (!(t.expected_order > 0))
    return "no order claimed";
  return "theoretical order " + report_number(t.expected_order);
}

Headline headline(const std::vector<CheckRecord> &records)
{
  Headline h;
  for (Category c : all_categories)
  {
    Headline::Tally t{c};
    for (const CheckRecord &r : records)
      if (r.check->category == c)
      {
        ++t.run;
        t.passed += r.pass() ? 1 : 0;
        if (!r.pass())
          ++(c == Category::validation && r.error.empty() ? h.model_errors : h.code_failures);
      }
    if (t.run > 0)
      h.categories.push_back(t);
  }
  return h;
}

std::string Headline::text() const
{
  std::string line;
  for (const Tally &t : categories)
  {
    line += (line.empty() ? "" : "; ") + std::string(category_name(t.category)) + " " + std::to_string(t.passed) + "/" +
            std::to_string(t.run) + " pass";
    if (t.category == Category::validation && model_errors > 0)
      line += " (" + std::to_string(model_errors) +
              " model error found: a finding about the model, not a failure of the code)";
  }
  if (code_failures > 0)
    line += "; " + std::to_string(code_failures) + " FAIL (a failure of the code or of a solution)";
  return line;
}

std::string Headline::counts() const
{
  std::size_t passed = 0, run = 0;
  for (const Tally &t : categories)
  {
    passed += t.passed;
    run += t.run;
  }
  return std::to_string(passed) + " of " + std::to_string(run) + " checks pass";
}

std::string banner(const nlohmann::json &provenance)
{
  const auto field = [&](const char *key) { return provenance.value(key, std::string("unrecorded")); };
  const bool quick = provenance.value("mode", "quick") == "quick";
  return std::string(quick ? "Quick mode: fewer levels and shorter runs; the bulk checks run on small lattices, not "
                             "on the thesis's prepared samples (demvv verify --full runs them at full size)."
                           : "Full mode: every level and the bulk checks on the prepared samples.") +
         " Run " + field("started_utc") + ", commit " + field("git_sha") + ", on " + field("host") + " (" +
         field("cpu_model") + ").";
}

std::vector<std::string> report_scope(const nlohmann::json &provenance)
{
  std::vector<std::string> scope = {
    "This report covers one build of demvv (its sources_sha256, compiler and flags are in the provenance below) "
    "and the case decks named under each check, with the FNV-1a 64 of their text; decks a check writes in its own "
    "code belong to the build. It verifies the DEM engine (linear, bonded and Burger's contacts, the "
    "velocity-Verlet step, walls and platens, bond breakage, the measurement of stress and strain) and the "
    "continuum companion (Burger's equations by CVODE, the deal.II viscoelastic cylinder) against closed forms, "
    "observed orders and independent solvers; it estimates the numerical uncertainty of the bulk recipe (time "
    "step, loading rate, seeds); and it calibrates the rate-temperature model of the thesis's Table 7.4 at one "
    "condition and validates it at the others.",
    "Intended use: evidence that demvv solves the equations its documentation states, for uniaxial compression "
    "of bonded sphere packings within the parameter ranges of these checks. A signature below is for that use "
    "only. Not covered: other loading paths (triaxial, shear, indirect tension), particles other than spheres, "
    "rates and temperatures outside the law's range (0 to 20 C), and any claim about real asphalt beyond the "
    "validation checks' conditions; a validation failure is a finding about the model, not about the code."};
  if (provenance.value("mode", "quick") == "quick")
    scope.push_back("This is a quick report: the bulk checks (time step, loading rate, seeds, calibration, "
                    "validation) ran on small lattices, so it verifies their code paths, not the numerical "
                    "uncertainty of thesis-size samples. Sign a report of demvv verify --full for that.");
  return scope;
}

const char *const sign_off_statement =
  "A signature attests that the signer has read each check's requirement, reference, tolerances and verdict in "
  "this report, for the build and decks it names, and accepts them for the intended use stated above. It does "
  "not extend to another build, another deck or another use.";
const std::vector<const char *> sign_off_roles = {"prepared by", "reviewed by", "approved by"};

std::string case_decks_text(const CheckRecord &record)
{
  if (record.decks.empty())
    return "none read: its decks are written in the check's code (part of the build's sources_sha256)";
  std::string text;
  for (const auto &[path, hash] : record.decks)
    text += (text.empty() ? "" : ", ") + path + " (FNV-1a 64 " + hash + ")";
  return text;
}

std::vector<CheckRecord> run_checks(const CheckContext &ctx, const std::string &only, bool verbose)
{
  std::vector<CheckRecord> out;
  for (const Check &c : check_registry())
  {
    if (!only.empty() && std::string(c.id).find(only) == std::string::npos &&
        std::string(c.title).find(only) == std::string::npos)
      continue;
    CheckRecord r;
    r.check = &c;
    ctx.decks_read.clear();
    const auto start = std::chrono::steady_clock::now();
    try
    {
      r.outcome = c.run(ctx);
    }
    catch (const MissingCaseDeck &)
    {
      throw; // bad input to the whole verification, not this check's result
    }
    catch (const std::exception &e)
    {
      r.error = e.what();
    }
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    r.decks = ctx.decks_read;
    if (verbose)
      std::cerr << (r.pass() ? "PASS " : "FAIL ") << c.id << "  " << c.title << "  (" << report_number(r.seconds)
                << " s)" << (r.error.empty() ? "" : "  error: " + r.error) << "\n";
    out.push_back(std::move(r));
  }
  return out;
}

nlohmann::json report_json(const std::vector<CheckRecord> &records, const nlohmann::json &provenance)
{
  nlohmann::json checks = nlohmann::json::array();
  std::size_t failed = 0;
  for (const CheckRecord &r : records)
  {
    nlohmann::json metrics = nlohmann::json::array();
    for (const Metric &m : r.outcome.metrics)
      metrics.push_back({{"metric", m.name},
                         {"value", m.value},
                         {"tolerance", m.tolerance},
                         {"comparison", m.at_least ? ">=" : "<="},
                         {"tolerance_class", std::string(1, tolerance_class_letter(m.tolerance_class))},
                         {"tolerance_reason", m.reason},
                         {"pass", m.pass}});
    nlohmann::json tables = nlohmann::json::array();
    for (const ConvergenceTable &t : r.outcome.tables)
    {
      nlohmann::json rows = nlohmann::json::array();
      for (const ConvergenceRow &row : t.rows)
        rows.push_back({{"h", row.h}, {"error", row.error}, {"observed_order", row.order}});
      tables.push_back({{"title", t.title},
                        {"h", t.h_name},
                        {"error", t.error_name},
                        {"expected_order", t.expected_order},
                        {"reference", reference_text(t)},
                        {"levels", rows}});
    }
    nlohmann::json classes = nlohmann::json::array();
    for (ToleranceClass t : r.check->tolerance_classes)
      classes.push_back(std::string(1, tolerance_class_letter(t)));
    failed += r.pass() ? 0 : 1;
    checks.push_back({{"id", r.check->id},
                      {"title", r.check->title},
                      {"requirement", r.check->requirement},
                      {"category", category_name(r.check->category)},
                      {"family", r.check->family},
                      {"tolerance_classes", classes},
                      {"reference", r.check->reference},
                      {"metrics", metrics},
                      {"convergence", tables},
                      {"notes", r.outcome.notes},
                      {"error", r.error},
                      {"runtime_s", r.seconds},
                      {"case_decks_fnv1a64", r.decks},
                      {"pass", r.pass()}});
  }
  return {{"checks", checks},
          {"summary", {{"total", records.size()}, {"failed", failed}, {"passed", records.size() - failed}}},
          {"provenance", provenance}};
}

std::string report_markdown(const std::vector<CheckRecord> &records, const nlohmann::json &provenance)
{
  std::ostringstream o;
  const Headline head = headline(records);
  o << "# demvv verification report\n\n"
    << "**" << head.text() << "** (" << head.counts() << ").\n\n"
    << banner(provenance) << "\n\n## Scope and intended use\n\n";
  for (const std::string &paragraph : report_scope(provenance))
    o << paragraph << "\n\n";
  o << "Categories follow thesis §2.5: *code verification* (is the equation solved right), *solution "
       "verification* (how accurate is this solution), *calibration* (parameters fitted to data) and "
       "*validation* (is it the right equation); demvv adds *model comparison* (DEM against the continuum of the "
       "same contacts, held to the identity between them). Each metric has a tolerance class: A algebraic (round-off), "
       "B time-discretised (truncation and its order), C event-resolved (one step), D statistical (seeds); "
       "docs/verification_catalogue.md defines them.\n\n";
  o << "## Requirements\n\n| id | requirement | classes | category | reference | case decks | verdict | runtime [s] "
       "|\n|---|---|---|---|---|---|---|---|\n";
  for (const CheckRecord &r : records)
    o << "| " << r.check->id << " | " << r.check->requirement << " | "
      << tolerance_class_list(r.check->tolerance_classes) << " | " << category_name(r.check->category) << " | "
      << r.check->reference << " | " << case_decks_text(r) << " | " << (r.pass() ? "PASS" : "**FAIL**") << " | "
      << report_number(r.seconds) << " |\n";
  o << "\n## Metrics\n\n| id | metric | class | value | tolerance | verdict | why this tolerance |\n"
    << "|---|---|---|---|---|---|---|\n";
  for (const CheckRecord &r : records)
  {
    if (!r.error.empty())
      o << "| " << r.check->id << " | (the check stopped: " << r.error << ") | | | | **FAIL** | |\n";
    for (const Metric &m : r.outcome.metrics)
      o << "| " << r.check->id << " | " << m.name << " | " << tolerance_class_letter(m.tolerance_class) << " | "
        << report_number(m.value) << " | " << (m.at_least ? ">= " : "<= ") << report_number(m.tolerance) << " | "
        << (m.pass ? "PASS" : "**FAIL**") << " | " << m.reason << " |\n";
  }
  bool any_table = false;
  for (const CheckRecord &r : records)
    for (const ConvergenceTable &t : r.outcome.tables)
    {
      if (!any_table)
        o << "\n## Convergence studies\n";
      any_table = true;
      o << "\n### " << r.check->id << ": " << t.title << " (" << reference_text(t) << ")\n\n"
        << "| level | " << t.h_name << " | " << t.error_name << " | observed order |\n|---|---|---|---|\n";
      for (std::size_t k = 0; k < t.rows.size(); ++k)
        o << "| " << k << " | " << report_number(t.rows[k].h) << " | " << report_number(t.rows[k].error) << " | "
          << (k ? report_number(t.rows[k].order) : "-") << " |\n";
    }
  bool any_note = false;
  for (const CheckRecord &r : records)
    for (const std::string &n : r.outcome.notes)
    {
      if (!any_note)
        o << "\n## Notes\n\n";
      any_note = true;
      o << "- **" << r.check->id << "**: " << n << "\n";
    }
  o << "\n## Sign-off\n\n" << sign_off_statement << "\n\n| role | name | date | signature |\n|---|---|---|---|\n";
  for (const char *role : sign_off_roles)
    o << "| " << role << " | | | |\n";
  o << "\n## Provenance\n\n```json\n" << json_text(provenance, 2) << "\n```\n";
  return o.str();
}
} // namespace demvv
