#include "app/plot/run_figures.h"

#include "app/decks/csv_input.h"
#include "app/decks/deck.h"
#include "app/io/input.h"
#include "app/io/output.h"
#include "app/io/text.h"
#include "app/plot/studies.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>
#include <sys/stat.h>

namespace demvv
{
namespace
{
bool exists(const std::string &path)
{
  struct stat st
  {
  };
  return stat(path.c_str(), &st) == 0;
}

/// A CSV file of the run, read to learn which columns hold data (nan where
/// the run had no value); figures refer to it from RUN_DIR/plots as
/// `from_plots`.
struct RunTable
{
  std::unique_ptr<CsvTable> table;
  std::string from_plots;

  RunTable(const std::string &run_dir, const std::string &file) : from_plots("../" + file)
  {
    // A run directory may come from anyone: its tables are read only as
    // regular files of its own, never through a link to a file elsewhere.
    const std::string path = run_dir + "/" + file;
    std::error_code ec;
    const std::filesystem::file_status st = std::filesystem::symlink_status(path, ec);
    if (ec || !std::filesystem::exists(st))
      return;
    if (!std::filesystem::is_regular_file(st))
      throw DeckError(path + ": a link or a special file, not a table the run wrote: expected a regular file");
    table = std::make_unique<CsvTable>(CsvTable::read(path, CsvTable::Values::any_number));
  }
  bool usable() const { return table && table->rows() > 0; }
  bool has(const std::string &column) const { return usable() && table->has(column); }
  /// A column with at least one non-zero finite value.
  bool carries(const std::string &column) const
  {
    if (!has(column))
      return false;
    for (std::size_t r = 0; r < table->rows(); ++r)
    {
      const double v = table->get(r, column);
      if (v != 0 && std::isfinite(v))
        return true;
    }
    return false;
  }
};

struct Line
{
  std::string title, column;
  double scale = 1;
  CurveStyle style = CurveStyle::line;
  bool right_axis = false;
};

struct Axes
{
  std::string name, title, x_label, y_label;
  std::string y2_label = "";
};

/// A figure of columns of one table against one of its columns; lines whose
/// column the table lacks are left out, and so is a figure with no line.
void add_figure(std::vector<Figure> &out, const RunTable &t, const Axes &axes, const std::string &x_column,
                double x_scale, const std::vector<Line> &lines, bool log_y = false)
{
  if (!t.has(x_column))
    return;
  Figure f;
  f.name = axes.name;
  f.title = axes.title;
  f.x_label = axes.x_label;
  f.y_label = axes.y_label;
  f.y2_label = axes.y2_label;
  f.log_y = log_y;
  for (const Line &l : lines)
    if (t.has(l.column) && (!log_y || t.carries(l.column)))
    {
      Curve c = column_curve(l.title, t.from_plots, x_column, l.column, x_scale, l.scale, l.style);
      c.right_axis = l.right_axis;
      f.curves.push_back(std::move(c));
    }
  if (!f.curves.empty())
    out.push_back(std::move(f));
}

const std::vector<Line> energy_lines = {
  {"kinetic", "kinetic_energy_j"},
  {"strain (contacts and bonds)", "strain_energy_j"},
  {"friction dissipated", "friction_dissipated_j"},
  {"damping dissipated", "damping_dissipated_j"},
  {"released by broken bonds", "bond_energy_released_j"},
  {"boundary work", "boundary_work_j", 1, CurveStyle::dashed},
  {"gravity work", "gravity_work_j", 1, CurveStyle::dashed},
};

/// The balance error in its own figure (beside the ledger it is a line near
/// zero that hides the small terms), with the boundary work on the right
/// axis to read it against.
const std::vector<Line> residual_lines = {
  {"residual (supplied - held - dissipated)", "energy_residual_j"},
  {"boundary work, for scale (right axis)", "boundary_work_j", 1, CurveStyle::dashed, true},
};

const std::vector<Line> broken_by_mode = {
  {"tension", "bonds_broken_tension"},
  {"shear", "bonds_broken_shear"},
  {"displacement criterion", "bonds_broken_displacement"},
};

void uniaxial_figures(const std::string &dir, std::vector<Figure> &out)
{
  const RunTable s(dir, "series.csv");
  const std::string strain = "axial strain [%]";
  add_figure(out, s, {"stress_strain", "Axial stress against axial strain", strain, "axial stress [MPa]"},
             "axial_strain", 100,
             {{"mean of the platens", "axial_stress_pa", 1e-6},
              {"top platen", "axial_stress_top_pa", 1e-6, CurveStyle::dashed},
              {"bottom platen", "axial_stress_bottom_pa", 1e-6, CurveStyle::dashed}});
  add_figure(out, s,
             {"damage", "Stress and bonds broken against strain (thesis Fig. 6.1)", strain, "axial stress [MPa]",
              "bonds broken [% of installed]"},
             "axial_strain", 100,
             {{"axial stress", "axial_stress_pa", 1e-6},
              {"bonds broken", "bonds_broken_fraction", 100, CurveStyle::dashed, true}});
  add_figure(
    out, s,
    {"radial_strain", "Radial strain of the gauges against axial strain", strain, "radial strain [%] (-(r - r0)/r0)"},
    "axial_strain", 100, {{"radial strain", "radial_strain", 100}});
  add_figure(out, s, {"bonds_broken_by_mode", "Bonds broken by mode", strain, "bonds broken"}, "axial_strain", 1e2,
             broken_by_mode);
  add_figure(out, s, {"energy", "Energy ledger", strain, "energy [J]"}, "axial_strain", 100, energy_lines);
  add_figure(out, s, {"energy_residual", "Energy balance error", strain, "residual [J]", "boundary work [J]"},
             "axial_strain", 100, residual_lines);
  add_figure(out, s, {"time_step", "Time step", "time [s]", "time step [µs]"}, "time_s", 1,
             {{"time step", "time_step_s", 1e6}});
  add_figure(out, s, {"quasi_static", "Quasi-static indicators", strain, "ratio [-]"}, "axial_strain", 100,
             {{"unbalanced force ratio", "unbalanced_force_ratio"}, {"inertial number", "inertial_number"}}, true);
}

void scene_figures(const std::string &dir, std::vector<Figure> &out)
{
  const RunTable s(dir, "series.csv");
  add_figure(out, s, {"energy", "Energy ledger", "time [s]", "energy [J]"}, "time_s", 1, energy_lines);
  add_figure(out, s, {"energy_residual", "Energy balance error", "time [s]", "residual [J]", "boundary work [J]"},
             "time_s", 1, residual_lines);
  add_figure(out, s, {"time_step", "Time step", "time [s]", "time step [µs]"}, "time_s", 1,
             {{"time step", "time_step_s", 1e6}});
  std::vector<Line> counts = {{"contacts", "contacts"}, {"bonds intact", "bonds_intact"}};
  for (const Line &l : broken_by_mode)
    counts.push_back({"bonds broken in " + l.title, l.column, 1, CurveStyle::dashed});
  add_figure(out, s, {"contacts_and_bonds", "Contacts and bonds", "time [s]", "count"}, "time_s", 1, counts);
  std::vector<Line> forces;
  if (s.usable())
    for (const std::string &c : s.table->header())
      if (c.size() > 8 && c.compare(c.size() - 2, 2, "_n") == 0 && c.find("_force_") != std::string::npos &&
          s.carries(c))
        forces.push_back({c.substr(0, c.size() - 2), c});
  add_figure(out, s, {"wall_forces", "Forces on the walls (force on the wall)", "time [s]", "force [N]"}, "time_s", 1,
             forces);
  // One tracked pair: its forces (several pairs share the file, row by row,
  // and are left to the user's own filter).
  const RunTable c(dir, "contacts.csv");
  bool one_pair = c.has("first") && c.has("second");
  for (std::size_t r = 1; one_pair && r < c.table->rows(); ++r)
    one_pair =
      c.table->get(r, "first") == c.table->get(0, "first") && c.table->get(r, "second") == c.table->get(0, "second");
  if (one_pair)
    add_figure(
      out, c, {"contact_forces", "Forces of the tracked contact (normal > 0 in compression)", "time [s]", "force [N]"},
      "time_s", 1, {{"normal", "normal_force_n"}, {"shear (magnitude)", "shear_force_n", 1, CurveStyle::dashed}});
}

void burgers_ode_figures(const std::string &dir, std::vector<Figure> &out)
{
  const RunTable s(dir, "series.csv");
  add_figure(out, s, {"force", "Force of the Burger's element", "time [s]", "force [N]"}, "time_s", 1,
             {{"CVODE", "force_n"}, {"closed form", "force_closed_form_n", 1, CurveStyle::dashed}});
  add_figure(out, s, {"displacement", "Displacement of the Burger's element", "time [s]", "displacement [m]"}, "time_s",
             1, {{"CVODE", "displacement_m"}, {"closed form", "displacement_closed_form_m", 1, CurveStyle::dashed}});
  add_figure(out, s, {"internal", "Internal displacements", "time [s]", "displacement [m]"}, "time_s", 1,
             {{"Kelvin element", "kelvin_displacement_m"}, {"Maxwell dashpot", "maxwell_dashpot_displacement_m"}});
}

void cylinder_curves(const RunTable &s, std::vector<Figure> &out)
{
  const std::vector<Line> stress = {
    {"finite elements", "axial_stress_pa", 1e-6},
    {"closed form (homogeneous)", "axial_stress_closed_form_pa", 1e-6, CurveStyle::dashed}};
  add_figure(out, s, {"stress_strain", "Axial stress against axial strain", "axial strain [%]", "axial stress [MPa]"},
             "axial_strain", 100, stress);
  add_figure(out, s, {"stress_time", "Axial stress against time", "time [s]", "axial stress [MPa]"}, "time_s", 1,
             stress);
  add_figure(out, s, {"radial_strain", "Radial strain at mid-height", "axial strain [%]", "radial strain [%]"},
             "axial_strain", 100,
             {{"finite elements", "radial_strain", 100},
              {"closed form (homogeneous)", "radial_strain_closed_form", 100, CurveStyle::dashed}});
}

/// A compare run: DEM, calibrated and affine continuum side by side.
void compare_figures(const RunTable &s, std::vector<Figure> &out)
{
  const auto sides = [](const std::string &quantity, const std::string &unit, double scale)
  {
    return std::vector<Line>{{"DEM", quantity + "_dem" + unit, scale},
                             {"continuum, calibrated", quantity + "_calibrated" + unit, scale, CurveStyle::dashed},
                             {"continuum, affine", quantity + "_affine" + unit, scale, CurveStyle::dashed}};
  };
  add_figure(out, s, {"stress_time", "Axial stress against time", "time [s]", "axial stress [MPa]"}, "time_s", 1,
             sides("axial_stress", "_pa", 1e-6));
  add_figure(out, s, {"strain_time", "Axial strain against time", "time [s]", "axial strain [%]"}, "time_s", 1,
             sides("axial_strain", "", 100));
  add_figure(out, s, {"radial_strain", "Radial strain against time", "time [s]", "radial strain [%]"}, "time_s", 1,
             sides("radial_strain", "", 100));
  add_figure(out, s, {"difference", "DEM minus continuum", "time [s]", "axial stress difference [MPa]"}, "time_s", 1,
             {{"DEM - calibrated", "stress_difference_calibrated_pa", 1e-6},
              {"DEM - affine", "stress_difference_affine_pa", 1e-6, CurveStyle::dashed}});
  if (!s.has("axial_strain_dem"))
    return;
  Figure f;
  f.name = "stress_strain";
  f.title = "Axial stress against axial strain";
  f.x_label = "axial strain [%]";
  f.y_label = "axial stress [MPa]";
  for (const auto &[title, side] : std::vector<std::pair<std::string, std::string>>{
         {"DEM", "dem"}, {"continuum, calibrated", "calibrated"}, {"continuum, affine", "affine"}})
    f.curves.push_back(column_curve(title, s.from_plots, "axial_strain_" + side, "axial_stress_" + side + "_pa", 100,
                                    1e-6, side == "dem" ? CurveStyle::line : CurveStyle::dashed));
  out.push_back(std::move(f));
}

void mesh_figure(const std::string &dir, std::vector<Figure> &out)
{
  if (!exists(dir + "/mesh.csv"))
    return;
  Figure f;
  f.name = "mesh";
  f.title = "Finite-element mesh (cell edges)";
  f.x_label = "r or x [mm]";
  f.y_label = "z [mm]";
  f.key = KeyPlace::none;
  f.equal_axes = true;
  f.curves.push_back(column_curve("mesh", "../mesh.csv", "1", "2", 1e3, 1e3));
  out.push_back(std::move(f));
}

std::vector<double> numbers(const nlohmann::json &j)
{
  std::vector<double> v;
  for (const auto &x : j)
    v.push_back(x.get<double>());
  return v;
}

void gci_figures(const std::string &dir, const nlohmann::json &summary, std::vector<Figure> &out)
{
  Figure levels;
  levels.name = "levels";
  levels.title = "Axial stress on every mesh of the study";
  levels.x_label = "axial strain [%]";
  levels.y_label = "axial stress [MPa]";
  for (int k = 1; exists(dir + "/level_" + std::to_string(k) + "/series.csv"); ++k)
    levels.curves.push_back(column_curve("level " + std::to_string(k), "../level_" + std::to_string(k) + "/series.csv",
                                         "axial_strain", "axial_stress_pa", 100, 1e-6));
  if (!levels.curves.empty())
    out.push_back(std::move(levels));
  const auto &study = summary.at("gci").at(0);
  for (auto it = study.begin(); it != study.end(); ++it)
  {
    if (!it->is_object() || !it->contains("extrapolated"))
      continue;
    const nlohmann::json &g = *it;
    GciLevels l{numbers(g.at("cell_sizes_m_fine_to_coarse")), numbers(g.at("values_fine_to_coarse")),
                g.at("extrapolated").get<double>(), g.at("observed_order").get<double>(),
                g.at("gci_fine").get<double>()};
    std::string quantity = it.key();
    if (quantity.size() > 3 && quantity.compare(quantity.size() - 3, 3, "_pa") == 0)
      quantity.resize(quantity.size() - 3);
    for (char &c : quantity)
      c = c == '_' ? ' ' : c;
    out.push_back(
      gci_figure(figure_name("gci_" + it.key()), quantity, l, 1e3, 1e-6, "cell size [mm]", quantity + " [MPa]"));
  }
}

/// The balls of a section table (app/io/section.h) in rows [from, to) as
/// circles, in mm.
Curve section_circles(const CsvTable &t, std::size_t from, std::size_t to)
{
  Curve c = curve("balls (cut by y = 0)", {}, {}, CurveStyle::circles);
  for (std::size_t r = from; r < to; ++r)
  {
    c.x.push_back(t.get(r, "x_m"));
    c.y.push_back(t.get(r, "z_m"));
    c.radius.push_back(t.get(r, "section_radius_m"));
  }
  c.x_scale = c.y_scale = 1e3;
  c.colour = 8;
  return c;
}

Figure section_picture(std::string name, std::string title, std::string caption)
{
  Figure f = make_figure(std::move(name), std::move(title), "x [mm]", "z [mm]", {}, std::move(caption));
  f.equal_axes = true;
  f.key = KeyPlace::right;
  return f;
}

/// The sample's section at the end of the run (section.csv) with the bonds
/// that broke within one ball radius of the plane (bond_breaks.csv) marked
/// by mode, where they broke: where the sample cracked (Figs. 7.7, A.3).
void section_figure(const std::string &dir, std::vector<Figure> &out)
{
  const RunTable cut(dir, "section.csv");
  if (!cut.has("x_m") || !cut.has("z_m") || !cut.has("section_radius_m"))
    return;
  Figure f = section_picture("section", "Section at the end, with broken bonds",
                             "The balls the plane y = 0 cuts, as the circles they leave on it, and the bonds broken "
                             "within one ball radius of the plane, at the point where each broke.");
  f.curves.push_back(section_circles(*cut.table, 0, cut.table->rows()));
  const std::vector<double> &r = f.curves.back().radius;
  const double near = *std::max_element(r.begin(), r.end());
  const RunTable breaks(dir, "bond_breaks.csv");
  const char *modes[] = {"broken: tension", "broken: shear", "broken: displacement"};
  const bool placed = breaks.has("mode") && breaks.has("x_m") && breaks.has("y_m") && breaks.has("z_m");
  for (int mode = 1; mode <= 3 && placed; ++mode)
  {
    Curve c = curve(modes[mode - 1], {}, {}, CurveStyle::points);
    for (std::size_t k = 0; k < breaks.table->rows(); ++k)
      if (breaks.table->get(k, "mode") == mode && std::abs(breaks.table->get(k, "y_m")) < near)
      {
        c.x.push_back(breaks.table->get(k, "x_m"));
        c.y.push_back(breaks.table->get(k, "z_m"));
      }
    c.x_scale = c.y_scale = 1e3;
    c.colour = mode;
    c.point_type = mode == 2 ? 5 : 7;
    if (!c.x.empty())
      f.curves.push_back(std::move(c));
  }
  out.push_back(std::move(f));
}

/// Thesis Figs. 5.2-5.3: the packing's section after the first stage (the
/// balls placed at half radius), the second (grown) and the last
/// (released), from preparation_sections.csv; every stage is in the file.
void preparation_section_figures(const std::string &dir, const nlohmann::json &summary, std::vector<Figure> &out)
{
  const RunTable cut(dir, "preparation_sections.csv");
  const nlohmann::json stages = summary.value("preparation_stages", nlohmann::json::array());
  if (!cut.has("stage") || !cut.has("x_m") || !cut.has("z_m") || !cut.has("section_radius_m") || !stages.is_array() ||
      stages.empty())
    return;
  const CsvTable &t = *cut.table;
  std::vector<std::size_t> shown = {0, 1, stages.size() - 1};
  shown.erase(std::unique(shown.begin(), shown.end()), shown.end());
  for (const std::size_t stage : shown)
  {
    std::size_t from = 0;
    while (from < t.rows() && t.get(from, "stage") < double(stage))
      ++from;
    std::size_t to = from;
    while (to < t.rows() && t.get(to, "stage") == double(stage))
      ++to;
    if (to == from || stage >= stages.size() || !stages[stage].is_object())
      continue;
    Figure f =
      section_picture("preparation_stage_" + std::to_string(stage),
                      "Section, stage " + std::to_string(stage) + ": " + stages[stage].value("stage", std::string()),
                      "The balls the plane y = 0 cuts, as the circles they leave on it (every stage's "
                      "section is in preparation_sections.csv).");
    f.curves.push_back(section_circles(t, from, to));
    out.push_back(std::move(f));
  }
}

/// Thesis Fig. 5.5: the mean stress of the packed sample against the
/// reduction of every radius (stage 4 of the preparation), step by step,
/// with the stress target the steps aim below.
void prepare_figures(const nlohmann::json &summary, std::vector<Figure> &out)
{
  const nlohmann::json &prep = summary.value("preparation", nlohmann::json::object());
  if (!prep.contains("radius_reduction") || prep.at("radius_reduction").size() < 2)
    return;
  std::vector<double> change, stress;
  for (const auto &step : prep.at("radius_reduction"))
  {
    change.push_back(step.at("radius_change").get<double>());
    stress.push_back(step.at("mean_stress_pa").get<double>());
  }
  Figure f = make_figure("radius_reduction", "Isotropic stress against the reduction of the radii",
                         "relative change of every radius [%]", "mean stress of the packing [Pa]",
                         {curve("each step, settled", change, stress, CurveStyle::markers_and_line)},
                         "Stage 4 of the preparation: every radius scaled, the packing settled, its mean stress "
                         "measured (secant steps towards half the target).");
  f.log_y = true;
  f.curves.front().x_scale = 100;
  const nlohmann::json target = summary.value("stress_target_pa", nlohmann::json());
  if (target.is_number())
  {
    const double pa = target.get<double>();
    f.curves.push_back(curve("stress target", {change.front(), change.back()}, {pa, pa}, CurveStyle::dashed));
    f.curves.back().x_scale = 100;
  }
  out.push_back(std::move(f));
}

void mms_figures(const std::string &dir, const nlohmann::json &summary, std::vector<Figure> &out)
{
  const RunTable t(dir, "convergence.csv");
  if (!t.usable())
    return;
  const auto column = [&](const std::string &c)
  {
    std::vector<double> v;
    for (std::size_t r = 0; r < t.table->rows(); ++r)
      v.push_back(t.table->get(r, c));
    return v;
  };
  const std::vector<double> h = column("cell_size_m"), dt = column("time_step_s");
  const bool in_space = h.front() != h.back();
  Figure f;
  f.name = "convergence";
  f.title = std::string("Convergence to the manufactured solution in ") + (in_space ? "space" : "time");
  f.x_label = in_space ? "cell size [m]" : "time step [s]";
  f.y_label = "relative error [-]";
  const nlohmann::json expected = summary.value("expected_orders", nlohmann::json::object());
  for (auto it = expected.begin(); it != expected.end(); ++it)
    if (t.has(it.key()))
      add_order_study(f, it.key(), in_space ? h : dt, column(it.key()), it->get<double>());
  if (!f.curves.empty())
    out.push_back(std::move(f));
}
} // namespace

/// A finite number of a (possibly foreign) summary, else NaN.
double summary_number(const nlohmann::json &j, const std::string &key, std::size_t index = 0)
{
  if (!j.is_object() || !j.contains(key))
    return std::nan("");
  const nlohmann::json &v = j.at(key).is_array() && index < j.at(key).size() ? j.at(key).at(index) : j.at(key);
  return v.is_number() && std::isfinite(v.get<double>()) ? v.get<double>() : std::nan("");
}

void uniaxial_run_figures(const std::string &dir, const nlohmann::json &summary, std::vector<Figure> &out)
{
  uniaxial_figures(dir, out);
  section_figure(dir, out);
  // The stress-strain figure marks what the summary reports from it: the
  // peak (the largest row) and the initial-modulus fit over its window, the
  // fitted line itself (slope and intercept), so a reader sees which part
  // of the curve each number comes from.
  const auto figure = std::find_if(out.begin(), out.end(), [](const Figure &f) { return f.name == "stress_strain"; });
  if (figure == out.end())
    return;
  const double peak = summary_number(summary, "peak_stress_pa"), at = summary_number(summary, "strain_at_peak");
  if (std::isfinite(peak) && std::isfinite(at))
  {
    Curve c = curve("peak: " + format_number(peak * 1e-6, 4) + " MPa at " + format_number(at * 100, 3) + " %",
                    {at * 100}, {peak * 1e-6}, CurveStyle::points);
    c.colour = 7;
    figure->curves.push_back(std::move(c));
  }
  const double modulus = summary_number(summary, "initial_modulus_pa");
  const double intercept = summary_number(summary, "initial_modulus_intercept_pa");
  const double from = summary_number(summary, "fit_window_axial_strain", 0);
  const double to = summary_number(summary, "fit_window_axial_strain", 1);
  if (std::isfinite(modulus) && std::isfinite(intercept) && std::isfinite(from) && std::isfinite(to) && to > from)
  {
    Curve c = curve("initial modulus " + format_number(modulus * 1e-9, 4) + " GPa, fitted over " +
                      format_number(from * 100, 3) + "-" + format_number(to * 100, 3) + " %",
                    {from * 100, to * 100}, {(modulus * from + intercept) * 1e-6, (modulus * to + intercept) * 1e-6},
                    CurveStyle::dashed);
    c.colour = 8;
    figure->curves.push_back(std::move(c));
  }
}

void scene_run_figures(const std::string &dir, const nlohmann::json &, std::vector<Figure> &out)
{
  scene_figures(dir, out);
}

void burgers_ode_run_figures(const std::string &dir, const nlohmann::json &, std::vector<Figure> &out)
{
  burgers_ode_figures(dir, out);
}

void cylinder_run_figures(const std::string &dir, const nlohmann::json &summary, std::vector<Figure> &out)
{
  if (summary.contains("gci"))
    return gci_figures(dir, summary, out);
  cylinder_curves(RunTable(dir, "series.csv"), out);
  mesh_figure(dir, out);
}

void mms_run_figures(const std::string &dir, const nlohmann::json &summary, std::vector<Figure> &out)
{
  mms_figures(dir, summary, out);
}

void prepare_run_figures(const std::string &dir, const nlohmann::json &summary, std::vector<Figure> &out)
{
  prepare_figures(summary, out);
  preparation_section_figures(dir, summary, out);
}

void compare_run_figures(const std::string &dir, const nlohmann::json &, std::vector<Figure> &out)
{
  compare_figures(RunTable(dir, "compare.csv"), out);
}

std::vector<Figure> run_figures(const std::string &run_dir, const DeckKinds &kinds)
{
  const std::string path = run_dir + "/summary.json";
  if (!exists(path))
    throw DeckError(run_dir + ": not a demvv run directory (expected " + path + ")");
  try
  {
    const nlohmann::json summary =
      parse_json_input(read_input(path, "run summary", max_summary_bytes), path, "run summary");
    std::vector<Figure> out;
    if (!summary.is_object() || !summary.contains("kind") || !summary.at("kind").is_string())
      throw DeckError(path + ": names no kind of run (a run still in progress, or a summary demvv did not write): "
                             "expected the summary of a run that has ended");
    const DeckKind *kind = find_deck_kind(kinds, summary.at("kind").get<std::string>());
    if (!kind)
    {
      const std::string shown = one_line(summary.at("kind").get<std::string>().substr(0, 40), '?');
      throw DeckError(path + ": kind '" + shown +
                      "' is no deck kind of this demvv: expected the summary of a run it made");
    }
    if (kind->figures)
      kind->figures(run_dir, summary, out);
    // Each figure names its run: the deck's title, else the run directory
    // (quoted safely into the script by gnuplot.cpp; kept short).
    const nlohmann::json title = summary.value("title", nlohmann::json());
    std::string run_name = title.is_string() ? title.get<std::string>() : "";
    if (run_name.empty())
      run_name = std::filesystem::path(run_dir).lexically_normal().filename().string();
    if (run_name.empty() || run_name == ".")
      run_name = std::filesystem::absolute(run_dir).lexically_normal().parent_path().filename().string();
    if (run_name.size() > 60)
    {
      std::size_t cut = 57; // not inside a UTF-8 sequence
      while (cut > 0 && (static_cast<unsigned char>(run_name[cut]) & 0xC0) == 0x80)
        --cut;
      run_name = run_name.substr(0, cut) + "...";
    }
    for (Figure &f : out)
      f.title += " (" + run_name + ")";
    return out;
  }
  catch (const nlohmann::json::exception &e)
  {
    throw DeckError(path + ": a field is missing or of another type than a run writes (" + one_line(e.what()) +
                    "): expected the summary.json of a run demvv made, unedited");
  }
}

std::vector<DrawnFigure> plot_run(const std::string &run_dir, const DeckKinds &kinds)
{
  const std::string dir = run_dir + "/plots";
  std::vector<DrawnFigure> figures = draw_figures(run_figures(run_dir, kinds), dir);
  // A figure of an earlier drawing that these data no longer give (a
  // column or a kind changed) would be read as this run's: its files go,
  // and the line of figures not drawn says so.  Only figures demvv wrote
  // (a NAME.gp beside them) are touched, never through a link.
  std::vector<std::string> drawn_now;
  for (const DrawnFigure &f : figures)
    drawn_now.push_back(f.name);
  std::error_code ec;
  std::vector<std::string> stale;
  for (const auto &entry : std::filesystem::directory_iterator(dir, ec))
    if (entry.path().extension() == ".gp" && entry.symlink_status(ec).type() == std::filesystem::file_type::regular &&
        std::find(drawn_now.begin(), drawn_now.end(), entry.path().stem().string()) == drawn_now.end())
      stale.push_back(entry.path().stem().string());
  std::sort(stale.begin(), stale.end());
  for (const std::string &name : stale)
  {
    for (const char *extension : {".gp", ".svg", ".csv", ".log"})
      remove_regular_file(dir + "/" + name + extension);
    DrawnFigure gone;
    gone.name = name;
    gone.problem = "removed, a figure of an earlier drawing that these data no longer give";
    figures.push_back(gone);
  }
  return figures;
}
} // namespace demvv
