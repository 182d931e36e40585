// A continuum computation that cannot go on: an ODE or linear solver that
// fails, or a non-finite result.  The caller keeps its outputs up to `time`
// and stops with exit code 3.
#pragma once

#include <stdexcept>
#include <string>

namespace continuum
{
class NumericalFailure : public std::runtime_error
{
public:
  NumericalFailure(double time, long step, const std::string &what) : std::runtime_error(what), time_(time), step_(step)
  {
  }
  double time() const { return time_; } ///< simulated time of the failure [s]
  long step() const { return step_; }   ///< time step (or ODE output) where it happened

private:
  double time_;
  long step_;
};
} // namespace continuum
