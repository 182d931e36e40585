#include "dem/speed_bench.h"

#include "dem/bonds.h"
#include "dem/protocol_uniaxial.h"

#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

namespace dem
{
BallSpec bench_ball()
{
  BallSpec ball;
  ball.density = 2650;
  ball.kn = 1.2e7;
  ball.ks = 1.2e6;
  ball.friction = 0.5;
  return ball;
}

WallProps bench_platen() { return {1.2e7, 0, 0}; }

Specimen bench_lattice_specimen(Lattice lattice, double particles)
{
  const double r = bench_ball_radius;
  const double fill = lattice == Lattice::simple_cubic ? pi / 6 : pi / (3 * std::sqrt(2.0));
  const double d = std::cbrt(particles * 4.0 / 3.0 * pi * r * r * r / fill * 4 / pi);
  // Only the centres are counted while searching, so that a large specimen
  // is built once.
  const auto count = [&](double scale)
  { return static_cast<double>(lattice_cylinder(lattice, r, d * scale, d * scale).centres.size()); };
  double best_scale = 1, best = count(1);
  for (double scale = 0.9; scale <= 1.2; scale += 0.005)
  {
    const double n = count(scale);
    if (std::abs(n - particles) < std::abs(best - particles))
    {
      best = n;
      best_scale = scale;
    }
  }
  return lattice_specimen(lattice, r, d * best_scale, d * best_scale, bench_ball(), bench_platen(), {}, false);
}

BenchTiming time_compression(Simulation &sim, WallIndex bottom, WallIndex top, double area, long steps, int repeat)
{
  sim.refresh_contacts();
  for (Contact &c : sim.contacts().entries())
    c.unbond();
  BondSettings bonds;
  bonds.normal_strength = bonds.shear_strength = 1e12;
  bond_touching_pairs(sim.contacts(), sim.particles(), bonds);
  UniaxialSettings load;
  load.platen_speed = 0.01;
  load.final_strain = 1;
  UniaxialCompression test(sim, bottom, top, area, load);

  const long warmup = std::min<long>(200, steps);
  sim.invalidate_neighbors();
  for (long k = 0; k < warmup; ++k)
    sim.step(test);
  BenchTiming out;
  out.seconds = std::numeric_limits<double>::infinity();
  for (int r = 0; r < repeat; ++r)
  {
    const auto start = std::chrono::steady_clock::now();
    for (long k = 0; k < steps; ++k)
      sim.step(test);
    out.seconds =
      std::min(out.seconds, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  for (const Contact &c : sim.contacts().entries())
    out.touching += c.state.touching() ? 1 : 0;
  return out;
}

double peak_resident_bytes()
{
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return 1024.0 * static_cast<double>(usage.ru_maxrss); // Linux reports kilobytes
}
} // namespace dem
