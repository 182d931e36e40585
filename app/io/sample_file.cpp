#include "app/io/sample_file.h"

#include "app/io/input.h"
#include "app/io/output.h"
#include "app/io/text.h"

#include "dem/contact_model.h"
#include "dem/neighbors.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string_view>

namespace demvv
{
namespace
{
using nlohmann::json;

json vec(const dem::Vec3 &v) { return json::array({v.x(), v.y(), v.z()}); }

/// The units a sample file declares (and the only ones it may declare).
constexpr const char *sample_units = "SI (m, kg, s, N, J); compression positive";

const std::vector<std::string> ball_columns = {"x_m",
                                               "y_m",
                                               "z_m",
                                               "radius_m",
                                               "density_kgpm3",
                                               "kn_npm",
                                               "ks_npm",
                                               "friction",
                                               "vx_mps",
                                               "vy_mps",
                                               "vz_mps",
                                               "wx_radps",
                                               "wy_radps",
                                               "wz_radps",
                                               "hold_velocity",
                                               "hold_spin",
                                               "boundary_work_j",
                                               "body_work_j",
                                               "damping_work_j",
                                               "kinetic_energy_j"};

const std::vector<std::string> state_columns = {
  "touching",  "normal_force_n", "overlap_m",       "nx",           "ny", "nz", "shear_x_n",
  "shear_y_n", "shear_z_n",      "friction_work_j", "bond_energy_j"};

constexpr int format_version = 2;

/// Contact columns: pair, constants, bond (with its break distance from
/// version 2 on), ContactState, then the law's own state (none in a version
/// 1 file).
std::vector<std::string> contact_columns(const std::vector<std::string_view> &law_fields, int version)
{
  std::vector<std::string> c = {
    "first", "second", "kn_npm", "ks_npm", "friction", "bonded", "normal_strength_n", "shear_strength_n"};
  if (version >= 2)
    c.push_back("break_distance_m");
  c.insert(c.end(), state_columns.begin(), state_columns.end());
  for (std::string_view f : law_fields)
    c.push_back("law_" + std::string(f));
  return c;
}

/// The registry row of a sample's contact law.
const dem::LawEntry &sample_law(const std::string &keyword, const std::string &path)
{
  const dem::LawEntry *law = dem::find_law(keyword);
  if (!law)
    throw DeckError(path + ": contact_law '" + keyword + "' is not a contact law of this demvv");
  return *law;
}

std::vector<std::string> wall_contact_columns()
{
  std::vector<std::string> c = {"wall", "ball"};
  c.insert(c.end(), state_columns.begin(), state_columns.end());
  return c;
}

void append_state(json &row, const dem::ContactState &s)
{
  for (double v : {s.touching() ? 1.0 : 0.0, s.normal_force, s.overlap, s.normal.x(), s.normal.y(), s.normal.z(),
                   s.shear_force.x(), s.shear_force.y(), s.shear_force.z(), s.friction_work, s.bond_energy})
    row.push_back(v);
}

/// The fields of a parsed sample file, each read with its type and range
/// checked: any problem is the one-line error naming the file, the field
/// (as "walls[1].direction" or "balls.rows[5].radius_m"), its value and
/// what was expected.
class Fields
{
public:
  explicit Fields(std::string path) : path_(std::move(path)) {}

  [[noreturn]] void fail(const std::string &key, const json &value, const std::string &expected) const
  {
    std::string text = value.dump(-1, ' ', false, json::error_handler_t::replace);
    if (text.size() > 60)
      text = text.substr(0, 57) + "...";
    fail_key(path_, key, text, expected);
  }

  /// Refuses a member of `object` (at `key`, "" for the top level) that is
  /// not among `known`: a misspelt or foreign field would otherwise be
  /// accepted and never read.
  void only(const json &object, const std::string &key, std::initializer_list<const char *> known) const
  {
    if (!object.is_object())
      return;
    for (const auto &item : object.items())
      if (std::find_if(known.begin(), known.end(), [&](const char *k) { return item.key() == k; }) == known.end())
      {
        std::string list;
        for (const char *k : known)
          list += (list.empty() ? "" : ", ") + std::string(k);
        throw DeckError(path_ + ": key '" + (key.empty() ? "" : key + ".") + escaped(item.key().substr(0, 60)) +
                        "' is not a field of a demvv sample file here: expected one of " + list);
      }
  }

