// The compare kind's verdict (app/kinds/compare.h) on DEM summaries whose
// conditions are known: inside the correspondence identity the difference
// passes or fails against the deck's tolerance; outside it, the result is
// a model-form difference that names every condition that failed and is
// never judged against the tolerance.
#include "app/kinds/compare.h"

#include <catch2/catch.hpp>

#include <string>

namespace
{
/// A DEM summary inside the identity: no bond broken, no slip, quasi-static.
nlohmann::json quiet_bulk()
{
  return {{"bonds", {{"broken_tension", 0}, {"broken_shear", 0}, {"broken_displacement", 0}}},
          {"energy_j", {{"friction", 0.0}, {"strain", 2.5e-3}}},
          {"rate", {{"quasi_static_indicators", {{"max_inertial_number", 1e-5}}}}}};
}

bool names(const nlohmann::json &list, const std::string &part)
{
  for (const auto &item : list)
    if (item.get<std::string>().find(part) != std::string::npos)
      return true;
  return false;
}
} // namespace

TEST_CASE("compare verdict: inside the identity the tolerance decides")
{
  demvv::CompareSpec spec;
  spec.tolerance = 0.05;
  spec.bonded_platens = false;
  const nlohmann::json pass = demvv::identity_verdict(spec, true, quiet_bulk(), 0.049);
  CHECK(pass.at("inside_identity") == true);
  CHECK(pass.at("result") == "pass");
  CHECK(pass.at("conditions_failed").empty());
  const nlohmann::json fail = demvv::identity_verdict(spec, true, quiet_bulk(), 0.051);
  CHECK(fail.at("result") == "fail");
  CHECK(fail.at("line").get<std::string>().find("FAIL") != std::string::npos);
}

TEST_CASE("compare verdict: outside the identity a model-form difference, naming what failed")
{
  demvv::CompareSpec spec;
  spec.tolerance = 0.05;
  spec.bonded_platens = false;
  nlohmann::json bulk = quiet_bulk();
  bulk["bonds"]["broken_shear"] = 3;
  // A difference within the tolerance is still not a pass outside the identity.
  const nlohmann::json broken = demvv::identity_verdict(spec, true, bulk, 0.01);
  CHECK(broken.at("inside_identity") == false);
  CHECK(broken.at("result") == "model-form difference");
  CHECK(broken.at("conditions_failed").size() == 1);
  CHECK(names(broken.at("conditions_failed"), "3 broke"));
  CHECK(broken.at("line").get<std::string>().find("not judged against a tolerance") != std::string::npos);

  bulk["energy_j"]["friction"] = 1e-3; // slip well above 1e-6 of the stored energy
  bulk["rate"]["quasi_static_indicators"]["max_inertial_number"] = 2e-3;
  spec.bonded_platens = true;
  const nlohmann::json all = demvv::identity_verdict(spec, false, bulk, 0.2);
  CHECK(all.at("result") == "model-form difference");
  CHECK(all.at("conditions_failed").size() == 5);
  CHECK(all.at("conditions_held").empty());
  for (const char *condition :
       {"same-shape", "no bond broken", "no friction slip", "frictionless platens", "quasi-static"})
    CHECK(names(all.at("conditions_failed"), condition));
}
