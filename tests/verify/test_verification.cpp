// Every check of the verification registry, as a test: the same code that
// writes the report decides the test, so the two can never disagree.
//
// The tests are not typed out here: one Catch2 TEST_CASE per registry row
// is generated at configure time from the registry's source
// (check_tests.cmake), named by the row's id and title and tagged [verify]
// and [<family>], so catch_discover_tests makes each check its own ctest
// test and a new row is a new test with no edit here (a row the generator
// missed fails the completeness test below).  Each metric is asserted with its value, tolerance, class and
// reason in the message (a validation check's metrics must be measured,
// not pass: validation may fail), and its tolerance class must be one its row
// declares; every declared class must be used, so the catalogue
// (docs/verification_catalogue.md) lists exactly the classes a check
// measures.  The last test keeps that committed catalogue in step with the
// registry.
#include "tests/verify/check_test.h"
#include "verify/checks/catalogue.h"
#include "verify/checks/check.h"
#include "verify/report/report.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>
#include <string>

void demvv_test::require_check(std::string_view id)
{
  const demvv::Check *check = demvv::find_check(id);
  REQUIRE(check != nullptr);
  const demvv::CheckOutcome outcome = check->run({demvv::default_cases_dir(), true, 0, {}});
  REQUIRE_FALSE(outcome.metrics.empty());
  const std::set<demvv::ToleranceClass> declared(check->tolerance_classes.begin(), check->tolerance_classes.end());
  std::set<demvv::ToleranceClass> used;
  for (const demvv::Metric &m : outcome.metrics)
  {
    INFO(id << ": " << m.name << " = " << m.value << (m.at_least ? " >= " : " <= ") << m.tolerance << " (class "
            << demvv::tolerance_class_letter(m.tolerance_class) << ": " << m.reason << ")");
    // Validation may fail: a validation check's test asks that every
    // comparison is made (a finite metric); the verdict is the report's.
    if (check->category == demvv::Category::validation)
      CHECK(std::isfinite(m.value));
    else
      CHECK(m.pass);
    CHECK(declared.count(m.tolerance_class) == 1);
    used.insert(m.tolerance_class);
  }
  INFO(id << " declares tolerance classes " << demvv::tolerance_class_list(check->tolerance_classes)
          << " in its registry row; its metrics use " << demvv::tolerance_class_list({used.begin(), used.end()}));
  CHECK(used == declared);
}

TEST_CASE("every registry row has its generated test", "[verify]")
{
  std::vector<std::string_view> rows;
  for (const demvv::Check &c : demvv::check_registry())
    rows.push_back(c.id);
  CHECK(rows == demvv_test::generated_check_ids);
}

TEST_CASE("every registry row is complete and declares its tolerance classes in order", "[verify]")
{
  std::set<std::string_view> ids;
  for (const demvv::Check &c : demvv::check_registry())
  {
    INFO("check " << c.id);
    CHECK(ids.insert(c.id).second);
    CHECK_FALSE(c.title.empty());
    CHECK_FALSE(c.family.empty());
    CHECK(c.requirement.rfind("demvv", 0) == 0);
    CHECK_FALSE(c.reference.empty());
    CHECK(c.run != nullptr);
    CHECK_FALSE(c.tolerance_classes.empty());
    CHECK(std::adjacent_find(c.tolerance_classes.begin(), c.tolerance_classes.end(),
                             [](demvv::ToleranceClass a, demvv::ToleranceClass b)
                             { return a >= b; }) == c.tolerance_classes.end());
  }
}