  /// Member `name` of the object at `key` (missing: the one-line error).
  const json &member(const json &object, const std::string &key, const std::string &name,
                     const std::string &expected) const
  {
    const std::string full = key.empty() ? name : key + "." + name;
    if (!object.is_object())
      fail(key.empty() ? "(top level)" : key, object, "expected a JSON object");
    const auto it = object.find(name);
    if (it == object.end())
      throw DeckError(path_ + ": key '" + full + "' is missing: expected " + expected);
    return *it;
  }

  enum class Sign
  {
    any,
    non_negative,
    positive,
  };

  double real(const json &j, const std::string &key, Sign sign = Sign::any, const std::string &unit = "") const
  {
    const double v = j.is_number() ? j.get<double>() : std::nan("");
    const bool ok = std::isfinite(v) && (sign == Sign::any || (sign == Sign::positive ? v > 0 : v >= 0));
    if (!ok)
      fail(key, j,
           std::string("expected a finite number") +
             (sign == Sign::positive       ? " > 0"
              : sign == Sign::non_negative ? " >= 0"
                                           : "") +
             (unit.empty() ? "" : " (" + unit + ")"));
    return v;
  }

  /// An integral number in [min, max] (integers may be written as 3 or 3.0).
  long long integer(const json &j, const std::string &key, long long min, long long max, const std::string &what) const
  {
    const double v = j.is_number() ? j.get<double>() : std::nan("");
    if (!(v >= double(min) && v <= double(max) && v == std::floor(v)))
      fail(key, j, "expected " + what + ", an integer in [" + std::to_string(min) + ", " + std::to_string(max) + "]");
    return j.is_number_integer() ? j.get<long long>() : static_cast<long long>(v);
  }

  bool flag(const json &j, const std::string &key) const
  {
    if (j.is_boolean())
      return j.get<bool>();
    if (j.is_number() && (j.get<double>() == 0 || j.get<double>() == 1))
      return j.get<double>() == 1;
    fail(key, j, "expected true or false (or 1 or 0)");
  }

  std::string text(const json &j, const std::string &key) const
  {
    if (!j.is_string())
      fail(key, j, "expected a string");
    return j.get<std::string>();
  }

  dem::Vec3 vec3(const json &j, const std::string &key, const std::string &unit, bool nonzero = false) const
  {
    const bool shape =
      j.is_array() && j.size() == 3 && std::all_of(j.begin(), j.end(), [](const json &x) { return x.is_number(); });
    dem::Vec3 v = dem::Vec3::Zero();
    if (shape)
      v = {j[0].get<double>(), j[1].get<double>(), j[2].get<double>()};
    if (!shape || !v.allFinite() || (nonzero && !(v.norm() > 0)))
      fail(key, j,
           std::string("expected three finite numbers") + (nonzero ? ", not all zero" : "") + " (" + unit + ")");
    return v;
  }

  /// The rows of a {columns, rows} table, each an array of `columns.size()` values.
  const json &table(const json &doc, const std::string &name, const std::vector<std::string> &columns) const
  {
    const json &t = member(doc, "", name, "a {columns, rows} table: expected a demvv sample file");
    only(t, name, {"columns", "rows"});
    const json &written = member(t, name, "columns", "the column names");
    if (!written.is_array() || written != json(columns))
    {
      std::string list;
      for (const std::string &c : columns)
        list += (list.empty() ? "" : ",") + c;
      fail(name + ".columns", written, "expected the columns this demvv writes: " + list);
    }
    const json &rows = member(t, name, "rows", "an array of rows");
    if (!rows.is_array())
      fail(name + ".rows", rows, "expected an array of rows");
    for (std::size_t r = 0; r < rows.size(); ++r)
      if (!rows[r].is_array() || rows[r].size() != columns.size())
        fail(row_key(name, r), rows[r], "expected an array of " + std::to_string(columns.size()) + " values");
    return rows;
  }

  static std::string row_key(const std::string &table, std::size_t r)
  {
    return table + ".rows[" + std::to_string(r) + "]";
  }

  /// Key of one value of a table row: "balls.rows[5].radius_m".
  static std::string cell_key(const std::string &table, std::size_t r, const std::string &column)
  {
    return row_key(table, r) + "." + column;
  }

