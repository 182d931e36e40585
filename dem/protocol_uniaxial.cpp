#include "dem/protocol_uniaxial.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace dem
{
UniaxialCompression::UniaxialCompression(const Simulation &sim, WallIndex bottom, WallIndex top, double area,
                                         const UniaxialSettings &settings)
  : bottom_(bottom), top_(top), area_(area), height0_(0), speed_(0), start_time_(sim.time()),
    largest_radius_(sim.particles().max_radius()), settings_(settings)
{
  height0_ = separation(sim);
  speed_ = settings.platen_speed > 0 ? settings.platen_speed : settings.strain_rate * height0_;
}

double UniaxialCompression::separation(const Simulation &sim) const
{
  const Wall &b = sim.walls()[bottom_];
  return (sim.walls()[top_].point - b.point).dot(b.direction);
}

double UniaxialCompression::axial_strain(const Simulation &sim) const
{
  return (height0_ - separation(sim)) / height0_;
}

double UniaxialCompression::platen_stress(const Simulation &sim, WallIndex w) const
{
  return -sim.wall_force(w).dot(sim.walls()[w].direction) / area_;
}

bool UniaxialCompression::finished(const Simulation &sim) const
{
  return scheduled() ? elapsed(sim) >= settings_.duration : axial_strain(sim) >= settings_.final_strain;
}

double UniaxialCompression::time_left(const Simulation &sim) const
{
  if (scheduled())
    return std::max(0.0, settings_.duration - elapsed(sim));
  // The approach covers speed t^2 / (2 ramp) during the ramp and
  // speed (t - ramp / 2) after it.
  const double distance = settings_.final_strain * height0_, ramp = settings_.ramp_time;
  const double total =
    distance / speed_ >= 0.5 * ramp ? distance / speed_ + 0.5 * ramp : std::sqrt(2 * ramp * distance / speed_);
  return std::max(0.0, total - (sim.time() - start_time_));
}

double UniaxialCompression::scheduled_speed(const Simulation &sim)
{
  const double dt = sim.time_step();
  if (!(dt > 0))
    return 0;
  if (settings_.stress_schedule)
  {
    const double proportional = servo_platen_speed(sim, top_, area_, stress_top(sim),
                                                   settings_.stress_schedule(elapsed(sim) + dt), settings_.servo);
    servo_integral_ += settings_.servo.integral * proportional;
    return proportional + servo_integral_;
  }
  // The approach that puts the platens on the schedule at the end of the step.
  return (settings_.strain_schedule(elapsed(sim) + dt) - axial_strain(sim)) * height0_ / dt;
}

void UniaxialCompression::drive(Simulation &sim)
{
  // Platens closer than one ball radius hold no sample: a load beyond its
  // strength (a creep stress, a servo) crushed it and drove the balls out
  // sideways, and the platens would pass each other.  No strain measured
  // from here on means anything.  (A ball still between them overlaps a
  // platen by half its radius before that: Simulation::
  // check_contact_overlaps names it first.)
  const double gap = separation(sim);
  if (gap < largest_radius_)
  {
    std::ostringstream what;
    what << "the sample collapsed: the platens are " << gap << " m apart (axial strain " << axial_strain(sim)
         << "), less than the largest ball radius " << largest_radius_
         << " m, with the balls pushed out from between them; the load exceeded what the sample can carry";
    throw NumericalFault(sim.steps(), sim.time(), -1, what.str());
  }
  double speed = 0;
  if (scheduled())
    speed = scheduled_speed(sim);
  else
  {
    const double ramp = settings_.ramp_time > 0 ? std::min(1.0, elapsed(sim) / settings_.ramp_time) : 1.0;
    speed = speed_ * ramp;
  }
  Wall &top = sim.walls()[top_];
  Wall &bottom = sim.walls()[bottom_];
  if (settings_.both_platens && !settings_.stress_schedule)
  {
    top.velocity = 0.5 * speed * top.direction;
    bottom.velocity = 0.5 * speed * bottom.direction;
  }
  else
  {
    top.velocity = speed * top.direction;
    bottom.velocity.setZero();
  }
}
} // namespace dem
