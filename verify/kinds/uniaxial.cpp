#include "verify/kinds/uniaxial.h"

#include "verify/run/analysis.h"
#include "verify/decks/deck_sections.h"
#include "verify/io/paraview.h"
#include "verify/kinds/prepare.h"

#include "dem/measure.h"
#include "dem/protocol_uniaxial.h"
#include "dem/specimen.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cmath>
#include <limits>
#include <sstream>

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
  s.choice("source", "lattice", {"lattice", "file"},
           "Where the balls come from: 'file' loads a prepared sample (thesis ch. 5); 'lattice' builds a "
           "regular lattice cylinder, a verification sample only.");
  s.text("file", "",
         "For source = file: a sample file (.json) written by a prepare run, or a prepare deck (.prm) whose "
         "sample is prepared on first use and cached under runs/samples/; relative to this deck.");
  s.choice("lattice", "fcc", {"fcc", "sc"}, "For source = lattice: face-centred or simple cubic.");
  s.real("ball radius", 0.885e-3, 0, inf, "m", "Radius of every ball (thesis: 1.77 mm diameter sand).", true);
  s.real("diameter", 0.0311, 0, inf, "m", "Target diameter of the sample (the rim balls fit inside).", true);
  s.real("height", 0.0311, 0, inf, "m", "Target height of the sample (the balls fit inside).", true);
  s.leave();
  declare_ball_properties(s);
  declare_contact_law(s);
  declare_bonds(s, {"touching", "sample", "none"});
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
  declare_rate(s);
  declare_motion(s, "0, 0, 0", 0.7);
  s.enter("measurement");
  s.real("gauge thickness", 0.8, 0, 1, "-",
         "Height of the central band of radial-strain gauges as a fraction of the sample height (thesis §5.4.3).",
         true);
  s.real("sphere radius", 0.3, 0, 0.5, "-",
         "Radius of the two measurement spheres (on the axis at 1/3 and 2/3 of the height) as a fraction of "
         "the sample diameter.",
         true);
  s.real_list("gauge study", "", 0, 20, "-",
              "Extra gauge thicknesses (fractions of the height) whose radial strain is recorded beside that of "
              "all circumference balls, as in thesis Fig. 5.13; empty for none.  Writes gauge_study.csv.");
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
/// Largest ratio numerator / denominator of two series columns over the
/// rows at axial strain >= from_strain (denominator "" means 1).
double max_after(const Series &s, double from_strain, const std::string &numerator,
                 const std::string &denominator = "")
{
  const std::vector<double> strain = s.column("axial_strain"), a = s.column(numerator);
  const std::vector<double> b = denominator.empty() ? std::vector<double>(a.size(), 1.0) : s.column(denominator);
  double out = 0;
  for (std::size_t k = 0; k < a.size(); ++k)
    if (strain[k] >= from_strain && b[k] > 0)
      out = std::max(out, a[k] / b[k]);
  return out;
}

std::string num_text(double v)
{
  std::ostringstream o;
  o << v;
  return o.str();
}

/// gauge_study.csv: for each band, its gauges and its radial strain's error
/// against all circumference balls, at the end and averaged over the rows
/// past a tenth of the final circumference strain (thesis Fig. 5.13).
void write_gauge_study(const std::string &path, const Series &series, const std::vector<double> &study,
                       const std::vector<dem::RadialGauges> &gauges, const std::string &convention)
{
  const auto all = series.column("radial_strain_circumference");
  CsvSeries out(path, convention + "; error = 100 (gauge - circumference) / circumference",
                {"gauge_thickness", "gauges", "error_at_end_percent", "mean_abs_error_percent"});
  for (std::size_t k = 0; k < study.size(); ++k)
  {
    const auto band = series.column("radial_strain_gauge_" + num_text(study[k]));
    double sum = 0;
    std::size_t n = 0;
    for (std::size_t r = 0; r < all.size(); ++r)
      if (std::abs(all[r]) > 0.1 * std::abs(all.back()) && all[r] != 0)
      {
        sum += std::abs(100 * (band[r] - all[r]) / all[r]);
        ++n;
      }
    const double at_end = all.back() != 0 ? 100 * (band.back() - all.back()) / all.back() : std::nan("");
    out.write({study[k], double(gauges[k].size()), at_end, n ? sum / n : std::nan("")});
  }
}

const std::vector<std::string> series_columns = {
  "time_s", "axial_strain", "axial_stress_pa", "axial_stress_top_pa", "axial_stress_bottom_pa",
  "radial_strain", "bonds_broken_fraction", "bonds_broken_tension", "bonds_broken_shear", "bonds_broken_displacement",
  "coordination_number", "coordination_number_spheres", "porosity_spheres", "unbalanced_force_ratio", "inertial_number", "time_step_s",
  "kinetic_energy_j", "strain_energy_j", "friction_dissipated_j", "damping_dissipated_j",
  "bond_energy_released_j", "boundary_work_j", "energy_residual_j"};
} // namespace

