// The Burger's chain and the Burger's solid (thesis §2.4.2, §3.4.3, §7.2).
//
// A Burger's chain is a Maxwell element (spring K0, dashpot C_inf) in series
// with a Kelvin element (spring K1 parallel to dashpot C1).  The same four
// numbers describe a contact (N/m, N s/m; displacement and force) or a
// material point in one dimension (Pa, Pa s; strain and stress).
//
// A Burger's solid is the three-dimensional, isotropic, linear viscoelastic
// material the continuum companion uses.  Its deviatoric response is a
// Burger's chain in shear (deviatoric stress s = 2 G0 e_el, Maxwell
// dashpot s = 2 eta0 de_v/dt, Kelvin s = 2 G1 e_k + 2 eta1 de_k/dt).  Its
// volumetric response is either
//  - elastic: p = K (tr eps), K = E0 / (3 (1 - 2 nu)), or
//  - the same Burger's shape as in shear ("same shape"): every bulk constant
//    is K/G times the shear constant, so Poisson's ratio is the same
//    constant nu at every time scale.
// The deck describes both with a Young-type chain (E0, eta_inf, E1, eta1)
// and the instantaneous Poisson's ratio nu: the shear chain is the Young
// chain over 2 (1 + nu), the bulk chain (same shape) over 3 (1 - 2 nu).
//
// Under homogeneous uniaxial stress the solid behaves as a one-dimensional
// chain (uniaxial()): its creep compliance is J_G(t)/3 + J_K(t)/9, with
// J_G, J_K the shear and bulk creep compliances, which is again of the form
// of eq. 2.15.  That chain, put into eq. 7.18, is the closed form the
// frictionless cylinder must reproduce (check V20).
#pragma once

#include <string>

namespace continuum
{
struct BurgersChain
{
  double maxwell_spring = 0;  ///< K0 [N/m] or E0, G0, K0 [Pa]
  double maxwell_dashpot = 0; ///< C_inf [N s/m] or a viscosity [Pa s]
  double kelvin_spring = 0;   ///< K1 [N/m] or [Pa]
  double kelvin_dashpot = 0;  ///< C1 [N s/m] or [Pa s]

  /// Every constant times c (a change of units, or a homogenisation factor).
  BurgersChain scaled(double c) const;
  /// Retardation time of the Kelvin element C1/K1 [s].
  double kelvin_time() const { return kelvin_dashpot / kelvin_spring; }
  /// True when all four constants are positive and finite.
  bool valid() const;
};

enum class BulkResponse
{
  elastic,    ///< p = K tr(eps): Burger's in shear only
  same_shape, ///< bulk chain = (K/G) x shear chain: constant Poisson's ratio
};

struct BurgersSolid
{
  BurgersChain young;   ///< E0 [Pa], eta_inf [Pa s], E1 [Pa], eta1 [Pa s] (Young-type)
  double poisson = 0.3; ///< instantaneous Poisson's ratio nu, in (-1, 0.5)
  BulkResponse bulk = BulkResponse::same_shape;

  /// G0, eta0, G1, eta1 [Pa, Pa s] = young / (2 (1 + nu)).
  BurgersChain shear() const;
  /// K0, zeta0, K1, zeta1 [Pa, Pa s] = young / (3 (1 - 2 nu)) (the same-shape bulk chain).
  BurgersChain bulk_chain() const;
  /// Instantaneous bulk modulus K0 [Pa].
  double bulk_modulus() const;
  /// The 1-D chain with the same response as this solid under uniaxial stress.
  BurgersChain uniaxial() const;
  /// Lateral strain of a homogeneous uniaxial-stress state with the given
  /// axial strain and stress (any sign convention, the same for both) [-].
  double lateral_strain(double axial_strain, double axial_stress) const;
  /// Empty if the solid is admissible, else what is wrong (one phrase).
  std::string problem() const;
};
} // namespace continuum
