// Engine-level checks (V04, V06, V07, V10).
#pragma once

#include "verify/checks/check.h"

namespace demvv
{
CheckOutcome check_objectivity(const CheckContext &ctx);
CheckOutcome check_critical_step(const CheckContext &ctx);
CheckOutcome check_second_order(const CheckContext &ctx);
CheckOutcome check_neighbour_search(const CheckContext &ctx);
} // namespace demvv