namespace
{
/// The specimen of a uniaxial test, its simulation and its bonds.
struct Setup
{
  std::unique_ptr<dem::Simulation> sim;
  dem::Specimen cell; ///< wall indices, diameter, height, description
  dem::BondReport bonds;
  RateScaling rate;
};

/// The rate scaling of a test on a sample of the given height.
RateScaling uniaxial_rate(const Deck &deck, double height)
{
  const bool by_speed = deck.text("loading/control") == "platen speed";
  return read_rate(deck, by_speed ? deck.real("loading/platen speed") / height : deck.real("loading/strain rate"));
}

Setup lattice_setup(const Deck &deck)
{
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
  Setup s;
  s.rate = uniaxial_rate(deck, specimen.height);
  s.rate.scale_ball_stiffness(specimen.particles);
  s.sim = std::make_unique<dem::Simulation>(std::move(specimen.particles), std::move(specimen.walls),
                                            read_contact_law(deck, s.rate), read_motion(deck));
  s.cell = std::move(specimen);
  s.sim->refresh_contacts();
  if (deck.text("bonds/install") == "touching")
    s.bonds = dem::bond_touching_pairs(s.sim->contacts(), s.sim->particles(), read_bond_settings(deck));
  else if (deck.text("bonds/install") == "sample")
    deck.fail("bonds/install", "a lattice sample has no bonds of its own: expected touching or none");
  finish_bonds(deck, s.sim->contacts(), s.sim->particles(), s.rate);
  return s;
}

/// A prepared sample: its balls get the deck's properties, its platens the
/// deck's platen properties, its lateral wall (if still there) goes, and the
/// clock restarts at zero for the new test.
Setup sample_setup(const Deck &deck)
{
  if (deck.text("sample/file").empty())
    deck.fail("sample/file", "expected a sample file (.json) or a prepare deck (.prm) when source = file");
  SampleFile file = load_or_prepare_sample(deck.file("sample/file"), "runs/samples");
  dem::Snapshot &snap = file.snapshot;
  Setup s;
  s.rate = uniaxial_rate(deck, file.cell.height);
  dem::BallSpec ball;
  apply_ball_properties(deck, ball, s.rate);
  apply_test_properties(file, ball, read_wall_properties(deck, "platens"));

  s.sim = std::make_unique<dem::Simulation>(std::move(snap), read_contact_law(deck, s.rate), read_motion(deck));
  if (file.cell.lateral >= 0 && s.sim->walls()[file.cell.lateral].enabled)
    s.sim->set_wall_enabled(file.cell.lateral, false);
  const std::string mode = deck.text("bonds/install");
  if (mode != "sample")
  {
    for (dem::Contact &c : s.sim->contacts().entries())
      c.bond = dem::ContactBond{};
    if (mode == "touching")
      s.bonds = dem::bond_touching_pairs(s.sim->contacts(), s.sim->particles(), read_bond_settings(deck));
  }
  else
    for (const dem::Contact &c : s.sim->contacts().entries())
      s.bonds.bonded += c.bond.intact ? 1 : 0;
  finish_bonds(deck, s.sim->contacts(), s.sim->particles(), s.rate);
  s.cell = std::move(file.cell);
  std::ostringstream d;
  d << "prepared sample " << deck.text("sample/file") << " of " << s.sim->particles().size() << " balls";
  if (file.preparation.contains("solid_fraction_cell"))
    d << " (cell solid fraction " << file.preparation["solid_fraction_cell"].get<double>() << ", coordination "
      << file.preparation["coordination_number"].get<double>() << ")";
  s.cell.description = d.str();
  return s;
}
} // namespace

