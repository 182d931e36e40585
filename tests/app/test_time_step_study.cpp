// The time-step study's statistics (app/studies/time_step_study.h) on
// synthetic ensembles whose answer is known: q_ij = q* + C s_i^p + e_j +
// n_ij, with a seed effect e_j common to every level (the packing, which
// common random numbers cancel) and level noise n_ij; and the u_num a bulk
// run takes from a recorded study (app/run/numerical_uncertainty.h).
#include "app/run/numerical_uncertainty.h"
#include "app/studies/time_step_study.h"

#include "tests/test_folder.h"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <vector>

using Catch::Matchers::WithinAbs;
using Catch::Matchers::WithinRel;

namespace
{
const std::vector<double> safety = {0.8, 0.4, 0.2, 0.1};
const std::vector<double> seed_effect = {0.31, -0.52, 0.12, 0.44, -0.27, 0.05};

/// values[level][seed]; `noise` scales a fixed, zero-free pattern.
std::vector<std::vector<double>> ensemble(double exact, double c, double p, double noise)
{
  std::vector<std::vector<double>> v(safety.size());
  for (std::size_t i = 0; i < safety.size(); ++i)
    for (std::size_t j = 0; j < seed_effect.size(); ++j)
      v[i].push_back(exact + c * std::pow(safety[i], p) + seed_effect[j] +
                     noise * std::sin(1.7 * double(i + 1) + 2.3 * double(j + 1)));
  return v;
}
} // namespace

TEST_CASE("time-step study: an exact power law is recovered, whatever the seed effect", "[verify][time_step]")
{
  // No level noise: the paired changes are exact, so are the order
  // (round-off: a few ulp of logarithms) and Richardson's value (exact
  // for a single power term).
  const demvv::TimeStepAnalysis a = demvv::analyse_time_step(safety, ensemble(10.0, 2.0, 1.0, 0.0));
  REQUIRE(a.change.size() == 3);
  REQUIRE(a.order.size() == 2);
  for (const demvv::LevelChange &c : a.change)
    CHECK(c.resolved);
  CHECK_THAT(a.change[0].difference.mean, WithinRel(-0.8, 1e-12));
  for (const demvv::ObservedOrder &o : a.order)
  {
    REQUIRE(o.resolved);
    CHECK_THAT(o.order, WithinAbs(1.0, 1e-9));
  }
  // Richardson removes C s: q* plus the seeds' mean effect, 0.13 / 6.
  CHECK_THAT(a.extrapolated, WithinRel(10.0 + 0.13 / 6, 1e-12));
}

TEST_CASE("time-step study: order and its interval under level noise", "[verify][time_step]")
{
  // C s^2 with C = 1: changes 0.48, 0.12, 0.03; noise 1e-3 leaves them
  // resolved, the order within its own interval of 2.
  const demvv::TimeStepAnalysis a = demvv::analyse_time_step(safety, ensemble(5.0, 1.0, 2.0, 1e-3));
  for (const demvv::LevelChange &c : a.change)
    CHECK(c.resolved);
  for (const demvv::ObservedOrder &o : a.order)
  {
    REQUIRE(o.resolved);
    CHECK(o.low < 2.0);
    CHECK(o.high > 2.0);
    CHECK(o.high - o.low < 0.5);
  }
  // Finest level's bound: 1.25 |d| / (2^p - 1) with the resolved order.
  const double d = a.change.back().difference.mean, p = a.order.back().order;
  CHECK_THAT(a.error_bound.back(), WithinRel(1.25 * std::abs(d) / (std::pow(2.0, p) - 1), 1e-12));
  // Coarser levels carry more: the bound grows with the safety.
  CHECK(a.error_bound[0] > a.error_bound[1]);
  CHECK(a.error_bound[1] > a.error_bound[2]);
}

TEST_CASE("time-step study: a change within the noise is not resolved and gives no order", "[verify][time_step]")
{
  const demvv::TimeStepAnalysis a = demvv::analyse_time_step(safety, ensemble(5.0, 0.0, 1.0, 1e-2));
  for (const demvv::LevelChange &c : a.change)
    CHECK_FALSE(c.resolved);
  for (const demvv::ObservedOrder &o : a.order)
    CHECK_FALSE(o.resolved);
  CHECK(std::isnan(a.extrapolated));
  // The finest level's bound is the last change's bound over (r - 1) = 1.
  CHECK_THAT(a.error_bound.back(), WithinRel(a.change.back().bound(), 1e-14));
  for (double b : a.error_bound)
    CHECK(b > 0);
}

TEST_CASE("time-step study: a missing member drops out of the pairs that need it", "[verify][time_step]")
{
  auto v = ensemble(10.0, 2.0, 1.0, 0.0);
  v[1][3] = std::nan("");
  const demvv::TimeStepAnalysis a = demvv::analyse_time_step(safety, v);
  CHECK(a.level[1].n == seed_effect.size() - 1);
  CHECK(a.change[0].difference.n == seed_effect.size() - 1);
  CHECK(a.change[2].difference.n == seed_effect.size());
}

