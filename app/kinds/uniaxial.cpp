#include "app/kinds/uniaxial.h"

#include "app/decks/deck_sections.h"
#include "app/io/input.h"
#include "app/io/paraview.h"
#include "app/io/section.h"
#include "app/kinds/prepare.h"
#include "app/run/analysis.h"
#include "app/run/input_uncertainty.h"
#include "app/run/numerical_uncertainty.h"

#include "dem/measure.h"
#include "dem/protocol_uniaxial.h"
#include "dem/spatial_bands.h"
#include "dem/specimen.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <sstream>

namespace demvv
{
namespace
{
}

void declare_uniaxial(DeckSchema &s)
{
  s.text("title", "", "One line saying what this test is for (copied to summary.json).");
  s.enter("sample");
  s.choice("source", "lattice", {"lattice", "file"},
           "Where the balls come from: 'file' loads a prepared sample (thesis ch. 5); 'lattice' builds a "
           "regular lattice cylinder, a verification sample only.");
  s.file("file", "",
         "For source = file: a sample file (.json) written by a prepare run, or a prepare deck (.prm) whose "
         "sample is prepared on first use and cached in samples/ beside that deck ($DEMVV_CACHE when set).");
  s.choice("lattice", "fcc", {"fcc", "sc"}, "For source = lattice: face-centred or simple cubic.");
  s.real("ball radius", 0.885e-3, 0, inf, "m", "Radius of every ball (thesis: 1.77 mm diameter sand).",
         Interval::open_below);
  s.real("diameter", 0.0311, 0, inf, "m", "Target diameter of the sample (the rim balls fit inside).",
         Interval::open_below);
  s.real("height", 0.0311, 0, inf, "m", "Target height of the sample (the balls fit inside).", Interval::open_below);
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
         "Approach speed of the platens (thesis §6.3-6.4: 0.01 m/s is quasi-static).", Interval::open_below);
  s.real("strain rate", 0.3, 0, inf, "1/s", "Axial strain rate (compression positive).", Interval::open_below);
  s.real("ramp time", 0, 0, inf, "s", "The platen speed rises linearly from zero over this time (thesis §6.1).");
  s.real("final strain", 0.03, 0, 1, "-", "Axial strain at which the test stops (thesis: 3 %).", Interval::open_below);
  s.choice("moving platens", "top", {"top", "both"},
           "'top': the top platen moves, the bottom one is fixed (thesis); 'both': each moves at half speed "
           "(not for creep: its servo drives the top platen).");
  LoadingHistory::declare(s);
  s.leave();
  declare_rate(s);
  declare_motion(s, "0, 0, 0", 0.7);
  s.enter("measurement");
  s.real("gauge thickness", 0.8, 0, 1, "-",
         "Height of the central band of radial-strain gauges as a fraction of the sample height (thesis §5.4.3).",
         Interval::open_below);
  s.real("sphere radius", 0.3, 0, 0.5, "-",
         "Radius of the two measurement spheres (on the axis at 1/3 and 2/3 of the height) as a fraction of "
         "the sample diameter.",
         Interval::open_below);
  s.real_list("gauge study", "", 0, 20, "-",
              "Extra gauge thicknesses (fractions of the height) whose radial strain is recorded beside that of "
              "all circumference balls, as in thesis Fig. 5.13; empty for none.  Writes gauge_study.csv.");
  s.real_list("fit window", "0, 0.002", 2, 2, "-",
              "Axial strain interval over which the initial modulus and Poisson's ratio are fitted.");
  s.leave();
  s.enter("calibration");
  s.file("record", "",
         "The calibration.json of the demvv calibrate run that fitted this deck (its fitted.prm sets it; empty: "
         "none).  The run then refuses a deck whose fitted entries no longer hold the fitted values, and states "
         "in summary.json (uncertainty/input_calibration) the input uncertainty u_input of each calibrated "
         "quantity: the fitted values' standard errors through the model's sensitivity to them.");
  s.leave();
  s.enter("output");
  s.real("strain interval", 1e-4, 0, 1, "-", "Axial strain between output rows (constant-rate history).",
         Interval::open_below);
  s.real("time interval", 0, 0, inf, "s",
         "Time between output rows of the other histories (creep, relaxation, cyclic); 0: 1/500 of the test.");
  s.flag("paraview", false, "Write ParaView files (particles, contact forces, broken bonds) to paraview/.");
  s.real("paraview strain interval", 0.005, 0, 1, "-", "Axial strain between ParaView frames.", Interval::open_below);
  declare_checkpoint_interval(s);
  s.leave();
}

