#include "dem/spatial_order.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <tuple>

namespace dem
{
namespace
{
constexpr int bits_per_axis = 21; // 63 bits of key in all

/// Spreads the low 21 bits of v so that two zero bits follow each.
std::uint64_t spread_bits(std::uint64_t v)
{
  v &= (std::uint64_t{1} << bits_per_axis) - 1;
  v = (v | v << 32) & 0x1f00000000ffffULL;
  v = (v | v << 16) & 0x1f0000ff0000ffULL;
  v = (v | v << 8) & 0x100f00f00f00f00fULL;
  v = (v | v << 4) & 0x10c30c30c30c30c3ULL;
  v = (v | v << 2) & 0x1249249249249249ULL;
  return v;
}

/// A cell coordinate clamped into the key's range.
std::uint64_t cell_coordinate(double x, double lowest, double cell)
{
  const double c = std::floor((x - lowest) / cell);
  const double top = static_cast<double>((std::uint64_t{1} << bits_per_axis) - 1);
  return static_cast<std::uint64_t>(std::clamp(c, 0.0, top));
}
} // namespace

std::vector<Index> morton_order(const ParticleStore &p)
{
  const Index n = p.size();
  std::vector<Index> order(static_cast<std::size_t>(n));
  std::iota(order.begin(), order.end(), Index{0});
  if (n < 2)
    return order;
  Vec3 lowest = p.position[0];
  for (const Vec3 &x : p.position)
    lowest = lowest.cwiseMin(x);
  const double diameter = 2 * p.max_radius();
  const double cell = diameter > 0 ? diameter : 1.0;
  std::vector<std::uint64_t> key(static_cast<std::size_t>(n));
  for (Index b = 0; b < n; ++b)
  {
    const Vec3 &x = p.position[b];
    key[b] = spread_bits(cell_coordinate(x.x(), lowest.x(), cell)) |
             spread_bits(cell_coordinate(x.y(), lowest.y(), cell)) << 1 |
             spread_bits(cell_coordinate(x.z(), lowest.z(), cell)) << 2;
  }
  const auto rank = [&](Index b)
  { return std::make_tuple(key[b], p.position[b].z(), p.position[b].y(), p.position[b].x(), p.radius[b]); };
  std::stable_sort(order.begin(), order.end(), [&](Index a, Index b) { return rank(a) < rank(b); });
  return order;
}

ParticleStore renumbered(const ParticleStore &p, const std::vector<Index> &order)
{
  // Every array of the store is moved below: a new one must be added here.
  static_assert(sizeof(ParticleStore) == 18 * sizeof(std::vector<double>), "renumbered() moves every ball array");
  ParticleStore out;
  const auto move = [&order](const auto &from, auto &to)
  {
    to.resize(order.size());
    for (std::size_t k = 0; k < order.size(); ++k)
      to[k] = from[static_cast<std::size_t>(order[k])];
  };
  move(p.position, out.position);
  move(p.velocity, out.velocity);
  move(p.spin, out.spin);
  move(p.force, out.force);
  move(p.torque, out.torque);
  move(p.radius, out.radius);
  move(p.density, out.density);
  move(p.mass, out.mass);
  move(p.inertia, out.inertia);
  move(p.inv_mass, out.inv_mass);
  move(p.inv_inertia, out.inv_inertia);
  move(p.inv_radius, out.inv_radius);
  move(p.sqrt_inv_mass, out.sqrt_inv_mass);
  move(p.sqrt_shear_mobility, out.sqrt_shear_mobility);
  move(p.kn, out.kn);
  move(p.ks, out.ks);
  move(p.friction, out.friction);
  move(p.motion, out.motion);
  return out;
}

std::vector<Index> inverse_permutation(const std::vector<Index> &order)
{
  std::vector<Index> inverse(order.size());
  for (std::size_t k = 0; k < order.size(); ++k)
    inverse[static_cast<std::size_t>(order[k])] = static_cast<Index>(k);
  return inverse;
}
} // namespace dem
