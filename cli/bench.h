// demvv bench: the engine's throughput on the thesis's bonded sample.
//
// Builds a bonded lattice cylinder (H = D) of about N balls of radius
// 0.885 mm, density 2650 kg/m^3, kn = 1.2e7 N/m and ks = 1.2e6 N/m per ball,
// bonds too strong to break, local damping 0.7, automatic time step; drives
// the top platen down at 0.01 m/s; runs a warm-up, then times a fixed number
// of steps (the fastest of `repeat` timings) and prints one line:
// particles, contacts, steps, wall seconds, particle-steps per second,
// contact updates per second, threads, peak resident memory (the scenario
// is dem/speed_bench.h, shared with the DEM-only bench/dem_bench.cpp).
#pragma once

#include <string>

namespace demvv
{
struct BenchOptions
{
  long particles = 6000;
  long steps = 2000;
  int repeat = 3;
  int threads = 0;
  std::string lattice = "sc";
  std::string law = "linear";
  std::string sample; ///< a sample file or prepare deck instead of the lattice
};

int command_bench(const BenchOptions &options);
} // namespace demvv
