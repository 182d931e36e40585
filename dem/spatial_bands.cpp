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
} // namespace dem
