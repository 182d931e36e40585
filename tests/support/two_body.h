// Small systems for tests, built in a line or three (STYLE rule 8), on the
// builders the verification checks use (verify/checks_support.h).
#pragma once

#include "verify/checks/checks_support.h"

namespace demtest
{
using dem::Vec3;
using verify::ball;
using verify::undamped;

inline dem::Simulation make_sim(dem::ParticleStore p, dem::WallSet w = {},
                                dem::SimulationSettings s = undamped())
{
  return verify::linear_simulation(std::move(p), s, std::move(w));
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
