#include "servo.h"

#include "simulation.h"

#include <algorithm>
#include <cmath>

namespace dem
{
namespace
{
/// Number of balls touching wall w and the mean stiffness of those contacts.
std::pair<int, double> wall_contacts(const Simulation &sim, WallIndex w)
{
  const ParticleStore &p = sim.particles();
  int n = 0;
  double k = 0;
  for (Index b = 0; b < p.size(); ++b)
    if (sim.walls().state(w, b).touching)
    {
      ++n;
      k += in_series(p.kn[b], sim.walls()[w].props.kn);
    }
  return {n, n > 0 ? k / n : 0.0};
}

double separation(const Simulation &sim, const Specimen &cell)
{
  const Wall &b = sim.walls()[cell.bottom];
  return (sim.walls()[cell.top].point - b.point).dot(b.direction);
}

/// Speed (positive = away from the balls) that takes a wall towards its target.
double servo_speed(const Simulation &sim, WallIndex w, double area, double stress, const ServoSettings &s)
{
  const double dt = sim.time_step();
  const double v_max = s.max_step_fraction * sim.particles().min_radius() / dt;
  const auto [contacts, kn] = wall_contacts(sim, w);
  // The gain of eq. 3.15 with the number of contacts never taken below that
  // of a wall densely covered by balls, A / (2R)^2: a wall touching a few
  // balls (or none) would otherwise be given a huge gain and slam into the
  // packing.  The error is limited to the target itself, so that one step
  // moves a wall by at most the overlap that carries the target stress.
  const ParticleStore &p = sim.particles();
  const double r = p.min_radius();
  const double covering = area / (4 * r * r);
  const double stiffness = contacts > 0 ? kn : in_series(p.kn.empty() ? 0.0 : p.kn[0], sim.walls()[w].props.kn);
  const double gain = s.relaxation * area / (stiffness * std::max<double>(contacts, covering) * dt);
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
  const Wall &side = sim.walls()[cell.lateral];
  const double area = pi * side.radius * side.radius;
  CellStress s;
  s.bottom = -sim.wall_force(cell.bottom).dot(sim.walls()[cell.bottom].direction) / area;
  s.top = -sim.wall_force(cell.top).dot(sim.walls()[cell.top].direction) / area;
  // The balls push the cylinder outwards: sum of outward normal force components.
  double radial = 0;
  const ParticleStore &p = sim.particles();
  for (Index b = 0; b < p.size(); ++b)
  {
    const ContactState &c = sim.walls().state(cell.lateral, b);
    if (c.touching)
      radial += c.normal_force;
  }
  s.lateral = radial / (2 * pi * side.radius * separation(sim, cell));
  return s;
}

CellStress servo_cell(Simulation &sim, const Specimen &cell, const ServoSettings &settings)
{
  const CellStress s = cell_stress(sim, cell);
  Wall &side = sim.walls()[cell.lateral];
  const double platen_area = pi * side.radius * side.radius;
  const double side_area = 2 * pi * side.radius * separation(sim, cell);
  for (const auto &[w, stress] : {std::pair{cell.bottom, s.bottom}, std::pair{cell.top, s.top}})
  {
    Wall &wall = sim.walls()[w];
    wall.velocity = -servo_speed(sim, w, platen_area, stress, settings) * wall.direction;
  }
  side.radial_velocity = servo_speed(sim, cell.lateral, side_area, s.lateral, settings);
  return s;
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
