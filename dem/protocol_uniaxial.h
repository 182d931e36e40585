// Uniaxial compression between two platens (thesis §6.1).
//
// The top platen moves down at a speed that ramps linearly from zero to its
// final value over `ramp_time` (thesis §6.1: "the velocity of the upper wall
// was increased at a constant rate until reaching a predefined final
// velocity"); the bottom platen is fixed, or both move at half the speed
// when `both_platens` is set.  The final speed is the platen speed, or the
// strain rate times the initial height.  Axial strain is (H0 - H)/H0 from
// the platen separation; nominal stress is the force on a platen over the
// initial cross-section area (compression positive).
#pragma once

#include "dem/simulation.h"

namespace dem
{
struct UniaxialSettings
{
  double strain_rate = 0;   ///< 1/s, > 0 compressive (used when platen_speed == 0)
  double platen_speed = 0;  ///< m/s, relative approach speed of the platens
  double ramp_time = 0;     ///< s, linear ramp of the speed from zero
  double final_strain = 0;  ///< -, the test stops there
  bool both_platens = false;
};

class UniaxialCompression : public StepHooks
{
public:
  /// bottom and top are plane walls facing each other along z; area is the
  /// initial cross-section of the sample [m^2].
  UniaxialCompression(const Simulation &sim, WallIndex bottom, WallIndex top, double area,
                      const UniaxialSettings &settings);

  /// Sets the platen velocities for the coming step.
  void drive(Simulation &sim) const;
  /// The step hook: platens are driven before the forces of every step.
  void before_forces(Simulation &sim) override { drive(sim); }
  bool finished(const Simulation &sim) const { return axial_strain(sim) >= settings_.final_strain; }
  /// Simulated time until the platens have closed to the final strain on
  /// their schedule (the ramp, then the full speed) [s].
  double time_left(const Simulation &sim) const;

  double initial_height() const { return height0_; }
  double area() const { return area_; }
  double final_speed() const { return speed_; }
  double axial_strain(const Simulation &sim) const;
  /// Nominal stress on the top / bottom platen (compression positive) [Pa].
  double stress_top(const Simulation &sim) const { return platen_stress(sim, top_); }
  double stress_bottom(const Simulation &sim) const { return platen_stress(sim, bottom_); }

private:
  double separation(const Simulation &sim) const;
  double platen_stress(const Simulation &sim, WallIndex w) const;

  WallIndex bottom_, top_;
  double area_, height0_, speed_, start_time_;
  UniaxialSettings settings_;
};
} // namespace dem