namespace
{
/// Largest ratio numerator / denominator of two series columns over the
/// rows whose `clock` column is >= from (denominator "" means 1).
/// The inertial number above which a test is not quasi-static (the bulk
/// runs stay near 3e-5, the compare lattices below 5e-4; check V27 argues
/// the same bound).
constexpr double quasi_static_inertial_number = 1e-3;

double max_after(const Series &s, const std::string &clock, double from, const std::string &numerator,
                 const std::string &denominator = "")
{
  const std::vector<double> c = s.column(clock), a = s.column(numerator);
  const std::vector<double> b = denominator.empty() ? std::vector<double>(a.size(), 1.0) : s.column(denominator);
  double out = 0;
  for (std::size_t k = 0; k < a.size(); ++k)
    if (c[k] >= from && b[k] > 0)
      out = std::max(out, a[k] / b[k]);
  return out;
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
    const auto band = series.column("radial_strain_gauge_" + format_number(study[k], 6));
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

/// section.csv: the sample's vertical section at the end of the run
/// (app/io/section.h); the section figure marks on it the bonds that broke
/// near the plane.
void write_end_section(const std::string &path, const dem::Simulation &sim, const std::string &convention)
{
  CsvSeries out(path, convention + "; at the end of the run, " + section_note(), section_columns());
  for (const SectionCircle &c : vertical_section(sim.particles()))
    out.write({c.x, c.z, c.radius});
}

const std::vector<std::string> uniaxial_columns = {"time_s",
                                                 "axial_strain",
                                                 "axial_stress_pa",
                                                 "axial_stress_top_pa",
                                                 "axial_stress_bottom_pa",
                                                 "radial_strain",
                                                 "bonds_broken_fraction",
                                                 "bonds_broken_tension",
                                                 "bonds_broken_shear",
                                                 "bonds_broken_displacement",
                                                 "coordination_number",
                                                 "coordination_number_spheres",
                                                 "mean_contact_force_n",
                                                 "porosity_spheres",
                                                 "unbalanced_force_ratio",
                                                 "inertial_number",
                                                 "time_step_s",
                                                 "kinetic_energy_j",
                                                 "strain_energy_j",
                                                 "friction_dissipated_j",
                                                 "damping_dissipated_j",
                                                 "bond_energy_released_j",
                                                 "boundary_work_j",
                                                 "energy_residual_j"};
} // namespace

namespace
{
/// The specimen of a uniaxial test, its simulation and its bonds.
struct Setup
{
  std::unique_ptr<dem::Simulation> sim;
  dem::Specimen cell; ///< wall indices, diameter, height, description
  dem::BondReport bonds;
  ResolvedLoading loading;
  RateScaling rate; ///< at loading.strain_rate
};

Setup lattice_setup(const UniaxialSpec &spec)
{
  const dem::BallSpec ball = spec.balls;
  dem::Specimen specimen =
    dem::lattice_specimen(spec.lattice, spec.ball_radius, spec.diameter, spec.height, ball, spec.platens, {}, false);
  if (specimen.particles.size() < 2)
    spec.deck.fail("sample/diameter", format_number(spec.diameter),
                   "the sample holds fewer than two balls of the given radius: expected a diameter and height of "
                   "several ball diameters");
  Setup s;
  s.loading = resolve_loading(spec, specimen.height);
  s.rate = spec.rate.scaling(s.loading.strain_rate);
  s.rate.scale_ball_stiffness(specimen.particles);
  s.sim = std::make_unique<dem::Simulation>(std::move(specimen.particles), std::move(specimen.walls),
                                            spec.law.make(s.rate), spec.motion);
  s.cell = std::move(specimen);
  s.sim->refresh_contacts();
  if (spec.bonds.install == "touching")
    s.bonds = dem::bond_touching_pairs(s.sim->contacts(), s.sim->particles(), spec.bonds.settings);
  spec.bonds.finish(s.sim->contacts(), s.sim->particles(), s.rate);
  return s;
}

/// A prepared sample with the deck's properties; its bonds are kept
/// (install = sample), replaced (touching) or removed (none).  A sample
/// prepared first shows its progress when `progress` (not under --quiet).
Setup sample_setup(const UniaxialSpec &spec, bool progress)
{
  SampleFile file = load_or_prepare_sample(spec.sample_file, progress);
  Setup s;
  s.loading = resolve_loading(spec, file.cell.height);
  s.rate = spec.rate.scaling(s.loading.strain_rate);
  const nlohmann::json preparation = file.preparation;
  TestSample sample =
    open_test_sample(std::move(file), scaled(spec.balls, s.rate), spec.platens, spec.law.make(s.rate), spec.motion);
  s.sim = std::move(sample.sim);
  if (spec.bonds.install != "sample")
  {
    for (dem::Contact &c : s.sim->contacts().entries())
      c.unbond();
    if (spec.bonds.install == "touching")
      s.bonds = dem::bond_touching_pairs(s.sim->contacts(), s.sim->particles(), spec.bonds.settings);
  }
  else
    for (const dem::Contact &c : s.sim->contacts().entries())
      s.bonds.bonded += c.bonded ? 1 : 0;
  spec.bonds.finish(s.sim->contacts(), s.sim->particles(), s.rate);
  s.cell = std::move(sample.cell);
  std::ostringstream d;
  d << "prepared sample " << spec.sample_name << " of " << s.sim->particles().size() << " balls";
  const nlohmann::json fraction = preparation.value("solid_fraction_cell", nlohmann::json());
  const nlohmann::json coordination = preparation.value("coordination_number", nlohmann::json());
  if (fraction.is_number() && coordination.is_number())
    d << " (cell solid fraction " << fraction.get<double>() << ", coordination " << coordination.get<double>() << ")";
  s.cell.description = d.str();
  return s;
}

constexpr int band_count = dem::CylinderBands::count;
using BandArray = std::array<double, band_count>;

/// A uniaxial test as the DEM driver runs it: the platens move (thesis
/// §6.1), rows record stress, strains, breakage, structure and energies.
class UniaxialProtocol final : public DemProtocol
{
public:
  UniaxialProtocol(const UniaxialSpec &spec, const Setup &setup, const dem::Simulation &sim, Series &series)
    : spec_(spec), cell_(setup.cell), bonds_(setup.bonds), rate_(setup.rate), series_(series),
      test_(sim, setup.cell.bottom, setup.cell.top, setup.cell.area(), platens(spec, setup.loading)),
      gauges_(sim.particles(), dem::Vec3::Zero(), 0.5 * setup.cell.height, setup.cell.height, spec.gauge_thickness),
      circumference_(sim.particles(), dem::Vec3::Zero(), 0.5 * setup.cell.height, setup.cell.height, 1.0 + 1e-9),
      spheres_{{dem::Vec3(0, 0, setup.cell.height / 3), spec.sphere_radius * setup.cell.diameter},
               {dem::Vec3(0, 0, 2 * setup.cell.height / 3), spec.sphere_radius * setup.cell.diameter}},
      strain_rate_(setup.loading.strain_rate), history_(setup.loading.history)
  {
    // Gauge-thickness study (thesis §5.4.3, Fig. 5.13): the same measure
    // with bands of other thicknesses, against all balls on the circumference.
    for (double t : spec.gauge_study)
      study_gauges_.emplace_back(sim.particles(), dem::Vec3::Zero(), 0.5 * setup.cell.height, setup.cell.height, t);
    std::vector<std::string> columns = uniaxial_columns;
    if (!spec.gauge_study.empty())
    {
      for (double t : spec.gauge_study)
        columns.push_back("radial_strain_gauge_" + format_number(t, 6));
      columns.push_back("radial_strain_circumference");
    }
    if (test_.scheduled())
      columns.push_back(history_.stress_controlled() ? "axial_stress_prescribed_pa" : "axial_strain_prescribed");
    series_ = Series(columns);
    bonds_by_band_ = dem::bonds_by_band(sim, bands(sim));
  }

