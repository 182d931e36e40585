// Critical time step of the centred-difference scheme (thesis §3.3.3).
//
// The scheme of eq. 3.7-3.9 is stable for an undamped linear system while
// dt <= 2 / omega_max, omega_max^2 the largest eigenvalue of M^-1 K.  The
// thesis's eq. 3.11 (dt = sqrt(m/k)) is that limit for a chain; demvv instead
// bounds omega_max^2 for any assembly, rotations included, by the block
// Gershgorin theorem (Feingold & Varga 1962) applied to M^-1/2 K M^-1/2 with
// one 6x6 block per ball.  For a contact with normal stiffness K^n, shear
// stiffness K^s, contact arms a_A, a_B (the normal part does not couple to
// rotation for spheres):
//
//   ||block(A,A)|| <= K^n w_A + K^s b_A,
//   ||block(A,B)|| <= K^n sqrt(w_A w_B) + K^s sqrt(b_A b_B)
//                  <= K^n (w_A + w_B)/2 + K^s (b_A + b_B)/2,
//
// with w = 1/m and b = 1/m + a^2/I (zero where the motion is held).  The
// row bound of ball A is the sum of both over its contacts; omega_max^2 is
// at most the largest row bound, so
//
//   dt_crit >= 2 / sqrt(max_A sum_c [K^n (1.5 w_A + 0.5 w_B) + K^s (1.5 b_A + 0.5 b_B)]).
//
// The bound is exact for one ball against a wall with ks = 0 (row term
// K^n/m) and for two equal balls; it is conservative otherwise.  The engine
// uses a safety fraction (default 0.8) of it.
#pragma once

#include "types.h"

#include <cmath>

namespace dem
{
/// Row term of ball A for one contact (see header note), 1/s^2.
inline double stability_row_term(double kn, double ks, double w_self, double b_self,
                                 double w_other, double b_other)
{
  return kn * (1.5 * w_self + 0.5 * w_other) + ks * (1.5 * b_self + 0.5 * b_other);
}

/// b = 1/m + a^2/I of one ball at one contact.
inline double shear_mobility(double inv_mass, double inv_inertia, double arm)
{
  return inv_mass + arm * arm * inv_inertia;
}

/// The step 2/sqrt(bound); infinite for a ball without contacts.
inline double critical_step(double row_bound)
{
  return row_bound > 0 ? 2.0 / std::sqrt(row_bound) : infinity;
}
} // namespace dem
