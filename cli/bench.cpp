#include "cli/bench.h"

#include "app/decks/deck.h"
#include "app/io/input.h"
#include "app/io/sample_file.h"
#include "app/kinds/prepare.h"
#include "app/kinds/uniaxial.h"
#include "app/run/run.h"

#include "dem/speed_bench.h"

#include <omp.h>

#include <cmath>
#include <cstdio>

namespace demvv
{
int command_bench(const BenchOptions &o)
{
  const int threads = apply_threads({"", o.threads, false});
  dem::Lattice lattice;
  if (!dem::parse_lattice(o.lattice, lattice))
    throw DeckError("--lattice '" + o.lattice + "': expected sc or fcc");
  // A lattice cylinder of fewer sites is mostly surface and holds far fewer
  // balls than asked (8 gave 2, 27 gave 12); from 100 it is within 5 %.
  if (o.particles < 100)
    throw DeckError("--particles " + std::to_string(o.particles) +
                    ": expected at least 100 (a smaller lattice cylinder holds far fewer balls than asked)");
  if (o.steps < 1)
    throw DeckError("--steps " + std::to_string(o.steps) + ": expected at least 1 step");
  const dem::BallSpec ball = dem::bench_ball();
  const dem::WallProps platen = dem::bench_platen();

  dem::SimulationSettings settings;
  settings.local_damping = 0.7;
  auto model = dem::make_contact_model(o.law, {});
  if (!model)
    throw DeckError("--law '" + o.law + "': not a registered contact law");
  std::unique_ptr<dem::Simulation> sim_ptr;
  dem::Specimen cell;
  std::string source;
  if (!o.sample.empty())
  {
    TestSample sample =
      open_test_sample(load_or_prepare_sample(o.sample, true), ball, platen, std::move(model), settings);
    sim_ptr = std::move(sample.sim);
    cell = std::move(sample.cell);
    source = "prepared sample";
  }
  else
  {
    const double r = dem::bench_ball_radius;
    const double fill = lattice == dem::Lattice::simple_cubic ? dem::pi / 6 : dem::pi / (3 * std::sqrt(2.0));
    const double d = std::cbrt(o.particles * 4.0 / 3.0 * dem::pi * r * r * r / fill * 4 / dem::pi);
    const double sites = dem::lattice_cylinder_sites(lattice, r, 1.2 * d, 1.2 * d);
    check_memory(sites * sizeof(dem::Vec3) + dem::estimated_memory_bytes(sites, 3),
                 std::to_string(o.particles) + " balls", "demvv bench", "--particles", std::to_string(o.particles),
                 "expected fewer particles");
    cell = dem::bench_lattice_specimen(lattice, double(o.particles));
    sim_ptr =
      std::make_unique<dem::Simulation>(std::move(cell.particles), std::move(cell.walls), std::move(model), settings);
    source = o.lattice + " lattice";
  }
  dem::Simulation &sim = *sim_ptr;
  const dem::BenchTiming timing = dem::time_compression(sim, cell.bottom, cell.top, cell.area(), o.steps, o.repeat);
  const double n = sim.particles().size();
  std::printf("demvv bench: particles %.0f, contacts %zu, steps %ld, wall %.3f s, particle-steps/s %.3e, "
              "contact updates/s %.3e, threads %d (%s, %s law, dt %.3g s, best of %d), peak RSS %.0f MB\n",
              n, timing.touching, o.steps, timing.seconds, n * o.steps / timing.seconds,
              double(timing.touching) * o.steps / timing.seconds, threads, source.c_str(), o.law.c_str(),
              sim.time_step(), o.repeat, dem::peak_resident_bytes() / 1e6);
  return 0;
}
} // namespace demvv
