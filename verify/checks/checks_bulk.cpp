// Bulk-level code verification: V08 energy audit, V09 wave in a bonded chain,
// V11 lattice porosity and coordination.
#include "verify/checks/checks_bulk.h"

#include "app/kinds/compare.h"
#include "app/kinds/uniaxial.h"
#include "verify/checks/checks_support.h"

#include "dem/bonds.h"
#include "dem/measure.h"
#include "dem/sample_lattice.h"

#include <cmath>

namespace demvv
{
CheckOutcome check_energy_audit(const CheckContext &ctx)
{
  CheckOutcome out;
  const Deck deck = load_case(ctx, "v08_energy_audit");
  const UniaxialResult r = run_uniaxial(deck, run_options(ctx));
  if (r.status.fault)
    throw std::runtime_error(r.status.diagnostic());
  const auto residual = r.series.column("energy_residual_j");
  const auto work = r.series.column("boundary_work_j");
  const double released = r.series.column("bond_energy_released_j").back();
  const double friction = r.series.column("friction_dissipated_j").back();
  const double damping = r.series.column("damping_dissipated_j").back();
  out.metrics.push_back(bound("max |residual| over the run / final boundary work", max_abs(residual) / work.back(),
                              0.01, false, ToleranceClass::B,
                              "the requirement: residual below 1 % of the boundary work"));
  // The audit is only meaningful if every term is exercised.
  out.metrics.push_back(bound("bond energy released / boundary work", released / work.back(), 1e-3, true,
                              ToleranceClass::B, "breakage must occur for the audit to cover it"));
  out.metrics.push_back(bound("friction work / boundary work", friction / work.back(), 1e-3, true, ToleranceClass::B,
                              "slip must occur for the audit to cover it"));
  out.metrics.push_back(bound("damping work / boundary work", damping / work.back(), 1e-3, true, ToleranceClass::B,
                              "local damping must act for the audit to cover it"));
  const std::vector<double> strain = r.series.column("axial_strain");
  std::vector<double> accounted(strain.size(), 0.0);
  std::vector<Curve> curves = {curve("boundary work (supplied)", strain, work, CurveStyle::dashed)};
  for (const auto &[title, column] :
       std::vector<std::pair<std::string, std::string>>{{"kinetic", "kinetic_energy_j"},
                                                        {"strain (contacts and bonds)", "strain_energy_j"},
                                                        {"friction dissipated", "friction_dissipated_j"},
                                                        {"damping dissipated", "damping_dissipated_j"},
                                                        {"released by broken bonds", "bond_energy_released_j"}})
  {
    const std::vector<double> term = r.series.column(column);
    for (std::size_t k = 0; k < term.size(); ++k)
      accounted[k] += term[k];
    curves.push_back(curve(title, strain, term));
  }
  curves.insert(curves.begin() + 1, curve("held + dissipated (sum of the terms below)", strain, accounted));
  for (Curve &c : curves)
    c.x_scale = 100;
  out.figures.push_back(make_figure(
    "energy_ledger", "Energy audit of a bonded compression", "axial strain [%]", "energy [J]", std::move(curves),
    "The work the platens supply (dashed) against what the packing holds and has dissipated (their sum, solid); "
    "the metric is the largest gap between the two against the final work."));
  out.notes.push_back("energy audit on " + std::to_string(r.summary["sample"]["particles"].get<long>()) +
                      " balls; final boundary work " + num(work.back()) + " J, residual " + num(residual.back()) +
                      " J");
  return out;
}

CheckOutcome check_chain_wave(const CheckContext &ctx)
{
  CheckOutcome out;
  const SceneResult r = run_case(ctx, "v09_bonded_chain");
  const dem::ParticleStore &p = r.sim->particles();
  const double K = dem::ContactTable::pair_params(p, 0, 1).kn;
  const double c0 = 2 * p.radius[0] * std::sqrt(K / p.mass[1]);
  const double v = p.velocity[0].x();
  double arrival[2];
  const int stations[2] = {40, 160};
  std::vector<Curve> curves;
  for (int s = 0; s < 2; ++s)
  {
    const Series ball = r.particles.where("particle", stations[s]);
    const std::vector<double> t = ball.column("time_s");
    arrival[s] = first_crossing(t, ball.column("vx_mps"), 0.5 * v);
    // The continuum's front: ball 0 is a piston at v, so the long-wave
    // solution is a step of height v reaching ball n at n 2R / c0.
    std::vector<double> step;
    for (double time : t)
      step.push_back(time >= stations[s] * 2 * p.radius[0] / c0 ? v : 0.0);
    const std::string ball_name = "ball " + std::to_string(stations[s]);
    curves.push_back(curve("demvv, " + ball_name, t, ball.column("vx_mps")));
    curves.push_back(curve("long-wave step at n 2R / c0, " + ball_name, t, step, CurveStyle::dashed));
  }
  out.figures.push_back(make_figure(
    "chain_front", "Velocity front along a bonded chain driven at one end", "time [s]", "velocity v_x [m/s]",
    std::move(curves),
    "The discrete chain spreads the step into an oscillating front whose half-height point trails the long-wave "
    "step by a lag growing like n^(1/3); the check times the front at both balls, so the common lag cancels in "
    "the speed between them."));
  const double speed = (stations[1] - stations[0]) * 2 * p.radius[0] / (arrival[1] - arrival[0]);
  // The discrete chain disperses a step into an Airy-type front whose
  // half-amplitude point moves at c0 with a lag growing like n^(1/3); timing
  // the front at two stations cancels the common part.  The requirement
  // asks for 1 %.
  out.metrics.push_back(relative_error("front speed between balls 40 and 160 vs c0 = 2R sqrt(K/m)", speed, c0, 0.01,
                                       ToleranceClass::B, "the requirement: arrival of the front within 1 %"));
  out.notes.push_back("c0 = " + num(c0) + " m/s, measured " + num(speed) + " m/s");
  return out;
}

namespace
{
/// Bulk porosity of a lattice of balls of radius R squeezed so that centres
/// are (1 - squeeze) x 2R apart: ball volume minus the lenses it shares
/// (Z/2 per ball), per lattice volume.
double squeezed_porosity(dem::Lattice l, double R, double squeeze)
{
  const double d = 2 * R * (1 - squeeze);
  const double lens = dem::sphere_intersection_volume(R, R, d);
  const double ball = 4.0 / 3.0 * dem::pi * R * R * R;
  const int z = dem::lattice_coordination(l);
  const double a = (l == dem::Lattice::simple_cubic ? 2 * R : 2 * std::sqrt(2.0) * R) * (1 - squeeze);
  const double per_cell = l == dem::Lattice::simple_cubic ? 1 : 4;
  return 1 - per_cell * (ball - 0.5 * z * lens) / (a * a * a);
}
} // namespace

CheckOutcome check_lattice_measurements(const CheckContext & /*ctx*/)
{
  CheckOutcome out;
  const double R = 1e-3;
  for (double squeeze : {0.0, 0.01})
    for (dem::Lattice l : {dem::Lattice::simple_cubic, dem::Lattice::face_centred_cubic})
    {
      const int n = l == dem::Lattice::simple_cubic ? 16 : 12;
      dem::ParticleStore p;
      for (const dem::Vec3 &x : dem::lattice_box(l, R, n, n, n))
      {
        dem::BallSpec b;
        b.position = x * (1 - squeeze);
        b.radius = R;
        b.kn = 1e6;
        p.add(b);
      }
      const double a = (l == dem::Lattice::simple_cubic ? 2 * R : 2 * std::sqrt(2.0) * R) * (1 - squeeze);
      const dem::Vec3 centre = dem::Vec3::Ones() * (a * n / 2);
      dem::Simulation sim(std::move(p), {}, dem::make_contact_model("linear", {}), {});
      sim.refresh_contacts();
      dem::BondSettings bonds;
      bonds.normal_strength = bonds.shear_strength = 1;
      dem::bond_touching_pairs(sim.contacts(), sim.particles(), bonds);
      sim.compute_forces();

      const std::string name = std::string(dem::lattice_name(l)) + (squeeze > 0 ? " squeezed 1 %" : " touching");
      const double exact = squeezed_porosity(l, R, squeeze);
      // Porosity in one sphere depends on where the sphere sits on the
      // lattice; its average over sphere positions in a unit cell is the
      // bulk value exactly (the lattice is periodic).  The average is taken
      // with the k^3-point midpoint rule, whose error falls at least like
      // k^-2 for this continuous, piecewise-smooth integrand.
      ConvergenceTable table;
      table.title = "porosity in a sphere of radius 5R averaged over k^3 positions, " + name;
      table.h_name = "1/k";
      table.error_name = "|mean - bulk closed form|";
      table.expected_order = 2;
      table.reference = ConvergenceTable::Reference::least;
      for (int k : {2, 4, 6})
      {
        double sum = 0;
        for (int i = 0; i < k; ++i)
          for (int j = 0; j < k; ++j)
            for (int m = 0; m < k; ++m)
              sum += dem::porosity(sim.particles(), sim.contacts(),
                                   {centre + dem::Vec3(i + 0.5, j + 0.5, m + 0.5) * (a / k), 5 * R});
        table.add(1.0 / k, std::abs(sum / (k * k * k) - exact));
      }
      const double first = table.rows.front().error, last = table.rows.back().error;
      out.metrics.push_back(bound(name + ": porosity error at k = 6", last, std::min(1e-3, first / 9), false,
                                  ToleranceClass::B, "k^-2 decay from the k = 2 error, and below 1e-3"));
      out.tables.push_back(table);
      out.metrics.push_back(absolute_error(name + ": coordination number in a sphere of radius 5R",
                                           dem::coordination_number(sim.particles(), sim.contacts(), {centre, 5 * R}),
                                           dem::lattice_coordination(l), 0.0, ToleranceClass::A,
                                           "exact: every ball inside has all its lattice neighbours"));
    }
  return out;
}

namespace
{
/// A compare case on the 1000-ball sample (--quick) or the 6000-ball one.
CompareResult compare_case(const CheckContext &ctx, const std::string &name)
{
  Deck deck = load_case(ctx, name);
  if (!ctx.quick)
    deck.set("sample/file", "../p01_thesis_6000/case.prm");
  CompareResult r = run_compare(deck, run_options(ctx));
  if (r.status.fault)
    throw std::runtime_error(r.status.diagnostic());
  return r;
}
} // namespace

CheckOutcome check_packing_identity(const CheckContext &ctx)
{
  CheckOutcome out;
  const std::string sample = ctx.quick ? "1000-ball sample (p03)" : "6000-ball sample (p01)";
  for (const char *name :
       {"c10_identity_constant_rate", "c11_identity_creep", "c12_identity_relaxation", "c13_identity_cyclic"})
  {
    const CompareResult r = compare_case(ctx, name);
    const nlohmann::json &s = r.summary;
    const std::string history = s["loading"]["history"].get<std::string>();
    const bool creep = history == "creep";
    // What breaks the identity, each bounded on these decks: the platen
    // contacts are elastic springs in series with the Burger's network
    // (their share of the compliance, about 3 % at 10 K_m per ball, is
    // exact at t = 0 through the calibration and fades as the network
    // creeps: the stress ratio settles at 1.03 in relaxation, 1.012 with
    // four times stiffer platen contacts); inertia (inertial number below
    // 1e-3: the platen-contact oscillation is 1-2 % of the stress during a
    // ramp); geometry and contacts made (strains below 0.3 %: under 1 %).
    out.metrics.push_back(
      bound(history + ": max |DEM - calibrated continuum| / max, " + (creep ? "axial strain" : "axial stress"),
            s["difference_calibrated"]["relative"].get<double>(), 0.05, false, ToleranceClass::B,
            "platen springs <= 3 %, inertia (I < 1e-3) <= 2 %, geometry and contacts made at "
            "strains below 0.3 % < 1 %; continuum time-step error below 0.5 %"));
    out.metrics.push_back(bound(history + ": largest inertial number after the start-up",
                                s["uncertainty"]["dem_quasi_static_indicators"]["max_inertial_number"].get<double>(),
                                1e-3, false, ToleranceClass::B, "the quasi-static premise of the identity"));
    const std::string y = creep ? "axial_strain" : "axial_stress";
    Figure f = make_figure("identity_" + history.substr(0, history.find(' ')),
                           "DEM bulk vs calibrated continuum, " + history + ", " + sample, "time [s]",
                           creep ? "axial strain [%]" : "axial stress [kPa]",
                           {curve("DEM", r.series.column("time_s"), r.series.column(y + (creep ? "_dem" : "_dem_pa"))),
                            curve("continuum, calibrated (E/K_m x contact chain)", r.series.column("time_s"),
                                  r.series.column(y + (creep ? "_calibrated" : "_calibrated_pa")), CurveStyle::dashed),
                            curve("continuum, affine", r.series.column("time_s"),
                                  r.series.column(y + (creep ? "_affine" : "_affine_pa")), CurveStyle::dashed)});
    for (Curve &c : f.curves)
      c.y_scale = creep ? 100 : 1e-3;
    out.figures.push_back(std::move(f));
    out.notes.push_back(history + " on the " + sample + ": E_DEM = " + num(s["moduli"]["young_dem_pa"].get<double>()) +
                        " Pa, E_affine = " + num(s["moduli"]["young_affine_pa"].get<double>()) +
                        " Pa (non-affine ratio " + num(s["moduli"]["non_affine_ratio"].get<double>()) +
                        "), nu_DEM = " + num(s["moduli"]["poisson_dem"].get<double>()) +
                        ", Z = " + num(s["packing_measured"]["coordination_number"].get<double>()) + ", phi = " +
                        num(s["packing_measured"]["solid_fraction"].get<double>()) + "; affine route off by " +
                        num(s["difference_affine"]["relative"].get<double>()) + "; continuum time-step error " +
                        num(s["uncertainty"]["continuum_time_step_relative"].get<double>()));
  }

  // Model form, beside the identity: where it cannot hold, the comparison
  // must show it.  Modified Burger's contacts are elastic in compression,
  // so the network's stress does not relax with the continuum's.
  for (const char *name : {"c14_compare_modified_burgers", "c15_compare_bonded_platens"})
  {
    const CompareResult r = compare_case(ctx, name);
    const double gap = r.summary["difference_calibrated"]["relative"].get<double>();
    const bool modified = std::string(name) == "c14_compare_modified_burgers";
    if (modified)
      out.metrics.push_back(bound("modified Burger's: max |DEM - Burger's continuum| / max stress", gap, 0.2, true,
                                  ToleranceClass::B,
                                  "model form, not the identity: the normal contacts do not relax in compression, "
                                  "so the comparison must part by far more than the 5 % the identity allows"));
    Figure f = make_figure(modified ? "model_form_modified_burgers" : "model_form_bonded_platens",
                           modified ? "Modified Burger's contacts beside the Burger's continuum (relaxation)"
                                    : "Bonded platens: DEM rough platens beside the barrelling continuum (relaxation)",
                           "time [s]", "axial stress [kPa]",
                           {curve("DEM", r.series.column("time_s"), r.series.column("axial_stress_dem_pa")),
                            curve("continuum, calibrated", r.series.column("time_s"),
                                  r.series.column("axial_stress_calibrated_pa"), CurveStyle::dashed)});
    for (Curve &c : f.curves)
      c.y_scale = 1e-3;
    out.figures.push_back(std::move(f));
    out.notes.push_back(
      std::string(modified ? "model form, modified Burger's" : "model form, bonded platens") + " on the " + sample +
      ": largest difference " + num(gap) +
      " of the peak stress at t = " + num(r.summary["difference_calibrated"]["time_s"].get<double>()) +
      " s (reported, not pass/failed" + (modified ? " beyond parting visibly" : "") + "); continuum mesh error bound " +
      num(r.summary["uncertainty"]["continuum_mesh_relative_bound"].get<double>()));
  }
  return out;
}
} // namespace demvv
