#include "app/kinds/continuum_gci.h"

#include <cmath>

namespace demvv
{
GciResult grid_convergence_index(const double h[3], const double phi[3], double safety_factor)
{
  GciResult g;
  for (int i = 0; i < 3; ++i)
  {
    g.h[i] = h[i];
    g.phi[i] = phi[i];
  }
  const double nan = std::nan("");
  const double r21 = h[1] / h[0], r32 = h[2] / h[1];
  const double eps21 = phi[1] - phi[0], eps32 = phi[2] - phi[1];
  if (!(eps21 != 0 && eps32 != 0 && r21 > 1 && r32 > 1))
  {
    g.order = g.extrapolated = g.gci_fine = g.gci_coarse = g.asymptotic_ratio = nan;
    return g;
  }
  const double s = eps32 / eps21 > 0 ? 1.0 : -1.0;
  g.monotone = s > 0;
  // Fixed-point iteration for p (Celik et al. eq. 3-5); one pass when r21 = r32.
  double p = std::abs(std::log(std::abs(eps32 / eps21))) / std::log(r21);
  for (int k = 0; k < 100; ++k)
  {
    const double q = std::log((std::pow(r21, p) - s) / (std::pow(r32, p) - s));
    const double next = std::abs(std::log(std::abs(eps32 / eps21)) + q) / std::log(r21);
    const bool converged = std::abs(next - p) <= 1e-14 * std::max(1.0, p);
    p = next;
    if (converged)
      break;
  }
  g.order = p;
  const double r21p = std::pow(r21, p), r32p = std::pow(r32, p);
  g.extrapolated = (r21p * phi[0] - phi[1]) / (r21p - 1);
  g.approximate_error = std::abs(eps21 / phi[0]);
  g.extrapolated_error = std::abs((g.extrapolated - phi[0]) / g.extrapolated);
  g.gci_fine = safety_factor * g.approximate_error / (r21p - 1);
  g.gci_coarse = safety_factor * std::abs(eps32 / phi[1]) / (r32p - 1);
  g.asymptotic_ratio = g.gci_coarse / (r21p * g.gci_fine);
  return g;
}
} // namespace demvv
