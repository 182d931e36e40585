// Checks of the continuum companion (V12, V13, V18-V22).
#pragma once

#include "verify/checks/check.h"

#include "continuum/homogenisation.h"

#include <array>
#include <vector>

namespace demvv
{
CheckOutcome check_burgers_ode_histories(const CheckContext &ctx);  // V12
CheckOutcome check_burgers_creep(const CheckContext &ctx);          // V13
CheckOutcome check_affine_moduli(const CheckContext &ctx);          // V18
CheckOutcome check_network_identity(const CheckContext &ctx);       // V19
CheckOutcome check_frictionless_cylinder(const CheckContext &ctx);  // V20
CheckOutcome check_manufactured_solutions(const CheckContext &ctx); // V21
CheckOutcome check_bonded_gci(const CheckContext &ctx);             // V22

/// Affine (Voigt) moduli computed the long way: an affine strain imposed on
/// contacts with the given unit normals (weighted equally), forces
/// k_n (n . delta) n + k_s (delta - (n . delta) n) on branch vectors 2R n,
/// stress sigma = (contacts per volume) <f (x) 2R n>; K from an isotropic
/// strain, G from a shear.  With the normals of a spherical 4-design the
/// orientation average is exactly the isotropic one.
continuum::ElasticModuli discrete_affine_moduli(const std::vector<std::array<double, 3>> &normals,
                                                const continuum::PackingGeometry &packing, double normal_stiffness,
                                                double shear_stiffness);
/// Unit normals of the icosahedron's 12 vertices (a spherical 5-design).
std::vector<std::array<double, 3>> icosahedron_normals();
/// Unit normals of the dodecahedron's 20 vertices (a spherical 5-design).
std::vector<std::array<double, 3>> dodecahedron_normals();
} // namespace demvv