  /// A contact's state from its columns at `at`.
  dem::ContactState state(const json &row, std::size_t at, const std::string &table, std::size_t r) const
  {
    const auto v = [&](std::size_t k, Sign sign = Sign::any)
    { return real(row[at + k], cell_key(table, r, state_columns[k]), sign); };
    dem::ContactState s;
    const bool touching = flag(row[at], cell_key(table, r, state_columns[0]));
    s.normal_force = v(1);
    s.overlap = v(2);
    s.normal = {v(3), v(4), v(5)};
    // A contact that carries no force keeps no normal (ContactState).
    if (!touching)
      s.normal.setZero();
    else if (!s.touching())
      fail(cell_key(table, r, state_columns[3]), row[at + 3],
           "expected a touching contact's unit normal, not all zero");
    s.shear_force = {v(6), v(7), v(8)};
    s.friction_work = v(9);
    s.bond_energy = v(10);
    return s;
  }

  const std::string &path() const { return path_; }

private:
  std::string path_;
};

/// Where a wall index of the cell may point: its wall's shape, or -1.
void check_cell_wall(const Fields &f, const json &cell, const char *name, dem::WallIndex index,
                     const std::vector<dem::Wall> &walls, dem::WallShape shape)
{
  if (index < 0)
    return;
  if (index >= static_cast<dem::WallIndex>(walls.size()) || walls[index].shape != shape)
    f.fail(std::string("cell.") + name, cell.at(name),
           "expected -1 (none) or the index of a " +
             std::string(shape == dem::WallShape::plane ? "plane" : "cylinder") + " wall among the file's " +
             std::to_string(walls.size()) + " walls");
}
} // namespace

json report_json(const dem::PackingReport &r)
{
  const auto band_means_json = [](const dem::BandMeans &m)
  {
    json bands = json::array();
    for (int b = 0; b < dem::CylinderBands::count; ++b)
      bands.push_back({{"band", dem::CylinderBands::name(b)},
                       {"contacts", m.contacts[b]},
                       {"mean_normal_force_n", m.mean[b]},
                       {"half_width_95_n", m.half_width[b]}});
    return json{{"bands", bands},
                {"overall_mean_normal_force_n", m.overall_mean},
                {"anova_f", m.f_statistic},
                {"anova_p", m.p_value},
                {"note", "compressive ball-ball contacts at their contact points; six bands of equal volume (thirds of "
                         "the height, core r < R/sqrt(2) and rim); p treats contacts as independent"}};
  };
  json stages = json::array();
  for (const auto &s : r.stages)
    stages.push_back({{"name", s.name},
                      {"cycles", s.cycles},
                      {"converged", s.converged},
                      {"mean_stress_pa", s.mean_stress},
                      {"unbalanced_force_ratio", s.unbalanced_ratio},
                      {"solid_fraction", s.solid_fraction},
                      {"coordination_number", s.coordination}});
  json reduction = json::array();
  for (const auto &step : r.radius_reduction)
    reduction.push_back({{"radius_change", step.radius_change}, {"mean_stress_pa", step.mean_stress}});
  return {{"particles", r.particles},
          {"cell_diameter_m", r.cell_diameter},
          {"cell_height_m", r.cell_height},
          {"stages", stages},
          {"radius_change", r.radius_change},
          {"radius_reduction", reduction},
          {"solid_fraction_cost_of_radius_reduction", r.solid_fraction_cost},
          {"mean_stress_before_bonding_pa", r.stress_before_bonding},
          {"balls_below_min_contacts_before_expansion", r.rattlers_before},
          {"balls_below_min_contacts_after_expansion", r.rattlers_after},
          {"largest_expansion", r.largest_expansion},
          {"solid_fraction_cell", r.solid_fraction},
          {"measurement_sphere_porosity", {r.sphere_porosity[0], r.sphere_porosity[1]}},
          {"measurement_sphere_coordination", {r.sphere_coordination[0], r.sphere_coordination[1]}},
          {"coordination_number", r.coordination},
          {"fewest_contacts_of_a_ball", r.fewest_contacts},
          {"fabric_deviator_norm", r.fabric_deviator_norm},
          {"fabric_eigenvalues", {r.fabric_eigenvalues[0], r.fabric_eigenvalues[1], r.fabric_eigenvalues[2]}},
          {"bonds",
           {{"installed", r.bonds.bonded},
            {"removed", r.bonds.removed},
            {"truncated_strength_draws", r.bonds.truncated_draws},
            {"mean_normal_strength_n", r.bonds.mean_normal_strength},
            {"mean_shear_strength_n", r.bonds.mean_shear_strength}}},
          {"mean_contact_force_before_bonding_n", r.mean_contact_force_before},
          {"contact_force_bands_before_bonding", band_means_json(r.force_bands)},
          {"locked_in_mean_force_n", r.locked_in_mean_force},
          {"locked_in_max_force_n", r.locked_in_max_force},
          {"wall_seconds", r.wall_seconds}};
}

void apply_test_properties(SampleFile &sample, const dem::BallSpec &ball, const dem::WallProps &platen)
{
  dem::Snapshot &snap = sample.snapshot;
  dem::ParticleStore &p = snap.particles;
  for (dem::Index b = 0; b < p.size(); ++b)
  {
    p.density[b] = ball.density;
    p.kn[b] = ball.kn;
    p.ks[b] = ball.ks;
    p.friction[b] = ball.friction;
    p.set_radius(b, p.radius[b]); // mass and inertia from the new density
  }
  // The test's ledger starts at zero, as its clock does below: the
  // preparation's friction and bond energy stay the preparation's.
  for (dem::ContactRecord &c : snap.contacts)
  {
    c.params = dem::ContactTable::pair_params(p, c.first, c.second);
    c.state.friction_work = 0;
    c.state.bond_energy = 0;
  }
  for (dem::WallContact &c : snap.wall_contacts)
    c.state.friction_work = 0;
  snap.walls[sample.cell.bottom].props = platen;
  snap.walls[sample.cell.top].props = platen;
  const double last_step = snap.clock.last_time_step;
  snap.clock = dem::SimulationClock{};
  snap.clock.last_time_step = last_step;
}

std::string write_sample(const std::string &path, const SampleFile &sample)
{
  const dem::Snapshot &s = sample.snapshot;
  const dem::SimulationClock &c = s.clock;
  const std::string law_keyword = !s.contact_law.empty()        ? s.contact_law
                                  : !sample.contact_law.empty() ? sample.contact_law
                                                                : "linear";
  if (!s.contact_law.empty() && !sample.contact_law.empty() && s.contact_law != sample.contact_law)
    throw std::invalid_argument(path + ": the sample names contact law '" + sample.contact_law +
                                "' but its snapshot holds the state of '" + s.contact_law + "'");
  if (!s.law_states.empty() && s.law_states.size() != s.contacts.size())
    throw std::invalid_argument(path + ": " + std::to_string(s.law_states.size()) + " law states for " +
                                std::to_string(s.contacts.size()) + " contacts");
  const std::vector<std::string_view> &law_fields = sample_law(law_keyword, path).state_fields;
  json doc = {{"format", "demvv-sample"},
              {"format_version", format_version},
              {"units", sample_units},
              {"title", sample.title},
              {"seed", sample.seed},
              {"contact_law", law_keyword},
              {"cell",
               {{"diameter_m", sample.cell.diameter},
                {"height_m", sample.cell.height},
                {"bottom", sample.cell.bottom},
                {"top", sample.cell.top},
                {"lateral", sample.cell.lateral}}},
              {"preparation", sample.preparation},
              {"provenance", sample.provenance},
              {"clock",
               {{"time_s", c.time},
                {"steps", c.steps},
                {"last_time_step_s", c.last_time_step},
                {"initial_energy_j", c.initial_energy},
                {"initial_recorded", c.initial_recorded},
                {"removed_wall_strain_j", c.removed_wall_strain},
                {"removed_wall_friction_j", c.removed_wall_friction},
                {"bonds_broken_tension", c.broken_tension},
                {"bonds_broken_shear", c.broken_shear},
                {"bonds_broken_displacement", c.broken_displacement},
                {"retired_friction_work_j", c.retired.friction_work},
                {"retired_bond_energy_j", c.retired.bond_energy}}}};
  json walls = json::array();
  for (const dem::Wall &w : s.walls)
    walls.push_back({{"name", w.name},
                     {"shape", w.shape == dem::WallShape::plane ? "plane" : "cylinder"},
                     {"point_m", vec(w.point)},
                     {"direction", vec(w.direction)},
                     {"radius_m", w.radius},
                     {"velocity_mps", vec(w.velocity)},
                     {"radial_velocity_mps", w.radial_velocity},
                     {"kn_npm", w.props.kn},
                     {"ks_npm", w.props.ks},
                     {"friction", w.props.friction},
                     {"enabled", w.enabled}});
  doc["walls"] = walls;

  const dem::ParticleStore &p = s.particles;
  json balls = json::array();
  for (dem::Index b = 0; b < p.size(); ++b)
  {
    const dem::BallEnergy e = b < static_cast<dem::Index>(c.ball_energy.size()) ? c.ball_energy[b] : dem::BallEnergy{};
    balls.push_back(json::array({p.position[b].x(),
                                 p.position[b].y(),
                                 p.position[b].z(),
                                 p.radius[b],
                                 p.density[b],
                                 p.kn[b],
                                 p.ks[b],
                                 p.friction[b],
                                 p.velocity[b].x(),
                                 p.velocity[b].y(),
                                 p.velocity[b].z(),
                                 p.spin[b].x(),
                                 p.spin[b].y(),
                                 p.spin[b].z(),
                                 p.holds_velocity(b) ? 1 : 0,
                                 p.holds_spin(b) ? 1 : 0,
                                 e.boundary,
                                 e.body,
                                 e.damping,
                                 e.kinetic}));
  }
  doc["balls"] = {{"columns", ball_columns}, {"rows", balls}};

  json contacts = json::array();
  for (std::size_t e = 0; e < s.contacts.size(); ++e)
  {
    const dem::ContactRecord &k = s.contacts[e];
    json row = json::array({k.first, k.second, k.params.kn, k.params.ks, k.params.friction, k.bonded ? 1 : 0,
                            k.bond.normal_strength, k.bond.shear_strength});
    // No displacement criterion is an infinite distance: null in JSON.
    row.push_back(std::isfinite(k.bond.break_distance) ? json(k.bond.break_distance) : json(nullptr));
    append_state(row, k.state);
    const dem::LawState law = s.law_states.empty() ? dem::LawState{} : s.law_states[e];
    for (std::size_t f = 0; f < law_fields.size(); ++f)
      row.push_back(law.value[f]);
    contacts.push_back(row);
  }
  doc["contacts"] = {{"columns", contact_columns(law_fields, format_version)}, {"rows", contacts}};

  json wall_contacts = json::array();
  for (const dem::WallContact &c : s.wall_contacts)
  {
    const dem::ContactState &st = c.state;
    if (!st.touching() && st.friction_work == 0 && st.shear_force.isZero(0))
      continue;
    json row = json::array({static_cast<long>(c.wall), static_cast<long>(c.ball)});
    append_state(row, st);
    wall_contacts.push_back(row);
  }
  doc["wall_contacts"] = {{"columns", wall_contact_columns()}, {"rows", wall_contacts}};
  std::string text = json_text(doc) + "\n";
  write_atomically(path, text);
  return text;
}

SampleFile read_sample(const std::string &path)
{
  return parse_sample(read_input(path, "sample file", max_table_bytes), path);
}

SampleFile parse_sample(const std::string &text, const std::string &path)
{
  const json doc = parse_json_input(text, path, "demvv sample file");
  const Fields f(path);
  using Sign = Fields::Sign;
  if (!doc.is_object() || doc.value("format", json()) != "demvv-sample")
    throw DeckError(path + ": no \"format\": \"demvv-sample\" at the top level: expected a demvv sample file");
  const int version =
    static_cast<int>(f.integer(f.member(doc, "", "format_version", "the format version"), "format_version", 1,
                               format_version, "a format version this demvv reads"));
  f.only(doc, "",
         {"format", "format_version", "units", "title", "seed", "contact_law", "cell", "preparation", "provenance",
          "clock", "walls", "balls", "contacts", "wall_contacts"});
  if (doc.contains("units") && doc["units"] != sample_units)
    f.fail("units", doc["units"], std::string("expected \"") + sample_units + "\" (demvv reads and writes SI only)");
  SampleFile out;
  if (doc.contains("title"))
    out.title = f.text(doc["title"], "title");
  if (doc.contains("seed"))
    out.seed = f.integer(doc["seed"], "seed", std::numeric_limits<long long>::min() / 2,
                         std::numeric_limits<long long>::max() / 2, "a seed");
  out.contact_law = doc.contains("contact_law") ? f.text(doc["contact_law"], "contact_law") : "linear";
  // Version 1 files have no law state: every contact's is at rest.
  const std::vector<std::string_view> law_fields =
    version == 1 ? std::vector<std::string_view>{} : sample_law(out.contact_law, path).state_fields;
  // Free-form reports: an object, or null when the writer had none.
  for (const auto &[name, into] :
       {std::pair<const char *, json *>{"preparation", &out.preparation}, {"provenance", &out.provenance}})
  {
    const json &j = doc.value(name, json());
    if (!j.is_object() && !j.is_null())
      f.fail(name, j, "expected a JSON object (or null)");
    *into = j.is_null() ? json::object() : j;
  }

  dem::Snapshot &s = out.snapshot;
  const json &walls = f.member(doc, "", "walls", "an array of walls");
  if (!walls.is_array())
    f.fail("walls", walls, "expected an array of walls");
  for (std::size_t k = 0; k < walls.size(); ++k)
  {
    const json &w = walls[k];
    const std::string key = "walls[" + std::to_string(k) + "]";
    f.only(w, key,
           {"name", "shape", "point_m", "direction", "radius_m", "velocity_mps", "radial_velocity_mps", "kn_npm",
            "ks_npm", "friction", "enabled"});
    const auto at = [&](const char *name) -> const json & { return f.member(w, key, name, "a wall field"); };
    const auto sub = [&](const char *name) { return key + "." + name; };
    dem::Wall wall;
    wall.name = f.text(at("name"), sub("name"));
    const std::string shape = f.text(at("shape"), sub("shape"));
    if (shape != "plane" && shape != "cylinder")
      f.fail(sub("shape"), at("shape"), "expected plane or cylinder");
    wall.shape = shape == "plane" ? dem::WallShape::plane : dem::WallShape::cylinder;
    wall.point = f.vec3(at("point_m"), sub("point_m"), "m");
    wall.direction = f.vec3(at("direction"), sub("direction"), "-", true);
    wall.radius = f.real(at("radius_m"), sub("radius_m"),
                         wall.shape == dem::WallShape::cylinder ? Sign::positive : Sign::non_negative, "m");
    wall.velocity = f.vec3(at("velocity_mps"), sub("velocity_mps"), "m/s");
    wall.radial_velocity = f.real(at("radial_velocity_mps"), sub("radial_velocity_mps"), Sign::any, "m/s");
    wall.props = {f.real(at("kn_npm"), sub("kn_npm"), Sign::positive, "N/m"),
                  f.real(at("ks_npm"), sub("ks_npm"), Sign::non_negative, "N/m"),
                  f.real(at("friction"), sub("friction"), Sign::non_negative)};
    wall.enabled = f.flag(at("enabled"), sub("enabled"));
    s.walls.push_back(wall);
  }

  const json &cell = f.member(doc, "", "cell", "the cell (diameter, height and wall indices)");
  f.only(cell, "cell", {"diameter_m", "height_m", "bottom", "top", "lateral"});
  const auto cell_at = [&](const char *name) -> const json & { return f.member(cell, "cell", name, "a cell field"); };
  const long long wall_count = static_cast<long long>(s.walls.size());
  out.cell.diameter = f.real(cell_at("diameter_m"), "cell.diameter_m", Sign::non_negative, "m");
  out.cell.height = f.real(cell_at("height_m"), "cell.height_m", Sign::non_negative, "m");
  for (const auto &[name, index] : {std::pair<const char *, dem::WallIndex *>{"bottom", &out.cell.bottom},
                                    {"top", &out.cell.top},
                                    {"lateral", &out.cell.lateral}})
    *index = static_cast<dem::WallIndex>(
      f.integer(cell_at(name), std::string("cell.") + name, -1, wall_count - 1, "-1 (none) or a wall index"));
  check_cell_wall(f, cell, "bottom", out.cell.bottom, s.walls, dem::WallShape::plane);
  check_cell_wall(f, cell, "top", out.cell.top, s.walls, dem::WallShape::plane);
  check_cell_wall(f, cell, "lateral", out.cell.lateral, s.walls, dem::WallShape::cylinder);
  if (out.cell.top >= 0 && out.cell.top == out.cell.bottom)
    f.fail("cell.top", cell.at("top"), "expected another wall than cell.bottom");

  dem::SimulationClock &c = s.clock;
  const json &balls = f.table(doc, "balls", ball_columns);
  if (balls.size() > static_cast<std::size_t>(std::numeric_limits<dem::Index>::max()))
    f.fail("balls.rows", json(balls.size()), "expected fewer balls than a ball index can count");
  s.particles.reserve(static_cast<dem::Index>(balls.size()));
  for (std::size_t r = 0; r < balls.size(); ++r)
  {
    const json &row = balls[r];
    const auto v = [&](std::size_t k, Sign sign = Sign::any)
    { return f.real(row[k], Fields::cell_key("balls", r, ball_columns[k]), sign); };
    dem::BallSpec b;
    b.position = dem::Vec3(v(0), v(1), v(2));
    b.radius = v(3, Sign::positive);
    b.density = v(4, Sign::positive);
    b.kn = v(5, Sign::positive);
    b.ks = v(6, Sign::non_negative);
    b.friction = v(7, Sign::non_negative);
    b.velocity = dem::Vec3(v(8), v(9), v(10));
    b.spin = dem::Vec3(v(11), v(12), v(13));
    b.hold_velocity = f.flag(row[14], Fields::cell_key("balls", r, ball_columns[14]));
    b.hold_spin = f.flag(row[15], Fields::cell_key("balls", r, ball_columns[15]));
    s.particles.add(b);
    c.ball_energy.push_back({v(16), v(17), v(18), v(19)});
  }
  const auto n = static_cast<long long>(s.particles.size());
  const std::vector<std::string> columns = contact_columns(law_fields, version);
  const std::size_t state_at = version >= 2 ? 9 : 8;
  const std::size_t law_at = columns.size() - law_fields.size();
  s.contact_law = out.contact_law;
  const json &contacts = f.table(doc, "contacts", columns);
  for (std::size_t r = 0; r < contacts.size(); ++r)
  {
    const json &row = contacts[r];
    const auto key = [&](std::size_t k) { return Fields::cell_key("contacts", r, columns[k]); };
    const auto v = [&](std::size_t k, Sign sign = Sign::any) { return f.real(row[k], key(k), sign); };
    dem::ContactRecord k;
    k.first = static_cast<dem::Index>(f.integer(row[0], key(0), 0, n - 1, "a ball index"));
    k.second = static_cast<dem::Index>(f.integer(row[1], key(1), 0, n - 1, "a ball index"));
    if (k.second <= k.first)
      f.fail(key(1), row[1], "expected a ball index above first (" + std::to_string(k.first) + ")");
    // The table finds contacts by bisection: the rows must be sorted, each pair once.
    if (!s.contacts.empty() &&
        !(std::pair(s.contacts.back().first, s.contacts.back().second) < std::pair(k.first, k.second)))
      f.fail(Fields::row_key("contacts", r), row, "expected the rows sorted by (first, second), each pair once");
    k.params = {v(2, Sign::non_negative), v(3, Sign::non_negative), v(4, Sign::non_negative)};
    k.bonded = f.flag(row[5], key(5));
    k.bond.normal_strength = v(6, Sign::non_negative);
    k.bond.shear_strength = v(7, Sign::non_negative);
    // No displacement criterion is an infinite distance: null in JSON.
    if (version >= 2)
      k.bond.break_distance = row[8].is_null() ? inf : f.real(row[8], key(8), Sign::positive, "m");
    k.state = f.state(row, state_at, "contacts", r);
    s.contacts.push_back(k);
    if (law_fields.empty())
      continue;
    dem::LawState law;
    for (std::size_t l = 0; l < law_fields.size(); ++l)
      law.value[l] = v(law_at + l);
    s.law_states.push_back(law);
  }
  const json &wall_contacts = f.table(doc, "wall_contacts", wall_contact_columns());
  for (std::size_t r = 0; r < wall_contacts.size(); ++r)
  {
    const json &row = wall_contacts[r];
    const long long w =
      f.integer(row[0], Fields::cell_key("wall_contacts", r, "wall"), 0, wall_count - 1, "a wall index");
    const long long b = f.integer(row[1], Fields::cell_key("wall_contacts", r, "ball"), 0, n - 1, "a ball index");
    s.wall_contacts.push_back(
      {static_cast<dem::WallIndex>(w), static_cast<dem::Index>(b), f.state(row, 2, "wall_contacts", r)});
  }

  const json &clock = f.member(doc, "", "clock", "the clock (time, steps and the energy ledger)");
  f.only(clock, "clock",
         {"time_s", "steps", "last_time_step_s", "initial_energy_j", "initial_recorded", "removed_wall_strain_j",
          "removed_wall_friction_j", "bonds_broken_tension", "bonds_broken_shear", "bonds_broken_displacement",
          "retired_friction_work_j", "retired_bond_energy_j"});
  const auto at = [&](const char *name) -> const json & { return f.member(clock, "clock", name, "a clock field"); };
  const auto real = [&](const char *name, Sign sign = Sign::any)
  { return f.real(at(name), std::string("clock.") + name, sign); };
  const auto count = [&](const char *name)
  { return f.integer(at(name), std::string("clock.") + name, 0, std::numeric_limits<long>::max() / 2, "a count"); };
  c.time = real("time_s", Sign::non_negative);
  c.steps = static_cast<long>(count("steps"));
  c.last_time_step = real("last_time_step_s", Sign::non_negative);
  c.initial_energy = real("initial_energy_j");
  c.initial_recorded = f.flag(at("initial_recorded"), "clock.initial_recorded");
  c.removed_wall_strain = real("removed_wall_strain_j");
  c.removed_wall_friction = real("removed_wall_friction_j");
  c.broken_tension = static_cast<std::size_t>(count("bonds_broken_tension"));
  c.broken_shear = static_cast<std::size_t>(count("bonds_broken_shear"));
  c.broken_displacement =
    clock.contains("bonds_broken_displacement") ? static_cast<std::size_t>(count("bonds_broken_displacement")) : 0;
  c.retired.friction_work = real("retired_friction_work_j");
  c.retired.bond_energy = real("retired_bond_energy_j");
  return out;
}

void check_test_cell(const SampleFile &sample, const std::string &path)
{
  const dem::Specimen &cell = sample.cell;
  const std::vector<dem::Wall> &walls = sample.snapshot.walls;
  if (cell.bottom < 0 || cell.top < 0)
    fail_key(path, cell.bottom < 0 ? "cell.bottom" : "cell.top", "-1",
             "expected the index of a platen (a sample written by a prepare run names both)");
  if (!(cell.diameter > 0))
    fail_key(path, "cell.diameter_m", format_number(cell.diameter), "expected a diameter > 0 m");
  if (!(cell.height > 0))
    fail_key(path, "cell.height_m", format_number(cell.height), "expected a height > 0 m");
  const dem::Wall &bottom = walls[cell.bottom], &top = walls[cell.top];
  // A test moves the top platen along its normal and measures the strain
  // along the bottom one's: they must face each other across the sample.
  const dem::Vec3 up = bottom.direction.normalized(), down = top.direction.normalized();
  if ((up + down).norm() > 1e-6)
    fail_key(path, "walls[" + std::to_string(cell.top) + "].direction",
             format_number(top.direction.x()) + ", " + format_number(top.direction.y()) + ", " +
               format_number(top.direction.z()),
             "expected the top platen's normal opposite to the bottom platen's (walls[" + std::to_string(cell.bottom) +
               "].direction)");
  const double gap = (top.point - bottom.point).dot(up);
  if (!(gap > 0))
    fail_key(path, "walls[" + std::to_string(cell.top) + "].point_m", format_number(gap) + " m from the bottom platen",
             "expected the top platen above the bottom one, along the bottom platen's normal");
  // Every ball inside the cell, and no two piled on one another: a ball
  // beyond a wall never meets it (the test would measure nothing, or a
  // ball that falls for ever), and balls at one point have no contact
  // normal (and make every neighbour search quadratic).
  const dem::ParticleStore &balls = sample.snapshot.particles;
  const auto where = [&](dem::Index b)
  {
    const dem::Vec3 &x = balls.position[b];
    return format_number(x.x()) + ", " + format_number(x.y()) + ", " + format_number(x.z());
  };
  const auto row = [](dem::Index b) { return "balls.rows[" + std::to_string(b) + "]"; };
  for (dem::Index b = 0; b < balls.size(); ++b)
  {
    const double height = (balls.position[b] - bottom.point).dot(up);
    if (!(height >= 0 && height <= gap))
      fail_key(path, row(b), where(b) + " m",
               "expected a ball centre between the platens (0 ... " + format_number(gap) +
                 " m above the bottom platen; this one is " + format_number(height) + " m)");
    if (cell.lateral >= 0)
    {
      // A removed lateral wall (an unconfined test) confines nothing, but a
      // ball farther from the axis than the cell's diameter is no part of
      // the sample: it would carry load alone between the platens.
      const dem::Wall &side = walls[cell.lateral];
      const double reach = side.enabled ? side.radius : std::max(side.radius, cell.diameter);
      const dem::Vec3 axis = side.direction.normalized(), off = balls.position[b] - side.point;
      const double radial = (off - off.dot(axis) * axis).norm();
      if (!(radial <= reach))
        fail_key(path, row(b), where(b) + " m",
                 "expected a ball centre within " + format_number(reach) + " m of the lateral wall's axis (" +
                   (side.enabled ? "its radius" : "the cell's diameter: the wall is removed") + "; this one is " +
                   format_number(radial) + " m from it)");
    }
  }
  if (const std::optional<dem::DeepOverlap> deep = dem::first_deep_overlap(balls, 0.5))
  {
    const auto [i, j] = deep->pair;
    fail_key(path, row(j), where(j) + " m",
             "expected balls that overlap by at most half the smaller radius (it overlaps " + row(i) + " by " +
               format_number(deep->overlap) + " m)");
  }
}
} // namespace demvv
