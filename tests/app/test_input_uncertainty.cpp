// The input uncertainty of a run whose deck demvv calibrate fitted
// (app/run/input_uncertainty.h): u_input / |q| = sqrt(g^T C g) against
// hand-computed values, and the record's refusals as the deck's one-line
// errors.  (tests/cli/calibrate.sh checks it on a real calibration, a run and
// a sweep of its fitted deck.)
#include "app/decks/deck.h"
#include "app/kinds/deck_kinds.h"
#include "app/run/input_uncertainty.h"

#include "tests/test_folder.h"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <string>

using Catch::Matchers::Contains;
using Catch::Matchers::WithinRel;

namespace
{
/// A converged record fitting bonds/normal strength to 11 N: relative
/// standard error 0.075, peak stress 1e7 Pa with slope 1.35e7 Pa per unit
/// ln(strength), so g = 1.35 and u_input / peak = 1.35 x 0.075.
nlohmann::json one_parameter()
{
  return {{"status", "converged"},
          {"parameters",
           {{{"name", "bonds/normal strength"},
             {"keys", {"bonds/normal strength"}},
             {"deck_value", "11"},
             {"relative_standard_error", 0.075}}}},
          {"targets", {{{"quantity", "peak_stress_pa"}, {"fitted_mean", 1e7}, {"slope_per_ln_parameter", {1.35e7}}}}}};
}

demvv::Deck lattice(const nlohmann::json &record, const std::string &strength)
{
  const std::string path = demvv_tests::test_folder("calibration.json").string();
  std::ofstream(path) << record.dump();
  return demvv::Deck::from_file(demvv::deck_kinds(), std::string(DEMVV_TEST_DATA) + "/small_lattice.prm",
                                {"bonds/normal strength=" + strength, "calibration/record=" + path});
}
} // namespace

TEST_CASE("u_input: one fitted parameter is its standard error times the elasticity", "[app][input_uncertainty]")
{
  CHECK_THAT(demvv::calibrated_input_uncertainty(one_parameter(), "peak_stress_pa"), WithinRel(1.35 * 0.075, 1e-14));
  std::string why;
  CHECK(std::isnan(demvv::calibrated_input_uncertainty(one_parameter(), "strain_at_peak", &why)));
  CHECK_THAT(why, Contains("not a target"));
  nlohmann::json no_slope = one_parameter();
  no_slope["targets"][0]["slope_per_ln_parameter"][0] = nullptr;
  CHECK(std::isnan(demvv::calibrated_input_uncertainty(no_slope, "peak_stress_pa", &why)));
  CHECK_THAT(why, Contains("no finite slope"));
}

TEST_CASE("u_input: two correlated parameters give sqrt(g^T C g)", "[app][input_uncertainty]")
{
  // g = (1, 0.5), r = (0.1, 0.2), rho = -0.5: variance 0.01 + 0.01 - 0.01 =
  // 0.01; the same record uncorrelated gives 0.02, fully correlated
  // (0.1 + 0.1)^2 = 0.04.
  nlohmann::json c = {
    {"parameters",
     {{{"name", "a"}, {"relative_standard_error", 0.1}}, {{"name", "b"}, {"relative_standard_error", 0.2}}}},
    {"targets", {{{"quantity", "peak_stress_pa"}, {"fitted_mean", 4.0}, {"slope_per_ln_parameter", {4.0, 2.0}}}}},
    {"correlation", {{1.0, -0.5}, {-0.5, 1.0}}}};
  CHECK_THAT(demvv::calibrated_input_uncertainty(c, "peak_stress_pa"), WithinRel(0.1, 1e-14));
  c["correlation"] = {{1.0, 0.0}, {0.0, 1.0}};
  CHECK_THAT(demvv::calibrated_input_uncertainty(c, "peak_stress_pa"), WithinRel(std::sqrt(0.02), 1e-14));
  c["correlation"] = {{1.0, 1.0}, {1.0, 1.0}};
  CHECK_THAT(demvv::calibrated_input_uncertainty(c, "peak_stress_pa"), WithinRel(0.2, 1e-14));
  c.erase("correlation");
  std::string why;
  CHECK(std::isnan(demvv::calibrated_input_uncertainty(c, "peak_stress_pa", &why)));
  CHECK_THAT(why, Contains("no correlation"));
}

TEST_CASE("u_input: a deck states it only while it holds the fitted values", "[app][input_uncertainty]")
{
  const nlohmann::json block = demvv::input_uncertainty_block(lattice(one_parameter(), "11"));
  CHECK(block.at("estimated").get<bool>());
  CHECK_THAT(block.at("peak_stress_pa").at("u_input_relative").get<double>(), WithinRel(1.35 * 0.075, 1e-14));
  CHECK(block.at("initial_modulus_pa").at("u_input_relative").is_null());
  // The same value written otherwise is the same value.
  CHECK(demvv::input_uncertainty_block(lattice(one_parameter(), "1.1e1")).at("estimated").get<bool>());

  CHECK_THROWS_WITH(demvv::input_uncertainty_block(lattice(one_parameter(), "12")),
                    Contains("bonds/normal strength") && Contains("fitted 11 here: expected the fitted value"));
  nlohmann::json unconverged = one_parameter();
  unconverged["status"] = "not converged";
  CHECK_THROWS_WITH(demvv::input_uncertainty_block(lattice(unconverged, "11")),
                    Contains("calibration/record") && Contains("did not converge"));
  nlohmann::json damaged = one_parameter();
  damaged["parameters"][0]["name"] = 3;
  CHECK_THROWS_WITH(demvv::input_uncertainty_block(lattice(damaged, "11")), Contains("damaged or edited"));
  nlohmann::json foreign = one_parameter();
  foreign["parameters"][0]["keys"][0] = "bonds/no such entry";
  CHECK_THROWS_WITH(demvv::input_uncertainty_block(lattice(foreign, "11")), Contains("not an entry of this deck"));

  const demvv::Deck none =
    demvv::Deck::from_file(demvv::deck_kinds(), std::string(DEMVV_TEST_DATA) + "/small_lattice.prm");
  CHECK_FALSE(demvv::input_uncertainty_block(none).at("estimated").get<bool>());
}
