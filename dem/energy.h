// Energy bookkeeping of a DEM run (check V08).
//
// With W the work done on the balls by walls and held (kinematically driven)
// balls, and G the work of gravity, conservation reads
//
//   E_initial + W + G = E_kinetic + E_strain + D_friction + D_damping + E_released
//
// E_kinetic is evaluated at the force time t as 1/2 m v(t-dt/2).v(t+dt/2),
// the energy the centred-difference scheme conserves exactly for a linear
// spring; work and dissipation increments use the force at t and the
// mid-point velocity over the step centred on t.  The residual (left minus
// right) is therefore small but not zero; it is reported, not hidden.
#pragma once

namespace dem
{
struct EnergyLedger
{
  double kinetic = 0;       ///< J, translational + rotational, at the force time
  double strain = 0;        ///< J, stored in ball-ball and ball-wall contacts
  double friction = 0;      ///< J, dissipated by Coulomb slip (cumulative)
  double damping = 0;       ///< J, dissipated by local damping (cumulative)
  double bond_released = 0; ///< J, released when bonds broke (cumulative)
  double boundary_work = 0; ///< J, done by walls and held balls (cumulative)
  double body_work = 0;     ///< J, done by gravity (cumulative)
  double initial = 0;       ///< J, kinetic + strain at the first step

  double supplied() const { return initial + boundary_work + body_work; }
  double accounted() const { return kinetic + strain + friction + damping + bond_released; }
  double residual() const { return supplied() - accounted(); }
};
} // namespace dem
