// Scalar results extracted from series (summary.json of a uniaxial run).
//
//  - fit_line: least squares over the points with x in [lo, hi] (GSL's
//    gsl_fit_linear); the initial modulus is the slope of stress against
//    axial strain, Poisson's ratio the slope of -radial against axial strain.
//  - peak: the largest y and the x where it occurs.
//  - x_at_max_rate: the x where dy/dx is largest, from centred differences of
//    the series (one-sided at the ends); used for the strain at the maximum
//    bond-breakage rate, which the thesis claims coincides with the peak
//    stress (§6.2).
#pragma once

#include <cstddef>
#include <vector>

namespace demvv
{
struct LineFit
{
  double slope = 0;
  double intercept = 0;
  std::size_t points = 0; ///< points in the window; fewer than 2 means no fit
  double r_squared = 0;
};

LineFit fit_line(const std::vector<double> &x, const std::vector<double> &y, double lo, double hi);

/// The initial modulus (slope of axial stress against axial strain) and
/// Poisson's ratio (slope of -radial against axial strain) over [lo, hi].
struct ElasticFit
{
  LineFit modulus, poisson;
};
ElasticFit fit_elastic(const std::vector<double> &axial_strain, const std::vector<double> &axial_stress,
                       const std::vector<double> &radial_strain, double lo, double hi);

struct Peak
{
  double value = 0;
  double at = 0;
  std::size_t index = 0;
};

Peak peak(const std::vector<double> &x, const std::vector<double> &y);

/// max |v| (NaN for an empty v).
double max_abs(const std::vector<double> &v);
/// max |a - b| / max |b| (NaN for an empty or zero reference or unequal lengths).
double relative_deviation(const std::vector<double> &a, const std::vector<double> &b);

/// x where dy/dx is largest; returns false (and leaves `at`) with fewer than two points.
bool x_at_max_rate(const std::vector<double> &x, const std::vector<double> &y, double &at, double &rate);
} // namespace demvv