  /// Six bands of equal volume of the sample as it stands: between the
  /// platens, about the axis through x = y = 0, of the cell's radius.
  dem::CylinderBands bands(const dem::Simulation &sim) const
  {
    const dem::Wall &bottom = sim.walls()[cell_.bottom], &top = sim.walls()[cell_.top];
    dem::CylinderBands b;
    b.axis = bottom.direction.normalized();
    b.base = b.axis * bottom.point.dot(b.axis);
    b.height = (top.point - bottom.point).dot(b.axis);
    b.radius = 0.5 * cell_.diameter;
    return b;
  }

  void observe_breaks(const dem::Simulation &sim, const std::vector<dem::BondBreak> &breaks) override
  {
    if (breaks.empty())
      return;
    const dem::CylinderBands now = bands(sim);
    for (const dem::BondBreak &b : breaks)
      if (b.mode != dem::BreakMode::none)
        breaks_by_band_[static_cast<int>(b.mode) - 1][now.band(b.point)] += 1;
  }

  /// The platens' schedule of the resolved loading.
  static dem::UniaxialSettings platens(const UniaxialSpec &spec, const ResolvedLoading &resolved)
  {
    dem::UniaxialSettings load;
    const LoadingHistory &h = resolved.history;
    if (h.stress_controlled())
      load.stress_schedule = [h](double t) { return h.axial_stress(t); };
    else if (h.kind != LoadingHistory::Kind::constant_rate)
      load.strain_schedule = [h](double t) { return h.axial_strain(t); };
    load.duration = h.duration();
    load.servo.relaxation = h.servo_relaxation;
    load.servo.integral = 0.05;
    load.platen_speed = spec.by_platen_speed ? spec.platen_speed : 0;
    load.strain_rate = spec.strain_rate;
    load.ramp_time = spec.ramp_time;
    load.final_strain = spec.final_strain;
    load.both_platens = spec.both_platens;
    return load;
  }

