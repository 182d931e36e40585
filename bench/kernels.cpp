// demvv_kernel_bench: the step's kernels one by one (Google Benchmark), so
// that a change to one of them is measured apart from the others.
//
//   force_pass/LAW/BALLS   Simulation::compute_forces: every contact resolved
//                          with the law, each ball's resultant summed
//   integrate/BALLS        Simulation::integrate: the centred-difference
//                          update of every ball
//   rebuild/BALLS          Simulation::refresh_contacts: the neighbour cells
//                          and the contact table's merge
//   force_pass_packed/LAW/BALLS  the force pass on a packed sample
//                          instead of the lattice
//
// Each works on the speed benchmark's bonded sc lattice cylinder
// (dem/speed_bench.h) of about BALLS balls after 400 steps of its
// compression, so that the contacts carry force as in a run; the kernel is
// then repeated on that state (integrate runs the steps on, with each
// step's force pass outside the timing).  On the lattice every pair is in
// compression and no candidate is apart, so each branch of the contact
// step goes one way; the packed sample is chapter 5's preparation
// (dem/prep_packing.h) with the settings of the thesis sample p01 (cases/)
// at the given ball count, continued with the law and compressed the same
// way: bonded pairs in tension and in compression and candidates apart,
// whose shares its counters give (tension: of the bonded pairs; apart: of
// the entries).  Preparing it takes about a minute at 6000 balls, once
// per process and size whatever the laws.
// Threads: OpenMP's choice (OMP_NUM_THREADS fixes it).  Rates are given
// per ball (particle_steps, per second) and per contact entry (entries).
// CI builds the binary and runs it once, briefly, as a smoke test; it
// never times it.
#include "dem/prep_packing.h"
#include "dem/speed_bench.h"

#include <benchmark/benchmark.h>

#include <map>
#include <memory>
#include <string>
#include <utility>

namespace
{
/// The compressed lattice of about `balls` balls with the law `law`, built
/// once per process and kept for every benchmark that asks for it.
dem::Simulation &specimen(const std::string &law, double balls)
{
  static std::map<std::pair<std::string, double>, std::unique_ptr<dem::Simulation>> built;
  std::unique_ptr<dem::Simulation> &sim = built[{law, balls}];
  if (!sim)
  {
    dem::Specimen cell = dem::bench_lattice_specimen(dem::Lattice::simple_cubic, balls);
    dem::SimulationSettings settings;
    settings.local_damping = 0.7;
    const double area = cell.area();
    const dem::WallIndex bottom = cell.bottom, top = cell.top;
    sim = std::make_unique<dem::Simulation>(std::move(cell.particles), std::move(cell.walls),
                                            dem::make_contact_model(law, {}), settings);
    dem::time_compression(*sim, bottom, top, area, 200, 1);
  }
  return *sim;
}

/// The packed sample of about `balls` balls, prepared once per process.
const dem::PreparedSample &packed_sample(double balls)
{
  static std::map<double, dem::PreparedSample> prepared;
  auto it = prepared.find(balls);
  if (it == prepared.end())
  {
    dem::PackingSettings settings;
    settings.particles = static_cast<long>(balls);
    settings.ball = dem::bench_ball();
    settings.walls = dem::bench_platen();
    // The thesis sample's bonds hold it together through the settling; the
    // compression (time_compression) then bonds its touching pairs
    // unbreakably, as the lattice's and `demvv bench --sample`'s.
    settings.bonds.normal_strength = settings.bonds.shear_strength = 31.3; // N
    it = prepared.emplace(balls, dem::prepare_sample(settings)).first;
  }
  return it->second;
}

/// The packed sample continued with the law `law` and compressed, built
/// once per process.
dem::Simulation &packed_specimen(const std::string &law, double balls)
{
  static std::map<std::pair<std::string, double>, std::unique_ptr<dem::Simulation>> built;
  std::unique_ptr<dem::Simulation> &sim = built[{law, balls}];
  if (!sim)
  {
    const dem::PreparedSample &sample = packed_sample(balls);
    dem::SimulationSettings settings;
    settings.local_damping = 0.7;
    sim = std::make_unique<dem::Simulation>(sample.sim->snapshot(), dem::make_contact_model(law, {}), settings);
    const dem::Specimen &cell = sample.cell;
    dem::time_compression(*sim, cell.bottom, cell.top, cell.area(), 200, 1);
  }
  return *sim;
}

void report_rates(benchmark::State &state, const dem::Simulation &sim)
{
  const double iterations = static_cast<double>(state.iterations());
  state.counters["particle_steps"] =
    benchmark::Counter(iterations * sim.particles().size(), benchmark::Counter::kIsRate);
  state.counters["entries"] = benchmark::Counter(iterations * sim.contacts().size(), benchmark::Counter::kIsRate);
}

/// Times the force pass of `sim`, repeated at its balls' positions and velocities.
void time_force_pass(benchmark::State &state, dem::Simulation &sim)
{
  for (auto _ : state)
    sim.compute_forces();
  report_rates(state, sim);
}

void force_pass(benchmark::State &state, const std::string &law)
{
  time_force_pass(state, specimen(law, static_cast<double>(state.range(0))));
}

void integrate(benchmark::State &state)
{
  dem::Simulation &sim = specimen("linear", static_cast<double>(state.range(0)));
  for (auto _ : state)
  {
    state.PauseTiming(); // integrate needs this step's forces
    sim.compute_forces();
    state.ResumeTiming();
    sim.integrate();
  }
  report_rates(state, sim);
}

void force_pass_packed(benchmark::State &state, const std::string &law)
{
  dem::Simulation &sim = packed_specimen(law, static_cast<double>(state.range(0)));
  time_force_pass(state, sim);
  double bonded = 0, stretched = 0, apart = 0;
  for (const dem::Contact &c : sim.contacts().entries())
  {
    bonded += c.bonded;
    stretched += c.bonded && c.state.overlap < 0;
    apart += !c.state.touching();
  }
  state.counters["tension"] = bonded > 0 ? stretched / bonded : 0.0;
  state.counters["apart"] = apart / static_cast<double>(sim.contacts().size());
}

void rebuild(benchmark::State &state)
{
  dem::Simulation &sim = specimen("linear", static_cast<double>(state.range(0)));
  for (auto _ : state)
    sim.refresh_contacts();
  report_rates(state, sim);
}
} // namespace

BENCHMARK_CAPTURE(force_pass, linear, std::string("linear"))->Arg(6000)->Arg(60000)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(force_pass, burgers, std::string("burgers"))->Arg(6000)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(force_pass, modified_burgers, std::string("modified_burgers"))
  ->Arg(6000)
  ->Unit(benchmark::kMicrosecond);
BENCHMARK(integrate)->Arg(6000)->Arg(60000)->Unit(benchmark::kMicrosecond);
BENCHMARK(rebuild)->Arg(6000)->Arg(60000)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(force_pass_packed, linear, std::string("linear"))->Arg(500)->Arg(6000)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(force_pass_packed, burgers, std::string("burgers"))->Arg(6000)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(force_pass_packed, modified_burgers, std::string("modified_burgers"))
  ->Arg(6000)
  ->Unit(benchmark::kMicrosecond);

BENCHMARK_MAIN();
