// Spatial bands of a cylindrical sample, for the thesis's spatial claims.
//
// Fig. 5.6 says that under the isotropic state the compressive contact
// forces are "uniformly distributed throughout the sample".  demvv makes
// the claim a number: the sample is cut into six bands of equal volume,
// three heights (bottom, middle and top third) by two radii (the core,
// r < R / sqrt(2), and the rim), and the mean of a contact quantity in each
// band is set against the mean over the sample by a one-way analysis of
// variance:
//
//   F = [sum_b n_b (m_b - m)^2 / (B - 1)] / [sum_b sum_i (x_i - m_b)^2 / (N - B)],
//
// m_b the band means, m the overall mean, n_b the band counts, N their sum
// and B the bands that hold a contact; p = Q_F(F; B - 1, N - B) (GSL).  A
// small p says the bands differ by more than the scatter within them
// allows.  The test treats contacts as independent; forces in a packing are
// correlated along force chains a few balls long, so p is optimistic (too
// small) and the band means with their 95 % half-widths are the primary
// result.  Points outside the cylinder (a contact point beyond the wall by
// an overlap) count in the nearest band.
#pragma once

#include "dem/types.h"

#include <array>
#include <cstddef>
#include <vector>

namespace dem
{
class Simulation;

/// Six bands of equal volume of a cylinder: band = 2 * third + (rim ? 1 : 0),
/// thirds from the base up.
struct CylinderBands
{
  static constexpr int count = 6;
  Vec3 base = Vec3::Zero();  ///< m, the axis point of the bottom face
  Vec3 axis = Vec3::UnitZ(); ///< unit, bottom to top
  double height = 0;         ///< m
  double radius = 0;         ///< m

  int band(const Vec3 &p) const;
  /// "bottom core", "bottom rim", "middle core", ... "top rim".
  static const char *name(int band);
};

/// A contact quantity's means per band and the one-way ANOVA above.
struct BandMeans
{
  std::array<std::size_t, CylinderBands::count> contacts{};
  std::array<double, CylinderBands::count> mean{};       ///< band mean (NaN where empty)
  std::array<double, CylinderBands::count> half_width{}; ///< 95 % half-width of the band mean, 1.96 s_b / sqrt(n_b)
  double overall_mean = 0;
  double f_statistic = 0;
  double p_value = 1; ///< Q_F(F; B - 1, N - B); 1 when fewer than two bands or no scatter
};

/// `values[i]` at `points[i]`, by band.
BandMeans band_means(const CylinderBands &bands, const std::vector<Vec3> &points, const std::vector<double> &values);

/// The compressive normal forces [N] of the touching ball-ball contacts at
/// their contact points, by band.
BandMeans contact_force_bands(const Simulation &sim, const CylinderBands &bands);
} // namespace dem
