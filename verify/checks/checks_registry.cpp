// The verification registry: one row per check.  Each row says what demvv
// shall do, which family of checks it belongs to (the tag of its test), how
// the result is classified (thesis §2.5), which tolerance classes its
// metrics use, and what it is measured against; the tolerances and their
// reasons sit with the metrics in checks_*.cpp.  A new row is all it takes
// to add a check: its test and its catalogue entry follow from the row.
#include "verify/checks/check.h"
#include "verify/checks/checks_bulk.h"
#include "verify/checks/checks_burgers.h"
#include "verify/checks/checks_contact.h"
#include "verify/checks/checks_continuum.h"
#include "verify/checks/checks_engine.h"
#include "verify/checks/checks_solution.h"
#include "verify/checks/checks_validation.h"

namespace demvv
{
const std::vector<Check> &check_registry()
{
  using C = Category;
  using T = ToleranceClass;
  static const std::vector<Check> checks = {
    {"V01",
     "Linear normal impact",
     "contact",
     "demvv shall reproduce the duration, peak force and restitution of an undamped linear impact, ball-ball and "
     "ball-wall.",
     C::code_verification,
     {T::B, T::C},
     "Chung & Ooi (2011) tests 1-2: t_c = pi sqrt(m*/K), F_max = v0 sqrt(m* K), e = 1",
     &check_linear_impact},
    {"V02",
     "Contact bond to failure",
     "contact",
     "demvv shall carry tension and shear on a contact bond with the linear law until the strength, break it "
     "there by the PFC3D rules, and never break it in compression.",
     C::code_verification,
     {T::A, T::B, T::C},
     "thesis §3.4.2: F = K u until phi; forces zero (tension) or slip limit (shear)",
     &check_bond_failure},
    {"V03",
     "Coulomb slip",
     "contact",
     "demvv shall limit the shear force of an unbonded contact to mu F_n, and a locked block on an incline shall "
     "stick when tan(theta) <= mu and otherwise accelerate at g (sin - mu cos).",
     C::code_verification,
     {T::A, T::B, T::C},
     "Coulomb friction; block on an incline",
     &check_coulomb_slip},
    {"V04",
     "Objectivity",
     "engine",
     "demvv shall not change contact forces under a rigid rotation of a loaded pair (about any axis), nor under a "
     "renumbering of the balls.",
     C::code_verification,
     {T::A, T::B},
     "frame indifference; PFC3D shear-force rotation",
     &check_objectivity},
    {"V05",
     "Free flight",
     "engine",
     "demvv shall integrate free flight under gravity exactly (centred differences are exact for a constant "
     "force).",
     C::code_verification,
     {T::A},
     "x(t) = x0 + v0 t + g t^2 / 2",
     &check_free_flight},
    {"V06",
     "Critical time step",
     "engine",
     "demvv shall be stable for omega dt <= 2 and unstable beyond, and its automatic step bound shall never "
     "exceed the exact stability limit of the assembly.",
     C::code_verification,
     {T::A, T::B},
     "dt <= 2/omega_max, omega_max^2 = lambda_max(M^-1 K) (dense eigen-solve)",
     &check_critical_step},
    {"V07",
     "Second-order integrator",
     "engine",
     "demvv shall integrate translation and rotation with observed order 2 on smooth bonded oscillators.",
     C::code_verification,
     {T::B},
     "harmonic oscillator u = (v0/omega) sin(omega t)",
     &check_second_order},
    {"V08",
     "Energy audit",
     "bulk",
     "demvv shall account for all energy in a bulk run with damping, friction and bond breakage: boundary work = "
     "kinetic + strain + friction + damping + released bond energy, residual below 1 %.",
     C::code_verification,
     {T::B},
     "energy conservation",
     &check_energy_audit},
    {"V09",
     "Wave in a bonded chain",
     "bulk",
     "demvv shall propagate a velocity step along a bonded chain at the long-wave speed c0 = 2R sqrt(K/m) "
     "within 1 %.",
     C::code_verification,
     {T::B},
     "discrete chain, long-wave limit",
     &check_chain_wave},
    {"V10",
     "Neighbour search",
     "engine",
     "demvv's cell list with skin shall find exactly the pairs a brute-force search finds, and no touching pair "
     "shall escape it while balls move less than half the skin.",
     C::code_verification,
     {T::A},
     "O(N^2) brute force",
     &check_neighbour_search},
    {"V11",
     "Lattice porosity and coordination",
     "bulk",
     "demvv's measurement spheres shall give the porosity (overlaps corrected, eq. 5.2-5.3) and coordination "
     "number (eq. 5.4) of simple cubic and FCC arrays.",
     C::code_verification,
     {T::A, T::B},
     "1 - pi/6, 1 - pi/(3 sqrt 2), lens volumes; Z = 6, 12",
     &check_lattice_measurements},
    {"V12",
     "Burger's chain under prescribed displacement (SUNDIALS)",
     "continuum",
     "demvv shall integrate the Burger's chain of a contact or a material point with SUNDIALS CVODE to within 10 x "
     "the requested relative tolerance of its closed forms under constant-velocity, ramp-and-hold, cyclic and step "
     "displacements, with an error that tracks the tolerance from 1e-4 to 1e-12.",
     C::code_verification,
     {T::B},
     "thesis eq. 7.18-7.19; by linearity its superposition (ramp and hold) and hereditary integral (eq. 7.15-7.16)",
     &check_burgers_ode_histories},
    {"V13",
     "Burger's creep (SUNDIALS)",
     "continuum",
     "demvv shall reproduce the creep of a Burger's contact under a constant force, and of a material point under a "
     "constant stress, within 10 x the requested relative tolerance.",
     C::code_verification,
     {T::B},
     "thesis eq. 2.15: u = F [1/K0 + t/C_inf + (1 - exp(-t K1/C1))/K1]",
     &check_burgers_creep},
    {"V14",
     "Burger's contact update (Crank-Nicolson)",
     "burgers",
     "demvv's Burger's contact law shall converge to the constant-velocity closed form with observed order 2, and "
     "show its documented stiff-limit behaviour (A-stable, not L-stable) when K_k dt / (2 C_k) > 1.",
     C::code_verification,
     {T::A, T::B},
     "thesis eq. 3.25-3.35 against eq. 7.18-7.19",
     &check_burgers_update},
    {"V15",
     "Two-ball Burger's pull",
     "burgers",
     "demvv shall pull two balls joined by a Burger's contact apart at constant velocity with the force of the "
     "closed form.",
     C::code_verification,
     {T::B},
     "thesis eq. 7.18-7.19, Fig. 7.10",
     &check_burgers_pull},
    {"V16",
     "Viscosity scaling",
     "burgers",
     "demvv shall give the unscaled force-displacement curve when the velocity is multiplied and both viscosities "
     "divided by the same factor, not when C_inf alone is divided, and shall evaluate rate-dependent bond strength "
     "at the physical rate.",
     C::code_verification,
     {T::A, T::B},
     "thesis eq. 7.21, Fig. 7.8-7.10, eq. 7.23",
     &check_viscosity_scaling},
    {"V17",
     "Displacement criterion",
     "burgers",
     "demvv shall break a bonded Burger's contact when the centre distance has grown by delta_c, whatever the "
     "velocity, with the peak force of the closed form at u = delta_c.",
     C::code_verification,
     {T::C},
     "thesis appendix A, Fig. A.1; eq. 7.18 at t = delta_c / v",
     &check_displacement_criterion},
    {"V18",
     "Affine moduli of a packing",
     "continuum",
     "demvv shall compute the affine (Voigt) bulk and shear moduli and Poisson's ratio of an isotropic monodisperse "
     "packing, and the same-shape Burger's solid of Burger's contacts, exactly as an affine strain imposed on "
     "isotropically oriented contacts gives them.",
     C::code_verification,
     {T::A},
     "K = phi Z kn/(6 pi R), G = phi Z (2 kn + 3 ks)/(20 pi R), nu = (kn - ks)/(4 kn + ks); contact sums over "
     "spherical 5-designs",
     &check_affine_moduli},
    {"V19",
     "Viscoelastic network identity (continuum part)",
     "continuum",
     "demvv shall turn same-shape Burger's contact constants into a continuum Burger's solid, a priori (affine) or "
     "calibrated from an elastic DEM run's E and nu, whose stress between frictionless platens is (E/k_n) f_B(t) and "
     "whose radial strain is -nu times the axial strain.",
     C::code_verification,
     {T::A, T::B},
     "correspondence principle; f_B = thesis eq. 7.18 for one contact",
     &check_network_identity},
    {"V20",
     "Frictionless cylinder (patch test)",
     "continuum",
     "demvv's viscoelastic cylinder between frictionless platens shall reproduce the homogeneous response on every "
     "mesh, axisymmetric and 3D, to solver tolerance, and converge to the 1-D closed form with order 2 in the time "
     "step.",
     C::code_verification,
     {T::A, T::B},
     "material-point recursion of the same scheme; eq. 7.18 with the solid's uniaxial chain",
     &check_frictionless_cylinder},
    {"V21",
     "Manufactured solutions",
     "continuum",
     "demvv's viscoelastic cylinder shall converge to manufactured solutions at the theoretical rates: h^(p+1) in L2 "
     "and h^p in H1 and stress for Q_p elements, dt^2 in time.",
     C::code_verification,
     {T::A, T::B},
     "method of manufactured solutions (Roache 2002; Salari & Knupp 2000)",
     &check_manufactured_solutions},
    {"V22",
     "Bonded cylinder: grid convergence index",
     "continuum",
     "demvv shall estimate the discretisation uncertainty of the bonded-platen cylinder's peak stress and stress at "
     "1 % strain by Roache's grid convergence index, converging monotonically in the asymptotic range with a GCI "
     "below 1 % on the finest mesh.",
     C::solution_verification,
     {T::B},
     "Roache's GCI, Celik et al. (2008) J. Fluids Eng. 130:078001",
     &check_bonded_gci},
    {"V23",
     "Viscoelastic network identity on a packing (DEM part)",
     "bulk",
     "demvv's DEM bulk stress on a prepared packing with same-shape Burger's contacts, unbreakable bonds, no slip "
     "and frictionless platens shall follow the calibrated continuum (E/K_m times the contact chain) within 5 % "
     "under constant-rate, creep, relaxation and cyclic loading at a quasi-static rate; with modified Burger's "
     "contacts, outside the identity, the two shall part visibly (model form; bonded platens are reported).",
     C::model_comparison,
     {T::B},
     "correspondence principle: a linear viscoelastic network of same-shape contacts is (E/K_m) x one contact "
     "chain; the 1000-ball sample (--quick), the 6000-ball sample (--full)",
     &check_packing_identity},
    {"V24",
     "Calibration of the Table 7.4 model at one condition",
     "bulk",
     "demvv shall fit the bond strength of the thesis's Table 7.4 viscoelastic model (not given there) to the "
     "experiments' peak stress at 10 C and 0.1 1/s, from a start far off, within the seed ensemble's standard "
     "error, and state the fitted value's standard error.",
     C::calibration,
     {T::D},
     "thesis eq. 4.4: 10.3 MPa at 10 C, 0.1 1/s (law fitted to the tests of Table 4.1); GSL nonlinear least "
     "squares over seeds (demvv calibrate); a 54-ball lattice (--quick), the 1000-ball sample (--full)",
     &check_table_7_4_calibration},
    {"V25",
     "Validation of the Table 7.4 model against the rate-temperature law",
     "bulk",
     "demvv shall predict, with the bond strength calibrated at 10 C and 0.1 1/s and never refitted, the peak "
     "stress at the other conditions of Table 4.1 within 2 u_val of the experiments' law, with the strengths and "
     "stiffnesses scaled as the thesis does (slope built in) and with the viscosities alone (slope predicted), "
     "u_val holding the four parts of ASME V&V 20, and validate the strain at peak (rate-independent) and the "
     "initial modulus (exponent 0.29), which the calibration did not set.",
     C::validation,
     {T::D},
     "thesis eq. 4.3-4.4 (law of the tests, n = 0.29, k = 13.4e3 K), assumed 10 % standard uncertainty; "
     "validation comparison error E = S - D against u_val = sqrt(u_num^2 + u_input^2 + u_D^2 + u_S^2) (ASME V&V "
     "20); a 54-ball lattice (--quick), the 1000-ball sample (--full)",
     &check_table_7_4_validation},
    {"V26",
     "Time step of a bulk compression",
     "bulk",
     "demvv shall change a bonded uniaxial compression's stress at a fixed early strain by less than one step's "
     "worth, and its peak stress by less than half the seed ensemble's relative standard deviation, in the mean of "
     "ten paired seeds, when the time step safety factor is halved from 0.8 to 0.4 and to 0.2; the 95 % bound "
     "U_num on the time-step error of the default 0.8 shall stay within one step's worth and half the ensemble's "
     "95 % half-width of one run.",
     C::solution_verification,
     {T::C, T::D},
     "paired seed ensembles with common random numbers (the demvv time-step study); Roache's factor of safety for "
     "the finest level (Celik et al. 2008, J. Fluids Eng. 130:078001); the seed ensemble of V28; a 54-ball lattice "
     "(--quick), the 1000-ball sample (--full)",
     &check_time_step_safety},
    {"V27",
     "Loading rate of a bulk compression (quasi-static limit)",
     "bulk",
     "demvv shall change a bonded uniaxial compression's peak stress by less than half the seed ensemble's relative "
     "standard deviation, and its stress at a fixed early strain by less than 1e-3 with a change that shrinks, "
     "when the platen speed is halved from 0.02 m/s to 0.01 m/s and to 0.005 m/s.",
     C::solution_verification,
     {T::B, T::D},
     "thesis §6.3, Fig. 6.4: the peak converged at 0.01 m/s and below; the seed ensemble of V28; a 54-ball lattice "
     "(--quick), the 1000-ball sample (--full)",
     &check_loading_rate},
    {"V28",
     "Seed ensemble of a bulk compression",
     "bulk",
     "demvv shall quote a bonded uniaxial compression's peak stress as the mean over ten seeds with a 95 % "
     "half-width below 10 % of it, every seed's run shall pass its peak, and two disjoint sets of five seeds shall "
     "agree within twice their combined standard error.",
     C::solution_verification,
     {T::D},
     "Student-t confidence interval over independent samples; a 54-ball lattice with random bond strengths "
     "(--quick), ten prepared 1000-ball samples (--full)",
     &check_seed_ensemble},
  };
  return checks;
}
} // namespace demvv
