#include "dem/spatial_bands.h"

#include "dem/contact_model.h"
#include "dem/simulation.h"

#include <gsl/gsl_cdf.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace dem
{
int CylinderBands::band(const Vec3 &p) const
{
  const Vec3 d = p - base;
  const double along = d.dot(axis);
  const double across = (d - along * axis).norm();
  const int third = std::clamp(static_cast<int>(std::floor(3 * along / height)), 0, 2);
  return 2 * third + (across * across > 0.5 * radius * radius ? 1 : 0);
}

const char *CylinderBands::name(int band)
{
  static const char *const names[count] = {"bottom core", "bottom rim", "middle core",
                                           "middle rim",  "top core",   "top rim"};
  return names[band];
}

BandMeans band_means(const CylinderBands &bands, const std::vector<Vec3> &points, const std::vector<double> &values)
{
  constexpr int B = CylinderBands::count;
  BandMeans r;
  std::array<double, B> sum{}, squares{};
  std::vector<int> of(points.size());
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    of[i] = bands.band(points[i]);
    ++r.contacts[of[i]];
    sum[of[i]] += values[i];
  }
  double total = 0;
  std::size_t n = 0;
  int occupied = 0;
  for (int b = 0; b < B; ++b)
  {
    total += sum[b];
    n += r.contacts[b];
    occupied += r.contacts[b] > 0 ? 1 : 0;
    r.mean[b] = r.contacts[b] ? sum[b] / double(r.contacts[b]) : std::numeric_limits<double>::quiet_NaN();
  }
  r.overall_mean = n ? total / double(n) : 0;
  for (std::size_t i = 0; i < points.size(); ++i)
    squares[of[i]] += (values[i] - r.mean[of[i]]) * (values[i] - r.mean[of[i]]);
  double between = 0, within = 0;
  for (int b = 0; b < B; ++b)
  {
    if (r.contacts[b] == 0)
      continue;
    const double nb = double(r.contacts[b]);
    between += nb * (r.mean[b] - r.overall_mean) * (r.mean[b] - r.overall_mean);
    within += squares[b];
    r.half_width[b] = nb > 1 ? 1.96 * std::sqrt(squares[b] / (nb - 1) / nb) : std::numeric_limits<double>::quiet_NaN();
  }
  const double df_between = occupied - 1, df_within = double(n) - occupied;
  if (df_between >= 1 && df_within >= 1 && within > 0)
  {
    r.f_statistic = (between / df_between) / (within / df_within);
    r.p_value = gsl_cdf_fdist_Q(r.f_statistic, df_between, df_within);
  }
  return r;
}

BandMeans contact_force_bands(const Simulation &sim, const CylinderBands &bands)
{
  const ParticleStore &p = sim.particles();
  const ContactTable &contacts = sim.contacts();
  std::vector<Vec3> points;
  std::vector<double> forces;
  for (std::size_t c = 0; c < contacts.size(); ++c)
  {
    const Contact &k = contacts[c];
    if (!k.state.touching() || k.state.normal_force <= 0)
      continue;
    const ContactGeometry g = sphere_sphere(p, k.first, k.second);
    points.push_back(p.position[k.first] + g.arm_first * g.normal);
    forces.push_back(k.state.normal_force);
  }
  return band_means(bands, points, forces);
}

BandCounts band_counts(const std::array<double, CylinderBands::count> &observed,
                       const std::array<double, CylinderBands::count> &weights)
{
  constexpr int B = CylinderBands::count;
  constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  BandCounts r;
  r.observed = observed;
  double events = 0, weight = 0;
  for (int b = 0; b < B; ++b)
  {
    events += observed[b];
    weight += weights[b];
  }
  int expected_bands = 0;
  for (int b = 0; b < B; ++b)
  {
    r.expected[b] = weight > 0 ? events * weights[b] / weight : 0;
    r.ratio_low[b] = r.ratio_high[b] = nan;
    if (!(r.expected[b] > 0))
      continue;
    ++expected_bands;
    const double o = observed[b];
    r.chi_square += (o - r.expected[b]) * (o - r.expected[b]) / r.expected[b];
    r.ratio_low[b] = (o > 0 ? 0.5 * gsl_cdf_chisq_Pinv(0.025, 2 * o) : 0.0) / r.expected[b];
    r.ratio_high[b] = 0.5 * gsl_cdf_chisq_Pinv(0.975, 2 * o + 2) / r.expected[b];
  }
  r.degrees_of_freedom = std::max(0, expected_bands - 1);
  if (r.degrees_of_freedom >= 1 && events > 0)
    r.p_value = gsl_cdf_chisq_Q(r.chi_square, r.degrees_of_freedom);
  return r;
}

std::array<double, CylinderBands::count> bonds_by_band(const Simulation &sim, const CylinderBands &bands)
{
  std::array<double, CylinderBands::count> held{};
  const ParticleStore &p = sim.particles();
  for (const Contact &k : sim.contacts().entries())
    if (k.bonded)
      held[bands.band(centre_line_point(p, k.first, k.second))] += 1;
  return held;
}

namespace
{
DirectionMean direction_mean(const std::vector<double> &values)
{
  DirectionMean d;
  d.contacts = values.size();
  if (values.empty())
  {
    d.mean = d.half_width = std::numeric_limits<double>::quiet_NaN();
    return d;
  }
  double sum = 0, squares = 0;
  for (double v : values)
    sum += v;
  d.mean = sum / double(values.size());
  for (double v : values)
    squares += (v - d.mean) * (v - d.mean);
  const double n = double(values.size());
  d.half_width = n > 1 ? 1.96 * std::sqrt(squares / (n - 1) / n) : std::numeric_limits<double>::quiet_NaN();
  return d;
}
} // namespace

ContactDirections contact_directions(const Simulation &sim, const Vec3 &axis)
{
  const Vec3 a = axis.normalized();
  std::vector<double> compressive, tensile;
  for (const Contact &k : sim.contacts().entries())
  {
    if (!k.state.touching() || k.state.normal_force == 0)
      continue;
    const double c = k.state.normal.dot(a);
    (k.state.normal_force > 0 ? compressive : tensile).push_back(c * c);
  }
  return {direction_mean(compressive), direction_mean(tensile)};
}
} // namespace dem
