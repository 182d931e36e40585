// demvv_dem_bench: the engine's speed benchmark without deal.II or the
// command line of demvv, for scaling runs on other machines (a static
// binary: copy it and bench/scaling.sh, nothing to install).
//
//   demvv_dem_bench [BALLS [THREADS [STEPS [LATTICE [LAW]]]]]
//
// Runs dem/speed_bench.h on the lattice cylinder of about BALLS balls
// (default 6000) with THREADS OpenMP threads (default: OpenMP's choice),
// STEPS timed steps (default 1000, best of 3), lattice sc or fcc, contact
// law by keyword (default linear), and prints one line: balls, contacts,
// threads, particle-steps per second, peak resident memory in bytes and
// per ball, and a fingerprint of the final positions and velocities (FNV-1a
// of their bits): two builds whose arithmetic agrees print the same one.
#include "dem/speed_bench.h"

#include <omp.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>

namespace
{
std::uint64_t fingerprint(const dem::ParticleStore &p)
{
  std::uint64_t h = 14695981039346656037ull;
  for (const auto *field : {&p.position, &p.velocity})
    for (const dem::Vec3 &x : *field)
      for (int d = 0; d < 3; ++d)
      {
        std::uint64_t bits;
        std::memcpy(&bits, &x[d], sizeof bits);
        h = (h ^ bits) * 1099511628211ull;
      }
  return h;
}
} // namespace

int main(int argc, char **argv)
{
  const auto arg = [&](int k, const char *fallback) { return std::string(argc > k ? argv[k] : fallback); };
  const double balls = std::atof(arg(1, "6000").c_str());
  const int threads = std::atoi(arg(2, "0").c_str());
  const long steps = std::atol(arg(3, "1000").c_str());
  dem::Lattice lattice;
  std::unique_ptr<dem::ContactModel> model = dem::make_contact_model(arg(5, "linear"), {});
  if (!(balls >= 8) || threads < 0 || steps < 1 || !dem::parse_lattice(arg(4, "sc"), lattice) || !model)
  {
    std::fprintf(stderr, "usage: %s [BALLS>=8 [THREADS [STEPS>=1 [sc|fcc [LAW]]]]]\n", argv[0]);
    return 2;
  }
  if (threads > 0)
    omp_set_num_threads(threads);
  dem::Specimen cell = dem::bench_lattice_specimen(lattice, balls);
  dem::SimulationSettings settings;
  settings.local_damping = 0.7;
  const dem::WallIndex bottom = cell.bottom, top = cell.top;
  const double area = cell.area();
  dem::Simulation sim(std::move(cell.particles), std::move(cell.walls), std::move(model), settings);
  const dem::BenchTiming timing = dem::time_compression(sim, bottom, top, area, steps, 3);
  const double n = sim.particles().size(), peak = dem::peak_resident_bytes();
  std::printf("demvv_dem_bench: balls %.0f, contacts %zu, threads %d, steps %ld, wall %.3f s, "
              "particle-steps/s %.3e, peak RSS %.0f bytes, %.0f bytes/ball, fingerprint %016llx\n",
              n, timing.touching, omp_get_max_threads(), steps, timing.seconds, n * steps / timing.seconds, peak,
              peak / n, static_cast<unsigned long long>(fingerprint(sim.particles())));
  return 0;
}
