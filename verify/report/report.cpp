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

Headline headline(const std::vector<CheckRecord> &records)
{
  Headline h;
  for (Category c :
       {Category::code_verification, Category::solution_verification, Category::calibration, Category::validation})
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
    << banner(provenance) << "\n\n"
    << "Categories follow thesis §2.5: *code verification* (is the equation solved right), *solution "
       "verification* (how accurate is this solution), *calibration* (parameters fitted to data) and "
       "*validation* (is it the right equation). Each metric has a tolerance class: A algebraic (round-off), "
       "B time-discretised (truncation and its order), C event-resolved (one step), D statistical (seeds); "
       "docs/verification_catalogue.md defines them.\n\n";
  o << "## Requirements\n\n| id | requirement | classes | category | reference | verdict | runtime [s] |\n"
    << "|---|---|---|---|---|---|---|\n";
  for (const CheckRecord &r : records)
    o << "| " << r.check->id << " | " << r.check->requirement << " | "
      << tolerance_class_list(r.check->tolerance_classes) << " | " << category_name(r.check->category) << " | "
      << r.check->reference << " | " << (r.pass() ? "PASS" : "**FAIL**") << " | " << report_number(r.seconds) << " |\n";
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
      o << "\n### " << r.check->id << ": " << t.title << " (expected order " << t.expected_order << ")\n\n"
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
  o << "\n## Provenance\n\n```json\n" << json_text(provenance, 2) << "\n```\n";
  return o.str();
}
} // namespace demvv