TEST_CASE("the committed verification catalogue is what the registry generates", "[verify][catalogue]")
{
  const std::string path = demvv::committed_catalogue_path();
  std::ifstream in(path, std::ios::binary);
  std::ostringstream committed;
  committed << in.rdbuf();
  const std::string generated = demvv::verification_catalogue();
  // Name the first line that differs, so the message says what changed.
  std::istringstream a(committed.str()), b(generated);
  std::string line_a, line_b;
  int line = 0;
  while (true)
  {
    ++line;
    const bool more_a = static_cast<bool>(std::getline(a, line_a));
    const bool more_b = static_cast<bool>(std::getline(b, line_b));
    if (!more_a && !more_b)
      break;
    if (more_a != more_b || line_a != line_b)
    {
      FAIL(path << " is out of date with the check registry (first difference at line " << line
                << "). Regenerate it with: build/demvv catalogue --out docs/verification_catalogue.md\n"
                << "  committed: " << (more_a ? line_a : "(end of file)") << "\n"
                << "  generated: " << (more_b ? line_b : "(end of file)"));
    }
  }
  CHECK(committed.str() == generated);
}

TEST_CASE("a convergence figure says what its dashed line is", "[verify][report]")
{
  // Three tables of one synthetic outcome: a theoretical order, an order
  // fitted to the same points, and errors at round-off level (no order).
  demvv::CheckRecord record;
  record.check = demvv::find_check("V21");
  REQUIRE(record.check != nullptr);
  using Reference = demvv::ConvergenceTable::Reference;
  for (Reference reference : {Reference::theory, Reference::fitted, Reference::roundoff})
  {
    demvv::ConvergenceTable t;
    t.title = "study";
    t.expected_order = reference == Reference::roundoff ? 0 : 2;
    t.reference = reference;
    t.roundoff_bound = 1e-9;
    for (double h : {0.4, 0.2, 0.1})
      t.add(h, reference == Reference::roundoff ? 3e-16 / h : h * h);
    record.outcome.tables.push_back(t);
  }
  const std::vector<demvv::Figure> figures = demvv::check_figures(record);
  REQUIRE(figures.size() >= 3);
  const auto titles = [](const demvv::Figure &f)
  {
    std::string all;
    for (const demvv::Curve &c : f.curves)
      all += c.title + "; ";
    return all;
  };
  CHECK(titles(figures[0]).find("order 2 (theory)") != std::string::npos);
  CHECK(titles(figures[1]).find("order 2 (fitted to these points)") != std::string::npos);
  CHECK(titles(figures[1]).find("theory") == std::string::npos);
  // Round-off: the errors against the check's bound, never an order.
  CHECK(titles(figures[2]).find("round-off bound of the check") != std::string::npos);
  CHECK(titles(figures[2]).find("order 0") == std::string::npos);
  CHECK(titles(figures[2]).find("theory") == std::string::npos);
  CHECK(demvv::reference_text(record.outcome.tables[2]) == "no order: exact up to round-off, bound 1e-09");
}

TEST_CASE("a check of many convergence studies shows them as one table, figures folded", "[verify][report]")
{
  // Five studies (V21 has two dozen): a table of them, then their figures
  // under one fold; two studies stay figures in the open.
  for (const std::size_t studies : {std::size_t{5}, std::size_t{2}})
  {
    demvv::CheckRecord record;
    record.check = demvv::find_check("V21");
    REQUIRE(record.check != nullptr);
    for (std::size_t k = 0; k < studies; ++k)
    {
      demvv::ConvergenceTable t;
      t.title = "study " + std::to_string(k);
      t.expected_order = 2;
      for (double h : {0.4, 0.2, 0.1})
        t.add(h, h * h);
      record.outcome.tables.push_back(t);
    }
    const std::vector<std::vector<demvv::Figure>> figures = {demvv::check_figures(record)};
    const std::string page = demvv::report_html({record}, figures, nlohmann::json::object(), {});
    const std::size_t table = page.find("<table class=\"family\">"), fold = page.find("<details class=\"family\">");
    if (studies == 5)
    {
      REQUIRE(table != std::string::npos);
      REQUIRE(fold != std::string::npos);
      CHECK(table < fold);
      CHECK(page.find("<td>study 4</td><td>3</td><td>0.01</td><td>2</td>") != std::string::npos);
      const std::size_t last = page.find("v21_convergence_5", fold); // the fold holds all five
      REQUIRE(last != std::string::npos);
      CHECK(page.find("</details>", fold) > last);
    }
    else
    {
      CHECK(table == std::string::npos);
      CHECK(fold == std::string::npos);
    }
  }
}
