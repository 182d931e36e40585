// The Burger's solid advanced over one time step at a material point.
//
// Every Burger's chain (deviatoric: force s, displacement e, constants
// 2 G0, 2 eta0, 2 G1, 2 eta1; volumetric, same shape: force p, displacement
// tr(eps), constants K0, zeta0, K1, zeta1) is integrated with the
// trapezoidal (Crank-Nicolson) rule, exactly as the thesis integrates the
// contact law (eq. 3.25-3.35):
//   A = 1 + K1 dt/(2 C1),  B = 1 - K1 dt/(2 C1)
//   C = dt/(2 C1 A) + 1/K0 + dt/(2 C_inf),  D = dt/(2 C1 A) - 1/K0 + dt/(2 C_inf)
//   f^{n+1}   = (u^{n+1} - u^n + (1 - B/A) u_k^n - D f^n - dt (g_k/A + g_c)) / C     (3.34)
//   u_k^{n+1} = (B u_k^n + dt/(2 C1) (f^{n+1} + f^n) + dt g_k) / A                   (3.26)
// g_k, g_c are step-averaged strain-rate sources added to the Kelvin and
// Maxwell-dashpot equations; they are zero except for manufactured
// solutions (check V21).  The update is second order in dt (the
// trapezoidal rule), exact when the internal strains are quadratic in time,
// A-stable but not L-stable: for K1 dt/(2 C1) > 1 the Kelvin strain
// alternates in sign from step to step, decaying (B/A in (-1, 0)).
//
// The new force is affine in the new displacement: f^{n+1} = u^{n+1}/C + h,
// with h from the old state only.  For the solid this makes the step a
// linear elasticity problem with algorithmic moduli 2 mu = 1/C_dev and
// kappa = 1/C_vol (or the elastic bulk modulus) and a history stress; the
// finite element matrix depends on dt only.
//
// Tensors are three-dimensional: (r, theta, z) components for the
// axisymmetric cylinder, (x, y, z) in 3D.  Units: strain [-], stress [Pa],
// sources [1/s].
#pragma once

#include "continuum/burgers_chain.h"

#include <deal.II/base/symmetric_tensor.h>

#include <optional>

namespace continuum
{
using Tensor3 = dealii::SymmetricTensor<2, 3>;

class TrapezoidalChain
{
public:
  TrapezoidalChain(const BurgersChain &chain, double dt);

  /// d f^{n+1} / d u^{n+1} = 1/C [stiffness units].
  double stiffness() const { return 1.0 / c_; }

  /// f^{n+1} - stiffness() u^{n+1}: the part of eq. 3.34 fixed by the old state.
  template <typename T>
  T history(const T &total_old, const T &kelvin_old, const T &force_old, const T &kelvin_source,
            const T &dashpot_source) const
  {
    return (-total_old + (1 - b_ / a_) * kelvin_old - d_ * force_old - dt_ * (kelvin_source / a_ + dashpot_source)) /
           c_;
  }

  /// u_k^{n+1} (eq. 3.26).
  template <typename T>
  T kelvin(const T &kelvin_old, const T &force_old, const T &force_new, const T &kelvin_source) const
  {
    return (b_ * kelvin_old + dt_ / (2 * kelvin_dashpot_) * (force_new + force_old) + dt_ * kelvin_source) / a_;
  }

private:
  double dt_, kelvin_dashpot_, a_, b_, c_, d_;
};

/// What a material point carries from step to step.
struct PointState
{
  Tensor3 strain; ///< total strain eps^n
  Tensor3 stress; ///< sigma^n [Pa]
  Tensor3 kelvin; ///< Kelvin strain eps_k^n (deviatoric only when the bulk is elastic)
};

/// Step-averaged sources (g^n + g^{n+1})/2 of the internal-strain equations [1/s].
struct PointSources
{
  Tensor3 kelvin;
  Tensor3 dashpot;
};

class SolidStep
{
public:
  SolidStep(const BurgersSolid &solid, double dt);

  double shear_stiffness() const { return deviatoric_.stiffness(); } ///< 2 mu_alg [Pa]
  double bulk_stiffness() const;                                     ///< kappa_alg [Pa]
  /// The algorithmic stress of a strain: 2 mu dev(eps) + kappa tr(eps) I [Pa].
  Tensor3 stress(const Tensor3 &strain) const;
  /// sigma^{n+1} - stress(eps^{n+1}): what the old state contributes [Pa].
  Tensor3 history(const PointState &old, const PointSources &sources) const;
  /// The state at the end of the step for the new total strain.
  PointState advance(const PointState &old, const Tensor3 &strain, const PointSources &sources) const;

private:
  TrapezoidalChain deviatoric_;
  std::optional<TrapezoidalChain> volumetric_; ///< empty: elastic bulk
  double elastic_bulk_;
};
} // namespace continuum
