// Roache's grid convergence index, by the procedure of Celik et al. (2008),
// "Procedure for estimation and reporting of uncertainty due to
// discretization in CFD applications", J. Fluids Eng. 130:078001.
//
// Three solutions phi_1 (fine), phi_2, phi_3 (coarse) on meshes of
// representative size h_1 < h_2 < h_3, r21 = h2/h1, r32 = h3/h2:
//   eps32 = phi3 - phi2, eps21 = phi2 - phi1, s = sign(eps32 / eps21)
//   p = |ln|eps32/eps21| + q(p)| / ln r21,  q(p) = ln((r21^p - s)/(r32^p - s))
//       (fixed-point iteration; q = 0 when r21 = r32)
//   phi_ext = (r21^p phi1 - phi2) / (r21^p - 1)
//   e_a = |(phi1 - phi2)/phi1|,  e_ext = |(phi_ext - phi1)/phi_ext|
//   GCI_fine = 1.25 e_a / (r21^p - 1)
// and Roache's asymptotic-range ratio GCI_32 / (r21^p GCI_21), which is 1
// when the three meshes are in the asymptotic range.  s < 0 means
// oscillatory convergence: the procedure does not apply (monotone = false).
#pragma once

namespace demvv
{
struct GciResult
{
  double phi[3] = {0, 0, 0};     ///< fine, medium, coarse
  double h[3] = {0, 0, 0};       ///< representative mesh sizes, fine to coarse
  double order = 0;              ///< observed order p (NaN if undefined)
  double extrapolated = 0;       ///< phi_ext^21
  double approximate_error = 0;  ///< e_a^21
  double extrapolated_error = 0; ///< e_ext^21
  double gci_fine = 0;           ///< GCI_fine^21 (relative)
  double gci_coarse = 0;         ///< GCI^32 (relative, on phi_2)
  double asymptotic_ratio = 0;   ///< GCI^32 / (r21^p GCI^21)
  bool monotone = false;
};

GciResult grid_convergence_index(const double h[3], const double phi[3], double safety_factor = 1.25);
} // namespace demvv