  std::string convention() const
  {
    return "demvv uniaxial '" + spec_.deck.name +
           "': SI units; compression positive for axial stress and strain; radial strain = -(r - r0)/r0; "
           "sample: " +
           cell_.description;
  }

  std::string label() const override { return "uniaxial " + spec_.deck.name; }
  std::string clock_name() const override { return test_.scheduled() ? "time_s" : "axial_strain"; }
  double clock(const dem::Simulation &sim) const override
  {
    return test_.scheduled() ? test_.elapsed(sim) : test_.axial_strain(sim);
  }
  double fraction_done(const dem::Simulation &sim) const override
  {
    return test_.scheduled() ? test_.elapsed(sim) / history_.duration() : test_.axial_strain(sim) / spec_.final_strain;
  }
  bool finished(const dem::Simulation &sim) const override { return test_.finished(sim); }
  double time_left(const dem::Simulation &sim) const override { return test_.time_left(sim); }
  [[noreturn]] void refuse_duration(const std::string &expected) const override
  {
    if (spec_.by_platen_speed)
      spec_.deck.fail("loading/platen speed", format_number(spec_.platen_speed), expected);
    spec_.deck.fail("loading/strain rate", format_number(spec_.strain_rate), expected);
  }
  std::string state_text(const dem::Simulation &sim) const override
  {
    char text[96];
    std::snprintf(text, sizeof text, "strain %.4f, stress %.4g MPa", test_.axial_strain(sim),
                  0.5e-6 * (test_.stress_top(sim) + test_.stress_bottom(sim)));
    return text;
  }

  void before_forces(dem::Simulation &sim) override { test_.before_forces(sim); }
  std::vector<double> checkpoint_values() const override
  {
    std::vector<double> v = {test_.servo_integral(), servo_error_, servo_square_sum_, servo_rows_};
    v.insert(v.end(), bonds_by_band_.begin(), bonds_by_band_.end());
    for (const BandArray &mode : breaks_by_band_)
      v.insert(v.end(), mode.begin(), mode.end());
    return v;
  }
  void restore_values(const std::vector<double> &values) override
  {
    test_.set_servo_integral(values[0]);
    servo_error_ = values[1];
    servo_square_sum_ = values[2];
    servo_rows_ = values[3];
    auto at = values.begin() + 4;
    for (BandArray *counts : {&bonds_by_band_, &breaks_by_band_[0], &breaks_by_band_[1], &breaks_by_band_[2]})
    {
      std::copy(at, at + band_count, counts->begin());
      at += band_count;
    }
  }
  /// Simulated duration of the test [s].
  double duration() const { return history_.duration(); }

  void measure(const dem::Simulation &sim) override
  {
    const double s_top = test_.stress_top(sim), s_bottom = test_.stress_bottom(sim);
    const double stress = 0.5 * (s_top + s_bottom);
    const double broken_t = double(sim.bonds_broken(dem::BreakMode::tension));
    const double broken_s = double(sim.bonds_broken(dem::BreakMode::shear));
    const double broken_d = double(sim.bonds_broken(dem::BreakMode::displacement));
    const double porosity = 0.5 * (dem::porosity(sim.particles(), sim.contacts(), spheres_[0]) +
                                   dem::porosity(sim.particles(), sim.contacts(), spheres_[1]));
    const double sphere_coordination = 0.5 * (dem::coordination_number(sim.particles(), sim.contacts(), spheres_[0]) +
                                              dem::coordination_number(sim.particles(), sim.contacts(), spheres_[1]));
    // Inertial number I = strain rate * d * sqrt(rho / p), p = sigma/3
    // for uniaxial stress; quasi-static when I << 1e-3.
    const double inertial =
      stress > 0 ? strain_rate_ * 2 * spec_.ball_radius * std::sqrt(spec_.balls.density / (stress / 3)) : 0.0;
    const double installed = static_cast<double>(std::max<std::size_t>(bonds_.bonded, 1));
    row_ = {sim.time(),
            test_.axial_strain(sim),
            stress,
            s_top,
            s_bottom,
            gauges_.radial_strain(sim.particles()),
            (broken_t + broken_s + broken_d) / installed,
            broken_t,
            broken_s,
            broken_d,
            dem::coordination_number(sim.particles(), sim.contacts()),
            sphere_coordination,
            dem::contact_force_statistics(sim.contacts()).mean,
            porosity,
            dem::unbalanced_force_ratio(sim.particles(), sim.contacts()),
            inertial,
            sim.time_step()};
    if (!spec_.gauge_study.empty())
    {
      for (const dem::RadialGauges &g : study_gauges_)
        row_.push_back(g.radial_strain(sim.particles()));
      row_.push_back(circumference_.radial_strain(sim.particles()));
    }
    if (test_.scheduled())
    {
      const double t = test_.elapsed(sim);
      row_.push_back(history_.stress_controlled() ? history_.axial_stress(t) : history_.axial_strain(t));
      if (history_.stress_controlled() && t >= history_.hold_start())
      {
        const double error = (s_top - history_.hold_stress) / history_.hold_stress;
        servo_error_ = std::max(servo_error_, std::abs(error));
        servo_square_sum_ += error * error;
        ++servo_rows_;
      }
    }
  }

