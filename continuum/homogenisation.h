// From contact constants to continuum moduli (checks V18-V19).
//
// A priori, affine (Voigt) homogenisation of an isotropic, monodisperse
// packing of spheres of radius R [m], solid fraction phi, coordination
// number Z, contact stiffnesses k_n, k_s [N/m]: every contact follows the
// mean strain, so (with branch vectors 2R n and <n n n n> isotropic)
//   K  = phi Z k_n / (6 pi R)                       bulk modulus [Pa]
//   G  = phi Z (2 k_n + 3 k_s) / (20 pi R)          shear modulus [Pa]
//   nu = (k_n - k_s) / (4 k_n + k_s)                Poisson's ratio [-]
// (Makse et al. 1999; Agnolin & Roux 2007).  Real packings relax
// non-affinely and are softer; check V18 reports that gap.
//
// Burger's contacts with one shape (every shear constant = r x the normal
// one) behave, by the correspondence principle, like elastic contacts with
// k_n(s) the Burger's operator and k_s(s) = r k_n(s).  Both affine moduli
// are homogeneous of degree one in (k_n, k_s), so E(s) = c_E k_n(s) with
// c_E = E(k_n = 1, k_s = r) [1/m], and nu is the constant (1 - r)/(4 + r):
// a same-shape Burger's solid whose Young chain is c_E times the contact
// chain.  The calibrated route replaces c_E by E/k_n measured on an elastic
// DEM run of the same sample (check V19) and nu by the measured one.
#pragma once

#include "continuum/burgers_chain.h"

namespace continuum
{
struct PackingGeometry
{
  double coordination = 0;   ///< Z, contacts per particle [-]
  double solid_fraction = 0; ///< phi [-]
  double radius = 0;         ///< R [m]
};

struct ElasticModuli
{
  double bulk = 0;    ///< K [Pa]
  double shear = 0;   ///< G [Pa]
  double young = 0;   ///< E = 9 K G / (3 K + G) [Pa]
  double poisson = 0; ///< nu = (3 K - 2 G) / (2 (3 K + G)) [-]
};

/// Affine (Voigt) moduli of the packing for contact stiffnesses k_n, k_s [N/m].
ElasticModuli affine_moduli(const PackingGeometry &packing, double normal_stiffness, double shear_stiffness);

/// A same-shape Burger's solid from Burger's contacts (normal chain, shear
/// chain = shear_ratio x normal chain) by the affine route.
BurgersSolid affine_burgers_solid(const BurgersChain &normal_contact, double shear_ratio,
                                  const PackingGeometry &packing);

/// A same-shape Burger's solid from Burger's contacts by the calibrated
/// route: E and nu measured on an elastic run whose contacts had normal
/// stiffness reference_normal_stiffness [N/m].
BurgersSolid calibrated_burgers_solid(const BurgersChain &normal_contact, double young, double poisson,
                                      double reference_normal_stiffness);
} // namespace continuum
