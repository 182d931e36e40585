// A single material point of the Burger's solid under homogeneous uniaxial
// stress and a constant axial strain rate, advanced with exactly the update
// the cylinder uses at its quadrature points (burgers_update.h): each step
// the lateral strain is the one that makes the lateral stress zero.
//
// Between frictionless platens the cylinder is homogeneous, so every mesh
// must give this response to solver tolerance (the patch test,
// check V20); that the response itself converges to the closed form
// (eq. 7.18 with BurgersSolid::uniaxial()) is the separate question of the
// time discretisation.
//
// Sign convention of the results: compression positive (axial stress), and
// radial strain -(r - r0)/r0 (a bulging sample has negative radial strain).
#pragma once

#include "continuum/burgers_chain.h"

#include <vector>

namespace continuum
{
struct UniaxialResponse
{
  std::vector<double> time;          ///< [s], from 0
  std::vector<double> axial_strain;  ///< compression positive [-]
  std::vector<double> axial_stress;  ///< compression positive [Pa]
  std::vector<double> radial_strain; ///< -(r - r0)/r0 [-]
};

UniaxialResponse uniaxial_material_point(const BurgersSolid &solid, double strain_rate, double time_step,
                                         unsigned int steps);
} // namespace continuum
