#include "dem/bonds.h"

#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>

#include <algorithm>
#include <memory>
#include <numeric>
#include <vector>

namespace dem
{
namespace
{
struct GslRng
{
  explicit GslRng(std::uint64_t seed) : rng(gsl_rng_alloc(gsl_rng_mt19937), &gsl_rng_free)
  {
    gsl_rng_set(rng.get(), static_cast<unsigned long>(seed));
  }
  std::unique_ptr<gsl_rng, void (*)(gsl_rng *)> rng;
};
} // namespace

BondReport bond_touching_pairs(ContactTable &table, const ParticleStore &particles, const BondSettings &s)
{
  BondReport report;
  GslRng random(s.seed);
  const auto draw = [&](double mean)
  {
    if (s.cov <= 0)
      return mean;
    const double value = mean + gsl_ran_gaussian(random.rng.get(), s.cov * mean);
    const double floor = s.floor_fraction * mean;
    if (value < floor)
    {
      ++report.truncated_draws;
      return floor;
    }
    return value;
  };

  std::vector<std::size_t> bonded;
  for (std::size_t c = 0; c < table.size(); ++c)
  {
    Contact &k = table[c];
    const double gap = (particles.position[k.second] - particles.position[k.first]).norm() - particles.radius[k.first] -
                       particles.radius[k.second];
    const double tolerance = s.touch_tolerance * std::min(particles.radius[k.first], particles.radius[k.second]);
    if (gap > tolerance)
      continue;
    k.bonded = true;
    k.bond.normal_strength = draw(s.normal_strength);
    k.bond.shear_strength = draw(s.shear_strength);
    bonded.push_back(c);
  }

  const auto to_remove = static_cast<std::size_t>(std::llround(s.removed_fraction * bonded.size()));
  if (to_remove > 0)
  {
    // Fisher-Yates on the bonded list; the first `to_remove` entries go.
    for (std::size_t k = 0; k < to_remove; ++k)
    {
      const std::size_t pick = k + gsl_rng_uniform_int(random.rng.get(), bonded.size() - k);
      std::swap(bonded[k], bonded[pick]);
      table[bonded[k]].unbond();
    }
    report.removed = to_remove;
  }
  for (std::size_t k = to_remove; k < bonded.size(); ++k)
  {
    report.mean_normal_strength += table[bonded[k]].bond.normal_strength;
    report.mean_shear_strength += table[bonded[k]].bond.shear_strength;
  }
  report.bonded = bonded.size() - to_remove;
  if (report.bonded > 0)
  {
    report.mean_normal_strength /= static_cast<double>(report.bonded);
    report.mean_shear_strength /= static_cast<double>(report.bonded);
  }
  return report;
}

void bond_pair(ContactTable &table, const ParticleStore &particles, Index i, Index j, double normal_strength,
               double shear_strength)
{
  Contact &c = table.ensure(i, j, particles);
  c.bonded = true;
  c.bond.normal_strength = normal_strength;
  c.bond.shear_strength = shear_strength;
}

void scale_bond_strengths(ContactTable &table, double factor)
{
  for (Contact &c : table.entries())
    if (c.bonded)
    {
      c.bond.normal_strength *= factor;
      c.bond.shear_strength *= factor;
    }
}

void set_break_displacement(ContactTable &table, const ParticleStore &particles, double delta_c)
{
  for (Contact &c : table.entries())
    if (c.bonded)
      c.bond.break_distance = (particles.position[c.second] - particles.position[c.first]).norm() + delta_c;
}
} // namespace dem
