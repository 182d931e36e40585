#include "verify/checks/check.h"

#include "app/io/input.h"
#include "app/io/output.h"
#include "build_info.h"

#include <cmath>
#include <filesystem>

namespace demvv
{
std::string_view category_name(Category c)
{
  switch (c)
  {
  case Category::code_verification:
    return "code verification";
  case Category::solution_verification:
    return "solution verification";
  case Category::model_comparison:
    return "model comparison";
  case Category::calibration:
    return "calibration";
  case Category::validation:
    return "validation";
  }
  return "?";
}

char tolerance_class_letter(ToleranceClass t)
{
  switch (t)
  {
  case ToleranceClass::A:
    return 'A';
  case ToleranceClass::B:
    return 'B';
  case ToleranceClass::C:
    return 'C';
  case ToleranceClass::D:
    return 'D';
  }
  return '?';
}

std::string_view tolerance_class_name(ToleranceClass t)
{
  switch (t)
  {
  case ToleranceClass::A:
    return "algebraic";
  case ToleranceClass::B:
    return "time-discretised";
  case ToleranceClass::C:
    return "event-resolved";
  case ToleranceClass::D:
    return "statistical";
  }
  return "?";
}

std::string tolerance_class_list(const std::vector<ToleranceClass> &classes)
{
  std::string out;
  for (ToleranceClass t : classes)
    out += (out.empty() ? "" : ", ") + std::string(1, tolerance_class_letter(t));
  return out;
}

Metric relative_error(std::string name, double measured, double expected, double tolerance, ToleranceClass tc,
                      std::string reason)
{
  Metric m{std::move(name), 0, tolerance, false, tc, std::move(reason), false};
  if (!std::isfinite(measured) || !std::isfinite(expected) || expected == 0)
  {
    m.value = std::nan("");
    m.reason += " [FAILED: missing, zero or non-finite reference or value]";
    return m;
  }
  m.value = std::abs(measured - expected) / std::abs(expected);
  m.pass = m.value <= tolerance;
  return m;
}

Metric absolute_error(std::string name, double measured, double expected, double tolerance, ToleranceClass tc,
                      std::string reason)
{
  Metric m{std::move(name), std::abs(measured - expected), tolerance, false, tc, std::move(reason), false};
  m.pass = std::isfinite(m.value) && m.value <= tolerance;
  return m;
}

Metric bound(std::string name, double value, double limit, bool at_least, ToleranceClass tc, std::string reason)
{
  Metric m{std::move(name), value, limit, at_least, tc, std::move(reason), false};
  m.pass = std::isfinite(value) && (at_least ? value >= limit : value <= limit);
  return m;
}

bool CheckOutcome::pass() const
{
  if (metrics.empty())
    return false;
  for (const Metric &m : metrics)
    if (!m.pass)
      return false;
  return true;
}

const Check *find_check(std::string_view id)
{
  for (const Check &c : check_registry())
    if (c.id == id)
      return &c;
  return nullptr;
}

std::string default_cases_dir() { return std::string(build_info::source_dir) + "/cases"; }

std::string CheckContext::case_deck(const std::string &name) const
{
  const std::string deck = cases_dir + "/" + name + "/case.prm";
  if (!std::filesystem::is_regular_file(deck))
    throw MissingCaseDeck("the cases folder '" + cases_dir + "' has no " + name + "/case.prm");
  decks_read[name + "/case.prm"] = fnv1a_hex(read_input(deck, "case deck", max_deck_bytes));
  return deck;
}
} // namespace demvv
