#include "support/two_body.h"

#include <catch2/catch.hpp>
#include <cstdio>

using namespace demtest;

TEST_CASE("impact smoke")
{
  const double r = 1e-3, kn = 1e6;
  auto sim = two_balls(r, 2 * r + 1e-5, kn);
  sim.particles().velocity[0] = Vec3(0.05, 0, 0);
  sim.particles().velocity[1] = Vec3(-0.05, 0, 0);
  double fmax = 0, t_on = -1, t_off = -1;
  for (int s = 0; s < 200000; ++s)
  {
    sim.compute_forces();
    const double f = sim.particles().force[1].x();
    if (f > 0 && t_on < 0)
      t_on = sim.time();
    if (t_on > 0 && t_off < 0 && f == 0)
      t_off = sim.time();
    fmax = std::max(fmax, f);
    sim.integrate(false);
    if (t_off > 0)
      break;
  }
  const double m = sim.particles().mass[0];
  const double mstar = m / 2, K = kn / 2;
  std::printf("dt=%g tc=%g expected %g ; fmax=%g expected %g ; v after %g\n", sim.time_step(),
              t_off - t_on, dem::LinearLaw::collision_time(K, mstar), fmax,
              dem::LinearLaw::peak_force(K, mstar, 0.1), sim.particles().velocity[1].x());
}
