// Small systems for the engine's tests, built in a line or three (STYLE
// rule 8), on dem/ alone: demvv_dem_tests links nothing from verify/.
#pragma once

#include "dem/simulation.h"

#include <string_view>

namespace demtest
{
using dem::Vec3;

inline dem::BallSpec ball(const Vec3 &x, double r, double kn, double ks = 0, double mu = 0)
{
  dem::BallSpec b;
  b.position = x;
  b.radius = r;
  b.kn = kn;
  b.ks = ks;
  b.friction = mu;
  return b;
}

/// Settings for closed-form checks: no damping, no gravity; fixed_dt > 0 fixes the step.
inline dem::SimulationSettings undamped(double fixed_dt = 0)
{
  dem::SimulationSettings s;
  s.local_damping = 0;
  s.fixed_time_step = fixed_dt;
  return s;
}

/// A simulation of the law `law` with default constants (Table 7.2 for Burger's).
inline dem::Simulation make_sim(dem::ParticleStore p, dem::WallSet w = {}, dem::SimulationSettings s = undamped(),
                                std::string_view law = "linear")
{
  return dem::Simulation(std::move(p), std::move(w), dem::make_contact_model(law, {}), s);
}

/// Two balls along x, the second one at centre distance d from the first.
inline dem::Simulation two_balls(double r, double d, double kn, double ks = 0, double mu = 0)
{
  dem::ParticleStore p;
  p.add(ball(Vec3::Zero(), r, kn, ks, mu));
  p.add(ball(Vec3(d, 0, 0), r, kn, ks, mu));
  return make_sim(std::move(p));
}

/// A horizontal plane wall at z = 0 facing up.
inline dem::Wall floor_wall(double kn, double ks = 0, double mu = 0)
{
  dem::Wall w;
  w.name = "floor";
  w.direction = Vec3::UnitZ();
  w.props = {kn, ks, mu};
  return w;
}
} // namespace demtest