TEST_CASE("time-step study: a bulk run's u_num comes from the study that applies to it", "[verify][time_step]")
{
  const std::filesystem::path dir = demvv_tests::test_folder("studies");
  std::filesystem::create_directories(dir);
  // A study at 1000 balls: bounds 4 %, 3 %, 2 % at safeties 0.8, 0.4, 0.2.
  nlohmann::json levels = nlohmann::json::array();
  for (const auto &[safety, bound] : std::vector<std::pair<double, double>>{{0.8, 0.04}, {0.4, 0.03}, {0.2, 0.02}})
    levels.push_back({{"safety", safety}, {"u_num_bound_relative", bound}});
  const nlohmann::json study = {{"seeds", 5},
                                {"provenance", {{"sources_sha256", "abc"}, {"started_utc", "2026-12-02T00:00:00Z"}}},
                                {"quantities", {{"peak_stress_pa", {{"levels", levels}}}}}};
  std::ofstream(dir / "results_1000.json") << study.dump();

  const auto peak_bound = [&](double balls, double safety)
  {
    const nlohmann::json u = demvv::numerical_time_step_uncertainty(balls, safety, 0, dir.string());
    return u.value("estimated", false) ? u.at("peak_stress_pa").at("u_num_bound_relative_95").get<double>() : -1.0;
  };
  CHECK(peak_bound(1000, 0.8) == 0.04);
  CHECK(peak_bound(1500, 0.4) == 0.03);
  CHECK(peak_bound(600, 0.2) == 0.02);
  CHECK(peak_bound(1000, 0.5) == 0.04); // a finer step than 0.8 is covered by 0.8's bound
  CHECK(peak_bound(1000, 0.1) == 0.02); // finer than every level: the finest's
  CHECK(peak_bound(1000, 0.9) == -1.0); // coarser than every level: not estimated
  CHECK(peak_bound(54, 0.8) == -1.0);   // no study within a factor of two
  CHECK(peak_bound(2500, 0.8) == -1.0);
  const nlohmann::json u = demvv::numerical_time_step_uncertainty(1000, 0.8, 0, dir.string());
  CHECK(u.at("peak_stress_pa").at("u_num_relative").get<double>() == 0.02);
  CHECK(u.at("study_build") == "abc");
  CHECK_FALSE(demvv::numerical_time_step_uncertainty(54, 0.8, 0, dir.string()).at("why").get<std::string>().empty());

  // Steps compare as fractions of the undamped bound.  This study has no
  // "safety_bound": its safeties were of the undamped bound.  A run at 0.8
  // under local damping 0.7 steps 0.8 / sqrt(1.7) = 0.61 of it: covered by
  // the 0.8 level; at 0.6 (0.46 of it) still by 0.8, at 0.5 (0.38) by 0.4.
  const auto damped_bound = [&](double safety, double damping, const std::filesystem::path &folder)
  {
    const nlohmann::json b = demvv::numerical_time_step_uncertainty(1000, safety, damping, folder.string());
    return b.value("estimated", false) ? b.at("peak_stress_pa").at("u_num_bound_relative_95").get<double>() : -1.0;
  };
  CHECK(damped_bound(0.8, 0.7, dir) == 0.04);
  CHECK(damped_bound(0.6, 0.7, dir) == 0.04);
  CHECK(damped_bound(0.5, 0.7, dir) == 0.03);
  CHECK(u.at("step_fraction_of_undamped_bound").get<double>() == 0.8);
  // A study taken on the damped bound (local damping 0.7): its 0.8 level is
  // 0.61 of the undamped bound, so an undamped run at 0.8 is coarser than it.
  const std::filesystem::path damped_dir = dir / "damped";
  std::filesystem::create_directories(damped_dir);
  nlohmann::json damped_study = study;
  damped_study["safety_bound"] = "damped";
  damped_study["local_damping"] = 0.7;
  std::ofstream(damped_dir / "results_1000.json") << damped_study.dump();
  CHECK(damped_bound(0.8, 0.7, damped_dir) == 0.04);
  CHECK(damped_bound(0.4, 0.7, damped_dir) == 0.03);
  CHECK(damped_bound(0.8, 0, damped_dir) == -1.0);
  CHECK(damped_bound(0.6, 0, damped_dir) == 0.04);
}

TEST_CASE("time-step study: the recorded studies are read as they are", "[verify][time_step]")
{
  // The studies kept in cases/s02_time_step_study: what a 1000-ball run at
  // the default safety and damping states is the 0.8 level of
  // results_1000.json (taken on the undamped bound: 0.8 of the damped one
  // is 0.61 of it, finer than 0.8 and coarser than 0.4).
  const nlohmann::json u = demvv::numerical_time_step_uncertainty(1000, 0.8, 0.7);
  REQUIRE(u.value("estimated", false));
  std::ifstream in(demvv::time_step_study_dir() + "/results_1000.json");
  const nlohmann::json study = nlohmann::json::parse(in);
  const nlohmann::json &level = study.at("quantities").at("peak_stress_pa").at("levels").at(0);
  REQUIRE(level.at("safety").get<double>() == 0.8);
  CHECK(u.at("peak_stress_pa").at("u_num_bound_relative_95") == level.at("u_num_bound_relative"));
}
