#include "dem/measure.h"

#include <algorithm>
#include <cmath>

namespace dem
{
double sphere_intersection_volume(double a, double b, double d)
{
  if (d >= a + b)
    return 0.0;
  if (d <= std::abs(a - b))
  {
    const double r = std::min(a, b);
    return 4.0 / 3.0 * pi * r * r * r;
  }
  const double s = a + b - d;
  return pi * s * s * (d * d + 2 * d * (a + b) - 3 * (a - b) * (a - b)) / (12 * d);
}

namespace
{
double radial_distance(const Vec3 &x, const Vec3 &axis_point)
{
  return std::hypot(x.x() - axis_point.x(), x.y() - axis_point.y());
}
} // namespace

double porosity(const ParticleStore &particles, const ContactTable &contacts, const MeasurementSphere &sphere)
{
  double solid = 0;
  for (Index p = 0; p < particles.size(); ++p)
    solid +=
      sphere_intersection_volume(particles.radius[p], sphere.radius, (particles.position[p] - sphere.centre).norm());
  for (const Contact &c : contacts.entries())
  {
    if (!c.state.touching() || c.state.overlap <= 0)
      continue;
    const Vec3 &xi = particles.position[c.first];
    const Vec3 &xj = particles.position[c.second];
    const double d = (xj - xi).norm();
    const Vec3 point = xi + (particles.radius[c.first] - 0.5 * c.state.overlap) * (xj - xi) / d;
    if ((point - sphere.centre).norm() < sphere.radius)
      solid -= sphere_intersection_volume(particles.radius[c.first], particles.radius[c.second], d);
  }
  const double volume = 4.0 / 3.0 * pi * std::pow(sphere.radius, 3);
  return 1.0 - solid / volume;
}

double coordination_number(const ParticleStore &particles, const ContactTable &contacts,
                           const MeasurementSphere &sphere)
{
  const auto inside = [&](Index p) { return (particles.position[p] - sphere.centre).norm() < sphere.radius; };
  std::size_t balls = 0, ends = 0;
  for (Index p = 0; p < particles.size(); ++p)
    balls += inside(p) ? 1 : 0;
  for (const Contact &c : contacts.entries())
    if (c.state.touching())
      ends += (inside(c.first) ? 1 : 0) + (inside(c.second) ? 1 : 0);
  return balls > 0 ? static_cast<double>(ends) / static_cast<double>(balls) : 0.0;
}

double coordination_number(const ParticleStore &particles, const ContactTable &contacts)
{
  std::size_t touching = 0;
  for (const Contact &c : contacts.entries())
    touching += c.state.touching() ? 1 : 0;
  return particles.size() > 0 ? 2.0 * static_cast<double>(touching) / particles.size() : 0.0;
}

ContactForceStatistics contact_force_statistics(const ContactTable &contacts)
{
  ContactForceStatistics s;
  double sum = 0;
  for (std::size_t c = 0; c < contacts.size(); ++c)
    if (contacts[c].state.touching())
    {
      const double f = contacts.force(c).norm();
      sum += f;
      s.largest = std::max(s.largest, f);
      ++s.touching;
    }
  s.mean = s.touching ? sum / static_cast<double>(s.touching) : 0.0;
  return s;
}

double unbalanced_force_ratio(const ParticleStore &particles, const ContactTable &contacts)
{
  double resultant = 0;
  std::size_t free_balls = 0;
  for (Index p = 0; p < particles.size(); ++p)
    if (!particles.holds_velocity(p))
    {
      resultant += particles.force[p].norm();
      ++free_balls;
    }
  const ContactForceStatistics contact = contact_force_statistics(contacts);
  if (free_balls == 0 || contact.mean == 0)
    return 0.0;
  return (resultant / free_balls) / contact.mean;
}

Tensor3 average_stress(const Simulation &sim, double volume)
{
  const ParticleStore &p = sim.particles();
  Tensor3 sum = Tensor3::Zero();
  for (std::size_t c = 0; c < sim.contacts().size(); ++c)
  {
    const Contact &k = sim.contacts()[c];
    if (!k.state.touching())
      continue;
    sum += sim.contacts().force(c) * (p.position[k.second] - p.position[k.first]).transpose();
  }
  const WallSet &walls = sim.walls();
  for (WallIndex w = 0; w < walls.size(); ++w)
    for (Index b = 0; b < p.size(); ++b)
    {
      const ContactState &s = walls.state(w, b);
      if (!walls[w].enabled || !s.touching())
        continue;
      const Vec3 force = s.normal_force * s.normal + s.shear_force;
      sum += force * ((p.radius[b] - 0.5 * s.overlap) * s.normal).transpose();
    }
  return 0.5 * (sum + sum.transpose()) / volume;
}

double mean_stress(const Simulation &sim, double volume) { return average_stress(sim, volume).trace() / 3.0; }

Tensor3 fabric_tensor(const ParticleStore &particles, const ContactTable &contacts)
{
  Tensor3 sum = Tensor3::Zero();
  std::size_t n = 0;
  for (const Contact &c : contacts.entries())
  {
    if (!c.state.touching())
      continue;
    const Vec3 d = (particles.position[c.second] - particles.position[c.first]).normalized();
    sum += d * d.transpose();
    ++n;
  }
  return n > 0 ? Tensor3(sum / static_cast<double>(n)) : Tensor3(Tensor3::Identity() / 3.0);
}

std::vector<int> contacts_per_ball(const Simulation &sim)
{
  std::vector<int> count(static_cast<std::size_t>(sim.particles().size()), 0);
  for (const Contact &c : sim.contacts().entries())
    if (c.state.touching())
    {
      ++count[c.first];
      ++count[c.second];
    }
  for (WallIndex w = 0; w < sim.walls().size(); ++w)
    for (Index b = 0; b < sim.particles().size(); ++b)
      if (sim.walls()[w].enabled && sim.walls().state(w, b).touching())
        ++count[b];
  return count;
}

RadialGauges::RadialGauges(const ParticleStore &particles, const Vec3 &axis_point, double z_mid, double height,
                           double thickness)
  : axis_point_(axis_point)
{
  double outer = 0;
  for (Index p = 0; p < particles.size(); ++p)
    outer = std::max(outer, radial_distance(particles.position[p], axis_point) + particles.radius[p]);
  for (Index p = 0; p < particles.size(); ++p)
  {
    const double r = radial_distance(particles.position[p], axis_point);
    const bool on_rim = r + 3.0 * particles.radius[p] >= outer;
    const bool in_band = std::abs(particles.position[p].z() - z_mid) <= 0.5 * thickness * height;
    if (on_rim && in_band && r > 0)
    {
      members_.push_back(p);
      initial_radius_.push_back(r);
    }
  }
}

double RadialGauges::radial_strain(const ParticleStore &particles) const
{
  if (members_.empty())
    return 0.0;
  double sum = 0;
  for (std::size_t k = 0; k < members_.size(); ++k)
    sum -= (radial_distance(particles.position[members_[k]], axis_point_) - initial_radius_[k]) / initial_radius_[k];
  return sum / static_cast<double>(members_.size());
}
} // namespace dem
