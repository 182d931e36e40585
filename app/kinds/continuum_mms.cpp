#include "app/kinds/continuum_mms.h"

#include "app/io/output.h"
#include "app/kinds/continuum_cylinder.h"
#include "app/kinds/continuum_material.h"

#include "continuum/numerical_failure.h"

#include <chrono>
#include <cmath>
#include <limits>

namespace demvv
{
void declare_mms(DeckSchema &s)
{
  s.text("title", "", "One line saying what this study is for (copied to summary.json).");
  declare_cylinder_geometry(s);
  declare_continuum_material(s);
  s.enter("study");
  s.choice("variable", "space", {"space", "time"},
           "'space': refine the mesh (time functions quadratic, integrated exactly); 'time': halve the time step "
           "on one mesh (fields affine in space, represented exactly).");
  s.choice("model", "axisymmetric", {"axisymmetric", "3d"}, "Axisymmetric meridian or 3D quarter cylinder.");
  s.integer("degree", 2, 1, 4, "Polynomial degree p of the Q_p elements.");
  s.real_list("levels", "0, 1, 2, 3", 3, 8, "-",
              "Refinement levels (space) or halvings of the time step (time), increasing; the observed orders of "
              "the finest three are reported.");
  s.real("duration", 2, 0, inf, "s", "Time span T of the manufactured solution.", Interval::open_below);
  s.integer("time steps", 2, 1, 1000000, "Time steps at every level (space) or at level 0 (time).");
  s.integer("refinements", 0, 0, 8, "Mesh refinements of the time study.");
  s.real("solver tolerance", 1e-12, 0, 1e-3, "-", "Relative residual at which the CG solver stops.",
         Interval::open_below);
  s.leave();
}

MmsDeckSpec parse_mms(const Deck &deck)
{
  MmsDeckSpec spec;
  spec.deck = DeckRecord(deck);
  spec.title = deck.text("title");
  continuum::MmsSpec &study = spec.study;
  const CylinderGeometry geometry = parse_cylinder_geometry(deck);
  study.radius = geometry.radius;
  study.height = geometry.height;
  const ContinuumMaterial material = parse_continuum_material(deck);
  study.solid = material.solid;
  spec.material = material.description;
  study.variable = deck.text("study/variable") == "time" ? continuum::MmsVariable::time : continuum::MmsVariable::space;
  study.geometry =
    deck.text("study/model") == "3d" ? continuum::Geometry::three_dimensional : continuum::Geometry::axisymmetric;
  study.degree = static_cast<unsigned int>(deck.integer("study/degree"));
  study.levels.clear();
  for (const double v : deck.real_list("study/levels"))
  {
    if (!(v >= 0 && v <= 8 && v == std::floor(v)) || (!study.levels.empty() && v <= study.levels.back()))
      deck.fail("study/levels", "expected increasing integers between 0 and 8");
    study.levels.push_back(static_cast<unsigned int>(v));
  }
  study.duration = deck.real("study/duration");
  study.time_steps = static_cast<unsigned int>(deck.integer("study/time steps"));
  study.refinements = static_cast<unsigned int>(deck.integer("study/refinements"));
  study.solver_tolerance = deck.real("study/solver tolerance");
  return spec;
}

std::vector<ConvergenceTable> mms_tables(const std::vector<continuum::MmsLevel> &levels, const continuum::MmsSpec &spec)
{
  const bool space = spec.variable == continuum::MmsVariable::space;
  const double p = spec.degree;
  const std::string study =
    std::string(space ? "MMS in space, Q" : "MMS in time, Q") + std::to_string(spec.degree) +
    (spec.geometry == continuum::Geometry::axisymmetric ? " axisymmetric" : " 3D quarter") +
    (spec.solid.bulk == continuum::BulkResponse::same_shape ? ", same-shape bulk" : ", elastic bulk");
  struct Quantity
  {
    const char *name;
    double expected;
    double continuum::MmsLevel::*error;
  };
  const Quantity quantities[] = {
    {"relative L2 error of u", space ? p + 1 : 0, &continuum::MmsLevel::displacement_l2},
    {"relative H1-seminorm error of u", space ? p : 0, &continuum::MmsLevel::displacement_h1},
    {"relative L2 error of the stress", space ? p : 2, &continuum::MmsLevel::stress_l2},
    {"relative L2 error of the Kelvin strain", space ? p : 2, &continuum::MmsLevel::kelvin_l2}};
  std::vector<ConvergenceTable> tables;
  for (const Quantity &q : quantities)
  {
    ConvergenceTable t;
    t.title = study + ": " + q.name;
    t.h_name = space ? "h [m]" : "dt [s]";
    t.error_name = q.name;
    t.expected_order = q.expected;
    for (const continuum::MmsLevel &l : levels)
      t.add(space ? l.cell_size : l.time_step, l.*q.error);
    tables.push_back(t);
  }
  return tables;
}

MmsResult run_mms_deck(const Deck &deck, const RunOptions &options) { return run_mms_deck(parse_mms(deck), options); }

MmsResult run_mms_deck(const MmsDeckSpec &spec, const RunOptions &options)
{
  const int threads = apply_threads(options);
  const continuum::MmsSpec &study = spec.study;
  const bool writer = continuum::parallel_info().rank == 0 && !options.out_dir.empty();
  std::unique_ptr<RunDirectory> dir;
  if (writer)
    dir = std::make_unique<RunDirectory>(options.out_dir, spec.deck, threads, 0);

  MmsResult result;
  const auto start = std::chrono::steady_clock::now();
  try
  {
    result.levels = continuum::run_mms(study);
  }
  catch (const continuum::NumericalFailure &f)
  {
    record_failure(result.status, f);
  }
  result.status.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  result.status.writes_run_directory = continuum::parallel_info().rank == 0;

  const bool space = study.variable == continuum::MmsVariable::space;
  const std::vector<ConvergenceTable> tables = mms_tables(result.levels, study);
  const std::vector<std::string> names = {"displacement_l2", "displacement_h1", "stress_l2", "kelvin_l2"};
  nlohmann::json orders = nlohmann::json::object(), expected = nlohmann::json::object();
  for (std::size_t k = 0; k < names.size(); ++k)
  {
    orders[names[k]] = tables[k].last_order();
    expected[names[k]] = tables[k].expected_order;
  }
  result.summary = {{"kind", "mms"},
                    {"title", spec.title},
                    {"status", result.status.to_json()},
                    {"variable", space ? "space" : "time"},
                    {"model", geometry_keyword(study.geometry)},
                    {"degree", study.degree},
                    {"errors", "relative to the norm of the manufactured field, at the final time"},
                    {"observed_orders_finest_pair", orders},
                    {"expected_orders", expected},
                    {"material", spec.material},
                    {"wall_seconds", result.status.wall_seconds}};
  if (dir)
  {
    Series table({"level", "cells", "dofs", "cell_size_m", "time_step_s", "steps", "displacement_l2", "displacement_h1",
                  "stress_l2", "kelvin_l2", "order_displacement_l2", "order_displacement_h1", "order_stress_l2",
                  "order_kelvin_l2"});
    table.stream_to(dir->path("convergence.csv"), "demvv mms '" + spec.deck.name +
                                                    "': relative errors at the final time; orders against the "
                                                    "previous level (" +
                                                    std::string(space ? "h" : "dt") + ")");
    for (std::size_t i = 0; i < result.levels.size(); ++i)
    {
      const continuum::MmsLevel &l = result.levels[i];
      std::vector<double> row = {double(l.level), double(l.cells), double(l.dofs),
                                 l.cell_size,     l.time_step,     double(l.steps)};
      for (const ConvergenceTable &t : tables)
        row.push_back(t.rows[i].error);
      for (const ConvergenceTable &t : tables)
        row.push_back(i == 0 ? std::nan("") : t.rows[i].order);
      table.add(row);
    }
    write_atomically(dir->path("convergence.txt"), continuum::mms_convergence_text(result.levels, study.variable));
    dir->write_summary(result.summary);
  }
  return result;
}
} // namespace demvv
