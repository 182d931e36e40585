// Closed-form references for the continuum companion, built on the thesis's
// Burger's closed forms in dem/burgers_closed_form.h (eq. 7.18-7.19 and
// 2.15), which are not repeated here.  What is added follows from them by
// linearity and time invariance of the Burger's chain:
//   - the relaxation modulus Y(t) = (1/v) d f_v(t)/dt, the derivative of
//     eq. 7.18 (the thesis's eq. 7.16 in the lambda form):
//       Y(t) = [l1 (K0 + l2 C) e^{l1 t} - l2 (K0 + l1 C) e^{l2 t}] / (l1 - l2),
//     so Y(0) = K0; a displacement step u0 gives f = u0 Y(t);
//   - ramp-and-hold at rate v to t_r: f = f_v(t) - f_v(t - t_r) for t > t_r;
//   - u = A sin(w t): the hereditary integral (eq. 7.15)
//       f(t) = A w sum_i a_i (w sin wt - l_i cos wt + l_i e^{l_i t}) / (l_i^2 + w^2),
//     with Y(t) = sum_i a_i e^{l_i t}.
// Creep under a force step is eq. 2.15 itself.
#pragma once

#include "continuum/burgers_chain.h"
#include "continuum/burgers_ode.h"

#include "dem/burgers_closed_form.h"

#include <string>

namespace demvv
{
/// The thesis's constants (K0, C_inf, K1, C1) of a continuum chain.
dem::BurgersConstants burgers_constants(const continuum::BurgersChain &chain);

/// Whether a closed form exists for this control and history.
bool has_closed_form(continuum::Control control, const continuum::History &history);

/// The name of the closed form (for outputs), e.g. "eq. 7.18".
std::string closed_form_name(continuum::Control control, const continuum::History &history);

/// The closed-form response at time t: the force [N or Pa] under a
/// displacement history, the displacement [m or -] under a force step.
/// NaN where no closed form exists.
double closed_form(const continuum::BurgersChain &chain, continuum::Control control, const continuum::History &history,
                   double t);
} // namespace demvv
