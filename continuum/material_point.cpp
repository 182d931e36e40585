#include "continuum/material_point.h"

#include "continuum/burgers_update.h"

namespace continuum
{
UniaxialResponse uniaxial_material_point(const BurgersSolid &solid, double strain_rate, double time_step,
                                         unsigned int steps)
{
  const SolidStep step(solid, time_step);
  const double two_mu = step.shear_stiffness(), kappa = step.bulk_stiffness();
  UniaxialResponse out;
  PointState state;
  for (unsigned int n = 0; n <= steps; ++n)
  {
    if (n > 0)
    {
      // Components (r, theta, z), tension positive.  Lateral strain x makes
      // sigma_rr = two_mu (x - tr/3) + kappa tr + h_rr vanish, tr = eps_zz + 2 x.
      const double axial = -strain_rate * n * time_step;
      const Tensor3 h = step.history(state, {});
      const double lateral = -(axial * (kappa - two_mu / 3) + h[0][0]) / (two_mu / 3 + 2 * kappa);
      Tensor3 strain;
      strain[0][0] = strain[1][1] = lateral;
      strain[2][2] = axial;
      state = step.advance(state, strain, {});
    }
    out.time.push_back(n * time_step);
    out.axial_strain.push_back(-state.strain[2][2]);
    out.axial_stress.push_back(-state.stress[2][2]);
    out.radial_strain.push_back(-state.strain[0][0]);
  }
  return out;
}
} // namespace continuum
