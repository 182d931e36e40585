#include "uniaxial.h"

#include "analysis.h"
#include "deck_sections.h"
#include "paraview.h"

#include "measure.h"
#include "protocol_uniaxial.h"
#include "specimen.h"

#include <chrono>
#include <cmath>
#include <limits>

namespace verify
{
namespace
{
constexpr double inf = std::numeric_limits<double>::infinity();
}

void declare_uniaxial(DeckSchema &s)
{
  s.text("title", "", "One line saying what this test is for (copied to summary.json).");
  s.enter("sample");
  s.choice("source", "lattice", {"lattice"},
           "Where the balls come from: 'lattice' builds a regular lattice cylinder (a verification "
           "stand-in until prepared random samples are available).");
  s.choice("lattice", "fcc", {"fcc", "sc"}, "Lattice of the stand-in sample: face-centred or simple cubic.");
  s.real("ball radius", 0.885e-3, 0, inf, "m", "Radius of every ball (thesis: 1.77 mm diameter sand).", true);
  s.real("diameter", 0.0311, 0, inf, "m", "Target diameter of the sample (the rim balls fit inside).", true);
  s.real("height", 0.0311, 0, inf, "m", "Target height of the sample (the balls fit inside).", true);
  s.leave();
  declare_ball_properties(s);
  declare_contact_law(s);
  declare_bonds(s, {"touching", "none"});
  s.enter("platens");
  declare_wall_properties(s, 1.2e7, 0, 0);
  s.leave();
  s.enter("loading");
  s.choice("control", "platen speed", {"platen speed", "strain rate"},
           "Which of the two next entries sets the loading rate.");
  s.real("platen speed", 0.01, 0, inf, "m/s",
         "Approach speed of the platens (thesis §6.3-6.4: 0.01 m/s is quasi-static).", true);
  s.real("strain rate", 0.3, 0, inf, "1/s", "Axial strain rate (compression positive).", true);
  s.real("ramp time", 0, 0, inf, "s", "The platen speed rises linearly from zero over this time (thesis §6.1).");
  s.real("final strain", 0.03, 0, 1, "-", "Axial strain at which the test stops (thesis: 3 %).", true);
  s.choice("moving platens", "top", {"top", "both"},
           "'top': the top platen moves, the bottom one is fixed (thesis); 'both': each moves at half speed.");
  s.leave();
  declare_motion(s, "0, 0, 0", 0.7);
  s.enter("measurement");
  s.real("gauge thickness", 0.8, 0, 1, "-",
         "Height of the central band of radial-strain gauges as a fraction of the sample height (thesis §5.4.3).",
         true);
  s.real("sphere radius", 0.3, 0, 0.5, "-",
         "Radius of the two measurement spheres (on the axis at 1/3 and 2/3 of the height) as a fraction of "
         "the sample diameter.",
         true);
  s.real_list("fit window", "0, 0.002", 2, 2, "-",
              "Axial strain interval over which the initial modulus and Poisson's ratio are fitted.");
  s.leave();
  s.enter("output");
  s.real("strain interval", 1e-4, 0, 1, "-", "Axial strain between output rows.", true);
  s.flag("paraview", false, "Write ParaView files (particles, contact forces, broken bonds) to paraview/.");
  s.real("paraview strain interval", 0.005, 0, 1, "-", "Axial strain between ParaView frames.", true);
  s.leave();
}

namespace
{
const std::vector<std::string> series_columns = {
  "time_s", "axial_strain", "axial_stress_pa", "axial_stress_top_pa", "axial_stress_bottom_pa",
  "radial_strain", "bonds_broken_fraction", "bonds_broken_tension", "bonds_broken_shear",
  "coordination_number", "coordination_number_spheres", "porosity_spheres", "unbalanced_force_ratio", "inertial_number", "time_step_s",
  "kinetic_energy_j", "strain_energy_j", "friction_dissipated_j", "damping_dissipated_j",
  "bond_energy_released_j", "boundary_work_j", "energy_residual_j"};
} // namespace

UniaxialResult run_uniaxial(const Deck &deck, const RunOptions &options)
{
  const int threads = apply_threads(options);
  dem::Lattice lattice;
  dem::parse_lattice(deck.text("sample/lattice"), lattice);
  dem::BallSpec ball;
  apply_ball_properties(deck, ball);
  dem::Specimen specimen =
    dem::lattice_specimen(lattice, deck.real("sample/ball radius"), deck.real("sample/diameter"),
                          deck.real("sample/height"), ball, read_wall_properties(deck, "platens"), {}, false);
  if (specimen.particles.size() < 2)
    deck.fail("sample/diameter", "the sample holds fewer than two balls of the given radius: expected a "
                                 "diameter and height of several ball diameters");
  const double window_lo = deck.real_list("measurement/fit window")[0];
  const double window_hi = deck.real_list("measurement/fit window")[1];
  if (!(window_hi > window_lo))
    deck.fail("measurement/fit window", "expected two increasing strains");

  UniaxialResult result;
  const double area = specimen.area(), height0 = specimen.height, diameter = specimen.diameter;
  const dem::WallIndex bottom = specimen.bottom, top = specimen.top;
  result.sim = std::make_unique<dem::Simulation>(std::move(specimen.particles), std::move(specimen.walls),
                                                 read_contact_law(deck), read_motion(deck));
  dem::Simulation &sim = *result.sim;
  sim.refresh_contacts();
  dem::BondReport bonds;
  if (deck.text("bonds/install") == "touching")
    bonds = dem::bond_touching_pairs(sim.contacts(), sim.particles(), read_bond_settings(deck));

  dem::UniaxialSettings load;
  load.platen_speed = deck.text("loading/control") == "platen speed" ? deck.real("loading/platen speed") : 0;
  load.strain_rate = deck.real("loading/strain rate");
  load.ramp_time = deck.real("loading/ramp time");
  load.final_strain = deck.real("loading/final strain");
  load.both_platens = deck.text("loading/moving platens") == "both";
  const dem::UniaxialCompression test(sim, bottom, top, area, load);
  const dem::RadialGauges gauges(sim.particles(), dem::Vec3::Zero(), 0.5 * height0, height0,
                                 deck.real("measurement/gauge thickness"));
  const double sphere_r = deck.real("measurement/sphere radius") * diameter;
  const dem::MeasurementSphere spheres[2] = {{dem::Vec3(0, 0, height0 / 3), sphere_r},
                                             {dem::Vec3(0, 0, 2 * height0 / 3), sphere_r}};
  const double mean_radius = deck.real("sample/ball radius");
  const double density = deck.real("balls/density");
  const double strain_rate = test.final_speed() / height0;

  result.series = Series(series_columns);
  const std::string convention =
    "demvv uniaxial '" + deck.name() + "': SI units; compression positive for axial stress and strain; "
    "radial strain = -(r - r0)/r0; sample: " + specimen.description;
  RunFiles files(options, deck, threads, deck.integer("bonds/seed"), convention, deck.flag("output/paraview"));
  RunDirectory *dir = files.directory();
  ParaviewWriter *paraview = files.paraview();
  if (dir)
    result.series.stream_to(dir->path("series.csv"), convention);

  const double strain_interval = deck.real("output/strain interval");
  const double frame_interval = deck.real("output/paraview strain interval");
  double next_row = 0, next_frame = 0;
  Progress progress("uniaxial " + deck.name());
  const auto start = std::chrono::steady_clock::now();
  const auto installed = static_cast<double>(std::max<std::size_t>(bonds.bonded, 1));
  std::vector<double> row;

  try
  {
    for (;;)
    {
      test.drive(sim);
      sim.compute_forces();
      files.drain_breaks(sim);

      const double strain = test.axial_strain(sim);
      const bool last = test.finished(sim);
      const bool due = last || strain >= next_row;
      if (due)
      {
        const double s_top = test.stress_top(sim), s_bottom = test.stress_bottom(sim);
        const double stress = 0.5 * (s_top + s_bottom);
        const double broken_t = double(sim.bonds_broken(dem::BreakMode::tension));
        const double broken_s = double(sim.bonds_broken(dem::BreakMode::shear));
        const double porosity = 0.5 * (dem::porosity(sim.particles(), sim.contacts(), spheres[0]) +
                                       dem::porosity(sim.particles(), sim.contacts(), spheres[1]));
        const double sphere_coordination =
          0.5 * (dem::coordination_number(sim.particles(), sim.contacts(), spheres[0]) +
                 dem::coordination_number(sim.particles(), sim.contacts(), spheres[1]));
        // Inertial number I = strain rate * d * sqrt(rho / p), p = sigma/3
        // for uniaxial stress; quasi-static when I << 1e-3.
        const double inertial = stress > 0 ? strain_rate * 2 * mean_radius * std::sqrt(density / (stress / 3)) : 0.0;
        row = {sim.time(), strain, stress, s_top, s_bottom, gauges.radial_strain(sim.particles()),
               (broken_t + broken_s) / installed, broken_t, broken_s,
               dem::coordination_number(sim.particles(), sim.contacts()), sphere_coordination, porosity,
               dem::unbalanced_force_ratio(sim.particles(), sim.contacts()), inertial, sim.time_step()};
        next_row = strain + strain_interval;
        if (paraview && (last || strain >= next_frame))
        {
          paraview->write_frame(sim, sim.time());
          next_frame = strain + frame_interval;
        }
      }
      sim.integrate(due);
      if (due)
      {
        const dem::EnergyLedger e = sim.energy();
        row.insert(row.end(), {e.kinetic, e.strain, e.friction, e.damping, e.bond_released, e.boundary_work,
                               e.residual()});
        result.series.add(row);
      }
      if (last)
        break;
      progress.update(strain / load.final_strain, "strain " + std::to_string(strain));
    }
  }
  catch (const dem::NumericalFault &f)
  {
    record_fault(result.status, f);
  }
  progress.finish();
  result.status.steps = sim.steps();
  result.status.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  const auto eps = result.series.column("axial_strain");
  const auto sig = result.series.column("axial_stress_pa");
  const auto rad = result.series.column("radial_strain");
  const auto broken = result.series.column("bonds_broken_fraction");
  std::vector<double> minus_radial(rad.size());
  for (std::size_t k = 0; k < rad.size(); ++k)
    minus_radial[k] = -rad[k];
  const LineFit modulus = fit_line(eps, sig, window_lo, window_hi);
  const LineFit poisson = fit_line(eps, minus_radial, window_lo, window_hi);
  const Peak pk = peak(eps, sig);
  double break_strain = 0, break_rate = 0;
  const bool has_breaks = x_at_max_rate(eps, broken, break_strain, break_rate) && break_rate > 0;
  const dem::EnergyLedger e = sim.energy();
  const dem::Index n = sim.particles().size();

  result.summary = {
    {"kind", "uniaxial"},
    {"title", deck.text("title")},
    {"status", result.status.to_json()},
    {"sample", {{"description", specimen.description},
                {"particles", n},
                {"diameter_m", diameter},
                {"height_m", height0},
                {"area_m2", area},
                {"radial_gauges", gauges.size()},
                {"measurement_sphere_radius_m", sphere_r}}},
    {"contact_law", std::string(sim.model().name())},
    {"loading", {{"platen_speed_mps", test.final_speed()},
                 {"strain_rate_per_s", strain_rate},
                 {"ramp_time_s", load.ramp_time},
                 {"final_strain", load.final_strain},
                 {"moving_platens", load.both_platens ? "both" : "top"}}},
    {"peak_stress_pa", pk.value},
    {"strain_at_peak", pk.at},
    {"strain_at_max_breakage_rate", has_breaks ? nlohmann::json(break_strain) : nlohmann::json(nullptr)},
    {"max_breakage_rate_per_unit_strain", has_breaks ? nlohmann::json(break_rate) : nlohmann::json(nullptr)},
    {"initial_modulus_pa", modulus.points >= 2 ? nlohmann::json(modulus.slope) : nlohmann::json(nullptr)},
    {"poisson_ratio", poisson.points >= 2 ? nlohmann::json(poisson.slope) : nlohmann::json(nullptr)},
    {"fit_window_axial_strain", {window_lo, window_hi}},
    {"fit_points", modulus.points},
    {"fit_r_squared", {{"modulus", modulus.r_squared}, {"poisson", poisson.r_squared}}},
    {"bonds", {{"installed", bonds.bonded},
               {"removed", bonds.removed},
               {"truncated_strength_draws", bonds.truncated_draws},
               {"mean_normal_strength_n", bonds.mean_normal_strength},
               {"mean_shear_strength_n", bonds.mean_shear_strength},
               {"broken_tension", sim.bonds_broken(dem::BreakMode::tension)},
               {"broken_shear", sim.bonds_broken(dem::BreakMode::shear)}}},
    {"coordination_number_at_end", dem::coordination_number(sim.particles(), sim.contacts())},
    {"steps", sim.steps()},
    {"last_time_step_s", sim.time_step()},
    {"critical_time_step_bound_s", sim.critical_time_step()},
    {"neighbour_rebuilds", sim.neighbors().rebuilds()},
    {"energy_j", {{"kinetic", e.kinetic}, {"strain", e.strain}, {"friction", e.friction},
                  {"damping", e.damping}, {"bond_released", e.bond_released},
                  {"boundary_work", e.boundary_work}, {"residual", e.residual()}}},
    {"wall_seconds", result.status.wall_seconds},
    {"particle_steps_per_second",
     result.status.wall_seconds > 0 ? double(n) * sim.steps() / result.status.wall_seconds : 0.0}};
  if (dir)
    dir->write_summary(result.summary);
  return result;
}
} // namespace verify
