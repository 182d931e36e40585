// The Burger's chain as an ordinary differential equation, integrated with
// SUNDIALS CVODE (variable-order BDF, Newton iteration, dense Jacobian;
// SUNDIALS 6 API with a SUNContext).
//
// Unknowns (thesis eq. 3.19-3.23, 7.2-7.11), for a contact [m, N] or a
// material point in one dimension [-, Pa]:
//   u_k  displacement of the Kelvin element (spring K1 || dashpot C1)
//   u_c  displacement of the Maxwell dashpot C_inf
//   f    force, carried by every element in series
// and the ODE system, from rest (u_k = u_c = 0, f(0) = K0 u(0+) or F(0+)):
//   du_k/dt = (f - K1 u_k) / C1                        (eq. 3.24, 7.5)
//   du_c/dt = f / C_inf                                (eq. 7.10)
//   df/dt   = K0 (du/dt - du_k/dt - du_c/dt)           (eq. 7.3, 7.8)
// under a prescribed displacement u(t), or df/dt = dF/dt under a prescribed
// force F(t), with u = f/K0 + u_k + u_c.  The Maxwell spring's extension
// u - u_k - u_c = f/K0 (eq. 7.2, 7.7) is a linear invariant of this
// system, which BDF methods conserve (a linear Newton iteration with the
// exact Jacobian); carrying f as a state, rather than computing it as
// K0 (u - u_k - u_c), keeps the error control on the force itself instead
// of on a difference of two growing displacements.
//
// Histories with a kink (ramp-and-hold) are integrated piecewise: CVODE
// stops at the kink and restarts there, so its error control never straddles
// a jump in du/dt.  A prescribed step is the limit t -> 0+ of the history
// (the elastic jump f(0+) = K0 u0, or u(0+) = F/K0).
//
// Tolerances: the relative tolerance rtol is the caller's.  The absolute
// tolerances default to 1e-3 rtol times the scale of each unknown (largest
// |u| prescribed, or the creep displacement |F| J(t_end) under a force; the
// force scale is K0 times that under a displacement, |F| under a force), so
// that relative control decides everywhere except at zero crossings.
#pragma once

#include "continuum/burgers_chain.h"

#include <functional>
#include <vector>

namespace continuum
{
enum class Control
{
  displacement, ///< u(t) prescribed [m or -], force computed
  force,        ///< f(t) prescribed [N or Pa], displacement computed
};

/// A prescribed history x(t) of displacement or force, from x(0) = 0.
struct History
{
  enum class Shape
  {
    constant_rate, ///< x = rate t
    ramp_and_hold, ///< x = rate min(t, ramp_time)
    cyclic,        ///< x = amplitude sin(2 pi frequency t)
    step,          ///< x = level for t > 0
    general,       ///< any piecewise-smooth history the caller describes
  };
  Shape shape = Shape::constant_rate;
  double rate = 0;      ///< [unit/s]
  double ramp_time = 0; ///< [s]
  double amplitude = 0; ///< [unit]
  double frequency = 0; ///< [Hz]
  double level = 0;     ///< [unit]
  /// Shape::general: x(t); dx/dt at t on the piece that begins at the
  /// second argument; the kinks; the largest |x| over the history.
  std::function<double(double)> general_value;
  std::function<double(double, double)> general_rate;
  std::vector<double> general_kinks;
  double general_magnitude = 0;

  static History constant_rate(double rate);
  static History ramp_and_hold(double rate, double ramp_time);
  static History cyclic(double amplitude, double frequency);
  static History step(double level);
  static History general(std::function<double(double)> value, std::function<double(double, double)> rate,
                         std::vector<double> kinks, double largest_magnitude);

  double value(double t) const;
  /// dx/dt at t on the smooth piece of the history that begins at
  /// piece_start (so at a kink: the left derivative for the piece that ends
  /// there, the right one for the piece that begins there); 0 for a step.
  double rate_of_change(double t, double piece_start) const;
  /// Times > 0 where the derivative jumps.
  std::vector<double> kinks() const;
  /// Largest |x| over [0, t_end].
  double largest_magnitude(double t_end) const;
};

struct OdeTolerances
{
  double relative = 1e-8;
  double absolute = 0; ///< displacements [m or -]; 0: 1e-3 relative x displacement scale
  long max_steps = 1000000;
};

/// The solution at one output time.
struct OdeState
{
  double time = 0;         ///< [s]
  double displacement = 0; ///< u [m or -]
  double force = 0;        ///< f [N or Pa]
  double kelvin = 0;       ///< u_k [m or -]
  double dashpot = 0;      ///< u_c [m or -]
};

struct OdeStatistics
{
  long steps = 0;
  long rhs_evaluations = 0;
  long jacobian_evaluations = 0;
  long error_test_failures = 0;
  long restarts = 0;             ///< restarts at kinks of the history
  double absolute_tolerance = 0; ///< on the displacements [m or -]
};

class BurgersOde
{
public:
  BurgersOde(const BurgersChain &chain, Control control, const History &history);

  /// The solution at each of `times` (non-decreasing, >= 0).  Throws
  /// NumericalFailure if CVODE fails.
  std::vector<OdeState> solve(const std::vector<double> &times, const OdeTolerances &tolerances,
                              OdeStatistics *statistics = nullptr) const;
  /// The same, handing each output to `on_output` as soon as it is computed
  /// (so that a failure keeps every earlier output).
  void solve(const std::vector<double> &times, const OdeTolerances &tolerances,
             const std::function<void(const OdeState &)> &on_output, OdeStatistics *statistics = nullptr) const;

  /// The displacement scale the default absolute tolerance refers to [m or -].
  double displacement_scale(double t_end) const;

  /// d(u_k, u_c, f)/dt at time t on the piece of the history that begins
  /// at piece_start (the right-hand side above).
  void rates(double t, double piece_start, const double state[3], double rate[3]) const;
  /// The displacement and the rest of a state at time t.
  OdeState observe(double t, const double state[3]) const;
  /// The state at t = 0+.
  void initial_state(double state[3]) const;

private:
  BurgersChain chain_;
  Control control_;
  History history_;
};
} // namespace continuum
