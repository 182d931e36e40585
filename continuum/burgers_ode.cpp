#include "continuum/burgers_ode.h"

#include "continuum/numerical_failure.h"

#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>

namespace continuum
{
namespace
{
constexpr double two_pi = 6.283185307179586476925;

// --- SUNDIALS objects with their destructors --------------------------------
struct ContextFree
{
  void operator()(SUNContext c) const { SUNContext_Free(&c); }
};
struct VectorFree
{
  void operator()(N_Vector v) const { N_VDestroy(v); }
};
struct MatrixFree
{
  void operator()(SUNMatrix m) const { SUNMatDestroy(m); }
};
struct SolverFree
{
  void operator()(SUNLinearSolver s) const { SUNLinSolFree(s); }
};
struct CvodeFree
{
  void operator()(void *mem) const { CVodeFree(&mem); }
};
using Context = std::unique_ptr<std::remove_pointer_t<SUNContext>, ContextFree>;
using Vector = std::unique_ptr<std::remove_pointer_t<N_Vector>, VectorFree>;
using Matrix = std::unique_ptr<std::remove_pointer_t<SUNMatrix>, MatrixFree>;
using Solver = std::unique_ptr<std::remove_pointer_t<SUNLinearSolver>, SolverFree>;
using Memory = std::unique_ptr<void, CvodeFree>;

/// What the callbacks see: the ODE, the start of the current smooth piece
/// of the history and the last CVODE error message.
struct UserData
{
  const BurgersOde *ode;
  const BurgersChain *chain;
  Control control;
  double piece_start;
  std::string error;
};

int right_hand_side(sunrealtype t, N_Vector y, N_Vector ydot, void *user)
{
  const auto *data = static_cast<UserData *>(user);
  const double state[3] = {NV_Ith_S(y, 0), NV_Ith_S(y, 1), NV_Ith_S(y, 2)};
  double rate[3];
  data->ode->rates(t, data->piece_start, state, rate);
  for (int i = 0; i < 3; ++i)
    NV_Ith_S(ydot, i) = rate[i];
  return std::isfinite(rate[0]) && std::isfinite(rate[1]) && std::isfinite(rate[2]) ? 0 : -1;
}

/// The exact Jacobian of (u_k', u_c', f') with respect to (u_k, u_c, f).
int jacobian(sunrealtype /*t*/, N_Vector /*y*/, N_Vector /*fy*/, SUNMatrix J, void *user, N_Vector /*tmp1*/,
             N_Vector /*tmp2*/, N_Vector /*tmp3*/)
{
  const auto *data = static_cast<UserData *>(user);
  const BurgersChain &c = *data->chain;
  SUNMatZero(J);
  SM_ELEMENT_D(J, 0, 0) = -c.kelvin_spring / c.kelvin_dashpot;
  if (data->control == Control::force)
    return 0; // the force is the prescribed F(t): no dependence on the state
  SM_ELEMENT_D(J, 0, 2) = 1 / c.kelvin_dashpot;
  SM_ELEMENT_D(J, 1, 2) = 1 / c.maxwell_dashpot;
  SM_ELEMENT_D(J, 2, 0) = c.maxwell_spring * c.kelvin_spring / c.kelvin_dashpot;
  SM_ELEMENT_D(J, 2, 2) = -c.maxwell_spring * (1 / c.kelvin_dashpot + 1 / c.maxwell_dashpot);
  return 0;
}

void keep_error(int /*code*/, const char *module, const char *function, char *message, void *user)
{
  static_cast<UserData *>(user)->error = std::string(module) + "/" + function + ": " + message;
}

/// Adds CVODE's counters since the last (re)initialisation to `total`.
void add_counters(void *mem, OdeStatistics &total)
{
  long steps = 0, rhs = 0, jacobians = 0, failures = 0;
  CVodeGetNumSteps(mem, &steps);
  CVodeGetNumRhsEvals(mem, &rhs);
  CVodeGetNumJacEvals(mem, &jacobians);
  CVodeGetNumErrTestFails(mem, &failures);
  total.steps += steps;
  total.rhs_evaluations += rhs;
  total.jacobian_evaluations += jacobians;
  total.error_test_failures += failures;
}

void require(int flag, const char *call)
{
  if (flag < 0)
    throw std::runtime_error(std::string("demvv bug: SUNDIALS ") + call + " failed: " + CVodeGetReturnFlagName(flag));
}
} // namespace

// --- histories -------------------------------------------------------------
History History::constant_rate(double rate)
{
  History h;
  h.rate = rate;
  return h;
}

History History::ramp_and_hold(double rate, double ramp_time)
{
  History h;
  h.shape = Shape::ramp_and_hold;
  h.rate = rate;
  h.ramp_time = ramp_time;
  return h;
}

History History::cyclic(double amplitude, double frequency)
{
  History h;
  h.shape = Shape::cyclic;
  h.amplitude = amplitude;
  h.frequency = frequency;
  return h;
}

History History::step(double level)
{
  History h;
  h.shape = Shape::step;
  h.level = level;
  return h;
}

History History::general(std::function<double(double)> value, std::function<double(double, double)> rate,
                         std::vector<double> kinks, double largest_magnitude)
{
  History h;
  h.shape = Shape::general;
  h.general_value = std::move(value);
  h.general_rate = std::move(rate);
  h.general_kinks = std::move(kinks);
  h.general_magnitude = largest_magnitude;
  return h;
}

double History::value(double t) const
{
  switch (shape)
  {
  case Shape::constant_rate:
    return rate * t;
  case Shape::ramp_and_hold:
    return rate * std::min(t, ramp_time);
  case Shape::cyclic:
    return amplitude * std::sin(two_pi * frequency * t);
  case Shape::step:
    return level; // the limit t -> 0+ at t = 0
  case Shape::general:
    return general_value(t);
  }
  return 0;
}

double History::rate_of_change(double t, double piece_start) const
{
  switch (shape)
  {
  case Shape::constant_rate:
    return rate;
  case Shape::ramp_and_hold:
    return piece_start < ramp_time ? rate : 0.0;
  case Shape::cyclic:
    return amplitude * two_pi * frequency * std::cos(two_pi * frequency * t);
  case Shape::step:
    return 0;
  case Shape::general:
    return general_rate(t, piece_start);
  }
  return 0;
}

std::vector<double> History::kinks() const
{
  if (shape == Shape::general)
    return general_kinks;
  if (shape == Shape::ramp_and_hold && ramp_time > 0)
    return {ramp_time};
  return {};
}

double History::largest_magnitude(double t_end) const
{
  switch (shape)
  {
  case Shape::constant_rate:
    return std::abs(rate) * t_end;
  case Shape::ramp_and_hold:
    return std::abs(rate) * std::min(t_end, ramp_time);
  case Shape::cyclic:
    return frequency * t_end >= 0.25 ? std::abs(amplitude) : std::abs(value(t_end));
  case Shape::step:
    return std::abs(level);
  case Shape::general:
    return general_magnitude;
  }
  return 0;
}

// --- the ODE ---------------------------------------------------------------
BurgersOde::BurgersOde(const BurgersChain &chain, Control control, const History &history)
  : chain_(chain), control_(control), history_(history)
{
  if (!chain.valid())
    throw std::invalid_argument("BurgersOde: every spring and dashpot constant must be positive and finite");
}

OdeState BurgersOde::observe(double t, const double state[3]) const
{
  OdeState s;
  s.time = t;
  s.kelvin = state[0];
  s.dashpot = state[1];
  if (control_ == Control::displacement)
  {
    s.displacement = history_.value(t);
    s.force = state[2];
  }
  else
  {
    s.force = history_.value(t);
    s.displacement = s.force / chain_.maxwell_spring + state[0] + state[1];
  }
  return s;
}

void BurgersOde::initial_state(double state[3]) const
{
  state[0] = state[1] = 0;
  const double x = history_.value(0);
  state[2] = control_ == Control::displacement ? chain_.maxwell_spring * x : x;
}

void BurgersOde::rates(double t, double piece_start, const double state[3], double rate[3]) const
{
  const bool displacement = control_ == Control::displacement;
  const double f = displacement ? state[2] : history_.value(t);
  rate[0] = (f - chain_.kelvin_spring * state[0]) / chain_.kelvin_dashpot;
  rate[1] = f / chain_.maxwell_dashpot;
  const double x_rate = history_.rate_of_change(t, piece_start);
  rate[2] = displacement ? chain_.maxwell_spring * (x_rate - rate[0] - rate[1]) : x_rate;
}

double BurgersOde::displacement_scale(double t_end) const
{
  const double x = history_.largest_magnitude(t_end);
  if (control_ == Control::displacement)
    return x;
  // Creep displacement of the largest force after t_end (eq. 2.15 bound).
  return x * (1 / chain_.maxwell_spring + t_end / chain_.maxwell_dashpot + 1 / chain_.kelvin_spring);
}

std::vector<OdeState> BurgersOde::solve(const std::vector<double> &times, const OdeTolerances &tolerances,
                                        OdeStatistics *statistics) const
{
  std::vector<OdeState> out;
  out.reserve(times.size());
  solve(
    times, tolerances, [&](const OdeState &s) { out.push_back(s); }, statistics);
  return out;
}

void BurgersOde::solve(const std::vector<double> &times, const OdeTolerances &tolerances,
                       const std::function<void(const OdeState &)> &on_output, OdeStatistics *statistics) const
{
  if (times.empty())
    return;
  const double t_end = times.back();
  double scale = displacement_scale(t_end);
  if (!(scale > 0))
    scale = 1;
  const double atol = tolerances.absolute > 0 ? tolerances.absolute : 1e-3 * tolerances.relative * scale;

  SUNContext raw_context = nullptr;
  require(SUNContext_Create(nullptr, &raw_context), "SUNContext_Create");
  const Context context(raw_context);
  const Vector y(N_VNew_Serial(3, context.get())), absolute(N_VNew_Serial(3, context.get()));
  if (!y || !absolute)
    throw std::runtime_error("demvv bug: SUNDIALS could not allocate the ODE state");
  double start[3];
  initial_state(start);
  for (int i = 0; i < 3; ++i)
    NV_Ith_S(y.get(), i) = start[i];
  NV_Ith_S(absolute.get(), 0) = NV_Ith_S(absolute.get(), 1) = atol;
  NV_Ith_S(absolute.get(), 2) = chain_.maxwell_spring * atol;
  const Memory memory(CVodeCreate(CV_BDF, context.get()));
  const Matrix matrix(SUNDenseMatrix(3, 3, context.get()));
  const Solver solver(SUNLinSol_Dense(y.get(), matrix.get(), context.get()));
  if (!memory || !matrix || !solver)
    throw std::runtime_error("demvv bug: SUNDIALS could not allocate the ODE solver");

  UserData data{this, &chain_, control_, 0.0, {}};
  void *mem = memory.get();
  require(CVodeInit(mem, right_hand_side, 0.0, y.get()), "CVodeInit");
  require(CVodeSetUserData(mem, &data), "CVodeSetUserData");
  require(CVodeSetErrHandlerFn(mem, keep_error, &data), "CVodeSetErrHandlerFn");
  require(CVodeSVtolerances(mem, tolerances.relative, absolute.get()), "CVodeSVtolerances");
  require(CVodeSetLinearSolver(mem, solver.get(), matrix.get()), "CVodeSetLinearSolver");
  require(CVodeSetJacFn(mem, jacobian), "CVodeSetJacFn");
  require(CVodeSetMaxNumSteps(mem, tolerances.max_steps), "CVodeSetMaxNumSteps");

  // The history is smooth between its kinks: integrate one piece at a time.
  // CVODE may step past an output time (it interpolates back) but never
  // past the end of a piece, its stop time; there it restarts.  (SUNDIALS
  // 6.4 cannot clear a stop time, so after the last kink it is put beyond
  // any output.)
  const std::vector<double> kinks = history_.kinks();
  const auto piece_end = [&](double start)
  {
    const auto next = std::find_if(kinks.begin(), kinks.end(), [&](double kink) { return kink > start; });
    return next == kinks.end() ? std::numeric_limits<double>::infinity() : *next;
  };
  double end = piece_end(0);
  if (std::isfinite(end))
    require(CVodeSetStopTime(mem, end), "CVodeSetStopTime");
  OdeStatistics counted;
  counted.absolute_tolerance = atol;
  const auto integrate = [&](double tout, std::size_t k)
  {
    sunrealtype reached = 0;
    const int flag = CVode(mem, tout, y.get(), &reached, CV_NORMAL);
    if (flag < 0)
      throw NumericalFailure(reached, static_cast<long>(k),
                             "CVODE failed (" + std::string(CVodeGetReturnFlagName(flag)) + "): " + data.error);
    // A step that ends on the stop time returns the state there even when
    // tout lies before it: interpolate back to tout.
    if (reached != tout)
      require(CVodeGetDky(mem, tout, 0, y.get()), "CVodeGetDky");
  };
  const auto restart = [&]()
  {
    // y holds the state at `end`, where the derivative of the history
    // jumps: restart the BDF history (which resets CVODE's counters too).
    add_counters(mem, counted);
    data.piece_start = end;
    require(CVodeReInit(mem, end, y.get()), "CVodeReInit");
    ++counted.restarts;
    end = piece_end(end);
    require(CVodeSetStopTime(mem, std::isfinite(end) ? end : 2 * t_end + 1), "CVodeSetStopTime");
  };
  for (std::size_t k = 0; k < times.size(); ++k)
  {
    const double target = times[k];
    if (k > 0 && target < times[k - 1])
      throw std::invalid_argument("BurgersOde::solve: output times must be non-decreasing and >= 0");
    while (target > end)
    {
      // The output lies beyond this piece: get the state at its end (CVODE
      // may already have stepped there) and restart.
      sunrealtype internal = 0;
      CVodeGetCurrentTime(mem, &internal);
      if (internal >= end)
        require(CVodeGetDky(mem, end, 0, y.get()), "CVodeGetDky");
      else
        integrate(end, k);
      restart();
    }
    if (target > data.piece_start)
      integrate(target, k);
    const double state[3] = {NV_Ith_S(y.get(), 0), NV_Ith_S(y.get(), 1), NV_Ith_S(y.get(), 2)};
    const OdeState output = observe(target, state);
    if (!std::isfinite(output.force) || !std::isfinite(output.displacement))
      throw NumericalFailure(target, static_cast<long>(k), "the ODE solution is not finite");
    on_output(output);
  }

  if (statistics)
  {
    add_counters(mem, counted);
    *statistics = counted;
  }
}
} // namespace continuum
