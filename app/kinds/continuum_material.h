// The `material` section of continuum decks (cylinder, mms): a Burger's
// solid (continuum/burgers_chain.h) given directly, or obtained from
// Burger's contact constants by one of the two homogenisation routes
// (continuum/homogenisation.h):
//   direct      E0, nu, eta_inf, E1, eta1 of the solid
//   affine      contact chain x c_E, c_E = affine E(k_n = 1, k_s = r) of a
//               packing with the deck's Z, phi, R; nu = (1 - r)/(4 + r)
//   calibrated  contact chain x E/k_n, with E and nu measured on an elastic
//               run (numbers, or initial_modulus_pa and poisson_ratio of its
//               summary.json) whose contacts had normal stiffness k_n
// The two homogenised routes need one Burger's shape in shear and in bulk
// (model = same shape); the deck is refused otherwise.
#pragma once

#include "app/decks/deck.h"

#include "continuum/burgers_chain.h"

#include <nlohmann/json.hpp>

namespace demvv
{
void declare_continuum_material(DeckSchema &s);

/// The section, parsed and validated: the solid (moduli in Pa, viscosities
/// in Pa s) and what summary.json says of where it came from.
struct ContinuumMaterial
{
  continuum::BurgersSolid solid;
  nlohmann::json description; ///< the route, its inputs and the resulting moduli (for summary.json)
};

/// Reads every key of the section once (and, for a calibrated material, its
/// summary file); throws DeckError (one line) on an inadmissible material.
ContinuumMaterial parse_continuum_material(const Deck &deck);

/// The moduli of a solid as JSON (Young, shear, bulk and uniaxial chains, nu).
nlohmann::json describe_solid(const continuum::BurgersSolid &solid);
} // namespace demvv
