// The engine's speed benchmark: a bonded specimen compressed between
// platens, timed step by step.
//
// The specimen is the thesis's bonded sample in miniature (§6.2): balls of
// radius 0.885 mm, density 2650 kg/m^3, kn = 1.2e7 N/m and ks = 1.2e6 N/m
// per ball, friction 0.5, frictionless shear-free platens of kn = 1.2e7 N/m;
// either a lattice cylinder (H = D) of about N balls or a prepared sample.
// Every touching pair is bonded with bonds too strong to break, the top
// platen moves down at 0.01 m/s (uniaxial compression, protocol_uniaxial.h),
// and after a warm-up of up to 200 steps a fixed number of steps is timed
// `repeat` times; the fastest timing is kept, the least disturbed measure of
// what the code can do on a shared machine.  The warm-up rebuilds the
// neighbour list and contact table once, as every real run does many times,
// so that the peak memory includes what a rebuild holds.  Both `demvv bench` and the
// DEM-only `demvv_dem_bench` run it, so their figures are comparable.
#pragma once

#include "dem/simulation.h"
#include "dem/specimen.h"

namespace dem
{
/// The benchmark's ball and platen properties (position and radius unset).
BallSpec bench_ball();
WallProps bench_platen();
/// Ball radius of the lattice specimens [m].
inline constexpr double bench_ball_radius = 0.885e-3;

/// The lattice cylinder (H = D) whose ball count is closest to `particles`.
Specimen bench_lattice_specimen(Lattice lattice, double particles);

struct BenchTiming
{
  double seconds = 0;       ///< s, the fastest of the timed runs
  std::size_t touching = 0; ///< contacts carrying force at the end
};

/// Bonds every touching pair of `sim` (unbreakable bonds), then compresses
/// the specimen between walls `bottom` and `top` (cross-section `area`
/// [m^2]) and times `steps` steps `repeat` times.
BenchTiming time_compression(Simulation &sim, WallIndex bottom, WallIndex top, double area, long steps, int repeat);

/// Peak resident memory of this process so far [bytes] (getrusage).
double peak_resident_bytes();
} // namespace dem
