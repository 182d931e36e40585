// Burger's contact laws and the rate laws (thesis §3.4.3, §7.2.2, eq. 4.3,
// 7.23) at the level of the law: what checks V14-V17 do not
// already cover through `demvv verify` (test_verification.cpp).
#include "dem/contact_resolve.h"
#include "dem/law_burgers.h"
#include "dem/law_linear.h"
#include "dem/rate_scaling.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <sstream>

namespace
{
/// A value rounded to one significant figure, as Table 4.2 prints it.
double one_figure(double v)
{
  std::ostringstream o;
  o.precision(0); // scientific: one digit before the point, none after
  o << std::scientific << v;
  return std::stod(o.str());
}

const dem::ContactParams none;
} // namespace

TEST_CASE("Table 4.2: temperature-compensated strain rates of eq. 4.3", "[burgers][rate]")
{
  // Table 4.2 prints one significant figure; eq. 4.3 with k = 13.4e3 K,
  // T_0 = 283 K (10 C) and T in kelvin = 273 + C must give exactly those.
  const dem::RateLaw law;
  struct Row
  {
    double celsius, rate, compensated;
  };
  const Row table[] = {{0, 0.02, 0.1},    {10, 0.02, 0.02}, {10, 0.1, 0.1}, {10, 0.5, 0.5},
                       {20, 0.02, 0.004}, {20, 0.1, 0.02},  {20, 0.5, 0.1}};
  for (const Row &r : table)
  {
    INFO(r.celsius << " C, " << r.rate << " 1/s");
    CHECK(one_figure(law.compensated_rate(r.rate, 273 + r.celsius)) == Approx(r.compensated).epsilon(1e-12));
  }
  // eq. 7.23 at the reference point is 1, and n = 0.29 per decade.
  CHECK(law.strength_factor(0.1, 283) == Approx(1).epsilon(1e-15));
  CHECK(law.strength_factor(1.0, 283) == Approx(std::pow(10.0, 0.29)).epsilon(1e-14));
}

TEST_CASE("a Burger's shear element with rigid Kelvin and no dashpots is the linear law", "[burgers]")
{
  // C_m, C_k -> infinity and K_k -> infinity leave the Maxwell spring: the
  // update must reduce to F_s <- F_s - K_m dU_s (law_linear.h) up to the
  // O(1/C) and O(1/K_k) terms, here below 1e-12 relative.
  const double km = 6e6;
  const dem::BurgersContactConstants k{{km, 1e30, 1e30, 1e30}, {km, 1e30, 1e30, 1e30}, 0};
  const dem::BurgersLaw burgers(k);
  const dem::LinearLaw linear;
  dem::ContactParams p;
  p.ks = km;
  dem::BurgersHistory h;
  dem::LinearLaw::History none_history;
  const dem::Vec3 old_force(0.3, -0.2, 0), increment(1e-7, 2e-7, 0);
  const dem::Vec3 a = burgers.shear_force(p, old_force, increment, h, 1e-6);
  const dem::Vec3 b = linear.shear_force(p, old_force, increment, none_history, 1e-6);
  CHECK((a - b).norm() <= 1e-12 * b.norm());
}

TEST_CASE("modified Burger's: elastic in compression, a relaxed Burger's element from U = 0 in tension", "[burgers]")
{
  const double e0 = 5.5e6, dt = 1e-6;
  const dem::BurgersConstants element{5.5e6, 5.5e6, 5.5e6, 5.5e6};
  const dem::ModifiedBurgersLaw law({element, element, e0});
  const dem::BurgersCoefficients co(element, dt);
  dem::BurgersHistory h;
  const auto step = [&](double overlap)
  {
    const double f = law.normal_force(none, overlap, h, dt);
    law.commit(h, overlap, f, dem::Vec3::Zero(), dem::Vec3::Zero(), dt);
    return f;
  };
  // Compression: F = E_0 U exactly, and the Burger's state stays at rest.
  CHECK(step(2e-6) == Approx(e0 * 2e-6).epsilon(1e-15));
  CHECK(h.normal_force == 0);
  CHECK(h.normal_kelvin == 0);
  CHECK(h.overlap == 0);
  // First step in tension: the element starts from rest at U = 0, so the
  // force is U / C (eq. 3.34 with zero history).
  const double first = step(-1e-6);
  CHECK(first == Approx(-1e-6 / co.c).epsilon(1e-14));
  // Further tension follows eq. 3.34 with the stored state.
  const dem::BurgersHistory before = h;
  const double second = step(-3e-6);
  CHECK(second == Approx(co.force(-2e-6, before.normal_kelvin, before.normal_force)).epsilon(1e-14));
  // Back in compression: the viscous force is dropped and the state reset.
  CHECK(step(1e-6) == Approx(e0 * 1e-6).epsilon(1e-15));
  CHECK(h.normal_kelvin == 0);
  CHECK(h.normal_force == 0);
}

TEST_CASE("the Burger's element stores what its springs hold", "[burgers]")
{
  // Under creep at constant force F the Maxwell spring holds F^2 / (2 K_0)
  // and the Kelvin spring tends to F^2 / (2 K_1) (u_k -> F / K_1).
  const dem::BurgersConstants k{2e6, 1e6, 4e6, 1e5};
  const dem::BurgersCoefficients co(k, 1e-4);
  double uk = 0;
  const double f = 3.0;
  for (int s = 0; s < 20000; ++s)
    uk = co.kelvin(uk, s == 0 ? 0.0 : f, f);
  CHECK(uk == Approx(f / k.kelvin_stiffness).epsilon(1e-9));
  CHECK(dem::burgers_energy(k, f, uk) ==
        Approx(0.5 * f * f / k.maxwell_stiffness + 0.5 * f * f / k.kelvin_stiffness).epsilon(1e-9));
}

TEST_CASE("an unbonded Burger's contact slips at mu F_n and carries no tension (frictional contacts, §7.4)",
          "[burgers]")
{
  // The bond and slip rules of contact_resolve.h are the same for every
  // law: an unbonded contact (a removed bond, thesis §7.4) limits the shear
  // force to mu F_n and drops tension.
  const dem::BurgersLaw law(dem::BurgersContactConstants{});
  dem::ContactParams params;
  params.friction = 0.7;
  params.ks = 1e6;
  bool bonded = false;
  const dem::ContactBond no_bond;
  dem::ContactState state;
  dem::BurgersHistory h;
  dem::ContactGeometry g{dem::Vec3::UnitX(), 1e-6,    dem::Vec3(0, 1e-2, 0), dem::Vec3::Zero(), dem::Vec3::Zero(),
                         0.885e-3,           0.885e-3};
  const double dt = 1e-6;
  dem::ResolvedContact r{};
  for (int s = 0; s < 200; ++s)
    r = dem::resolve_contact(law, params, bonded, no_bond, state, h, g, dt);
  REQUIRE(state.normal_force > 0);
  CHECK(state.shear_force.norm() == Approx(params.friction * state.normal_force).epsilon(1e-12));
  CHECK(state.friction_work > 0);
  // Pulled apart while still overlapping less: never a tensile force.
  g.overlap = 0.5e-6;
  g.velocity_difference = dem::Vec3(1, 0, 0);
  r = dem::resolve_contact(law, params, bonded, no_bond, state, h, g, dt);
  CHECK(state.normal_force >= 0);
}
