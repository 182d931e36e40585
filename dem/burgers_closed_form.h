// The Burger's model in one dimension and its closed forms (thesis §2.4.2,
// §3.4.3, §7.2.1).
//
// A Maxwell element (spring K0 = K_m, dashpot C_inf = C_m) in series with a
// Kelvin element (spring K1 = K_k, dashpot C1 = C_k).  Units: stiffnesses
// N/m, viscosities N s/m for a contact; the same formulas hold for a
// material point with moduli in Pa and viscosities in Pa s (strain for
// displacement, stress for force).
//
// Force under a constant velocity v from rest (eq. 7.18-7.19):
//   f(t) = v [ (K0 + l2 C_inf)/(l1 - l2) e^{l1 t}
//            + (K0 + l1 C_inf)/(l2 - l1) e^{l2 t} + C_inf ],
//   l1,2 = (-p1 +- sqrt(p1^2 - 4 p2)) / (2 p2),
//   p1 = C1/K1 + C_inf (1/K0 + 1/K1),  p2 = C1 C_inf / (K0 K1),
// so f(0) = 0, f'(0) = K0 v and f -> C_inf v.  p1^2 - 4 p2 > 0 for all
// positive constants, so both roots are real and negative.
//
// Displacement under a constant force F applied at t = 0 (creep, eq. 2.15):
//   u(t) = F [ 1/K0 + t/C_inf + (1 - e^{-t/tau}) / K1 ],  tau = C1/K1.
//
// These are the references the Burger's contact law, the SUNDIALS ODE and
// the continuum cylinder are verified against.
#pragma once

#include <cmath>

namespace dem
{
struct BurgersConstants
{
  double maxwell_stiffness = 0; ///< K0 (K_m), N/m
  double maxwell_viscosity = 0; ///< C_inf (C_m), N s/m
  double kelvin_stiffness = 0;  ///< K1 (K_k), N/m
  double kelvin_viscosity = 0;  ///< C1 (C_k), N s/m

  /// p1, p2 of the force equation f + p1 f' + p2 f'' = q1 u' + q2 u'' (eq. 7.14).
  double p1() const
  {
    return kelvin_viscosity / kelvin_stiffness + maxwell_viscosity * (1.0 / maxwell_stiffness + 1.0 / kelvin_stiffness);
  }
  double p2() const { return kelvin_viscosity * maxwell_viscosity / (maxwell_stiffness * kelvin_stiffness); }

  /// The roots lambda_1 > lambda_2 of eq. 7.19 [1/s] (both negative).
  double lambda1() const { return (-p1() + std::sqrt(p1() * p1() - 4 * p2())) / (2 * p2()); }
  double lambda2() const { return (-p1() - std::sqrt(p1() * p1() - 4 * p2())) / (2 * p2()); }

  /// Force at time t under a constant velocity v from rest (eq. 7.18) [N].
  double constant_velocity_force(double t, double v) const
  {
    const double l1 = lambda1(), l2 = lambda2();
    const double k0 = maxwell_stiffness, c = maxwell_viscosity;
    return v * ((k0 + l2 * c) / (l1 - l2) * std::exp(l1 * t) + (k0 + l1 * c) / (l2 - l1) * std::exp(l2 * t) + c);
  }

  /// Displacement at time t under a constant force F applied at t = 0 (eq. 2.15) [m].
  double creep_displacement(double t, double force) const
  {
    const double tau = kelvin_viscosity / kelvin_stiffness;
    return force * (1.0 / maxwell_stiffness + t / maxwell_viscosity + (1.0 - std::exp(-t / tau)) / kelvin_stiffness);
  }

  /// Every constant multiplied by a factor for the viscosities only (thesis
  /// §7.3 viscosity scaling, eq. 7.21).
  BurgersConstants with_viscosities_scaled(double factor) const
  {
    return {maxwell_stiffness, maxwell_viscosity * factor, kelvin_stiffness, kelvin_viscosity * factor};
  }
};
} // namespace dem
