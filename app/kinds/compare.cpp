#include "app/kinds/compare.h"

#include "app/io/output.h"
#include "app/kinds/continuum_cylinder.h"
#include "app/run/analysis.h"

#include "dem/contact_model.h"
#include "dem/law_burgers.h"

#include "continuum/cylinder.h"
#include "continuum/homogenisation.h"
#include "continuum/numerical_failure.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

namespace demvv
{
void declare_compare(DeckSchema &s)
{
  declare_uniaxial(s);
  s.enter("comparison");
  s.choice("platens", "frictionless", {"frictionless", "bonded"},
           "Platens of both sides: 'frictionless' (the deck's DEM platens, and continuum platens that constrain "
           "only the axial displacement: a homogeneous state) or 'bonded' (DEM platens whose friction holds the "
           "balls, shear stiffness = normal; continuum platens that also hold the radial displacement: "
           "barrelling).");
  s.real("calibration strain", 0.002, 0, 0.1, "-",
         "Axial strain of the elastic calibration run (constant rate, every viscosity x 1e12); the measurement "
         "fit window must lie inside it.",
         Interval::open_below);
  s.integer("continuum degree", 2, 1, 4, "Polynomial degree of the continuum cylinder's Q_p elements.");
  s.integer("continuum refinements", 2, 1, 6,
            "Global refinements of the continuum mesh (cells about R / 2^refinements wide); the mesh error is "
            "estimated one level coarser.");
  s.integer("continuum time steps", 200, 2, 1000000,
            "Uniform continuum time steps over the history; the time-step error is estimated at half as many.");
  s.flag("dem time step study", false,
         "Run the DEM bulk test again at half the time-step safety and report the largest difference (the DEM "
         "side's time-step sensitivity).");
  s.real("tolerance", 0.05, 0, 1, "-",
         "Largest relative difference of the compared quantity (DEM against the calibrated continuum) that passes "
         "inside the correspondence identity's conditions (same-shape chains, no bond broken, no friction slip, "
         "frictionless platens, quasi-static: inertial number below 1e-3): what inertia, geometric "
         "nonlinearity, contact changes and platen compliance leave at small strain (check V23 argues 5 %).  "
         "Outside those conditions the difference is a model-form difference, reported with the conditions that "
         "failed, never passed or failed.",
         Interval::open_below);
  s.leave();
}

CompareSpec parse_compare(const Deck &deck)
{
  CompareSpec spec;
  spec.dem = parse_uniaxial(deck);
  if (spec.dem.law.keyword != "burgers" && spec.dem.law.keyword != "modified_burgers")
    deck.fail("contact law/law", "the continuum is a Burger's solid built from the contacts: expected burgers or "
                                 "modified_burgers");
  if (spec.dem.history.kind == LoadingHistory::Kind::constant_rate && spec.dem.final_strain > 0.2)
    deck.fail("loading/final strain",
              "the continuum is small-strain theory and cannot take this history: expected at most 0.2");
  spec.bonded_platens = deck.text("comparison/platens") == "bonded";
  spec.calibration_strain = deck.real("comparison/calibration strain");
  if (spec.dem.fit_to > spec.calibration_strain)
    deck.fail("measurement/fit window", "the elastic fit reaches beyond the calibration run: expected a window "
                                        "inside comparison/calibration strain (" +
                                          format_number(spec.calibration_strain) + ")");
  spec.degree = static_cast<unsigned int>(deck.integer("comparison/continuum degree"));
  spec.refinements = static_cast<unsigned int>(deck.integer("comparison/continuum refinements"));
  spec.time_steps = static_cast<unsigned int>(deck.integer("comparison/continuum time steps"));
  spec.dem_time_step_study = deck.flag("comparison/dem time step study");
  spec.tolerance = deck.real("comparison/tolerance");
  if (spec.bonded_platens)
  {
    // Friction far above any force ratio a compression test reaches: the
    // platen contacts stick, as bonded continuum platens do.
    spec.dem.platens.ks = spec.dem.platens.kn;
    spec.dem.platens.friction = 100;
  }
  return spec;
}

namespace
{
/// One continuum cylinder's response, step by step.
struct ContinuumCurve
{
  std::vector<double> time, strain, stress, radial;
  continuum::CylinderMesh mesh;
  double wall_seconds = 0;
};

ContinuumCurve compress_cylinder(const continuum::CylinderSpec &test)
{
  ContinuumCurve c;
  const auto start = std::chrono::steady_clock::now();
  continuum::CompressionTest compression(test);
  c.mesh = compression.mesh();
  compression.run(
    [&](const continuum::CylinderStep &s)
    {
      c.time.push_back(s.time);
      c.strain.push_back(s.axial_strain);
      c.stress.push_back(s.axial_stress);
      c.radial.push_back(s.radial_strain);
    });
  c.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return c;
}

/// y(t) by linear interpolation in a table of increasing times (held at the ends).
double at_time(const std::vector<double> &times, const std::vector<double> &ys, double t)
{
  const auto it = std::upper_bound(times.begin(), times.end(), t);
  if (it == times.begin())
    return ys.front();
  if (it == times.end())
    return ys.back();
  const std::size_t k = static_cast<std::size_t>(it - times.begin());
  const double w = (t - times[k - 1]) / (times[k] - times[k - 1]);
  return ys[k - 1] + w * (ys[k] - ys[k - 1]);
}

std::vector<double> resampled(const std::vector<double> &times, const std::vector<double> &ys,
                              const std::vector<double> &at)
{
  std::vector<double> out;
  for (double t : at)
    out.push_back(at_time(times, ys, t));
  return out;
}

/// The largest |a - b| over max |b|, and the row where it occurs.
struct Gap
{
  double relative = std::nan("");
  std::size_t row = 0;
};

Gap largest_gap(const std::vector<double> &a, const std::vector<double> &b)
{
  Gap g;
  const double scale = max_abs(b);
  if (!(scale > 0))
    return g;
  double worst = -1;
  for (std::size_t k = 0; k < a.size(); ++k)
    if (std::abs(a[k] - b[k]) > worst)
    {
      worst = std::abs(a[k] - b[k]);
      g.row = k;
    }
  g.relative = worst / scale;
  return g;
}

/// A uniaxial run's options for a part of the comparison in `part/` of the run directory.
RunOptions part_options(const RunOptions &options, const std::string &part)
{
  RunOptions o = options;
  o.out_dir = options.out_dir.empty() ? "" : options.out_dir + "/" + part;
  o.resume = false;
  o.pause_after = 0;
  o.resumable_alone = false;
  return o;
}

/// The deck's contact constants (rate-scaled) as a normal chain [N/m, N s/m],
/// the shear-to-normal ratio r and whether every shear constant is r x
/// the normal one.
struct ContactChain
{
  continuum::BurgersChain normal;
  double shear_ratio = 0;
  bool same_shape = false;
  double reference_stiffness = 0; ///< K_ref [N/m]
};

/// The contacts' chains as the law itself reads its constants
/// (BurgersLawT::constants_from), scaled by the rate.
ContactChain contact_chain(const UniaxialSpec &spec, const RateScaling &rate)
{
  const bool modified = spec.law.keyword == "modified_burgers";
  const dem::LawParameters p = spec.law.scaled_constants(rate);
  const dem::BurgersContactConstants k =
    modified ? dem::ModifiedBurgersLaw::constants_from(p) : dem::BurgersLaw::constants_from(p);
  ContactChain c;
  c.normal = {k.normal.maxwell_stiffness, k.normal.maxwell_viscosity, k.normal.kelvin_stiffness,
              k.normal.kelvin_viscosity};
  c.shear_ratio = k.shear.maxwell_stiffness / k.normal.maxwell_stiffness;
  c.same_shape = true;
  for (const auto &[shear, normal] : {std::pair{k.shear.maxwell_viscosity, k.normal.maxwell_viscosity},
                                      std::pair{k.shear.kelvin_stiffness, k.normal.kelvin_stiffness},
                                      std::pair{k.shear.kelvin_viscosity, k.normal.kelvin_viscosity}})
    c.same_shape = c.same_shape && std::abs(shear / normal - c.shear_ratio) <= 1e-12 * c.shear_ratio;
  c.reference_stiffness = modified ? k.compression_stiffness : k.normal.maxwell_stiffness;
  return c;
}

const std::vector<std::string> compare_columns = {"time_s",
                                                  "axial_strain_dem",
                                                  "axial_stress_dem_pa",
                                                  "radial_strain_dem",
                                                  "axial_strain_calibrated",
                                                  "axial_stress_calibrated_pa",
                                                  "radial_strain_calibrated",
                                                  "axial_strain_affine",
                                                  "axial_stress_affine_pa",
                                                  "radial_strain_affine",
                                                  "stress_difference_calibrated_pa",
                                                  "stress_difference_affine_pa",
                                                  "strain_difference_calibrated",
                                                  "strain_difference_affine"};

/// Whether the run lies inside the correspondence identity's conditions
/// (SPEC: same-shape Burger's chains, a fixed bonded network, no slip,
/// frictionless platens, quasi-static), and what its difference then means.
nlohmann::json gap_json(const Gap &g, const Series &s)
{
  if (!std::isfinite(g.relative))
    return nullptr;
  return {{"relative", g.relative}, {"time_s", s.row(g.row)[0]}, {"axial_strain_dem", s.row(g.row)[1]}};
}
} // namespace

nlohmann::json identity_verdict(const CompareSpec &spec, bool same_shape, const nlohmann::json &bulk, double difference)
{
  const nlohmann::json &bonds = bulk.at("bonds");
  const long broken =
    bonds.value("broken_tension", 0L) + bonds.value("broken_shear", 0L) + bonds.value("broken_displacement", 0L);
  const nlohmann::json &energy = bulk.at("energy_j");
  const double slip = energy.value("friction", 0.0), stored = std::abs(energy.value("strain", 0.0));
  const nlohmann::json &qs = bulk.at("rate").at("quasi_static_indicators");
  const double inertial = qs.value("max_inertial_number", 0.0);
  const std::vector<std::pair<std::string, bool>> conditions = {
    {"same-shape chains (every shear constant the same multiple of the normal one)", same_shape},
    {"no bond broken (" + std::to_string(broken) + " broke)", broken == 0},
    {"no friction slip (friction dissipated " + format_number(slip) + " J against " + format_number(stored) +
       " J stored)",
     slip <= 1e-6 * stored},
    {"frictionless platens", !spec.bonded_platens},
    {"quasi-static (largest inertial number " + format_number(inertial) + " below 1e-3)", inertial < 1e-3}};
  nlohmann::json failed = nlohmann::json::array(), held = nlohmann::json::array();
  for (const auto &[condition, ok] : conditions)
    (ok ? held : failed).push_back(condition);
  nlohmann::json v = {{"inside_identity", failed.empty()},
                      {"conditions_held", held},
                      {"conditions_failed", failed},
                      {"difference_relative", std::isfinite(difference) ? nlohmann::json(difference) : nullptr},
                      {"tolerance_relative", spec.tolerance}};
  const std::string percent = format_number(100 * difference, 3) + " %";
  if (failed.empty())
  {
    const bool pass = difference <= spec.tolerance;
    v["result"] = pass ? "pass" : "fail";
    v["line"] = std::string("inside the correspondence identity: DEM against the calibrated continuum ") + percent +
                (pass ? " within " : " beyond ") + "the tolerance " + format_number(100 * spec.tolerance) +
                " %: " + (pass ? "pass" : "FAIL");
  }
  else
  {
    std::string why;
    for (const auto &f : failed)
      why += (why.empty() ? "" : "; ") + f.get<std::string>();
    v["result"] = "model-form difference";
    v["line"] = "model-form difference (outside the correspondence identity: " + why +
                "): DEM against the "
                "calibrated continuum " +
                percent + ", not judged against a tolerance";
  }
  return v;
}

CompareResult run_compare(const CompareSpec &spec, const RunOptions &options)
{
  if (continuum::parallel_info().ranks > 1)
    throw DeckError(spec.dem.deck.path + ": a compare deck runs in one process (OpenMP threads for the DEM, a small "
                                         "continuum): expected no mpirun");
  const int threads = apply_threads(options);
  CompareResult out;
  std::unique_ptr<RunDirectory> dir;
  if (!options.out_dir.empty())
    dir = std::make_unique<RunDirectory>(options.out_dir, spec.dem.deck, threads,
                                         static_cast<long long>(spec.dem.bonds.settings.seed));
  const auto start = std::chrono::steady_clock::now();
  const auto finish = [&](nlohmann::json summary)
  {
    out.status.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    summary["status"] = out.status.to_json();
    summary["wall_seconds"] = out.status.wall_seconds;
    out.summary = summary;
    if (dir)
      dir->write_summary(summary);
  };
  nlohmann::json summary = {{"kind", "compare"}, {"title", spec.dem.title}};

  // 1. The elastic calibration on this sample: the same contacts, elastic
  // (every constant the law declares a viscosity 1e12 times larger: the
  // dashpots lock and each chain is its springs).
  UniaxialSpec elastic = spec.dem;
  for (const dem::LawConstant &c : dem::find_law(elastic.law.keyword)->deck_constants)
    if (c.scaling == dem::RateScaled::viscosity)
      elastic.law.constants.values[std::string(c.key)] = 1e12 * elastic.law.constants[c];
  elastic.history = LoadingHistory{};
  elastic.history.ramp_time = spec.dem.ramp_time;
  elastic.history.final_strain = spec.calibration_strain;
  elastic.final_strain = spec.calibration_strain;
  elastic.output.interval = spec.calibration_strain / 50;
  elastic.output.paraview = false;
  elastic.gauge_study.clear();
  const UniaxialResult calibration = run_uniaxial(elastic, part_options(options, "calibration"));
  out.status = calibration.status;
  const nlohmann::json &cs = calibration.summary;
  summary["calibration"] = {{"run", "calibration/"},
                            {"young_modulus_pa", cs["initial_modulus_pa"]},
                            {"poisson_ratio", cs["poisson_ratio"]},
                            {"fit_window_axial_strain", cs["fit_window_axial_strain"]},
                            {"fit_r_squared", cs["fit_r_squared"]},
                            {"note", "the deck's contacts with every viscosity x 1e12: each Burger's element is its "
                                     "Maxwell spring on the test's time scale"}};
  const ElasticFit &fit = calibration.elastic;
  if (out.status.fault || out.status.interrupted_by || fit.modulus.points < 2 || fit.poisson.points < 2)
  {
    if (!out.status.fault && !out.status.interrupted_by)
    {
      out.status.fault = true;
      out.status.message = "the elastic calibration gave no modulus (no rows inside the fit window)";
    }
    finish(summary);
    return out;
  }
  const double young = fit.modulus.slope, poisson = fit.poisson.slope;

  // 2. The DEM bulk test.
  const UniaxialResult bulk = run_uniaxial(spec.dem, part_options(options, "dem"));
  out.status = bulk.status;
  if (out.status.fault || out.status.interrupted_by)
  {
    finish(summary);
    return out;
  }
  const Series &d = bulk.series;
  const std::vector<double> time = d.column("time_s");

  // 3. The packing, measured on the same sample at the start of the test.
  const dem::ParticleStore &balls = bulk.sim->particles();
  double radius = 0;
  for (dem::Index b = 0; b < balls.size(); ++b)
    radius += balls.radius[b];
  radius /= double(balls.size());
  const continuum::PackingGeometry packing{d.column("coordination_number_spheres").front(),
                                           1 - d.column("porosity_spheres").front(), radius};
  const RateScaling rate = spec.dem.rate.scaling(bulk.loading.strain_rate);
  const ContactChain chain = contact_chain(spec.dem, rate);
  const continuum::ElasticModuli affine =
    continuum::affine_moduli(packing, chain.reference_stiffness, chain.shear_ratio * chain.reference_stiffness);

  // 4. The continuum by both routes, with the same history on the sample's size.
  LoadingHistory history = bulk.loading.history;
  if (history.kind == LoadingHistory::Kind::constant_rate)
    history.final_strain = d.column("axial_strain").back();
  continuum::CylinderSpec test;
  test.radius = 0.5 * bulk.sample_diameter;
  test.height = bulk.sample_height;
  test.platens = spec.bonded_platens ? continuum::Platens::bonded : continuum::Platens::frictionless;
  test.degree = spec.degree;
  test.refinements = spec.refinements;
  test.time_steps = spec.time_steps;
  apply_history(history, test);
  if (!test.axial_strain_history && !test.axial_stress_history)
  {
    // A constant rate from rest: the same schedule as a function, so every
    // history takes one path.
    const LoadingHistory h = history;
    test.axial_strain_history = [h](double t) { return h.axial_strain(t); };
    test.duration = h.duration();
  }
  continuum::CylinderSpec calibrated_test = test, affine_test = test;
  calibrated_test.solid = continuum::calibrated_burgers_solid(chain.normal, young, poisson, chain.reference_stiffness);
  // The affine route is the calibrated one with the affine moduli (for
  // same-shape Burger's contacts this is continuum::affine_burgers_solid).
  affine_test.solid =
    continuum::calibrated_burgers_solid(chain.normal, affine.young, affine.poisson, chain.reference_stiffness);
  ContinuumCurve calibrated, by_affine, half_steps, coarser;
  try
  {
    calibrated = compress_cylinder(calibrated_test);
    by_affine = compress_cylinder(affine_test);
    continuum::CylinderSpec t = calibrated_test;
    t.time_steps = std::max(1u, spec.time_steps / 2);
    half_steps = compress_cylinder(t);
    t = calibrated_test;
    t.refinements = spec.refinements - 1;
    coarser = compress_cylinder(t);
  }
  catch (const continuum::NumericalFailure &f)
  {
    record_failure(out.status, f);
    finish(summary);
    return out;
  }

  // 5. Side by side at the DEM's rows.
  out.series = Series(compare_columns);
  if (dir)
    out.series.stream_to(dir->path("compare.csv"),
                         "demvv compare '" + spec.dem.deck.name +
                           "': SI units; compression positive; radial strain = -(r - r0)/r0 (DEM: gauge band; "
                           "continuum: surface at mid-height); continuum interpolated in time at the DEM rows; "
                           "differences are DEM - continuum");
  const std::vector<double> e_dem = d.column("axial_strain"), s_dem = d.column("axial_stress_pa"),
                            r_dem = d.column("radial_strain");
  const auto cal_e = resampled(calibrated.time, calibrated.strain, time),
             cal_s = resampled(calibrated.time, calibrated.stress, time),
             cal_r = resampled(calibrated.time, calibrated.radial, time),
             aff_e = resampled(by_affine.time, by_affine.strain, time),
             aff_s = resampled(by_affine.time, by_affine.stress, time),
             aff_r = resampled(by_affine.time, by_affine.radial, time);
  for (std::size_t k = 0; k < time.size(); ++k)
    out.series.add({time[k], e_dem[k], s_dem[k], r_dem[k], cal_e[k], cal_s[k], cal_r[k], aff_e[k], aff_s[k], aff_r[k],
                    s_dem[k] - cal_s[k], s_dem[k] - aff_s[k], e_dem[k] - cal_e[k], e_dem[k] - aff_e[k]});

  // 6. What differs, and how much of it the numerics could explain.
  const bool creep = history.stress_controlled();
  const std::string compared = creep ? "axial strain (the stress is prescribed)" : "axial stress";
  const Gap cal_gap = creep ? largest_gap(e_dem, cal_e) : largest_gap(s_dem, cal_s);
  const Gap aff_gap = creep ? largest_gap(e_dem, aff_e) : largest_gap(s_dem, aff_s);
  const auto quantity = [&](const ContinuumCurve &c) { return creep ? c.strain : c.stress; };
  const double scale = max_abs(quantity(calibrated));
  const double time_error = max_abs(
                              [&]
                              {
                                const auto coarse = resampled(half_steps.time, quantity(half_steps), calibrated.time);
                                std::vector<double> diff;
                                for (std::size_t k = 0; k < coarse.size(); ++k)
                                  diff.push_back((quantity(calibrated)[k] - coarse[k]) / 3);
                                return diff;
                              }()) /
                            scale;
  const double mesh_error = relative_deviation(quantity(coarser), quantity(calibrated));
  nlohmann::json dem_sensitivity = nullptr;
  if (spec.dem_time_step_study)
  {
    UniaxialSpec finer = spec.dem;
    finer.motion.time_step_safety *= 0.5;
    const UniaxialResult rerun = run_uniaxial(finer, part_options(options, "dem_half_time_step"));
    if (!rerun.status.fault && !rerun.status.interrupted_by)
    {
      const std::string column = creep ? "axial_strain" : "axial_stress_pa";
      const auto again = resampled(rerun.series.column("time_s"), rerun.series.column(column), time);
      dem_sensitivity = {{"run", "dem_half_time_step/"},
                         {"time_step_safety", finer.motion.time_step_safety},
                         {"largest_relative_difference", relative_deviation(d.column(column), again)}};
    }
  }
  const nlohmann::json &qs = bulk.summary["rate"]["quasi_static_indicators"];
  summary["sample"] = bulk.summary["sample"];
  summary["contact_law"] = bulk.summary["contact_law"];
  summary["loading"] = bulk.summary["loading"];
  summary["platens"] = spec.bonded_platens ? "bonded" : "frictionless";
  summary["contacts"] = {{"normal_chain_n_per_m_and_n_s_per_m",
                          {chain.normal.maxwell_spring, chain.normal.maxwell_dashpot, chain.normal.kelvin_spring,
                           chain.normal.kelvin_dashpot}},
                         {"shear_ratio", chain.shear_ratio},
                         {"same_shape", chain.same_shape},
                         {"reference_stiffness_n_per_m", chain.reference_stiffness}};
  summary["packing_measured"] = {{"coordination_number", packing.coordination},
                                 {"solid_fraction", packing.solid_fraction},
                                 {"mean_radius_m", packing.radius},
                                 {"where", "the two measurement spheres at the start of the DEM bulk test"}};
  summary["moduli"] = {{"young_dem_pa", young},
                       {"poisson_dem", poisson},
                       {"young_affine_pa", affine.young},
                       {"poisson_affine", affine.poisson},
                       {"non_affine_ratio", young / affine.young},
                       {"note", "E_DEM / E_affine below 1: the packing relaxes non-affinely (its contacts do not "
                                "follow the mean strain), which the affine (Voigt) route ignores"}};
  summary["compared_quantity"] = compared;
  summary["verdict"] = identity_verdict(spec, chain.same_shape, bulk.summary, cal_gap.relative);
  out.status.verdict = summary["verdict"]["line"].get<std::string>();
  summary["difference_calibrated"] = gap_json(cal_gap, out.series);
  summary["difference_affine"] = gap_json(aff_gap, out.series);
  summary["uncertainty"] = {{"continuum_time_step_relative", time_error},
                            {"continuum_mesh_relative_bound", mesh_error},
                            {"continuum_note",
                             "time: (fine - half steps) / 3, Richardson for order 2; mesh: the difference from one "
                             "refinement coarser, a bound (exact for frictionless platens: a homogeneous state)"},
                            {"dem_time_step", dem_sensitivity},
                            {"dem_quasi_static_indicators", qs}};
  summary["continuum"] = {{"degree", spec.degree},
                          {"refinements", spec.refinements},
                          {"cells", calibrated.mesh.cells},
                          {"time_steps", spec.time_steps},
                          {"wall_seconds", calibrated.wall_seconds + by_affine.wall_seconds + half_steps.wall_seconds +
                                             coarser.wall_seconds}};
  summary["calibrated_solid_uniaxial_chain_pa_and_pa_s"] = {
    calibrated_test.solid.young.maxwell_spring, calibrated_test.solid.young.maxwell_dashpot,
    calibrated_test.solid.young.kelvin_spring, calibrated_test.solid.young.kelvin_dashpot};
  summary["runs"] = {{"calibration", "calibration/"}, {"dem", "dem/"}};
  finish(summary);
  return out;
}

CompareResult run_compare(const Deck &deck, const RunOptions &options)
{
  return run_compare(parse_compare(deck), options);
}
} // namespace demvv
