// Calibration and validation against the thesis's laboratory laws
// (thesis ch. 4, eq. 4.3-4.4; §7.5.3, Table 7.4): the Table 7.4 model's bond
// strength calibrated at one condition (V24), its peak stress predicted at
// every other condition of Table 4.1 and compared with the law (V25).
#pragma once

#include "verify/checks/check.h"

namespace demvv
{
CheckOutcome check_table_7_4_calibration(const CheckContext &ctx);
CheckOutcome check_table_7_4_validation(const CheckContext &ctx);
} // namespace demvv
