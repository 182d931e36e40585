#include "app/reference/continuum_reference.h"

#include <cmath>

namespace demvv
{
namespace
{
using continuum::Control;
using Shape = continuum::History::Shape;

constexpr double two_pi = 6.283185307179586476925;

/// The coefficients a_i of Y(t) = a1 e^{l1 t} + a2 e^{l2 t}.
void relaxation_coefficients(const dem::BurgersConstants &b, double &a1, double &a2)
{
  const double l1 = b.lambda1(), l2 = b.lambda2(), k0 = b.maxwell_stiffness, c = b.maxwell_viscosity;
  a1 = l1 * (k0 + l2 * c) / (l1 - l2);
  a2 = -l2 * (k0 + l1 * c) / (l1 - l2);
}

double relaxation_modulus(const dem::BurgersConstants &b, double t)
{
  double a1, a2;
  relaxation_coefficients(b, a1, a2);
  return a1 * std::exp(b.lambda1() * t) + a2 * std::exp(b.lambda2() * t);
}

double cyclic_force(const dem::BurgersConstants &b, double amplitude, double frequency, double t)
{
  const double w = two_pi * frequency;
  double a[2];
  relaxation_coefficients(b, a[0], a[1]);
  const double l[2] = {b.lambda1(), b.lambda2()};
  double f = 0;
  for (int i = 0; i < 2; ++i)
    f += a[i] * (w * std::sin(w * t) - l[i] * std::cos(w * t) + l[i] * std::exp(l[i] * t)) / (l[i] * l[i] + w * w);
  return amplitude * w * f;
}
} // namespace

dem::BurgersConstants burgers_constants(const continuum::BurgersChain &chain)
{
  return {chain.maxwell_spring, chain.maxwell_dashpot, chain.kelvin_spring, chain.kelvin_dashpot};
}

bool has_closed_form(Control control, const continuum::History &history)
{
  return history.shape != Shape::general && (control == Control::displacement || history.shape == Shape::step);
}

std::string closed_form_name(Control control, const continuum::History &history)
{
  if (control == Control::force)
    return history.shape == Shape::step ? "eq. 2.15 (creep)" : "none";
  switch (history.shape)
  {
  case Shape::constant_rate:
    return "eq. 7.18 (constant velocity)";
  case Shape::ramp_and_hold:
    return "eq. 7.18 superposed (ramp and hold)";
  case Shape::cyclic:
    return "eq. 7.15-7.16 hereditary integral of a sine";
  case Shape::step:
    return "eq. 7.16 relaxation modulus (displacement step)";
  case Shape::general:
    break;
  }
  return "none";
}

double closed_form(const continuum::BurgersChain &chain, Control control, const continuum::History &history, double t)
{
  const dem::BurgersConstants b = burgers_constants(chain);
  if (control == Control::force)
    return history.shape == Shape::step ? b.creep_displacement(t, history.level) : std::nan("");
  switch (history.shape)
  {
  case Shape::constant_rate:
    return b.constant_velocity_force(t, history.rate);
  case Shape::ramp_and_hold:
    return b.constant_velocity_force(t, history.rate) -
           (t > history.ramp_time ? b.constant_velocity_force(t - history.ramp_time, history.rate) : 0.0);
  case Shape::cyclic:
    return cyclic_force(b, history.amplitude, history.frequency, t);
  case Shape::step:
    return history.level * relaxation_modulus(b, t);
  case Shape::general:
    break;
  }
  return std::nan("");
}
} // namespace demvv
