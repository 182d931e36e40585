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

/// Events counted by band (bond breaks, Figs 7.7 and A.3) against a uniform
/// expectation: with w_b the share of the bonds that band held at the
/// start, a break that strikes every bond alike gives E_b = w_b N of the N
/// breaks.  X^2 = sum_b (O_b - E_b)^2 / E_b over the bands with E_b > 0,
/// p = Q_chi2(X^2; B' - 1) (GSL), and each ratio O_b / E_b carries the
/// exact (Garwood) 95 % Poisson interval of O_b,
///
///   [chi2_inv(0.025; 2 O_b) / 2, chi2_inv(0.975; 2 O_b + 2) / 2] / E_b.
///
/// Breaks come in cascades (a broken bond loads its neighbours), so they
/// are not independent and p is optimistic (too small); the ratios with
/// their intervals are the primary result.
struct BandCounts
{
  std::array<double, CylinderBands::count> observed{};
  std::array<double, CylinderBands::count> expected{};
  std::array<double, CylinderBands::count> ratio_low{};  ///< 95 % bound of O_b / E_b (NaN where E_b = 0)
  std::array<double, CylinderBands::count> ratio_high{}; ///< 95 % bound of O_b / E_b (NaN where E_b = 0)
  double chi_square = 0;
  int degrees_of_freedom = 0;
  double p_value = 1; ///< 1 when fewer than two bands are expected to hold events, or none was observed
};

BandCounts band_counts(const std::array<double, CylinderBands::count> &observed,
                       const std::array<double, CylinderBands::count> &weights);

/// The bonded ball-ball contacts by band, at their centre_line_point (particles.h).
std::array<double, CylinderBands::count> bonds_by_band(const Simulation &sim, const CylinderBands &bands);

/// Directions of the force-carrying ball-ball contacts (Fig. 7.4): the mean
/// of (n . axis)^2 over the contacts in compression and over those in
/// tension, each with its 95 % half-width 1.96 s / sqrt(n).  An isotropic
/// set gives 1/3; contacts running mainly along the axis give more, mainly
/// across it less.
struct DirectionMean
{
  std::size_t contacts = 0;
  double mean = 0;       ///< mean (n . axis)^2 [-] (NaN for no contact)
  double half_width = 0; ///< 95 % half-width of the mean (NaN for fewer than two)
};

struct ContactDirections
{
  DirectionMean compressive, tensile;
};

ContactDirections contact_directions(const Simulation &sim, const Vec3 &axis);
} // namespace dem
