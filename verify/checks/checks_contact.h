// Contact-level checks (VERIFICATION.md items 1, 2, 3, 5).
#pragma once

#include "verify/checks/check.h"

namespace verify
{
CheckOutcome check_linear_impact(const CheckContext &ctx);
CheckOutcome check_bond_failure(const CheckContext &ctx);
CheckOutcome check_coulomb_slip(const CheckContext &ctx);
CheckOutcome check_free_flight(const CheckContext &ctx);
} // namespace verify
