// The verification registry: one row per check (STYLE rule 2).  Each row
// says what demvv shall do, how the result is classified (thesis §2.5) and
// what it is measured against; the tolerances and their reasons sit with
// the metrics in checks_*.cpp.
#include "check.h"
#include "checks_contact.h"

namespace verify
{
const std::vector<Check> &check_registry()
{
  using C = Category;
  static const std::vector<Check> checks = {
    {"V01", "Linear normal impact",
     "demvv shall reproduce the duration, peak force and restitution of an undamped linear impact, ball-ball and "
     "ball-wall.",
     C::code_verification, 'C', "Chung & Ooi (2011) tests 1-2: t_c = pi sqrt(m*/K), F_max = v0 sqrt(m* K), e = 1",
     &check_linear_impact},
    {"V02", "Contact bond to failure",
     "demvv shall carry tension and shear on a contact bond with the linear law until the strength, break it "
     "there by the PFC3D rules, and never break it in compression.",
     C::code_verification, 'C', "thesis §3.4.2: F = K u until phi; forces zero (tension) or slip limit (shear)",
     &check_bond_failure},
    {"V03", "Coulomb slip",
     "demvv shall limit the shear force of an unbonded contact to mu F_n, and a locked block on an incline shall "
     "stick when tan(theta) <= mu and otherwise accelerate at g (sin - mu cos).",
     C::code_verification, 'A', "Coulomb friction; block on an incline", &check_coulomb_slip},
    {"V05", "Free flight",
     "demvv shall integrate free flight under gravity exactly (centred differences are exact for a constant "
     "force).",
     C::code_verification, 'A', "x(t) = x0 + v0 t + g t^2 / 2", &check_free_flight},
  };
  return checks;
}
} // namespace verify
