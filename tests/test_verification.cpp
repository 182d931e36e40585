// Every check of the verification registry, as a test: the same code that
// writes the report decides the test, so the two can never disagree.  Each
// metric is asserted with its value, tolerance and reason in the message.
#include "verify/checks/check.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <string>

namespace
{
void require_check(const char *id)
{
  const verify::Check *check = verify::find_check(id);
  REQUIRE(check != nullptr);
  const verify::CheckOutcome outcome = check->run({verify::default_cases_dir(), true});
  REQUIRE_FALSE(outcome.metrics.empty());
  for (const verify::Metric &m : outcome.metrics)
  {
    INFO(id << ": " << m.name << " = " << m.value << (m.at_least ? " >= " : " <= ") << m.tolerance << " ("
            << m.reason << ")");
    CHECK(m.pass);
  }
}
} // namespace

TEST_CASE("V01 linear normal impact matches Chung & Ooi closed forms", "[verify][contact]") { require_check("V01"); }
TEST_CASE("V02 contact bond carries load to its strength and breaks by the PFC rules", "[verify][contact]")
{
  require_check("V02");
}
TEST_CASE("V03 Coulomb slip and block on an incline", "[verify][contact]") { require_check("V03"); }
TEST_CASE("V04 objectivity under rigid rotation and renumbering", "[verify][engine]") { require_check("V04"); }
TEST_CASE("V05 free flight is exact", "[verify][engine]") { require_check("V05"); }
TEST_CASE("V06 critical time step: stability limit and automatic bound", "[verify][engine]") { require_check("V06"); }
TEST_CASE("V07 integrator converges with order 2", "[verify][engine]") { require_check("V07"); }
TEST_CASE("V08 energy audit of a bulk run closes within 1 %", "[verify][bulk]") { require_check("V08"); }
TEST_CASE("V09 wave front in a bonded chain travels at c0", "[verify][bulk]") { require_check("V09"); }
TEST_CASE("V10 cell list with skin equals brute force", "[verify][engine]") { require_check("V10"); }
TEST_CASE("V11 lattice porosity and coordination", "[verify][bulk]") { require_check("V11"); }
TEST_CASE("V12 SUNDIALS Burger's chain matches eq. 7.18 and its superpositions", "[verify][continuum]")
{
  require_check("V12");
}
TEST_CASE("V13 SUNDIALS Burger's creep matches eq. 2.15", "[verify][continuum]") { require_check("V13"); }
TEST_CASE("V14 the Burger's CN update is second order and flips sign in the stiff limit", "[verify][burgers]")
{
  require_check("V14");
}
TEST_CASE("V15 a two-ball Burger's pull follows eq. 7.18", "[verify][burgers]") { require_check("V15"); }
TEST_CASE("V16 scaling both viscosities reproduces the unscaled curve, C_inf alone does not", "[verify][burgers]")
{
  require_check("V16");
}
TEST_CASE("V17 the displacement criterion breaks at delta_c at every velocity", "[verify][burgers]")
{
  require_check("V17");
}
TEST_CASE("V18 affine moduli equal the contact sums over isotropic normals", "[verify][continuum]")
{
  require_check("V18");
}
TEST_CASE("V19 same-shape continuum stress is c f_B by both homogenisation routes", "[verify][continuum]")
{
  require_check("V19");
}
TEST_CASE("V20 frictionless cylinder: patch test and time order", "[verify][continuum]") { require_check("V20"); }
TEST_CASE("V21 manufactured solutions converge at the theoretical orders", "[verify][continuum]")
{
  require_check("V21");
}
TEST_CASE("V22 bonded cylinder GCI below 1 % with monotone convergence", "[verify][continuum]")
{
  require_check("V22");
}

TEST_CASE("every registered check has a test above", "[verify]")
{
  // Adding a check to the registry without a test here fails this case.
  const std::vector<std::string> tested = {"V01", "V02", "V03", "V04", "V05", "V06", "V07", "V08", "V09",
                                           "V10", "V11", "V12", "V13", "V14", "V15", "V16", "V17", "V18", "V19", "V20", "V21", "V22"};
  for (const verify::Check &c : verify::check_registry())
  {
    INFO("check " << c.id);
    CHECK(std::find(tested.begin(), tested.end(), std::string(c.id)) != tested.end());
  }
}
