#include "verify/io/sample_file.h"

#include "verify/decks/deck.h"
#include "verify/io/output.h"

#include "dem/contact_model.h"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string_view>

namespace verify
{
namespace
{
using nlohmann::json;

json vec(const dem::Vec3 &v) { return json::array({v.x(), v.y(), v.z()}); }

dem::Vec3 vec(const json &j) { return {j.at(0).get<double>(), j.at(1).get<double>(), j.at(2).get<double>()}; }

const std::vector<std::string> ball_columns = {
  "x_m",          "y_m",          "z_m",          "radius_m",      "density_kgpm3",  "kn_npm",
  "ks_npm",       "friction",     "vx_mps",       "vy_mps",        "vz_mps",         "wx_radps",
  "wy_radps",     "wz_radps",     "hold_velocity", "hold_spin",    "boundary_work_j", "body_work_j",
  "damping_work_j", "kinetic_energy_j"};

const std::vector<std::string> state_columns = {"touching", "normal_force_n", "overlap_m", "nx",
                                                "ny",       "nz",             "shear_x_n", "shear_y_n",
                                                "shear_z_n", "friction_work_j", "bond_energy_j"};

constexpr int format_version = 2;

/// Contact columns: pair, constants, bond (with its break distance from
/// version 2 on), ContactState, then the law's own state (none in a version
/// 1 file).
std::vector<std::string> contact_columns(const std::vector<std::string_view> &law_fields, int version)
{
  std::vector<std::string> c = {"first",    "second",           "kn_npm",          "ks_npm",
                                "friction", "bonded",           "normal_strength_n", "shear_strength_n"};
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
  for (double v : {s.touching ? 1.0 : 0.0, s.normal_force, s.overlap, s.normal.x(), s.normal.y(), s.normal.z(),
                   s.shear_force.x(), s.shear_force.y(), s.shear_force.z(), s.friction_work, s.bond_energy})
    row.push_back(v);
}

dem::ContactState read_state(const json &row, std::size_t at)
{
  dem::ContactState s;
  s.touching = row.at(at).get<double>() != 0;
  s.normal_force = row.at(at + 1).get<double>();
  s.overlap = row.at(at + 2).get<double>();
  s.normal = {row.at(at + 3).get<double>(), row.at(at + 4).get<double>(), row.at(at + 5).get<double>()};
  s.shear_force = {row.at(at + 6).get<double>(), row.at(at + 7).get<double>(), row.at(at + 8).get<double>()};
  s.friction_work = row.at(at + 9).get<double>();
  s.bond_energy = row.at(at + 10).get<double>();
  return s;
}

/// Rows of a {columns, rows} table, checking its columns.
const json &table_rows(const json &doc, const char *name, const std::vector<std::string> &columns,
                       const std::string &path)
{
  if (!doc.contains(name))
    throw DeckError(path + ": no '" + std::string(name) + "' table: expected a demvv sample file");
  const json &t = doc.at(name);
  if (t.at("columns").get<std::vector<std::string>>() != columns)
    throw DeckError(path + ": table '" + std::string(name) + "' has other columns than this demvv writes");
  for (const json &row : t.at("rows"))
    if (row.size() != columns.size())
      throw DeckError(path + ": a row of table '" + std::string(name) + "' has " + std::to_string(row.size()) +
                      " values for " + std::to_string(columns.size()) + " columns");
  return t.at("rows");
}
} // namespace

json report_json(const dem::PackingReport &r)
{
  json stages = json::array();
  for (const auto &s : r.stages)
    stages.push_back({{"name", s.name},
                      {"cycles", s.cycles},
                      {"converged", s.converged},
                      {"mean_stress_pa", s.mean_stress},
                      {"unbalanced_force_ratio", s.unbalanced_ratio},
                      {"solid_fraction", s.solid_fraction},
                      {"coordination_number", s.coordination}});
  return {{"particles", r.particles},
          {"cell_diameter_m", r.cell_diameter},
          {"cell_height_m", r.cell_height},
          {"stages", stages},
          {"radius_change", r.radius_change},
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
          {"bonds", {{"installed", r.bonds.bonded},
                     {"removed", r.bonds.removed},
                     {"truncated_strength_draws", r.bonds.truncated_draws},
                     {"mean_normal_strength_n", r.bonds.mean_normal_strength},
                     {"mean_shear_strength_n", r.bonds.mean_shear_strength}}},
          {"mean_contact_force_before_bonding_n", r.mean_contact_force_before},
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
  for (dem::Contact &c : snap.contacts)
    c.params = dem::ContactTable::pair_params(p, c.first, c.second);
  snap.walls[sample.cell.bottom].props = platen;
  snap.walls[sample.cell.top].props = platen;
  const double last_step = snap.clock.last_time_step;
  snap.clock = dem::SimulationClock{};
  snap.clock.last_time_step = last_step;
}

void write_sample(const std::string &path, const SampleFile &sample)
{
  const dem::Snapshot &s = sample.snapshot;
  const dem::SimulationClock &c = s.clock;
  const std::string law_keyword =
    !s.contact_law.empty() ? s.contact_law : !sample.contact_law.empty() ? sample.contact_law : "linear";
  if (!s.contact_law.empty() && !sample.contact_law.empty() && s.contact_law != sample.contact_law)
    throw std::invalid_argument(path + ": the sample names contact law '" + sample.contact_law +
                                "' but its snapshot holds the state of '" + s.contact_law + "'");
  if (!s.law_states.empty() && s.law_states.size() != s.contacts.size())
    throw std::invalid_argument(path + ": " + std::to_string(s.law_states.size()) + " law states for " +
                                std::to_string(s.contacts.size()) + " contacts");
  const std::vector<std::string_view> &law_fields = sample_law(law_keyword, path).state_fields;
  json doc = {{"format", "demvv-sample"},
              {"format_version", format_version},
              {"units", "SI (m, kg, s, N, J); compression positive"},
              {"title", sample.title},
              {"seed", sample.seed},
              {"contact_law", law_keyword},
              {"cell", {{"diameter_m", sample.cell.diameter},
                        {"height_m", sample.cell.height},
                        {"bottom", sample.cell.bottom},
                        {"top", sample.cell.top},
                        {"lateral", sample.cell.lateral}}},
              {"preparation", sample.preparation},
              {"provenance", sample.provenance},
              {"clock", {{"time_s", c.time},
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
    balls.push_back(json::array({p.position[b].x(), p.position[b].y(), p.position[b].z(), p.radius[b], p.density[b], p.kn[b],
                     p.ks[b], p.friction[b], p.velocity[b].x(), p.velocity[b].y(), p.velocity[b].z(),
                     p.spin[b].x(), p.spin[b].y(), p.spin[b].z(), p.holds_velocity(b) ? 1 : 0,
                     p.holds_spin(b) ? 1 : 0, e.boundary, e.body, e.damping, e.kinetic}));
  }
  doc["balls"] = {{"columns", ball_columns}, {"rows", balls}};

  json contacts = json::array();
  for (std::size_t e = 0; e < s.contacts.size(); ++e)
  {
    const dem::Contact &k = s.contacts[e];
    json row = json::array({k.first, k.second, k.params.kn, k.params.ks, k.params.friction, k.bond.intact ? 1 : 0,
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
  for (std::size_t slot = 0; slot < s.wall_history.size(); ++slot)
  {
    const dem::ContactState &st = s.wall_history[slot];
    if (!st.touching && st.friction_work == 0 && st.shear_force.isZero(0))
      continue;
    json row = json::array({static_cast<long>(slot / p.size()), static_cast<long>(slot % p.size())});
    append_state(row, st);
    wall_contacts.push_back(row);
  }
  doc["wall_contacts"] = {{"columns", wall_contact_columns()}, {"rows", wall_contacts}};
  write_atomically(path, doc.dump() + "\n");
}

SampleFile read_sample(const std::string &path)
{
  json doc;
  try
  {
    doc = json::parse(read_file(path));
  }
  catch (const std::runtime_error &)
  {
    throw DeckError(path + ": cannot read the sample file (does it exist?)");
  }
  catch (const json::exception &e)
  {
    throw DeckError(path + ": not a valid sample file (JSON error: " + std::string(e.what()) + ")");
  }
  const int version = doc.value("format_version", 0);
  if (doc.value("format", "") != "demvv-sample" || version < 1 || version > format_version)
    throw DeckError(path + ": not a demvv sample file of format version 1 to " + std::to_string(format_version));
  try
  {
    SampleFile out;
    out.title = doc.value("title", "");
    out.seed = doc.value("seed", 0LL);
    out.contact_law = doc.value("contact_law", "linear");
    // Version 1 files have no law state: every contact's is at rest.
    const std::vector<std::string_view> law_fields =
      version == 1 ? std::vector<std::string_view>{} : sample_law(out.contact_law, path).state_fields;
    out.preparation = doc.value("preparation", json::object());
    out.provenance = doc.value("provenance", json::object());
    const json &cell = doc.at("cell");
    out.cell.diameter = cell.at("diameter_m");
    out.cell.height = cell.at("height_m");
    out.cell.bottom = cell.at("bottom");
    out.cell.top = cell.at("top");
    out.cell.lateral = cell.at("lateral");

    dem::Snapshot &s = out.snapshot;
    for (const json &w : doc.at("walls"))
    {
      dem::Wall wall;
      wall.name = w.at("name");
      wall.shape = w.at("shape") == "plane" ? dem::WallShape::plane : dem::WallShape::cylinder;
      wall.point = vec(w.at("point_m"));
      wall.direction = vec(w.at("direction"));
      wall.radius = w.at("radius_m");
      wall.velocity = vec(w.at("velocity_mps"));
      wall.radial_velocity = w.at("radial_velocity_mps");
      wall.props = {w.at("kn_npm").get<double>(), w.at("ks_npm").get<double>(), w.at("friction").get<double>()};
      wall.enabled = w.at("enabled");
      s.walls.push_back(wall);
    }
    dem::SimulationClock &c = s.clock;
    for (const json &row : table_rows(doc, "balls", ball_columns, path))
    {
      dem::BallSpec b;
      b.position = dem::Vec3(row[0].get<double>(), row[1].get<double>(), row[2].get<double>());
      b.radius = row[3];
      b.density = row[4];
      b.kn = row[5];
      b.ks = row[6];
      b.friction = row[7];
      b.velocity = dem::Vec3(row[8].get<double>(), row[9].get<double>(), row[10].get<double>());
      b.spin = dem::Vec3(row[11].get<double>(), row[12].get<double>(), row[13].get<double>());
      b.hold_velocity = row[14].get<double>() != 0;
      b.hold_spin = row[15].get<double>() != 0;
      if (!(b.radius > 0))
        throw DeckError(path + ": a ball has radius " + row[3].dump() + ": expected a radius > 0 m");
      s.particles.add(b);
      c.ball_energy.push_back({row[16].get<double>(), row[17].get<double>(), row[18].get<double>(),
                               row[19].get<double>()});
    }
    const auto n = static_cast<long>(s.particles.size());
    const std::vector<std::string> columns = contact_columns(law_fields, version);
    const std::size_t state_at = version >= 2 ? 9 : 8;
    const std::size_t law_at = columns.size() - law_fields.size();
    s.contact_law = out.contact_law;
    for (const json &row : table_rows(doc, "contacts", columns, path))
    {
      dem::Contact k;
      k.first = row[0];
      k.second = row[1];
      if (k.first < 0 || k.second >= n || k.first >= k.second)
        throw DeckError(path + ": contact (" + row[0].dump() + ", " + row[1].dump() + ") does not name two balls");
      k.params = {row[2].get<double>(), row[3].get<double>(), row[4].get<double>()};
      k.bond.intact = row[5].get<double>() != 0;
      k.bond.normal_strength = row[6];
      k.bond.shear_strength = row[7];
      if (version >= 2)
        k.bond.break_distance = row[8].is_null() ? std::numeric_limits<double>::infinity() : row[8].get<double>();
      k.state = read_state(row, state_at);
      s.contacts.push_back(k);
      if (law_fields.empty())
        continue;
      dem::LawState law;
      for (std::size_t f = 0; f < law_fields.size(); ++f)
        law.value[f] = row[law_at + f].get<double>();
      s.law_states.push_back(law);
    }
    s.wall_history.assign(static_cast<std::size_t>(n) * s.walls.size(), dem::ContactState{});
    for (const json &row : table_rows(doc, "wall_contacts", wall_contact_columns(), path))
    {
      const long w = row[0], b = row[1];
      if (w < 0 || w >= static_cast<long>(s.walls.size()) || b < 0 || b >= n)
        throw DeckError(path + ": wall contact (" + row[0].dump() + ", " + row[1].dump() + ") is out of range");
      s.wall_history[static_cast<std::size_t>(w * n + b)] = read_state(row, 2);
    }
    const json &clock = doc.at("clock");
    c.time = clock.at("time_s");
    c.steps = clock.at("steps");
    c.last_time_step = clock.at("last_time_step_s");
    c.initial_energy = clock.at("initial_energy_j");
    c.initial_recorded = clock.at("initial_recorded");
    c.removed_wall_strain = clock.at("removed_wall_strain_j");
    c.removed_wall_friction = clock.at("removed_wall_friction_j");
    c.broken_tension = clock.at("bonds_broken_tension");
    c.broken_shear = clock.at("bonds_broken_shear");
    c.broken_displacement = clock.value("bonds_broken_displacement", std::size_t{0});
    c.retired.friction_work = clock.at("retired_friction_work_j");
    c.retired.bond_energy = clock.at("retired_bond_energy_j");
    return out;
  }
  catch (const json::exception &e)
  {
    throw DeckError(path + ": malformed sample file (" + std::string(e.what()) + ")");
  }
}
} // namespace verify
