// Bulk-level checks of the engine (V08, V09, V11) and the viscoelastic
// network identity on a prepared packing (V23).
#pragma once

#include "verify/checks/check.h"

namespace demvv
{
CheckOutcome check_energy_audit(const CheckContext &ctx);
CheckOutcome check_chain_wave(const CheckContext &ctx);
CheckOutcome check_lattice_measurements(const CheckContext &ctx);
CheckOutcome check_packing_identity(const CheckContext &ctx);
} // namespace demvv
