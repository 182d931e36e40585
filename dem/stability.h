// Critical time step of the centred-difference scheme (thesis §3.3.3).
//
// The scheme of eq. 3.7-3.9 is stable for an undamped linear system while
// dt <= 2 / omega_max, omega_max^2 the largest eigenvalue of M^-1 K.  The
// thesis's eq. 3.11 (dt = sqrt(m/k)) is that limit for a chain; demvv instead
// bounds omega_max^2 for any assembly, rotations included, by the block
// Gershgorin theorem (Feingold & Varga 1962) applied to A = M^-1/2 K M^-1/2
// with one 6x6 block per ball: every eigenvalue of A is at most
// max_A sum_B ||A_AB||.  A contact between balls A and B with normal and
// shear stiffness K^n, K^s and arms a_A, a_B adds to the blocks
//
//   A_AA += K^n w_A (n n^T on translation) + K^s (P B_A)^T (P B_A),
//   A_AB += ...,   with w = 1/m, b = 1/m + a^2/I (zero where motion is held).
//
// For spheres the normal part acts only on the translation along n and the
// shear part is orthogonal to it, so the two parts add in orthogonal
// subspaces and their norms combine by max, not by sum:
//
//   ||contact part of A_AA|| = max(K^n w_A, K^s b_A),
//   ||A_AB||                <= max(K^n sqrt(w_A w_B), K^s sqrt(b_A b_B)).
//
// The row bound of ball A is the sum of both over its contacts (a wall is a
// partner with w = b = 0), and
//
//   dt_crit >= 2 / sqrt(max_A row_A).
//
// The bound is exact for one ball on a spring to a fixed support and for a
// free pair of equal balls in normal motion; it is conservative otherwise
// (exact_stability_limit() measures by how much on small assemblies).
//
// Local damping (PFC's, alpha in [0, 1)) lowers that limit.  The component
// force F - alpha |F| sign(v(t - dt/2)) of the fastest mode, which flips
// sign every step (x_n = (-1)^n a, so v(t - dt/2) has the sign of x_n and
// F = -k x_n the opposite one), is -(1 + alpha) k x_n: the flip-flop mode is
// an exact solution of the damped scheme with the stiffness (1 + alpha) k,
// and it grows once dt > 2 / sqrt((1 + alpha) omega^2).  The bound the step
// is taken from is therefore 2 / sqrt((1 + alpha) max_A row_A)
// (damped_row_bound); the engine uses a safety fraction (default 0.8) of
// it.  Without the factor, a two-ball sample at the default step and
// alpha = 0.7 (0.8 sqrt(1.7) = 1.04 of its limit) gained energy from its
// damping, every step.
#pragma once

#include "dem/types.h"

#include <algorithm>
#include <cmath>

namespace dem
{
/// Row term of ball A for one contact (see header note), 1/s^2.
/// sqrt_ww = sqrt(w_A w_B), sqrt_bb = sqrt(b_A b_B).
inline double stability_row_term(double kn, double ks, double w_self, double b_self, double sqrt_ww, double sqrt_bb)
{
  return std::max(kn * w_self, ks * b_self) + std::max(kn * sqrt_ww, ks * sqrt_bb);
}

/// b = 1/m + a^2/I of one ball at one contact.
inline double shear_mobility(double inv_mass, double inv_inertia, double arm)
{
  return inv_mass + arm * arm * inv_inertia;
}

/// Factor f with b(a) <= f^2 b(R) for an arm a (given 1/R), b(R) = 1/m + R^2/I: the arm
/// is at most R in compression, and b(a) <= (a/R)^2 b(R) beyond.  With
/// b(R) and its square root stored per ball, a contact needs no root.
inline double arm_factor(double arm, double inv_radius) { return std::max(1.0, arm * inv_radius); }

/// The row bound the step must resolve under local damping alpha (header
/// note): (1 + alpha) times the undamped one [1/s^2].
inline double damped_row_bound(double row_bound, double local_damping) { return (1 + local_damping) * row_bound; }

/// The step 2/sqrt(bound); infinite for a ball without contacts.
inline double critical_step(double row_bound) { return row_bound > 0 ? 2.0 / std::sqrt(row_bound) : infinity; }

/// Frequency error of centred differences on a linear oscillator resolved
/// by N steps per period (theta = omega dt = 2 pi / N): the scheme runs at
/// omega~ = (2 / dt) asin(omega dt / 2) (its exact discrete dispersion), so
/// periods and contact durations come out short by omega~ / omega - 1 =
/// (2 / theta) asin(theta / 2) - 1: 16 % at N = 3.93, 1 % at N = 12.8.
/// Unstable (1 returned) at theta >= 2, N <= pi.
inline double centred_difference_frequency_error(double steps_per_period)
{
  const double theta = 2 * pi / steps_per_period;
  return theta >= 2 ? 1.0 : (2 / theta) * std::asin(theta / 2) - 1;
}
class Simulation;

/// Largest eigenvalue of M^-1 K for the force-carrying contacts of a
/// simulation, from a dense eigen-solve (6 dof per ball; held dofs removed).
/// For verification on small assemblies only: O(N^3).
double exact_max_eigenvalue(const Simulation &sim);

/// 2 / sqrt(exact_max_eigenvalue): the exact stability limit [s].
double exact_stability_limit(const Simulation &sim);
} // namespace dem
