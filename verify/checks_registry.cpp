// The verification registry: one row per check (STYLE rule 2).  Each row
// says what demvv shall do, how the result is classified (thesis §2.5) and
// what it is measured against; the tolerances and their reasons sit with
// the metrics in checks_*.cpp.
#include "check.h"
#include "checks_bulk.h"
#include "checks_contact.h"
#include "checks_engine.h"

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
    {"V04", "Objectivity",
     "demvv shall not change contact forces under a rigid rotation of a loaded pair (about any axis), nor under a "
     "renumbering of the balls.",
     C::code_verification, 'B', "frame indifference; PFC3D shear-force rotation", &check_objectivity},
    {"V05", "Free flight",
     "demvv shall integrate free flight under gravity exactly (centred differences are exact for a constant "
     "force).",
     C::code_verification, 'A', "x(t) = x0 + v0 t + g t^2 / 2", &check_free_flight},
    {"V06", "Critical time step",
     "demvv shall be stable for omega dt <= 2 and unstable beyond, and its automatic step bound shall never "
     "exceed the exact stability limit of the assembly.",
     C::code_verification, 'A', "dt <= 2/omega_max, omega_max^2 = lambda_max(M^-1 K) (dense eigen-solve)",
     &check_critical_step},
    {"V07", "Second-order integrator",
     "demvv shall integrate translation and rotation with observed order 2 on smooth bonded oscillators.",
     C::code_verification, 'B', "harmonic oscillator u = (v0/omega) sin(omega t)", &check_second_order},
    {"V08", "Energy audit",
     "demvv shall account for all energy in a bulk run with damping, friction and bond breakage: boundary work = "
     "kinetic + strain + friction + damping + released bond energy, residual below 1 %.",
     C::code_verification, 'B', "energy conservation", &check_energy_audit},
    {"V09", "Wave in a bonded chain",
     "demvv shall propagate a velocity step along a bonded chain at the long-wave speed c0 = 2R sqrt(K/m) "
     "within 1 %.",
     C::code_verification, 'B', "discrete chain, long-wave limit", &check_chain_wave},
    {"V10", "Neighbour search",
     "demvv's cell list with skin shall find exactly the pairs a brute-force search finds, and no touching pair "
     "shall escape it while balls move less than half the skin.",
     C::code_verification, 'A', "O(N^2) brute force", &check_neighbour_search},
    {"V11", "Lattice porosity and coordination",
     "demvv's measurement spheres shall give the porosity (overlaps corrected, eq. 5.2-5.3) and coordination "
     "number (eq. 5.4) of simple cubic and FCC arrays.",
     C::code_verification, 'A', "1 - pi/6, 1 - pi/(3 sqrt 2), lens volumes; Z = 6, 12",
     &check_lattice_measurements},
  };
  return checks;
}
} // namespace verify
