#include "dem/servo.h"

#include "dem/simulation.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace dem
{
namespace
{
/// What touches one wall of the cell: contacts, their summed pair stiffness
/// and their summed normal force.
struct WallTally
{
  int contacts = 0;
  double stiffness = 0;    ///< N/m, sum over the contacts
  double normal_force = 0; ///< N, sum over the contacts
};

/// The tallies of the given walls, in one pass over the balls.
template <std::size_t N>
std::array<WallTally, N> tally_walls(const Simulation &sim, const std::array<WallIndex, N> &walls)
{
  const ParticleStore &p = sim.particles();
  std::array<WallTally, N> t;
  for (Index b = 0; b < p.size(); ++b)
    for (std::size_t k = 0; k < N; ++k)
    {
      const ContactState &c = sim.walls().state(walls[k], b);
      if (c.touching())
      {
        ++t[k].contacts;
        t[k].stiffness += in_series(p.kn[b], sim.walls()[walls[k]].props.kn);
        t[k].normal_force += c.normal_force;
      }
    }
  return t;
}

/// The tallies of bottom, top and lateral wall.
std::array<WallTally, 3> tally_cell_walls(const Simulation &sim, const Specimen &cell)
{
  return tally_walls<3>(sim, {cell.bottom, cell.top, cell.lateral});
}

double separation(const Simulation &sim, const Specimen &cell)
{
  const Wall &b = sim.walls()[cell.bottom];
  return (sim.walls()[cell.top].point - b.point).dot(b.direction);
}

CellStress stresses(const Simulation &sim, const Specimen &cell, const std::array<WallTally, 3> &t)
{
  const Wall &side = sim.walls()[cell.lateral];
  const double area = pi * side.radius * side.radius;
  CellStress s;
  s.bottom = -sim.wall_force(cell.bottom).dot(sim.walls()[cell.bottom].direction) / area;
  s.top = -sim.wall_force(cell.top).dot(sim.walls()[cell.top].direction) / area;
  // The balls push the cylinder outwards: the sum of their normal forces.
  s.lateral = t[2].normal_force / (2 * pi * side.radius * separation(sim, cell));
  return s;
}

/// Speed (positive = away from the balls) that takes a wall towards its target.
double servo_speed(const Simulation &sim, WallIndex w, const WallTally &t, double area, double stress,
                   const ServoSettings &s)
{
  const double dt = sim.time_step();
  const ParticleStore &p = sim.particles();
  const double r = p.min_radius();
  const double v_max = s.max_step_fraction * r / dt;
  // The gain of eq. 3.15 with the number of contacts never taken below that
  // of a wall densely covered by balls, A / (2R)^2: a wall touching a few
  // balls (or none) would otherwise be given a huge gain and slam into the
  // packing.  The error is limited to the target itself, so that one step
  // moves a wall by at most the overlap that carries the target stress.
  const double covering = area / (4 * r * r);
  const double stiffness =
    t.contacts > 0 ? t.stiffness / t.contacts : in_series(p.kn.empty() ? 0.0 : p.kn[0], sim.walls()[w].props.kn);
  const double gain = s.relaxation * area / (stiffness * std::max<double>(t.contacts, covering) * dt);
  const double limit = s.target_stress > 0 ? s.target_stress : std::abs(stress);
  const double error = std::clamp(stress - s.target_stress, -limit, limit);
  return std::clamp(gain * error, -v_max, v_max);
}
} // namespace

double CellStress::largest_error(double target) const
{
  return std::max({std::abs(bottom - target), std::abs(top - target), std::abs(lateral - target)});
}

CellStress cell_stress(const Simulation &sim, const Specimen &cell)
{
  return stresses(sim, cell, tally_cell_walls(sim, cell));
}

CellStress servo_cell(Simulation &sim, const Specimen &cell, const ServoSettings &settings)
{
  const std::array<WallTally, 3> t = tally_cell_walls(sim, cell);
  const CellStress s = stresses(sim, cell, t);
  Wall &side = sim.walls()[cell.lateral];
  const double platen_area = pi * side.radius * side.radius;
  const double side_area = 2 * pi * side.radius * separation(sim, cell);
  for (int k = 0; k < 2; ++k)
  {
    Wall &wall = sim.walls()[k == 0 ? cell.bottom : cell.top];
    const double speed =
      servo_speed(sim, k == 0 ? cell.bottom : cell.top, t[k], platen_area, k == 0 ? s.bottom : s.top, settings);
    wall.velocity = -speed * wall.direction;
  }
  side.radial_velocity = servo_speed(sim, cell.lateral, t[2], side_area, s.lateral, settings);
  return s;
}

double servo_platen_speed(const Simulation &sim, WallIndex platen, double area, double measured, double target,
                          const ServoSettings &settings)
{
  ServoSettings s = settings;
  s.target_stress = target;
  return -servo_speed(sim, platen, tally_walls<1>(sim, {platen})[0], area, measured, s);
}

void stop_walls(Simulation &sim, const Specimen &cell)
{
  for (WallIndex w : {cell.bottom, cell.top, cell.lateral})
    if (w >= 0)
    {
      sim.walls()[w].velocity.setZero();
      sim.walls()[w].radial_velocity = 0;
    }
}
} // namespace dem
