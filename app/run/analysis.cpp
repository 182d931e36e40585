#include "app/run/analysis.h"

#include <gsl/gsl_fit.h>

#include <algorithm>
#include <cmath>

namespace demvv
{
LineFit fit_line(const std::vector<double> &x, const std::vector<double> &y, double lo, double hi)
{
  std::vector<double> xs, ys;
  for (std::size_t k = 0; k < x.size() && k < y.size(); ++k)
    if (x[k] >= lo && x[k] <= hi)
    {
      xs.push_back(x[k]);
      ys.push_back(y[k]);
    }
  LineFit f;
  f.points = xs.size();
  if (xs.size() < 2)
    return f;
  double c00, c01, c11, sumsq;
  gsl_fit_linear(xs.data(), 1, ys.data(), 1, xs.size(), &f.intercept, &f.slope, &c00, &c01, &c11, &sumsq);
  double mean = 0, total = 0;
  for (double v : ys)
    mean += v;
  mean /= static_cast<double>(ys.size());
  for (double v : ys)
    total += (v - mean) * (v - mean);
  f.r_squared = total > 0 ? 1.0 - sumsq / total : 1.0;
  return f;
}

ElasticFit fit_elastic(const std::vector<double> &axial_strain, const std::vector<double> &axial_stress,
                       const std::vector<double> &radial_strain, double lo, double hi)
{
  std::vector<double> minus_radial(radial_strain.size());
  for (std::size_t k = 0; k < radial_strain.size(); ++k)
    minus_radial[k] = -radial_strain[k];
  return {fit_line(axial_strain, axial_stress, lo, hi), fit_line(axial_strain, minus_radial, lo, hi)};
}

Peak peak(const std::vector<double> &x, const std::vector<double> &y)
{
  Peak p;
  if (y.empty())
    return p;
  p.index = static_cast<std::size_t>(std::max_element(y.begin(), y.end()) - y.begin());
  p.value = y[p.index];
  p.at = x[p.index];
  return p;
}

bool x_at_max_rate(const std::vector<double> &x, const std::vector<double> &y, double &at, double &rate)
{
  const std::size_t n = std::min(x.size(), y.size());
  if (n < 2)
    return false;
  bool found = false;
  for (std::size_t k = 0; k < n; ++k)
  {
    const std::size_t a = k == 0 ? 0 : k - 1;
    const std::size_t b = k + 1 == n ? n - 1 : k + 1;
    if (x[b] == x[a])
      continue;
    const double r = (y[b] - y[a]) / (x[b] - x[a]);
    if (!found || r > rate)
    {
      rate = r;
      at = x[k];
      found = true;
    }
  }
  return found;
}
double max_abs(const std::vector<double> &v)
{
  if (v.empty())
    return std::nan("");
  double m = 0;
  for (double x : v)
    m = std::max(m, std::abs(x));
  return m;
}

double relative_deviation(const std::vector<double> &a, const std::vector<double> &b)
{
  std::vector<double> d(a.size());
  for (std::size_t k = 0; k < a.size(); ++k)
    d[k] = a[k] - b[k];
  const double scale = max_abs(b);
  return scale > 0 && a.size() == b.size() ? max_abs(d) / scale : std::nan("");
}
} // namespace demvv