UniaxialResult run_uniaxial(const Deck &deck, const RunOptions &options)
{
  const int threads = apply_threads(options);
  const double window_lo = deck.real_list("measurement/fit window")[0];
  const double window_hi = deck.real_list("measurement/fit window")[1];
  if (!(window_hi > window_lo))
    deck.fail("measurement/fit window", "expected two increasing strains");
  Setup setup = deck.text("sample/source") == "file" ? sample_setup(deck) : lattice_setup(deck);

  UniaxialResult result;
  const dem::Specimen &specimen = setup.cell;
  const double area = specimen.area(), height0 = specimen.height, diameter = specimen.diameter;
  const dem::WallIndex bottom = specimen.bottom, top = specimen.top;
  result.sim = std::move(setup.sim);
  dem::Simulation &sim = *result.sim;
  const dem::BondReport &bonds = setup.bonds;
  const RateScaling setup_rate = setup.rate;

  dem::UniaxialSettings load;
  load.platen_speed = deck.text("loading/control") == "platen speed" ? deck.real("loading/platen speed") : 0;
  load.strain_rate = deck.real("loading/strain rate");
  load.ramp_time = deck.real("loading/ramp time");
  load.final_strain = deck.real("loading/final strain");
  load.both_platens = deck.text("loading/moving platens") == "both";
  const dem::UniaxialCompression test(sim, bottom, top, area, load);
  const dem::RadialGauges gauges(sim.particles(), dem::Vec3::Zero(), 0.5 * height0, height0,
                                 deck.real("measurement/gauge thickness"));
  // Gauge-thickness study (thesis §5.4.3, Fig. 5.13): the same measure with
  // bands of other thicknesses, against all balls on the circumference.
  const std::vector<double> study = deck.real_list("measurement/gauge study");
  for (double t : study)
    if (!(t > 0 && t <= 1))
      deck.fail("measurement/gauge study", "expected thicknesses in (0, 1]");
  std::vector<dem::RadialGauges> study_gauges;
  for (double t : study)
    study_gauges.emplace_back(sim.particles(), dem::Vec3::Zero(), 0.5 * height0, height0, t);
  const dem::RadialGauges circumference(sim.particles(), dem::Vec3::Zero(), 0.5 * height0, height0, 1.0 + 1e-9);
  const double sphere_r = deck.real("measurement/sphere radius") * diameter;
  const dem::MeasurementSphere spheres[2] = {{dem::Vec3(0, 0, height0 / 3), sphere_r},
                                             {dem::Vec3(0, 0, 2 * height0 / 3), sphere_r}};
  const double mean_radius = deck.real("sample/ball radius");
  const double density = deck.real("balls/density");
  const double strain_rate = test.final_speed() / height0;

  std::vector<std::string> columns = series_columns;
  if (!study.empty())
  {
    for (double t : study)
      columns.push_back("radial_strain_gauge_" + num_text(t));
    columns.push_back("radial_strain_circumference");
  }
  result.series = Series(columns);
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
        const double broken_d = double(sim.bonds_broken(dem::BreakMode::displacement));
        const double porosity = 0.5 * (dem::porosity(sim.particles(), sim.contacts(), spheres[0]) +
                                       dem::porosity(sim.particles(), sim.contacts(), spheres[1]));
        const double sphere_coordination =
          0.5 * (dem::coordination_number(sim.particles(), sim.contacts(), spheres[0]) +
                 dem::coordination_number(sim.particles(), sim.contacts(), spheres[1]));
        // Inertial number I = strain rate * d * sqrt(rho / p), p = sigma/3
        // for uniaxial stress; quasi-static when I << 1e-3.
        const double inertial = stress > 0 ? strain_rate * 2 * mean_radius * std::sqrt(density / (stress / 3)) : 0.0;
        row = {sim.time(), strain, stress, s_top, s_bottom, gauges.radial_strain(sim.particles()),
               (broken_t + broken_s + broken_d) / installed, broken_t, broken_s, broken_d,
               dem::coordination_number(sim.particles(), sim.contacts()), sphere_coordination, porosity,
               dem::unbalanced_force_ratio(sim.particles(), sim.contacts()), inertial, sim.time_step()};
        if (!study.empty())
        {
          for (const dem::RadialGauges &g : study_gauges)
            row.push_back(g.radial_strain(sim.particles()));
          row.push_back(circumference.radial_strain(sim.particles()));
        }
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
        row.insert(row.begin() + static_cast<std::ptrdiff_t>(series_columns.size()) - 7,
                   {e.kinetic, e.strain, e.friction, e.damping, e.bond_released, e.boundary_work, e.residual()});
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
  const auto [modulus, poisson] = fit_elastic(eps, sig, rad, window_lo, window_hi);
  const Peak pk = peak(eps, sig);
  double break_strain = 0, break_rate = 0;
  const bool has_breaks = x_at_max_rate(eps, broken, break_strain, break_rate) && break_rate > 0;
  const dem::EnergyLedger e = sim.energy();
  const dem::Index n = sim.particles().size();

  // Rate scaling and whether the quasi-static assumption held (rows past
  // 10 % of the final strain: the start-up is excluded).
  const double settled = 0.1 * load.final_strain;
  nlohmann::json rate = setup_rate.to_json();
  rate["quasi_static_indicators"] = {
    {"from_axial_strain", settled},
    {"max_inertial_number", max_after(result.series, settled, "inertial_number")},
    {"max_unbalanced_force_ratio", max_after(result.series, settled, "unbalanced_force_ratio")},
    {"max_kinetic_to_strain_energy", max_after(result.series, settled, "kinetic_energy_j", "strain_energy_j")},
    {"note", "quasi-static when the inertial number stays well below 1e-3 and the kinetic energy is a small "
             "fraction of the stored energy"}};
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
    {"rate", rate},
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
               {"broken_shear", sim.bonds_broken(dem::BreakMode::shear)},
               {"broken_displacement", sim.bonds_broken(dem::BreakMode::displacement)}}},
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
  if (dir && !study.empty() && result.series.rows() > 0)
    write_gauge_study(dir->path("gauge_study.csv"), result.series, study, study_gauges, convention);
  if (dir)
    dir->write_summary(result.summary);
  return result;
}
} // namespace verify
