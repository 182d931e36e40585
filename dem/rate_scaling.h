// Strain-rate and temperature dependence (thesis §4.4.2, eq. 4.3, 7.22-7.23)
// and viscosity scaling (§7.3, eq. 7.21).
//
// Temperature-compensated strain rate (eq. 4.3):
//   rate_T = rate exp(k (1/T - 1/T_0)),   k = 13.4e3 K, T_0 = 283 K;
// bond strength and contact stiffness at (rate, T) relative to their values
// at the reference rate rate_0 = 0.1 1/s and T_0 (eq. 7.23):
//   B / B_0 = (rate_T / rate_0)^n,   n = 0.29.
// These are the thesis's fitted laws (validation data, not measurements).
//
// Viscosity scaling: a quasi-static test at the physical rate X can be run
// at rate Y with both viscosities multiplied by X / Y (eq. 7.21: the force
// is the same function of displacement when the velocity and both
// viscosities are scaled together).  Rate-dependent strengths must then be
// evaluated at the physical rate X.
#pragma once

#include <cmath>

namespace dem
{
struct RateLaw
{
  double exponent = 0.29;             ///< n
  double arrhenius = 13.4e3;          ///< k, K
  double reference_temperature = 283; ///< T_0, K
  double reference_rate = 0.1;        ///< rate_0, 1/s

  /// rate_T of eq. 4.3 [1/s] for a strain rate [1/s] at temperature T [K].
  double compensated_rate(double rate, double temperature) const
  {
    return rate * std::exp(arrhenius * (1 / temperature - 1 / reference_temperature));
  }

  /// B / B_0 of eq. 7.23 for a strain rate [1/s] at temperature T [K].
  double strength_factor(double rate, double temperature) const
  {
    return std::pow(compensated_rate(rate, temperature) / reference_rate, exponent);
  }
};

/// Factor on both viscosities that lets a run at `run_rate` stand for a
/// test at `physical_rate` (eq. 7.21).
inline double viscosity_scale(double physical_rate, double run_rate) { return physical_rate / run_rate; }
} // namespace dem