  void record(const dem::Simulation &sim) override
  {
    const dem::EnergyLedger e = sim.energy();
    row_.insert(row_.begin() + static_cast<std::ptrdiff_t>(uniaxial_columns.size()) - 7,
                {e.kinetic, e.strain, e.friction, e.damping, e.bond_released, e.boundary_work, e.residual()});
    series_.add(std::move(row_));
    row_.clear();
  }

  /// The initial modulus and Poisson's ratio over the deck's fit window.
  ElasticFit elastic_fit() const
  {
    return fit_elastic(series_.column("axial_strain"), series_.column("axial_stress_pa"),
                       series_.column("radial_strain"), spec_.fit_from, spec_.fit_to);
  }

  std::vector<SeriesFile> series_files() override { return {{&series_, "series.csv", convention()}}; }

  nlohmann::json summary(const dem::Simulation &sim, const RunStatus &status, const ContactResolution &resolution,
                         const RunDirectory *dir) const override
  {
    const auto eps = series_.column("axial_strain");
    const auto sig = series_.column("axial_stress_pa");
    const auto broken = series_.column("bonds_broken_fraction");
    const auto [modulus, poisson] = elastic_fit();
    const Peak pk = peak(eps, sig);
    double break_strain = 0, break_rate = 0;
    const bool has_breaks = x_at_max_rate(eps, broken, break_strain, break_rate) && break_rate > 0;
    const dem::EnergyLedger e = sim.energy();
    const dem::Index n = sim.particles().size();

    // Rate scaling and whether the quasi-static assumption held (rows past
    // 10 % of the final strain: the start-up is excluded).
    // (A scheduled test: rows past a tenth of its duration.)
    const std::string clock = clock_name();
    const double settled = test_.scheduled() ? 0.1 * history_.duration() : 0.1 * spec_.final_strain;
    nlohmann::json rate = rate_.to_json();
    const double inertial = max_after(series_, clock, settled, "inertial_number");
    rate["quasi_static_indicators"] = {
      {test_.scheduled() ? "from_time_s" : "from_axial_strain", settled},
      {"max_inertial_number", inertial},
      {"max_unbalanced_force_ratio", max_after(series_, clock, settled, "unbalanced_force_ratio")},
      {"max_kinetic_to_strain_energy", max_after(series_, clock, settled, "kinetic_energy_j", "strain_energy_j")},
      {"note", "quasi-static when the inertial number stays well below 1e-3 and the kinetic energy is a small "
               "fraction of the stored energy"}};
    nlohmann::json resolved = resolution.to_json();
    resolved.erase("warning");
    resolved["quasi_static_note"] = "a quasi-static test need not resolve contact oscillations (see the "
                                    "quasi-static indicators); no warning is given here";
    nlohmann::json summary = {
      {"kind", "uniaxial"},
      {"title", spec_.title},
      {"sample",
       {{"description", cell_.description},
        {"particles", n},
        {"diameter_m", cell_.diameter},
        {"height_m", cell_.height},
        {"area_m2", cell_.area()},
        {"radial_gauges", gauges_.size()},
        {"measurement_sphere_radius_m", spec_.sphere_radius * cell_.diameter}}},
      {"contact_law", std::string(sim.model().name())},
      {"loading", loading_json()},
      {"rate", rate},
      {"peak_stress_pa", pk.value},
      {"strain_at_peak", pk.at},
      {"strain_at_max_breakage_rate", has_breaks ? nlohmann::json(break_strain) : nlohmann::json(nullptr)},
      {"max_breakage_rate_per_unit_strain", has_breaks ? nlohmann::json(break_rate) : nlohmann::json(nullptr)},
      {"initial_modulus_pa", modulus.points >= 2 ? nlohmann::json(modulus.slope) : nlohmann::json(nullptr)},
      {"poisson_ratio", poisson.points >= 2 ? nlohmann::json(poisson.slope) : nlohmann::json(nullptr)},
      {"initial_modulus_intercept_pa",
       modulus.points >= 2 ? nlohmann::json(modulus.intercept) : nlohmann::json(nullptr)},
      {"fit_window_axial_strain", {spec_.fit_from, spec_.fit_to}},
      {"fit_points", modulus.points},
      {"fit_r_squared", {{"modulus", modulus.r_squared}, {"poisson", poisson.r_squared}}},
      {"bonds",
       {{"installed", bonds_.bonded},
        {"removed", bonds_.removed},
        {"truncated_strength_draws", bonds_.truncated_draws},
        {"mean_normal_strength_n", bonds_.mean_normal_strength},
        {"mean_shear_strength_n", bonds_.mean_shear_strength},
        {"broken_tension", sim.bonds_broken(dem::BreakMode::tension)},
        {"broken_shear", sim.bonds_broken(dem::BreakMode::shear)},
        {"broken_displacement", sim.bonds_broken(dem::BreakMode::displacement)}}},
      {"coordination_number_at_end", dem::coordination_number(sim.particles(), sim.contacts())},
      {"steps", sim.steps()},
      {"last_time_step_s", sim.time_step()},
      {"critical_time_step_bound_s", sim.critical_time_step()},
      {"uncertainty",
       {{"numerical_time_step",
         numerical_time_step_uncertainty(double(n), spec_.motion.time_step_safety, spec_.motion.local_damping)},
        {"input_calibration", spec_.input_uncertainty}}},
      {"contact_resolution", resolved},
      {"neighbour_rebuilds", sim.neighbors().rebuilds()},
      {"energy_j",
       {{"kinetic", e.kinetic},
        {"strain", e.strain},
        {"friction", e.friction},
        {"damping", e.damping},
        {"bond_released", e.bond_released},
        {"boundary_work", e.boundary_work},
        {"residual", e.residual()}}},
      {"wall_seconds", status.wall_seconds},
      {"particle_steps_per_second", status.wall_seconds > 0 ? double(n) * sim.steps() / status.wall_seconds : 0.0}};
    // A test meant to be quasi-static that was not says so (exit 0: a
    // dynamic test is a run a user may want, but not one to read as the
    // quasi-static answer).
    if (inertial > quasi_static_inertial_number)
      summary["warnings"].push_back(
        "not quasi-static: the inertial number reached " + format_number(inertial, 3) +
        " after the start-up (quasi-static well below " + format_number(quasi_static_inertial_number) +
        "), so the stresses hold a dynamic part; a slower platen or strain rate gives the quasi-static answer");
    summary["spatial"] = spatial_json(sim);
    if (dir && !spec_.gauge_study.empty() && series_.rows() > 0)
      write_gauge_study(dir->path("gauge_study.csv"), series_, spec_.gauge_study, study_gauges_, convention());
    if (dir)
      write_end_section(dir->path("section.csv"), sim, convention());
    return summary;
  }

private:
  /// Where bonds broke and which way the contact forces run (Figs 7.4,
  /// 7.7, A.3), as numbers (dem/spatial_bands.h).
  nlohmann::json spatial_json(const dem::Simulation &sim) const
  {
    nlohmann::json names = nlohmann::json::array();
    for (int b = 0; b < band_count; ++b)
      names.push_back(dem::CylinderBands::name(b));
    BandArray all{};
    for (const BandArray &mode : breaks_by_band_)
      for (int b = 0; b < band_count; ++b)
        all[b] += mode[b];
    const auto counts = [&](const BandArray &observed)
    {
      const dem::BandCounts c = dem::band_counts(observed, bonds_by_band_);
      nlohmann::json ratio = nlohmann::json::array();
      for (int b = 0; b < band_count; ++b)
        ratio.push_back(c.expected[b] > 0
                          ? nlohmann::json({c.observed[b] / c.expected[b], c.ratio_low[b], c.ratio_high[b]})
                          : nlohmann::json(nullptr));
      return nlohmann::json{{"observed", c.observed},
                            {"expected_uniform", c.expected},
                            {"ratio_and_95_interval", ratio},
                            {"chi_square", c.chi_square},
                            {"degrees_of_freedom", c.degrees_of_freedom},
                            {"p_value", c.p_value}};
    };
    const dem::ContactDirections d = dem::contact_directions(sim, bands(sim).axis);
    const auto finite = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); };
    const auto direction = [&](const dem::DirectionMean &m)
    {
      return nlohmann::json{
        {"contacts", m.contacts}, {"mean_cos2_to_axis", finite(m.mean)}, {"half_width_95", finite(m.half_width)}};
    };
    return {{"bands", names},
            {"bands_note", "six bands of equal volume: thirds of the height between the platens (bottom, middle, top) "
                           "x core (r < R/sqrt(2)) and rim; a break counts in the band of the point on its two balls' "
                           "line of centres (the midpoint of equal balls) at the break"},
            {"bonds_installed_by_band", bonds_by_band_},
            {"bond_breaks_by_band",
             {{"all", counts(all)},
              {"tension", counts(breaks_by_band_[0])},
              {"shear", counts(breaks_by_band_[1])},
              {"displacement", counts(breaks_by_band_[2])},
              {"note", "expected_uniform: the breaks shared as the bonds were at the start (every bond struck alike); "
                       "ratio observed/expected with the exact Poisson 95 % interval; chi-square against the uniform "
                       "share (p optimistic: breaks come in cascades, not independently)"}}},
            {"contact_directions_at_end",
             {{"compressive", direction(d.compressive)},
              {"tensile", direction(d.tensile)},
              {"isotropic", 1.0 / 3.0},
              {"note", "mean (n . axis)^2 of the ball-ball contacts carrying force at the end of the run, axis the "
                       "bottom platen's normal, with its 95 % half-width; above 1/3 mainly along the axis, below "
                       "across it"}}}};
  }

