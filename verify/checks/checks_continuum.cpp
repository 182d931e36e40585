// Code and solution verification of the continuum companion
// (V12, V13, V18-V22).  Every reference is a closed form
// (dem/burgers_closed_form.h and what follows from it by linearity,
// continuum_reference.h), an independent computation (the material-point
// recursion, a discrete affine sum over contact normals, a DEM run), or an
// observed order of convergence.
#include "verify/checks/checks_continuum.h"

#include "app/io/output.h"
#include "app/kinds/continuum_cylinder.h"
#include "app/kinds/continuum_mms.h"
#include "app/kinds/continuum_ode.h"
#include "app/kinds/uniaxial.h"
#include "app/reference/continuum_reference.h"
#include "verify/checks/checks_support.h"

#include "continuum/material_point.h"

#include <cmath>
#include <filesystem>
#include <limits>

#include <omp.h>
#include <unistd.h>

namespace demvv
{
namespace
{
constexpr double pi = 3.14159265358979323846;

OdeResult ode_case(const CheckContext &ctx, const std::string &name, const std::vector<std::string> &overrides)
{
  OdeResult r = run_burgers_ode(load_case(ctx, name, overrides), run_options(ctx));
  if (r.status.fault)
    throw std::runtime_error(name + ": " + r.status.diagnostic());
  return r;
}

CylinderResult cylinder_case(const CheckContext &ctx, const std::string &name,
                             const std::vector<std::string> &overrides)
{
  CylinderResult r = run_cylinder(load_case(ctx, name, overrides), run_options(ctx));
  if (r.status.fault)
    throw std::runtime_error(name + ": " + r.status.diagnostic());
  if (r.series.rows() < 2)
    throw std::runtime_error(name + ": the run produced no steps");
  return r;
}

std::string setting(const std::string &key, double value) { return key + "=" + num(value); }

// An affine displacement is exact in every Q_p mesh (isoparametric
// mapping), so the only error left is the CG solver's: relative residual
// 1e-12, amplified at most by the condition number, below 1e3 on meshes of
// a few hundred cells.
const char *patch_reason = "patch test: the affine solution is exact in every mesh; CG stops at a relative residual "
                           "of 1e-12 and the condition number is below 1e3";

// Tolerance of an ODE against its closed form (V12, V13): CVODE
// controls the local error of each step to rtol; for these stable,
// dissipative linear systems the global error stays a small multiple of it.
const char *ode_reason = "the requirement: SUNDIALS vs closed form <= 10 rtol (CVODE bounds the local error "
                         "per step by rtol; the global error of a dissipative linear system is a small multiple)";
} // namespace

// @sect3{V12: Burger's chain under prescribed displacement histories}

CheckOutcome check_burgers_ode_histories(const CheckContext &ctx)
{
  CheckOutcome out;
  const std::string name = "c01_burgers_ode_constant_velocity";
  const double rtol = load_case(ctx, name).real("solver/relative tolerance");
  struct Variant
  {
    const char *label;
    std::vector<std::string> overrides;
  };
  const Variant variants[] = {
    {"contact, constant velocity, vs eq. 7.18", {}},
    {"contact, ramp to 2 s and hold, vs eq. 7.18 superposed", {"loading/history=ramp and hold"}},
    {"contact, cyclic 0.1 m at 1 Hz, vs the hereditary integral", {"loading/history=cyclic"}},
    {"contact, displacement step 0.1 m, vs the relaxation modulus", {"loading/history=step", "loading/level=0.1"}},
    {"material point, strain rate 0.005 /s, vs eq. 7.18 in Pa",
     {"chain/scale=material point", "chain/maxwell spring=1e9", "chain/maxwell dashpot=2e9", "chain/kelvin spring=5e8",
      "chain/kelvin dashpot=5e8", "loading/rate=0.005"}},
  };
  for (const Variant &v : variants)
    out.metrics.push_back(bound(std::string(v.label) + ": max |f - f_closed| / max |f_closed|",
                                ode_case(ctx, name, v.overrides).relative_error, 10 * rtol, false, ToleranceClass::B,
                                ode_reason));

  // Work-precision: the error must follow the tolerance over eight decades.
  const char *histories[] = {"constant rate", "ramp and hold", "cyclic"};
  for (const char *history :
       ctx.quick ? std::vector<const char *>{histories[0]} : std::vector<const char *>{histories, histories + 3})
  {
    ConvergenceTable t;
    t.title = std::string("work-precision, ") + history + ": CVODE against its closed form";
    t.h_name = "rtol";
    t.error_name = "max |f - f_closed| / max |f_closed|";
    t.expected_order = 1;
    double lowest = inf, highest = 0;
    for (int k = 4; k <= 12; ++k)
    {
      const double tol = std::pow(10.0, -k);
      const double e =
        ode_case(ctx, name, {std::string("loading/history=") + history, setting("solver/relative tolerance", tol)})
          .relative_error;
      t.add(tol, e);
      lowest = std::min(lowest, e / tol);
      highest = std::max(highest, e / tol);
    }
    out.tables.push_back(t);
    if (std::string(history) == "constant rate")
    {
      out.metrics.push_back(bound("constant velocity, rtol = 1e-4 ... 1e-12: largest error / rtol", highest, 10, false,
                                  ToleranceClass::B, ode_reason));
      out.metrics.push_back(bound("constant velocity, rtol = 1e-4 ... 1e-12: smallest error / rtol", lowest, 0.1, true,
                                  ToleranceClass::B,
                                  "the error tracks the tolerance: never ten times below it either, so a tighter "
                                  "rtol buys accuracy in proportion (no round-off floor, no wasted work)"));
    }
    else
      out.notes.push_back(std::string(history) + ": error / rtol between " + num(lowest) + " and " + num(highest) +
                          " over rtol = 1e-4 ... 1e-12 (reported, not checked: the work-precision metrics "
                          "are asserted for constant velocity)");
  }
  return out;
}

// @sect3{V13: creep}

CheckOutcome check_burgers_creep(const CheckContext &ctx)
{
  CheckOutcome out;
  const std::string name = "c02_burgers_ode_creep";
  const double rtol = load_case(ctx, name).real("solver/relative tolerance");
  out.metrics.push_back(bound("contact, force step 1 MN: max |u - u_2.15| / max |u_2.15|",
                              ode_case(ctx, name, {}).relative_error, 10 * rtol, false, ToleranceClass::B, ode_reason));
  out.metrics.push_back(
    bound("material point, stress step 1 MPa: max |eps - eps_2.15| / max |eps_2.15|",
          ode_case(ctx, name,
                   {"chain/scale=material point", "chain/maxwell spring=1e9", "chain/maxwell dashpot=2e9",
                    "chain/kelvin spring=5e8", "chain/kelvin dashpot=5e8"})
            .relative_error,
          10 * rtol, false, ToleranceClass::B, ode_reason));
  ConvergenceTable t;
  t.title = "work-precision, creep: CVODE against eq. 2.15";
  t.h_name = "rtol";
  t.error_name = "max |u - u_2.15| / max |u_2.15|";
  t.expected_order = 1;
  double highest = 0;
  for (int k = 4; k <= 12; k += ctx.quick ? 2 : 1)
  {
    const double tol = std::pow(10.0, -k);
    const double e = ode_case(ctx, name, {setting("solver/relative tolerance", tol)}).relative_error;
    t.add(tol, e);
    highest = std::max(highest, e / tol);
  }
  out.tables.push_back(t);
  out.metrics.push_back(
    bound("creep, rtol = 1e-4 ... 1e-12: largest error / rtol", highest, 10, false, ToleranceClass::B, ode_reason));
  return out;
}

// @sect3{V18: affine moduli}

std::vector<std::array<double, 3>> icosahedron_normals()
{
  const double g = (1 + std::sqrt(5.0)) / 2, s = 1 / std::sqrt(1 + g * g);
  std::vector<std::array<double, 3>> n;
  for (const double a : {-1.0, 1.0})
    for (const double b : {-g, g})
    {
      n.push_back({{0, a * s, b * s}});
      n.push_back({{a * s, b * s, 0}});
      n.push_back({{b * s, 0, a * s}});
    }
  return n;
}

std::vector<std::array<double, 3>> dodecahedron_normals()
{
  const double g = (1 + std::sqrt(5.0)) / 2, s = 1 / std::sqrt(3.0);
  std::vector<std::array<double, 3>> n;
  for (const double a : {-1.0, 1.0})
    for (const double b : {-1.0, 1.0})
    {
      for (const double c : {-1.0, 1.0})
        n.push_back({{a * s, b * s, c * s}});
      n.push_back({{0, a * s / g, b * s * g}});
      n.push_back({{a * s / g, b * s * g, 0}});
      n.push_back({{b * s * g, 0, a * s / g}});
    }
  return n;
}

continuum::ElasticModuli discrete_affine_moduli(const std::vector<std::array<double, 3>> &normals,
                                                const continuum::PackingGeometry &packing, double normal_stiffness,
                                                double shear_stiffness)
{
  using Matrix = std::array<std::array<double, 3>, 3>;
  // Contacts per unit volume: N Z / 2 with N = phi V / (4/3 pi R^3).
  const double R = packing.radius;
  const double density = packing.solid_fraction * packing.coordination / (2 * 4.0 / 3.0 * pi * R * R * R);
  const auto stress = [&](const Matrix &strain)
  {
    Matrix sigma{};
    for (const auto &n : normals)
    {
      double delta[3] = {0, 0, 0}, along = 0;
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
          delta[i] += strain[i][j] * 2 * R * n[j];
      for (int i = 0; i < 3; ++i)
        along += delta[i] * n[i];
      for (int i = 0; i < 3; ++i)
      {
        const double force = normal_stiffness * along * n[i] + shear_stiffness * (delta[i] - along * n[i]);
        for (int j = 0; j < 3; ++j)
          sigma[i][j] += density / normals.size() * force * 2 * R * n[j];
      }
    }
    return sigma;
  };
  const double e = 1e-3;
  const Matrix isotropic = {{{{e, 0, 0}}, {{0, e, 0}}, {{0, 0, e}}}};
  const Matrix shear = {{{{0, e / 2, 0}}, {{e / 2, 0, 0}}, {{0, 0, 0}}}};
  const Matrix p = stress(isotropic), s = stress(shear);
  continuum::ElasticModuli m;
  m.bulk = (p[0][0] + p[1][1] + p[2][2]) / 3 / (3 * e);
  m.shear = s[0][1] / e;
  m.young = 9 * m.bulk * m.shear / (3 * m.bulk + m.shear);
  m.poisson = (3 * m.bulk - 2 * m.shear) / (2 * (3 * m.bulk + m.shear));
  return m;
}

CheckOutcome check_affine_moduli(const CheckContext & /*ctx*/)
{
  CheckOutcome out;
  const continuum::PackingGeometry packing{5.8, 0.635, 0.885e-3}; // thesis ch. 5
  const double kn = 6e6;
  // Sums of 12 or 20 terms of similar size: round-off ~1e-15; 1e-12 leaves
  // a margin of a thousand (class A).
  const char *reason = "the normals form a spherical 5-design, so the orientation average is exact; the "
                       "difference is round-off of a 20-term sum (~1e-15)";
  for (const double ks : {0.0, 0.1 * kn, kn})
    for (const auto &[label, normals] :
         {std::pair<const char *, std::vector<std::array<double, 3>>>{"icosahedron", icosahedron_normals()},
          {"dodecahedron", dodecahedron_normals()}})
    {
      const continuum::ElasticModuli exact = continuum::affine_moduli(packing, kn, ks);
      const continuum::ElasticModuli sum = discrete_affine_moduli(normals, packing, kn, ks);
      const std::string tag = std::string(label) + ", ks/kn = " + num(ks / kn) + ": ";
      out.metrics.push_back(
        relative_error(tag + "K = phi Z kn / (6 pi R)", exact.bulk, sum.bulk, 1e-12, ToleranceClass::A, reason));
      out.metrics.push_back(relative_error(tag + "G = phi Z (2 kn + 3 ks) / (20 pi R)", exact.shear, sum.shear, 1e-12,
                                           ToleranceClass::A, reason));
      out.metrics.push_back(absolute_error(tag + "nu = (kn - ks) / (4 kn + ks)", exact.poisson, sum.poisson, 1e-12,
                                           ToleranceClass::A, reason));
    }
  {
    std::vector<double> ratio, closed, fine, icosahedron, dodecahedron;
    for (int k = 0; k <= 50; ++k)
    {
      fine.push_back(k / 50.0);
      closed.push_back(continuum::affine_moduli(packing, kn, fine.back() * kn).poisson);
    }
    for (const double r : {0.0, 0.1, 0.25, 0.5, 0.75, 1.0})
    {
      ratio.push_back(r);
      icosahedron.push_back(discrete_affine_moduli(icosahedron_normals(), packing, kn, r * kn).poisson);
      dodecahedron.push_back(discrete_affine_moduli(dodecahedron_normals(), packing, kn, r * kn).poisson);
    }
    Figure f =
      make_figure("affine_poisson", "Affine Poisson's ratio against the contacts' stiffness ratio", "k_s / k_n [-]",
                  "Poisson's ratio [-]",
                  {curve("sum over the icosahedron's vertices", ratio, icosahedron, CurveStyle::points),
                   curve("sum over the dodecahedron's vertices (open)", ratio, dodecahedron, CurveStyle::points),
                   curve("closed form (k_n - k_s) / (4 k_n + k_s)", fine, closed, CurveStyle::dashed)},
                  "The orientation average of the closed forms against exact sums over two sets of contact normals; "
                  "Poisson's ratio depends on the stiffness ratio alone (1/4 for frictionless, 0 at k_s = k_n).");
    f.curves[1].point_type = 6; // an open circle around the icosahedron's filled one
    f.x_margins = true;
    out.figures.push_back(std::move(f));
  }
  // Same-shape Burger's contacts: every spring and dashpot of the solid's
  // Young chain is the affine E of contacts with that constant (normal) and
  // r times it (shear).
  const continuum::BurgersChain contact{5.5e6, 6e4, 5.5e6, 6e4};
  const double r = 0.1;
  const continuum::BurgersSolid solid = continuum::affine_burgers_solid(contact, r, packing);
  const auto icosahedron = icosahedron_normals();
  const auto young = [&](double k) { return discrete_affine_moduli(icosahedron, packing, k, r * k).young; };
  out.metrics.push_back(relative_error("same shape: Maxwell spring E0 = E_affine(K_m, r K_m)",
                                       solid.young.maxwell_spring, young(contact.maxwell_spring), 1e-12,
                                       ToleranceClass::A, reason));
  out.metrics.push_back(relative_error("same shape: Maxwell dashpot = E_affine(C_m, r C_m)",
                                       solid.young.maxwell_dashpot, young(contact.maxwell_dashpot), 1e-12,
                                       ToleranceClass::A, reason));
  out.metrics.push_back(relative_error("same shape: Kelvin spring E1 = E_affine(K_k, r K_k)", solid.young.kelvin_spring,
                                       young(contact.kelvin_spring), 1e-12, ToleranceClass::A, reason));
  out.metrics.push_back(relative_error("same shape: Kelvin dashpot = E_affine(C_k, r C_k)", solid.young.kelvin_dashpot,
                                       young(contact.kelvin_dashpot), 1e-12, ToleranceClass::A, reason));
  out.metrics.push_back(absolute_error("same shape: nu = (1 - r)/(4 + r)", solid.poisson,
                                       discrete_affine_moduli(icosahedron, packing, 1, r).poisson, 1e-12,
                                       ToleranceClass::A, reason));
  out.notes.push_back("code part only: the affine formulas against exact sums over contact normals. An affine strain "
                      "imposed on a frozen prepared packing (its own Z, phi and fabric) and the non-affine gap after "
                      "relaxation are not part of this check.");
  return out;
}

// @sect3{V19: viscoelastic network identity, continuum part}

CheckOutcome check_network_identity(const CheckContext &ctx)
{
  CheckOutcome out;
  // The calibrated route reads E and nu from a real elastic DEM run.  Its
  // 196 balls gain nothing from threads, and OpenMP threads competing for
  // busy cores slow it down many times: one thread, then the caller's count.
  const int threads = omp_get_max_threads();
  const UniaxialResult dem = run_uniaxial(load_case(ctx, "c07_dem_elastic_calibration"), {"", 1, false});
  omp_set_num_threads(threads);
  if (dem.status.fault)
    throw std::runtime_error("c07_dem_elastic_calibration: " + dem.status.diagnostic());
  const std::string dir = (std::filesystem::temp_directory_path() / ("demvv_v19_" + std::to_string(getpid()))).string();
  make_directories(dir);
  write_atomically(dir + "/summary.json", json_text(dem.summary, 2));
  const double young = dem.summary["initial_modulus_pa"].get<double>();
  const double poisson = dem.summary["poisson_ratio"].get<double>();

  struct Route
  {
    const char *label;
    const char *deck;
    std::vector<std::string> overrides;
  };
  const Route routes[] = {{"calibrated (E, nu of c07's summary.json)",
                           "c08_cylinder_calibrated",
                           {"material/calibrated/summary file=" + dir + "/summary.json"}},
                          {"affine (Z 5.8, phi 0.635)", "c09_cylinder_affine", {}}};
  for (const Route &route : routes)
  {
    const Deck deck = load_case(ctx, route.deck, route.overrides);
    const continuum::BurgersChain contact{
      deck.real("material/contact/maxwell stiffness"), deck.real("material/contact/maxwell viscosity"),
      deck.real("material/contact/kelvin stiffness"), deck.real("material/contact/kelvin viscosity")};
    const double r = deck.real("material/contact/shear ratio");
    // c = E / k_n, by the route's own measurement: the DEM run, or the
    // affine sum over contact normals (V18) with k_n = 1, k_s = r.
    const bool calibrated = std::string(route.deck) == "c08_cylinder_calibrated";
    const continuum::ElasticModuli unit = discrete_affine_moduli(icosahedron_normals(),
                                                                 {deck.real("material/affine/coordination number"),
                                                                  deck.real("material/affine/solid fraction"),
                                                                  deck.real("material/affine/particle radius")},
                                                                 1, r);
    const double c = calibrated ? young / deck.real("material/calibrated/reference normal stiffness") : unit.young;
    const double nu = calibrated ? poisson : unit.poisson;
    const double rate = deck.real("loading/strain rate");
    const long steps = deck.integer("discretisation/time steps");

    ConvergenceTable t;
    t.title = std::string(route.label) + ": continuum stress against c f_B(t)";
    t.h_name = "dt [s]";
    t.error_name = "max |sigma - c f_B| / max |c f_B|";
    t.expected_order = 2;
    double production = std::nan(""), radial = std::nan("");
    for (const long n : {steps, 2 * steps, 4 * steps, 8 * steps})
    {
      std::vector<std::string> o = route.overrides;
      o.push_back("discretisation/time steps=" + std::to_string(n));
      const CylinderResult run = cylinder_case(ctx, route.deck, o);
      const auto time = run.series.column("time_s"), eps = run.series.column("axial_strain");
      std::vector<double> reference, lateral;
      for (std::size_t k = 0; k < time.size(); ++k)
      {
        reference.push_back(c * burgers_constants(contact).constant_velocity_force(time[k], rate));
        lateral.push_back(-nu * eps[k]);
      }
      t.add(run.mesh.time_step, relative_deviation(run.series.column("axial_stress_pa"), reference));
      if (n == steps)
      {
        production = t.rows.back().error;
        radial = relative_deviation(run.series.column("radial_strain"), lateral);
      }
    }
    const double tau = std::min(contact.kelvin_time(), contact.maxwell_dashpot / contact.maxwell_spring);
    const double dt = t.rows.front().h;
    // Trapezoidal error of a mode e^{-t/tau} after its decay: ~ (dt/tau)^2 / 12
    // relative; ten times that bounds the sum over the chain's two modes.
    const double bound_estimate = 10 * (dt / tau) * (dt / tau) / 12;
    out.metrics.push_back(
      bound(std::string(route.label) + ": max |sigma - c f_B| / max |c f_B| at the deck's step", production,
            bound_estimate, false, ToleranceClass::B,
            "trapezoidal time error ~ (dt/tau)^2/12 for the shortest contact time tau = " + num(tau) + " s, times 10"));
    out.metrics.push_back(
      bound(std::string(route.label) + ": largest |observed order in dt - 2| over the finest "
                                       "three steps",
            t.largest_order_deviation(2), 0.1, false, ToleranceClass::B,
            "the trapezoidal update is second order (within 0.1 at each of the two finest halvings)"));
    // With one shape in shear and bulk the scheme keeps eps_r = -nu eps_a
    // exactly; what is left is the CG solver's residual (1e-12).
    out.metrics.push_back(bound(std::string(route.label) + ": max |eps_r + nu eps_a| / max |nu eps_a|", radial, 1e-9,
                                false, ToleranceClass::A,
                                "same-shape solid: lateral ratio exact in the scheme; solver tolerance 1e-12 times a "
                                "condition number below 1e3"));
    out.tables.push_back(t);
    out.notes.push_back(std::string(route.label) + ": c = E/k_n = " + num(c) + " 1/m, nu = " + num(nu));
  }
  std::filesystem::remove_all(dir);
  out.notes.push_back("elastic DEM run c07: E = " + num(young) + " Pa, nu = " + num(poisson) +
                      "; this check covers the continuum side of the identity only: a DEM packing of Burger's contacts "
                      "under the same loading is not part of it");
  return out;
}

// @sect3{V20: frictionless platens}

namespace
{
/// Largest relative difference of stress and radial strain between a cylinder run and the material point.
void compare_with_point(const CylinderResult &run, const continuum::UniaxialResponse &point, double &stress,
                        double &radial)
{
  stress = relative_deviation(run.series.column("axial_stress_pa"), point.axial_stress);
  radial = relative_deviation(run.series.column("radial_strain"), point.radial_strain);
}
} // namespace

CheckOutcome check_frictionless_cylinder(const CheckContext &ctx)
{
  CheckOutcome out;
  const std::string name = "c03_cylinder_frictionless";
  const continuum::CylinderSpec spec = parse_cylinder(load_case(ctx, name)).test;
  const double dt = spec.final_strain / spec.strain_rate / spec.time_steps;
  const continuum::UniaxialResponse point =
    continuum::uniaxial_material_point(spec.solid, spec.strain_rate, dt, spec.time_steps);

  const unsigned int first = ctx.quick ? 0 : 1;
  for (unsigned int level = first; level < first + 3; ++level)
  {
    const CylinderResult run = cylinder_case(ctx, name, {"discretisation/refinements=" + std::to_string(level)});
    double stress = 0, radial = 0;
    compare_with_point(run, point, stress, radial);
    const std::string mesh = std::to_string(run.mesh.cells) + " cells";
    out.metrics.push_back(bound(mesh + ": max |sigma - sigma_point| / max sigma_point", stress, 1e-9, false,
                                ToleranceClass::A, patch_reason));
    out.metrics.push_back(bound(mesh + ": max |eps_r - eps_r,point| / max |eps_r,point|", radial, 1e-9, false,
                                ToleranceClass::A, patch_reason));
  }

  // The 3D quarter cylinder: the same solution, its force on its own
  // (mapped) platen area; the nominal stress differs by the area error.
  const CylinderResult flat = cylinder_case(ctx, name, {"discretisation/refinements=0"});
  const CylinderResult solid = cylinder_case(ctx, name, {"discretisation/refinements=0", "discretisation/model=3d"});
  const double area_ratio = solid.mesh.platen_area / solid.mesh.mesh_platen_area;
  std::vector<double> own_area = solid.series.column("axial_stress_pa");
  for (double &s : own_area)
    s *= area_ratio;
  out.metrics.push_back(bound(
    "3D quarter (" + std::to_string(solid.mesh.cells) + " cells) vs axisymmetric: stress on the mesh's platen area",
    relative_deviation(own_area, flat.series.column("axial_stress_pa")), 1e-9, false, ToleranceClass::A, patch_reason));
  out.metrics.push_back(
    bound("3D quarter vs axisymmetric: radial strain",
          relative_deviation(solid.series.column("radial_strain"), flat.series.column("radial_strain")), 1e-9, false,
          ToleranceClass::A, patch_reason));
  out.notes.push_back("3D quarter: mapped platen area / pi R^2 = " + num(1 / area_ratio) +
                      " (Q2 mapping of the circle); the nominal stresses differ by that factor");

  // Time: the distance to the closed form is the trapezoidal rule's error.
  for (const char *model : {"same shape", "deviatoric"})
  {
    ConvergenceTable t;
    t.title = std::string("frictionless cylinder, ") + model + " bulk: stress against eq. 7.18 (uniaxial chain)";
    t.h_name = "dt [s]";
    t.error_name = "max |sigma - sigma_7.18| / max |sigma_7.18|";
    t.expected_order = 2;
    double production = std::nan(""), radial = std::nan("");
    for (unsigned int n = spec.time_steps / 2; n <= spec.time_steps * (ctx.quick ? 4u : 8u); n *= 2)
    {
      const CylinderResult run =
        cylinder_case(ctx, name,
                      {"discretisation/refinements=0", "discretisation/time steps=" + std::to_string(n),
                       std::string("material/model=") + model});
      t.add(run.mesh.time_step,
            relative_deviation(run.series.column("axial_stress_pa"), run.series.column("axial_stress_closed_form_pa")));
      if (n == spec.time_steps)
      {
        const std::string tag = std::string(model) == "same shape" ? "same_shape" : "deviatoric";
        out.figures.push_back(
          make_figure("stress_" + tag, std::string("Frictionless cylinder, ") + model + " bulk, at the deck's step",
                      "time [s]", "axial stress [MPa]",
                      {curve("finite elements", run.series.column("time_s"), run.series.column("axial_stress_pa")),
                       curve("eq. 7.18 (uniaxial chain)", run.series.column("time_s"),
                             run.series.column("axial_stress_closed_form_pa"), CurveStyle::dashed)}));
        for (Curve &c : out.figures.back().curves)
          c.y_scale = 1e-6;
        production = t.rows.back().error;
        radial = relative_deviation(run.series.column("radial_strain"), run.series.column("radial_strain_closed_form"));
      }
    }
    out.tables.push_back(t);
    const std::string tag = std::string(model) + " bulk: ";
    const char *budget = "0.1 % keeps the time error ten times below the 1 % discretisation budget of the "
                         "bonded-platen study, which uses the same step";
    out.metrics.push_back(bound(tag + "stress error against eq. 7.18 at the deck's step", production, 1e-3, false,
                                ToleranceClass::B, budget));
    out.metrics.push_back(bound(tag + "radial strain error against the closed form at the deck's step", radial, 1e-3,
                                false, ToleranceClass::B, budget));
    out.metrics.push_back(bound(
      tag + "largest |observed order in dt - 2| over the finest three steps", t.largest_order_deviation(2), 0.1, false,
      ToleranceClass::B, "the trapezoidal update is second order (within 0.1 at each of the two finest halvings)"));
  }
  return out;
}

// @sect3{V21: manufactured solutions}

CheckOutcome check_manufactured_solutions(const CheckContext &ctx)
{
  CheckOutcome out;
  struct Study
  {
    const char *deck;
    std::vector<std::string> overrides;
    bool quick;
  };
  const Study studies[] = {
    {"c05_mms_space", {}, true},
    {"c05_mms_space", {"study/degree=1"}, true},
    {"c05_mms_space", {"material/model=deviatoric"}, true},
    {"c05_mms_space", {"study/model=3d", "study/degree=1", "study/levels=0, 1, 2"}, true},
    {"c05_mms_space", {"study/levels=2, 3, 4, 5"}, false},
    {"c05_mms_space", {"study/model=3d", "study/levels=0, 1, 2, 3"}, false},
    {"c06_mms_time", {}, true},
    {"c06_mms_time", {"material/model=deviatoric"}, true},
    {"c06_mms_time", {"study/model=3d"}, false},
  };
  for (const Study &s : studies)
  {
    if (ctx.quick && !s.quick)
      continue;
    const MmsDeckSpec deck = parse_mms(load_case(ctx, s.deck, s.overrides));
    const MmsResult r = run_mms_deck(deck, run_options(ctx));
    if (r.status.fault)
      throw std::runtime_error(std::string(s.deck) + ": " + r.status.diagnostic());
    const continuum::MmsSpec &spec = deck.study;
    const std::vector<ConvergenceTable> tables = mms_tables(r.levels, spec);
    const bool space = spec.variable == continuum::MmsVariable::space;
    for (std::size_t k = 0; k < tables.size(); ++k)
    {
      ConvergenceTable t = tables[k];
      const bool displacement = k < 2;
      if (space && k < 3)
        out.metrics.push_back(bound(t.title + ": largest |observed - expected order| over the finest three levels",
                                    t.largest_order_deviation(t.expected_order), 0.1, false, ToleranceClass::B,
                                    "Q_p theory (L2 p+1, H1 and stress p), within 0.1"));
      else if (!space && !displacement)
        out.metrics.push_back(bound(t.title + ": largest |observed order - 2| over the finest three steps",
                                    t.largest_order_deviation(2), 0.1, false, ToleranceClass::B,
                                    "trapezoidal update, order 2 within 0.1"));
      else if (!space)
      {
        double largest = 0;
        for (const ConvergenceRow &row : t.rows)
          largest = std::max(largest, row.error);
        out.metrics.push_back(
          bound(t.title + ": largest error", largest, 1e-9, false, ToleranceClass::A, patch_reason));
        t.reference = ConvergenceTable::Reference::roundoff;
        t.roundoff_bound = 1e-9;
      }
      out.tables.push_back(t);
    }
  }
  return out;
}

// @sect3{V22: bonded platens, grid convergence index}

CheckOutcome check_bonded_gci(const CheckContext &ctx)
{
  CheckOutcome out;
  const CylinderResult r =
    cylinder_case(ctx, "c04_cylinder_bonded_gci",
                  {ctx.quick ? "study/gci refinements=1, 2, 3, 4" : "study/gci refinements=2, 3, 4, 5"});
  if (r.gci.size() != 4)
    throw std::runtime_error("c04_cylinder_bonded_gci: expected two GCI triplets");
  const char *quantities[] = {"peak stress", "stress at 1 % strain"};
  for (int q = 0; q < 2; ++q)
  {
    const GciResult &fine = r.gci[q], &coarse = r.gci[2 + q];
    const std::string tag = quantities[q];
    out.metrics.push_back(bound(tag + ": monotone convergence over the finest triplet (1 = yes)",
                                fine.monotone ? 1.0 : 0.0, 1, true, ToleranceClass::B,
                                "Celik et al. (2008): the GCI applies to monotone convergence only"));
    out.metrics.push_back(bound(tag + ": GCI_fine", fine.gci_fine, 0.01, false, ToleranceClass::B,
                                "the requirement: the finest mesh must carry a discretisation uncertainty below 1 %"));
    out.metrics.push_back(absolute_error(tag + ": |observed order - 1.5| (order in [1, 2])", fine.order, 1.5, 0.5,
                                         ToleranceClass::B,
                                         "the bonded platen edge is a fixed-free corner with a singular exponent "
                                         "lambda in (1/2, 1) (Williams 1952), so the platen force converges like "
                                         "h^(2 lambda), 2 lambda in (1, 2)"));
    out.metrics.push_back(absolute_error(tag + ": |order of the finest - the coarser triplet|", fine.order,
                                         coarse.order, 0.2, ToleranceClass::B,
                                         "asymptotic range: the observed order must not depend on the triplet "
                                         "(Roache's GCI ratio is phi1/phi2 identically for a constant refinement "
                                         "ratio, so it is reported, not tested)"));
    ConvergenceTable t;
    t.title = "bonded cylinder, " + tag + ": distance to the Richardson-extrapolated value";
    t.h_name = "h [m]";
    t.error_name = "|phi_h - phi_ext| / phi_ext";
    t.expected_order = fine.order;
    t.reference = ConvergenceTable::Reference::fitted;
    for (int i = 2; i >= 0; --i)
      t.add(fine.h[i], std::abs(fine.phi[i] - fine.extrapolated) / fine.extrapolated);
    out.tables.push_back(t);
    out.notes.push_back(tag + ": phi (fine to coarse) = " + num(fine.phi[0]) + ", " + num(fine.phi[1]) + ", " +
                        num(fine.phi[2]) + " Pa; p = " + num(fine.order) + " (coarser triplet " + num(coarse.order) +
                        "); phi_ext = " + num(fine.extrapolated) + " Pa; e_a = " + num(fine.approximate_error) +
                        "; e_ext = " + num(fine.extrapolated_error) + "; GCI_fine = " + num(fine.gci_fine) +
                        "; GCI_32 / (r^p GCI_21) = " + num(fine.asymptotic_ratio));
  }
  return out;
}
} // namespace demvv
