// Bulk-level checks of the engine (V08, V09, V11).
#pragma once

#include "verify/checks/check.h"

namespace verify
{
CheckOutcome check_energy_audit(const CheckContext &ctx);
CheckOutcome check_chain_wave(const CheckContext &ctx);
CheckOutcome check_lattice_measurements(const CheckContext &ctx);
} // namespace verify