  nlohmann::json loading_json() const
  {
    nlohmann::json j = {{"platen_speed_mps", test_.final_speed()},
                        {"strain_rate_per_s", strain_rate_},
                        {"ramp_time_s", spec_.ramp_time},
                        {"final_strain", spec_.final_strain},
                        {"moving_platens", spec_.both_platens ? "both" : "top"},
                        {"history", history_.name()}};
    if (test_.scheduled())
    {
      j.erase("final_strain");
      j.update(history_.to_json());
    }
    if (history_.stress_controlled())
    {
      j["servo_max_stress_error_fraction"] = servo_error_;
      j["servo_rms_stress_error_fraction"] = servo_rows_ > 0 ? std::sqrt(servo_square_sum_ / servo_rows_) : 0.0;
      j["servo_error_note"] = "top platen stress against the hold stress over the output rows of the hold; the "
                              "largest includes the packing's own oscillation";
    }
    return j;
  }

  const UniaxialSpec &spec_;
  const dem::Specimen &cell_;
  const dem::BondReport &bonds_;
  const RateScaling &rate_;
  Series &series_;
  dem::UniaxialCompression test_;
  dem::RadialGauges gauges_, circumference_;
  std::vector<dem::RadialGauges> study_gauges_;
  dem::MeasurementSphere spheres_[2];
  double strain_rate_;
  LoadingHistory history_;
  double servo_error_ = 0; ///< creep: largest |top stress - hold stress| / hold stress during the hold
  double servo_square_sum_ = 0, servo_rows_ = 0; ///< creep: for the RMS of that error
  std::vector<double> row_;
  BandArray bonds_by_band_{};                 ///< bonds each band held at the start
  std::array<BandArray, 3> breaks_by_band_{}; ///< tension, shear, displacement breaks by band
};
} // namespace

