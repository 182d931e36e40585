// Small systems in a line or three: a ball, undamped settings, a simulation
// of a law with its default constants.  The engine's own tests and the
// verification checks build their two-ball and few-ball systems from these.
#pragma once

#include "dem/contact_model.h"
#include "dem/simulation.h"

#include <string_view>

namespace dem::small_systems
{
/// A ball of radius r [m] at x [m] with stiffnesses kn, ks [N/m] and friction mu.
inline BallSpec ball(const Vec3 &x, double r, double kn, double ks = 0, double mu = 0)
{
  BallSpec b;
  b.position = x;
  b.radius = r;
  b.kn = kn;
  b.ks = ks;
  b.friction = mu;
  return b;
}

/// Settings for closed-form checks: no damping, no gravity; fixed_dt > 0
/// fixes the step [s], allow_unstable runs it even above the stability bound.
inline SimulationSettings undamped(double fixed_dt = 0, bool allow_unstable = false)
{
  SimulationSettings s;
  s.local_damping = 0;
  s.fixed_time_step = fixed_dt;
  s.allow_unstable_step = allow_unstable;
  return s;
}

/// A simulation of the law `law` with its default constants (Table 7.2 for Burger's).
inline Simulation simulation(ParticleStore p, WallSet w = {}, SimulationSettings s = undamped(),
                             std::string_view law = "linear")
{
  return Simulation(std::move(p), std::move(w), make_contact_model(law, {}), s);
}
} // namespace dem::small_systems
