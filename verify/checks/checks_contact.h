// Contact-level checks (V01, V02, V03, V05).
#pragma once

#include "verify/checks/check.h"

namespace demvv
{
CheckOutcome check_linear_impact(const CheckContext &ctx);
CheckOutcome check_bond_failure(const CheckContext &ctx);
CheckOutcome check_coulomb_slip(const CheckContext &ctx);
CheckOutcome check_free_flight(const CheckContext &ctx);
} // namespace demvv
