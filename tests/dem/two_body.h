// Small systems for the engine's tests, built in a line or three (STYLE
// rule 8), on dem/ alone: demvv_dem_tests links nothing from verify/.
#pragma once

#include "dem/small_systems.h"

#include <string_view>

namespace demtest
{
using dem::Vec3;

using dem::small_systems::ball;
using dem::small_systems::undamped;

/// A simulation of the law `law` with default constants (Table 7.2 for Burger's).
inline dem::Simulation make_sim(dem::ParticleStore p, dem::WallSet w = {}, dem::SimulationSettings s = undamped(),
                                std::string_view law = "linear")
{
  return dem::small_systems::simulation(std::move(p), std::move(w), s, law);
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