TestSample open_test_sample(SampleFile file, const dem::BallSpec &ball, const dem::WallProps &platens,
                            std::unique_ptr<dem::ContactModel> law, const dem::SimulationSettings &motion)
{
  apply_test_properties(file, ball, platens);
  TestSample t;
  t.sim = std::make_unique<dem::Simulation>(std::move(file.snapshot), std::move(law), motion);
  if (file.cell.lateral >= 0 && t.sim->walls()[file.cell.lateral].enabled)
    t.sim->set_wall_enabled(file.cell.lateral, false);
  t.cell = std::move(file.cell);
  return t;
}

UniaxialSpec parse_uniaxial(const Deck &deck)
{
  UniaxialSpec spec;
  spec.deck = DeckRecord(deck);
  spec.title = deck.text("title");
  spec.from_file = deck.text("sample/source") == "file";
  if (spec.from_file)
  {
    if (deck.text("sample/file").empty())
      deck.fail("sample/file", "expected a sample file (.json) or a prepare deck (.prm) when source = file");
    spec.sample_file = deck.file("sample/file");
    spec.sample_name = deck.text("sample/file");
    if (!std::filesystem::exists(spec.sample_file))
      deck.fail("sample/file", "no such file (" + spec.sample_file +
                                 "): expected a sample file (.json) or a prepare deck (.prm), relative to the deck");
    if (!std::filesystem::is_regular_file(spec.sample_file))
      deck.fail("sample/file", "not a regular file (a directory, device or pipe): expected a sample file (.json) "
                               "or a prepare deck (.prm)");
  }
  dem::parse_lattice(deck.text("sample/lattice"), spec.lattice);
  spec.ball_radius = deck.real("sample/ball radius");
  spec.diameter = deck.real("sample/diameter");
  spec.height = deck.real("sample/height");
  if (!spec.from_file)
  {
    const double sites = dem::lattice_cylinder_sites(spec.lattice, spec.ball_radius, spec.diameter, spec.height);
    check_memory(sites * sizeof(dem::Vec3) + dem::estimated_memory_bytes(sites, 3),
                 "a lattice of " + format_number(sites) + " sites", deck.path(), "sample/ball radius",
                 deck.text("sample/ball radius"), "expected a larger ball radius or a smaller sample");
  }
  spec.balls = parse_ball_properties(deck);
  spec.law = LawSpec::parse(deck);
  spec.bonds = BondSpec::parse(deck);
  if (!spec.from_file && spec.bonds.install == "sample")
    deck.fail("bonds/install", "a lattice sample has no bonds of its own: expected touching or none");
  spec.platens = parse_wall_properties(deck, "platens");
  spec.by_platen_speed = deck.text("loading/control") == "platen speed";
  spec.platen_speed = deck.real("loading/platen speed");
  spec.strain_rate = deck.real("loading/strain rate");
  spec.ramp_time = deck.real("loading/ramp time");
  spec.final_strain = deck.real("loading/final strain");
  spec.both_platens = deck.text("loading/moving platens") == "both";
  spec.history = LoadingHistory::parse(deck);
  if (spec.history.stress_controlled() && spec.both_platens)
    deck.fail("loading/moving platens", "creep drives the top platen by a servo: expected top");
  spec.time_interval = deck.real("output/time interval");
  spec.rate = RateSpec::parse(deck);
  spec.motion = parse_motion(deck);
  spec.gauge_thickness = deck.real("measurement/gauge thickness");
  spec.sphere_radius = deck.real("measurement/sphere radius");
  spec.gauge_study = deck.real_list("measurement/gauge study");
  for (double t : spec.gauge_study)
    if (!(t > 0 && t <= 1))
      deck.fail("measurement/gauge study", "expected thicknesses in (0, 1]");
  const std::vector<double> window = deck.real_list("measurement/fit window");
  spec.fit_from = window[0];
  spec.fit_to = window[1];
  if (!(spec.fit_to > spec.fit_from))
    deck.fail("measurement/fit window", "expected two increasing strains");
  if (!(spec.fit_from < spec.final_strain))
    deck.fail("measurement/fit window", "expected a window that starts below loading/final strain (" +
                                          format_number(spec.final_strain) + "): the test stops before it");
  spec.output.interval = deck.real("output/strain interval");
  spec.output.paraview = deck.flag("output/paraview");
  spec.output.paraview_interval = deck.real("output/paraview strain interval");
  spec.output.checkpoint_interval = deck.real("output/checkpoint interval");
  spec.input_uncertainty = input_uncertainty_block(deck);
  return spec;
}

