// Solution verification of DEM bulk results (thesis §6.3-6.4): how large
// the numerical and statistical uncertainty of a bonded uniaxial
// compression's peak stress is.  The time step (V26), the platen speed's
// quasi-static limit (V27) and the seed ensemble (V28), each run through the
// sweep engine.
#pragma once

#include "verify/checks/check.h"

namespace demvv
{
CheckOutcome check_time_step_safety(const CheckContext &ctx);
CheckOutcome check_loading_rate(const CheckContext &ctx);
CheckOutcome check_seed_ensemble(const CheckContext &ctx);
} // namespace demvv
