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
//
// Other loading histories are schedules of time since the start: a
// prescribed axial strain eps(t) (relaxation, cyclic loading), which the
// platens follow by moving each step to where the schedule puts them at
// the end of the step, or a prescribed axial stress sigma(t) (creep), which
// a servo on the top platen tracks (eq. 3.12-3.16, servo.h) while the
// bottom one stays fixed.  A scheduled test ends at its duration.
#pragma once

#include "dem/servo.h"
#include "dem/simulation.h"

#include <functional>

namespace dem
{
struct UniaxialSettings
{
  double strain_rate = 0;  ///< 1/s, > 0 compressive (used when platen_speed == 0)
  double platen_speed = 0; ///< m/s, relative approach speed of the platens
  double ramp_time = 0;    ///< s, linear ramp of the speed from zero
  double final_strain = 0; ///< -, the test stops there
  bool both_platens = false;
  /// Prescribed axial strain at time t after the start (empty: constant speed) [-].
  std::function<double(double)> strain_schedule;
  /// Prescribed nominal axial stress at time t (servo on the top platen) [Pa].
  std::function<double(double)> stress_schedule;
  double duration = 0; ///< s, a scheduled test ends there
  ServoSettings servo; ///< creep: the platen servo's relaxation factor and speed limit
};

class UniaxialCompression : public StepHooks
{
public:
  /// bottom and top are plane walls facing each other along z; area is the
  /// initial cross-section of the sample [m^2].
  UniaxialCompression(const Simulation &sim, WallIndex bottom, WallIndex top, double area,
                      const UniaxialSettings &settings);

  /// Sets the platen velocities for the coming step.
  void drive(Simulation &sim);
  /// The step hook: platens are driven before the forces of every step.
  void before_forces(Simulation &sim) override { drive(sim); }
  bool finished(const Simulation &sim) const;
  bool scheduled() const { return settings_.strain_schedule || settings_.stress_schedule; }
  /// Time since the start of the test [s].
  double elapsed(const Simulation &sim) const { return sim.time() - start_time_; }
  /// Simulated time until the platens have closed to the final strain on
  /// their schedule (the ramp, then the full speed) [s].
  double time_left(const Simulation &sim) const;

  /// The held speed of the creep servo's integral action [m/s] (checkpoints keep it).
  double servo_integral() const { return servo_integral_; }
  void set_servo_integral(double speed) { servo_integral_ = speed; }

  double initial_height() const { return height0_; }
  double area() const { return area_; }
  double final_speed() const { return speed_; }
  double axial_strain(const Simulation &sim) const;
  /// Nominal stress on the top / bottom platen (compression positive) [Pa].
  double stress_top(const Simulation &sim) const { return platen_stress(sim, top_); }
  double stress_bottom(const Simulation &sim) const { return platen_stress(sim, bottom_); }

private:
  /// Approach speed of the platens for the coming step of a scheduled test [m/s].
  double scheduled_speed(const Simulation &sim);
  double separation(const Simulation &sim) const;
  double platen_stress(const Simulation &sim, WallIndex w) const;

  WallIndex bottom_, top_;
  double area_, height0_, speed_, start_time_;
  double largest_radius_; ///< m, the gap below which the sample has collapsed (radii are fixed in a test)
  double servo_integral_ = 0;
  UniaxialSettings settings_;
};
} // namespace dem
