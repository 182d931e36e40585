#include "app/kinds/continuum_cylinder.h"

#include "app/io/output.h"
#include "app/kinds/continuum_material.h"
#include "app/reference/continuum_reference.h"
#include "app/run/analysis.h"

#include "continuum/numerical_failure.h"

#include <chrono>
#include <cmath>
#include <limits>

namespace demvv
{
namespace
{
}

void declare_cylinder_geometry(DeckSchema &s)
{
  s.enter("geometry");
  s.real("radius", 0.01555, 0, inf, "m", "Radius R of the cylinder (the DEM stand-in sample: 31.1 mm diameter).",
         Interval::open_below);
  s.real("height", 0.0311, 0, inf, "m", "Height H of the cylinder, between R/4 and 16 R.", Interval::open_below);
  s.leave();
}

void declare_cylinder(DeckSchema &s)
{
  s.text("title", "", "One line saying what this run is for (copied to summary.json).");
  declare_cylinder_geometry(s);
  declare_continuum_material(s);
  s.enter("loading");
  s.choice("platens", "frictionless", {"frictionless", "bonded"},
           "Platen contact: 'frictionless' (axial displacement only: homogeneous, equals the 1-D closed form) or "
           "'bonded' (no radial motion on the platens: barrelling).");
  s.real("strain rate", 0.005, 0, inf, "1/s", "Axial strain rate, compression positive (thesis §7.2.3: 0.005).",
         Interval::open_below);
  s.real("final strain", 0.02, 0, 0.2, "-", "Axial strain at which a constant-rate test stops (small-strain theory).",
         Interval::open_below);
  s.real("ramp time", 0, 0, inf, "s",
         "The loading speed rises linearly from zero over this time (as the DEM platens do; creep: the stress "
         "rises over it).");
  LoadingHistory::declare(s);
  s.leave();
  s.enter("discretisation");
  s.choice("model", "axisymmetric", {"axisymmetric", "3d"},
           "'axisymmetric': (r, z) meridian with hoop strain and weight 2 pi r; '3d': a quarter cylinder with "
           "symmetry planes (a check of the axisymmetric model).");
  s.integer("degree", 2, 1, 4, "Polynomial degree p of the Q_p elements (and of the geometry mapping).");
  s.integer("refinements", 2, 0, 8,
            "Global refinements of the coarse mesh, whose cells are about R wide (h = R / 2^refinements).");
  s.integer("time steps", 100, 1, 10000000,
            "Uniform time steps to the final strain, or over the whole history (trapezoidal update, order 2; a "
            "kink of the history between two step times costs the step one order).");
  s.real("solver tolerance", 1e-12, 0, 1e-3, "-", "Relative residual at which the CG solver stops.",
         Interval::open_below);
  s.leave();
  s.enter("study");
  s.real_list("gci refinements", "", 0, 4, "-",
              "Empty: one run.  Three or four increasing refinement levels: a grid-convergence study (Roache's GCI, "
              "Celik et al. 2008) of the peak stress and the stress at 1 % strain, one run per level in "
              "level_<N>/; with four levels the coarser triplet is reported too.");
  s.real("gci safety factor", 1.25, 1, 3, "-", "Safety factor Fs of the GCI (1.25 for three meshes).");
  s.leave();
  s.enter("measurement");
  s.real_list("fit window", "0, 0.002", 2, 2, "-",
              "Axial strain interval over which the initial modulus and Poisson's ratio are fitted.");
  s.leave();
  s.enter("output");
  s.flag("paraview", false, "Write ParaView files (displacement, cell stresses, Kelvin strain) to paraview/.");
  s.integer("paraview every", 10, 1, 10000000, "Time steps between ParaView frames (the last step is always written).");
  s.leave();
}

continuum::History ode_history(const LoadingHistory &h)
{
  if (h.stress_controlled())
    return continuum::History::general([h](double t) { return h.axial_stress(t); },
                                       [h](double t, double p) { return h.rate_on_piece(t, p); }, h.kinks(),
                                       h.largest_prescribed());
  return continuum::History::general([h](double t) { return h.axial_strain(t); },
                                     [h](double t, double p) { return h.rate_on_piece(t, p); }, h.kinks(),
                                     h.largest_prescribed());
}

void apply_history(const LoadingHistory &h, continuum::CylinderSpec &cylinder)
{
  cylinder.strain_rate = h.strain_rate;
  cylinder.final_strain = h.final_strain;
  if (h.kind == LoadingHistory::Kind::constant_rate && h.ramp_time == 0)
    return;
  if (h.stress_controlled())
    cylinder.axial_stress_history = [h](double t) { return h.axial_stress(t); };
  else
    cylinder.axial_strain_history = [h](double t) { return h.axial_strain(t); };
  cylinder.duration = h.duration();
}

CylinderGeometry parse_cylinder_geometry(const Deck &deck)
{
  const CylinderGeometry g{deck.real("geometry/radius"), deck.real("geometry/height")};
  if (g.height < 0.25 * g.radius || g.height > 16 * g.radius)
    deck.fail("geometry/height", "expected a height between R/4 and 16 R (the coarse mesh has cells about R wide)");
  return g;
}

const char *geometry_keyword(continuum::Geometry geometry)
{
  return geometry == continuum::Geometry::three_dimensional ? "3d" : "axisymmetric";
}

double interpolate(const std::vector<double> &xs, const std::vector<double> &ys, double x)
{
  for (std::size_t k = 1; k < xs.size(); ++k)
    if (xs[k - 1] <= x && x <= xs[k])
      return ys[k - 1] + (ys[k] - ys[k - 1]) * (x - xs[k - 1]) / (xs[k] - xs[k - 1]);
  return std::nan("");
}

namespace
{
const std::vector<std::string> columns = {"time_s",
                                          "axial_strain",
                                          "axial_stress_pa",
                                          "radial_strain",
                                          "axial_stress_closed_form_pa",
                                          "radial_strain_closed_form",
                                          "cg_iterations",
                                          "axial_strain_closed_form"};

nlohmann::json number_or_null(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

const char *platens_keyword(continuum::Platens platens)
{
  return platens == continuum::Platens::bonded ? "bonded" : "frictionless";
}

/// The 1-D chain's response (CVODE) at every step time of a test with a
/// history; empty for a constant rate from rest, which has its closed form.
std::vector<continuum::OdeState> history_reference(const LoadingHistory &history, const continuum::CylinderSpec &test)
{
  if (!test.axial_strain_history && !test.axial_stress_history)
    return {};
  const continuum::BurgersOde ode(test.solid.uniaxial(), ode_control(history), ode_history(history));
  std::vector<double> times;
  for (unsigned int n = 0; n <= test.time_steps; ++n)
    times.push_back(test.duration * n / test.time_steps);
  continuum::OdeTolerances tolerances;
  tolerances.relative = 1e-10;
  return ode.solve(times, tolerances);
}

nlohmann::json loading_json(const LoadingHistory &history, const continuum::CylinderSpec &test)
{
  nlohmann::json j = history.to_json();
  j["platens"] = platens_keyword(test.platens);
  j["reference"] = test.axial_strain_history || test.axial_stress_history
                     ? "the 1-D chain under the same history (CVODE, relative tolerance 1e-10)"
                     : "eq. 7.18 (constant velocity)";
  if (history.kind != LoadingHistory::Kind::constant_rate)
    j.erase("final_strain");
  return j;
}

/// One compression test of a deck (`test` is its test at one level); the
/// series streams to series_path when it is not empty, and the mesh's edges
/// go beside it (mesh.csv) when one rank holds the whole mesh.
CylinderResult compress(const CylinderDeckSpec &spec, const continuum::CylinderSpec &test,
                        const std::string &series_path)
{
  CylinderResult run;
  run.series = Series(columns);
  if (!series_path.empty())
    run.series.stream_to(series_path, "demvv cylinder '" + spec.deck.name +
                                        "': SI units; compression positive for axial stress and strain; "
                                        "radial strain = -u_r/R at mid-height; closed form: eq. 7.18 with the "
                                        "solid's uniaxial chain (homogeneous state)");
  const dem::BurgersConstants uniaxial = burgers_constants(test.solid.uniaxial());
  const std::vector<continuum::OdeState> reference = history_reference(spec.history, test);
  const continuum::ParallelInfo mpi = continuum::parallel_info();
  Progress progress(mpi.rank == 0 ? "cylinder " + spec.deck.name : "");
  const auto start = std::chrono::steady_clock::now();
  long iterations = 0;
  try
  {
    continuum::CompressionTest compression(test);
    run.mesh = compression.mesh();
    if (!series_path.empty() && mpi.ranks == 1)
      write_atomically(series_path.substr(0, series_path.rfind('/') + 1) + "mesh.csv", compression.mesh_edges_csv());
    compression.run(
      [&](const continuum::CylinderStep &s)
      {
        double closed = 0, closed_strain = s.axial_strain;
        if (reference.empty())
          closed = uniaxial.constant_velocity_force(s.time, test.strain_rate);
        else
        {
          closed = reference[s.step].force;
          closed_strain = reference[s.step].displacement;
        }
        run.series.add({s.time, s.axial_strain, s.axial_stress, s.radial_strain, closed,
                        test.solid.lateral_strain(closed_strain, closed) + 0.0, double(s.iterations), closed_strain});
        iterations += s.iterations;
        run.status.steps = s.step;
        run.status.time = s.time;
        if (mpi.rank == 0)
          progress.update(double(s.step) / test.time_steps, "strain " + std::to_string(s.axial_strain));
      });
  }
  catch (const continuum::NumericalFailure &f)
  {
    record_failure(run.status, f);
  }
  progress.finish();
  run.status.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  run.status.writes_run_directory = mpi.rank == 0;

  const auto eps = run.series.column("axial_strain");
  const auto sig = run.series.column("axial_stress_pa");
  const auto rad = run.series.column("radial_strain");
  const auto closed = run.series.column("axial_stress_closed_form_pa");
  const auto [modulus, poisson] = fit_elastic(eps, sig, rad, spec.fit_from, spec.fit_to);
  const Peak pk = peak(eps, sig);
  double deviation = 0, scale = 0;
  for (std::size_t k = 0; k < sig.size(); ++k)
  {
    deviation = std::max(deviation, std::abs(sig[k] - closed[k]));
    scale = std::max(scale, std::abs(closed[k]));
  }
  run.summary = {
    {"kind", "cylinder"},
    {"title", spec.title},
    {"status", run.status.to_json()},
    {"geometry",
     {{"radius_m", test.radius},
      {"height_m", test.height},
      {"model", geometry_keyword(test.geometry)},
      {"nominal_platen_area_m2", run.mesh.platen_area},
      {"mesh_platen_area_m2", run.mesh.mesh_platen_area}}},
    {"material", spec.material},
    {"loading", loading_json(spec.history, test)},
    {"discretisation",
     {{"degree", test.degree},
      {"refinements", test.refinements},
      {"cells", run.mesh.cells},
      {"dofs", run.mesh.dofs},
      {"cell_size_m", run.mesh.cell_size},
      {"time_steps", test.time_steps},
      {"time_step_s", run.mesh.time_step},
      {"time_scheme", "trapezoidal (Crank-Nicolson), order 2"},
      {"solver", "CG + Trilinos AMG"},
      {"solver_tolerance", test.solver_tolerance},
      {"cg_iterations", iterations},
      {"mpi_ranks", run.mesh.ranks}}},
    {"peak_stress_pa", number_or_null(pk.value)},
    {"strain_at_peak", number_or_null(pk.at)},
    {"stress_at_1_percent_strain_pa", number_or_null(interpolate(eps, sig, 0.01))},
    {"initial_modulus_pa", modulus.points >= 2 ? nlohmann::json(modulus.slope) : nlohmann::json(nullptr)},
    {"poisson_ratio", poisson.points >= 2 ? nlohmann::json(poisson.slope) : nlohmann::json(nullptr)},
    {"fit_window_axial_strain", {spec.fit_from, spec.fit_to}},
    {"radial_strain_at_end", rad.empty() ? nlohmann::json(nullptr) : nlohmann::json(rad.back())},
    {"max_deviation_from_homogeneous_closed_form", number_or_null(scale > 0 ? deviation / scale : std::nan(""))},
    {"max_strain_deviation_from_homogeneous_closed_form",
     number_or_null(relative_deviation(eps, run.series.column("axial_strain_closed_form")))},
    {"wall_seconds", run.status.wall_seconds}};
  return run;
}

/// The refinement levels of a GCI study (empty: a single run).
std::vector<unsigned int> parse_study_levels(const Deck &deck)
{
  const std::string key = "study/gci refinements";
  std::vector<unsigned int> levels;
  for (const double v : deck.real_list(key))
  {
    if (!(v >= 0 && v <= 8 && v == std::floor(v)) || (!levels.empty() && v <= levels.back()))
      deck.fail(key, "expected increasing integer refinement levels between 0 and 8");
    levels.push_back(static_cast<unsigned int>(v));
  }
  if (!levels.empty() && levels.size() < 3)
    deck.fail(key, "expected three or four levels (a GCI needs three meshes)");
  return levels;
}

nlohmann::json gci_json(const GciResult &g)
{
  return {{"values_fine_to_coarse", {g.phi[0], g.phi[1], g.phi[2]}},
          {"cell_sizes_m_fine_to_coarse", {g.h[0], g.h[1], g.h[2]}},
          {"observed_order", number_or_null(g.order)},
          {"extrapolated", number_or_null(g.extrapolated)},
          {"approximate_relative_error", g.approximate_error},
          {"extrapolated_relative_error", number_or_null(g.extrapolated_error)},
          {"gci_fine", number_or_null(g.gci_fine)},
          {"gci_coarse", number_or_null(g.gci_coarse)},
          {"asymptotic_range_ratio", number_or_null(g.asymptotic_ratio)},
          {"monotone", g.monotone}};
}

/// GCI of the peak stress and the stress at 1 % strain over three levels.
void add_gci(const std::vector<CylinderResult> &runs, std::size_t finest, double safety, CylinderResult &out,
             nlohmann::json &summary)
{
  double h[3], peak_stress[3], at_one[3];
  for (int i = 0; i < 3; ++i)
  {
    const CylinderResult &r = runs[finest - i];
    h[i] = r.mesh.cell_size;
    peak_stress[i] = r.summary["peak_stress_pa"].is_number() ? r.summary["peak_stress_pa"].get<double>() : std::nan("");
    at_one[i] = r.summary["stress_at_1_percent_strain_pa"].is_number()
                  ? r.summary["stress_at_1_percent_strain_pa"].get<double>()
                  : std::nan("");
  }
  out.gci.push_back(grid_convergence_index(h, peak_stress, safety));
  out.gci.push_back(grid_convergence_index(h, at_one, safety));
  summary.push_back(
    {{"levels_fine_to_coarse",
      {runs[finest].summary["discretisation"]["refinements"], runs[finest - 1].summary["discretisation"]["refinements"],
       runs[finest - 2].summary["discretisation"]["refinements"]}},
     {"peak_stress_pa", gci_json(out.gci[out.gci.size() - 2])},
     {"stress_at_1_percent_strain_pa", gci_json(out.gci.back())}});
}
} // namespace

CylinderDeckSpec parse_cylinder(const Deck &deck)
{
  CylinderDeckSpec spec;
  spec.deck = DeckRecord(deck);
  spec.title = deck.text("title");
  continuum::CylinderSpec &test = spec.test;
  const CylinderGeometry geometry = parse_cylinder_geometry(deck);
  test.radius = geometry.radius;
  test.height = geometry.height;
  const ContinuumMaterial material = parse_continuum_material(deck);
  test.solid = material.solid;
  spec.material = material.description;
  test.platens =
    deck.text("loading/platens") == "bonded" ? continuum::Platens::bonded : continuum::Platens::frictionless;
  spec.history = LoadingHistory::parse(deck);
  apply_history(spec.history, test);
  test.time_steps = static_cast<unsigned int>(deck.integer("discretisation/time steps"));
  test.geometry = deck.text("discretisation/model") == "3d" ? continuum::Geometry::three_dimensional
                                                            : continuum::Geometry::axisymmetric;
  test.degree = static_cast<unsigned int>(deck.integer("discretisation/degree"));
  test.refinements = static_cast<unsigned int>(deck.integer("discretisation/refinements"));
  test.solver_tolerance = deck.real("discretisation/solver tolerance");
  test.paraview_every = static_cast<unsigned int>(deck.integer("output/paraview every"));
  spec.paraview = deck.flag("output/paraview");
  spec.gci_levels = parse_study_levels(deck);
  spec.gci_safety_factor = deck.real("study/gci safety factor");
  const std::vector<double> window = deck.real_list("measurement/fit window");
  if (!(window[1] > window[0]))
    deck.fail("measurement/fit window", "expected two increasing strains");
  spec.fit_from = window[0];
  spec.fit_to = window[1];
  return spec;
}

CylinderResult run_cylinder(const Deck &deck, const RunOptions &options)
{
  return run_cylinder(parse_cylinder(deck), options);
}

CylinderResult run_cylinder(const CylinderDeckSpec &spec, const RunOptions &options)
{
  const int threads = apply_threads(options);
  continuum::CylinderSpec test = spec.test;
  const std::vector<unsigned int> &levels = spec.gci_levels;
  const continuum::ParallelInfo mpi = continuum::parallel_info();
  const bool writer = mpi.rank == 0 && !options.out_dir.empty();
  std::unique_ptr<RunDirectory> dir;
  if (writer)
    dir = std::make_unique<RunDirectory>(options.out_dir, spec.deck, threads, 0);
  const bool paraview = spec.paraview && !options.out_dir.empty();

  if (levels.empty())
  {
    if (paraview)
      test.paraview_directory = options.out_dir + "/paraview";
    CylinderResult run = compress(spec, test, writer ? dir->path("series.csv") : "");
    if (dir)
      dir->write_summary(run.summary);
    return run;
  }

  std::vector<CylinderResult> runs;
  nlohmann::json level_summaries = nlohmann::json::array();
  RunStatus status;
  status.writes_run_directory = mpi.rank == 0;
  for (const unsigned int level : levels)
  {
    test.refinements = level;
    const std::string level_dir = options.out_dir + "/level_" + std::to_string(level);
    if (paraview)
      test.paraview_directory = level_dir + "/paraview";
    if (writer)
      make_directories(level_dir);
    runs.push_back(compress(spec, test, writer ? level_dir + "/series.csv" : ""));
    nlohmann::json &s = runs.back().summary;
    if (writer)
    {
      nlohmann::json copy = s;
      copy["provenance"] = provenance(threads, 0, spec.deck.resolved);
      copy["provenance"]["note"] = "one level of a GCI study: refinements overridden to " + std::to_string(level);
      write_atomically(level_dir + "/summary.json", json_text(copy, 2) + "\n");
    }
    level_summaries.push_back({{"refinements", level},
                               {"cells", runs.back().mesh.cells},
                               {"dofs", runs.back().mesh.dofs},
                               {"cell_size_m", runs.back().mesh.cell_size},
                               {"peak_stress_pa", s["peak_stress_pa"]},
                               {"stress_at_1_percent_strain_pa", s["stress_at_1_percent_strain_pa"]},
                               {"wall_seconds", runs.back().status.wall_seconds}});
    status.steps += runs.back().status.steps;
    status.wall_seconds += runs.back().status.wall_seconds;
    status.time = runs.back().status.time;
    if (runs.back().status.fault)
    {
      status.fault = true;
      status.step = runs.back().status.step;
      status.message = "level " + std::to_string(level) + ": " + runs.back().status.message;
      break;
    }
  }

  CylinderResult out;
  out.series = std::move(runs.back().series);
  out.mesh = runs.back().mesh;
  out.status = status;
  nlohmann::json studies = nlohmann::json::array();
  if (!status.fault)
  {
    add_gci(runs, runs.size() - 1, spec.gci_safety_factor, out, studies);
    if (runs.size() == 4)
      add_gci(runs, 2, spec.gci_safety_factor, out, studies);
  }
  out.summary = {
    {"kind", "cylinder"},         {"title", spec.title},
    {"status", status.to_json()}, {"study", "grid convergence index, Celik et al. (2008); finest triplet first"},
    {"levels", level_summaries},  {"gci", studies},
    {"material", spec.material},  {"wall_seconds", status.wall_seconds}};
  if (dir)
    dir->write_summary(out.summary);
  return out;
}
} // namespace demvv
