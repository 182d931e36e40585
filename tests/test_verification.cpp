// Every check of the verification registry, as a test: the same code that
// writes the report decides the test, so the two can never disagree.
//
// The tests are not typed out here: when the program starts, one Catch2 test
// per registry row is registered from check_registry(), named by the row's
// id and title and tagged [verify] and [<family>], so catch_discover_tests
// makes each check its own ctest test and a new row is a new test with no
// edit here.  Each metric is asserted with its value, tolerance, class and
// reason in the message, and its tolerance class must be one its row
// declares; every declared class must be used, so a row lists exactly the
// classes its check measures.
#include "verify/checks/check.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <deque>
#include <memory>
#include <set>
#include <string>

namespace
{
void require_check(std::string_view id)
{
  const verify::Check *check = verify::find_check(id);
  REQUIRE(check != nullptr);
  const verify::CheckOutcome outcome = check->run({verify::default_cases_dir(), true});
  REQUIRE_FALSE(outcome.metrics.empty());
  const std::set<verify::ToleranceClass> declared(check->tolerance_classes.begin(), check->tolerance_classes.end());
  std::set<verify::ToleranceClass> used;
  for (const verify::Metric &m : outcome.metrics)
  {
    INFO(id << ": " << m.name << " = " << m.value << (m.at_least ? " >= " : " <= ") << m.tolerance << " (class "
            << verify::tolerance_class_letter(m.tolerance_class) << ": " << m.reason << ")");
    CHECK(m.pass);
    CHECK(declared.count(m.tolerance_class) == 1);
    used.insert(m.tolerance_class);
  }
  INFO(id << " declares tolerance classes " << verify::tolerance_class_list(check->tolerance_classes)
          << " in its registry row; its metrics use "
          << verify::tolerance_class_list({used.begin(), used.end()}));
  CHECK(used == declared);
}

/// Runs one registered check; Catch owns it once registered.
class CheckInvoker : public Catch::ITestInvoker
{
public:
  explicit CheckInvoker(std::string_view id) : id_(id) {}
  void invoke() const override { require_check(id_); }

private:
  std::string_view id_; ///< points into the registry, which lives as long as the program
};

/// Registers one test per registry row.  Catch refers to names and tags by
/// StringRef, so they are kept in a deque, whose elements never move.
bool register_check_tests()
{
  static std::deque<std::string> names_and_tags;
  for (const verify::Check &c : verify::check_registry())
  {
    const std::string &name = names_and_tags.emplace_back(std::string(c.id) + " " + std::string(c.title));
    const std::string &tags = names_and_tags.emplace_back("[verify][" + std::string(c.family) + "]");
    // AutoReg hands the invoker to the test case, which owns it from then on.
    Catch::AutoReg(std::make_unique<CheckInvoker>(c.id).release(), CATCH_INTERNAL_LINEINFO, Catch::StringRef(),
                   Catch::NameAndTags{name, tags});
  }
  return true;
}

const bool check_tests_registered = register_check_tests();
} // namespace

TEST_CASE("every registry row is complete and declares its tolerance classes in order", "[verify]")
{
  REQUIRE(check_tests_registered);
  std::set<std::string_view> ids;
  for (const verify::Check &c : verify::check_registry())
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
                             [](verify::ToleranceClass a, verify::ToleranceClass b) { return a >= b; }) ==
          c.tolerance_classes.end());
  }
}
