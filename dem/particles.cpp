#include "dem/particles.h"

#include <algorithm>
#include <cmath>

namespace dem
{
Index ParticleStore::add(const BallSpec &spec)
{
  const Index p = size();
  position.push_back(spec.position);
  velocity.push_back(spec.velocity);
  spin.push_back(spec.spin);
  force.push_back(Vec3::Zero());
  torque.push_back(Vec3::Zero());
  radius.push_back(0);
  density.push_back(spec.density);
  mass.push_back(0);
  inertia.push_back(0);
  inv_mass.push_back(0);
  inv_inertia.push_back(0);
  sqrt_inv_mass.push_back(0);
  inv_radius.push_back(0);
  sqrt_shear_mobility.push_back(0);
  kn.push_back(spec.kn);
  ks.push_back(spec.ks);
  friction.push_back(spec.friction);
  motion.push_back(free_motion);
  set_radius(p, spec.radius);
  set_motion(p, spec.hold_velocity, spec.hold_spin);
  return p;
}

void ParticleStore::reserve(std::size_t n)
{
  for (auto *v : {&position, &velocity, &spin, &force, &torque})
    v->reserve(n);
  for (auto *v : {&radius, &density, &mass, &inertia, &inv_mass, &inv_inertia, &inv_radius, &sqrt_inv_mass,
                  &sqrt_shear_mobility, &kn, &ks, &friction})
    v->reserve(n);
  motion.reserve(n);
}

void ParticleStore::set_radius(Index p, double r)
{
  radius[p] = r;
  inv_radius[p] = r > 0 ? 1.0 / r : 0.0;
  mass[p] = density[p] * volume(p);
  inertia[p] = 0.4 * mass[p] * r * r;
  set_motion(p, holds_velocity(p), holds_spin(p));
}

void ParticleStore::set_motion(Index p, bool hold_velocity, bool hold_spin)
{
  motion[p] = static_cast<std::uint8_t>((hold_velocity ? velocity_held : 0) | (hold_spin ? spin_held : 0));
  inv_mass[p] = hold_velocity || mass[p] <= 0 ? 0.0 : 1.0 / mass[p];
  inv_inertia[p] = hold_spin || inertia[p] <= 0 ? 0.0 : 1.0 / inertia[p];
  sqrt_inv_mass[p] = std::sqrt(inv_mass[p]);
  sqrt_shear_mobility[p] = std::sqrt(inv_mass[p] + radius[p] * radius[p] * inv_inertia[p]);
}

double ParticleStore::max_radius() const
{
  return radius.empty() ? 0.0 : *std::max_element(radius.begin(), radius.end());
}

double ParticleStore::min_radius() const
{
  return radius.empty() ? 0.0 : *std::min_element(radius.begin(), radius.end());
}
} // namespace dem
