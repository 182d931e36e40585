// Burger's contact checks (V14-V17).
#pragma once

#include "verify/checks/check.h"

namespace demvv
{
CheckOutcome check_burgers_update(const CheckContext &ctx);
CheckOutcome check_burgers_pull(const CheckContext &ctx);
CheckOutcome check_viscosity_scaling(const CheckContext &ctx);
CheckOutcome check_displacement_criterion(const CheckContext &ctx);
} // namespace demvv
