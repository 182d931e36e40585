// Code verification of the viscoelastic cylinder by the method of
// manufactured solutions (check V21; Roache 2002, Salari & Knupp
// 2000).
//
// A displacement u(x, t) = phi(t) U(x), a Kelvin strain
// eps_k(x, t) = psi_k(t) E_k(x) and a Maxwell viscous strain
// eps_v(x, t) = psi_v(t) E_v(x) are chosen (smooth, zero at t = 0; the
// internal strains deviatoric when the bulk is elastic).  They define the
// stress sigma = C0 : (eps(u) - eps_k - eps_v) with the instantaneous
// moduli C0, and they solve the model once
//   - equilibrium gets the body force b = -div sigma (in cylindrical
//     coordinates for the axisymmetric model),
//   - the Kelvin and dashpot equations get the strain-rate sources
//     g = d(eps)/dt - (the model's rate at the manufactured state),
//   - the boundary gets u itself (u_r = 0 on the axis, where the field is
//     regular and needs no more).
// The discrete solution is then compared with the manufactured one at the
// final time: relative L2 and H1-seminorm errors of u, and relative L2
// errors of the stress and the Kelvin strain at the quadrature points.
//
// Two studies separate the two discretisations:
//  - space: U, E_k, E_v trigonometric; phi, psi quadratic in t, which the
//    trapezoidal update integrates exactly, so the error is spatial only.
//    Expected: L2(u) ~ h^(p+1), H1(u) ~ h^p, stress ~ h^p for Q_p.
//  - time: U affine, E_k, E_v constant (all exactly in the finite element
//    space, body force zero); phi, psi transcendental.  The error is that of
//    the time update only.  Expected: stress and Kelvin strain ~ dt^2.
#pragma once

#include "continuum/burgers_chain.h"
#include "continuum/cylinder.h"

#include <string>
#include <vector>

namespace continuum
{
enum class MmsVariable
{
  space, ///< refine the mesh, few exact time steps
  time,  ///< halve the time step on one mesh
};

struct MmsSpec
{
  BurgersSolid solid;
  Geometry geometry = Geometry::axisymmetric;
  MmsVariable variable = MmsVariable::space;
  unsigned int degree = 2;
  std::vector<unsigned int> levels = {0, 1, 2, 3}; ///< refinements (space) or step halvings (time)
  double radius = 0.01555;                         ///< [m]
  double height = 0.0311;                          ///< [m]
  double duration = 2;                             ///< manufactured time span T [s]
  unsigned int time_steps = 2;                     ///< steps at level 0 (space: every level)
  unsigned int refinements = 0;                    ///< mesh of the time study
  double solver_tolerance = 1e-12;
};

/// Errors at the final time, each relative to the norm of the manufactured field.
struct MmsLevel
{
  unsigned int level = 0;
  double cell_size = 0; ///< [m]
  double time_step = 0; ///< [s]
  unsigned long cells = 0;
  unsigned long dofs = 0;
  unsigned int steps = 0;
  double displacement_l2 = 0;
  double displacement_h1 = 0; ///< H1 seminorm
  double stress_l2 = 0;
  double kelvin_l2 = 0;
};

/// Runs every level of the study (on all MPI ranks; same result on each).
std::vector<MmsLevel> run_mms(const MmsSpec &spec);

/// The study as deal.II's ConvergenceTable prints it, with observed orders
/// (log2 reduction rates between successive levels).
std::string mms_convergence_text(const std::vector<MmsLevel> &levels, MmsVariable variable);
} // namespace continuum
