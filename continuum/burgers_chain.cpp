#include "continuum/burgers_chain.h"

#include <cmath>

namespace continuum
{
BurgersChain BurgersChain::scaled(double c) const
{
  return {c * maxwell_spring, c * maxwell_dashpot, c * kelvin_spring, c * kelvin_dashpot};
}

bool BurgersChain::valid() const
{
  for (const double v : {maxwell_spring, maxwell_dashpot, kelvin_spring, kelvin_dashpot})
    if (!(std::isfinite(v) && v > 0))
      return false;
  return true;
}

BurgersChain BurgersSolid::shear() const { return young.scaled(1.0 / (2 * (1 + poisson))); }

BurgersChain BurgersSolid::bulk_chain() const { return young.scaled(1.0 / (3 * (1 - 2 * poisson))); }

double BurgersSolid::bulk_modulus() const { return young.maxwell_spring / (3 * (1 - 2 * poisson)); }

BurgersChain BurgersSolid::uniaxial() const
{
  if (bulk == BulkResponse::same_shape)
    return young; // J = J_G (3K + G)/(9K) = J_G / (2 (1 + nu)): the Young chain itself
  // Elastic bulk: J(t) = 1/(9K) + J_G(t)/3.  The springs in series give
  // 1/(9K) + 1/(3 G0) = 1/E0; the viscous and delayed parts are 3x shear.
  const BurgersChain g = shear();
  return {young.maxwell_spring, 3 * g.maxwell_dashpot, 3 * g.kelvin_spring, 3 * g.kelvin_dashpot};
}

double BurgersSolid::lateral_strain(double axial_strain, double axial_stress) const
{
  if (bulk == BulkResponse::same_shape)
    return -poisson * axial_strain;
  // Volumetric strain is elastic: eps_a + 2 eps_l = sigma_a / (3 K).
  return 0.5 * (axial_stress / (3 * bulk_modulus()) - axial_strain);
}

std::string BurgersSolid::problem() const
{
  if (!young.valid())
    return "every modulus and viscosity must be positive and finite";
  if (!(poisson > -1 && poisson < 0.5))
    return "Poisson's ratio must lie in (-1, 0.5)";
  return {};
}
} // namespace continuum
