// The analysis helpers of verify/run (line fits, peaks, rates), each
// against an exact value.
#include "app/run/analysis.h"

#include <catch2/catch.hpp>

#include <vector>

using Catch::Matchers::WithinRel;

TEST_CASE("analysis: line fit and peak and largest rate", "[verify][analysis]")
{
  const std::vector<double> x = {0, 1, 2, 3, 4, 5};
  const std::vector<double> y = {1, 3, 5, 7, 6, 2};
  const auto fit = demvv::fit_line(x, y, 0, 3);
  CHECK(fit.points == 4);
  CHECK_THAT(fit.slope, WithinRel(2.0, 1e-14));
  CHECK_THAT(fit.intercept, WithinRel(1.0, 1e-14));
  const auto pk = demvv::peak(x, y);
  CHECK(pk.value == 7);
  CHECK(pk.at == 3);
  double at = 0, rate = 0;
  REQUIRE(demvv::x_at_max_rate(x, std::vector<double>{0, 0, 1, 5, 8, 8}, at, rate));
  CHECK(at == 3); // centred differences 0.5, 2.5, 3.5, 1.5 at x = 1..4
  CHECK(rate == 3.5);
}