ResolvedLoading resolve_loading(const UniaxialSpec &spec, double sample_height)
{
  ResolvedLoading r;
  r.strain_rate = spec.by_platen_speed ? spec.platen_speed / sample_height : spec.strain_rate;
  r.history = spec.history;
  r.history.strain_rate = r.strain_rate;
  return r;
}

UniaxialResult run_uniaxial(const UniaxialSpec &spec, const RunOptions &options)
{
  const int threads = apply_threads(options);
  Setup setup = spec.from_file ? sample_setup(spec, options.progress) : lattice_setup(spec);
  UniaxialResult result;
  result.loading = setup.loading;
  result.sample_diameter = setup.cell.diameter;
  result.sample_height = setup.cell.height;
  result.sim = std::move(setup.sim);
  UniaxialProtocol protocol(spec, setup, *result.sim, result.series);
  RunFiles files(options, spec.deck, threads, static_cast<long long>(spec.bonds.settings.seed), protocol.convention(),
                 spec.output.paraview);
  DemOutputSpec output = spec.output;
  if (spec.history.kind != LoadingHistory::Kind::constant_rate)
  {
    // The other histories are clocked in time.
    const double duration = protocol.duration();
    output.interval = spec.time_interval > 0 ? spec.time_interval : duration / 500;
    output.paraview_interval = duration / 20;
  }
  DemOutcome outcome = run_dem(*result.sim, protocol, files, output, options);
  result.status = outcome.status;
  result.summary = std::move(outcome.summary);
  result.elastic = protocol.elastic_fit();
  return result;
}

UniaxialResult run_uniaxial(const Deck &deck, const RunOptions &options)
{
  return run_uniaxial(parse_uniaxial(deck), options);
}
} // namespace demvv
