#include "app/kinds/scene.h"

#include "app/decks/csv_input.h"
#include "app/decks/deck_sections.h"
#include "app/io/input.h"
#include "app/io/text.h"

#include "dem/measure.h"
#include "dem/neighbors.h"
#include "dem/spatial_order.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <sstream>

namespace demvv
{
namespace
{

void declare_plane(DeckSchema &s)
{
  s.flag("enabled", true, "Whether this plane wall exists (false keeps it in the deck, switched off).");
  s.vector3("point", "0, 0, 0", "m", "A point on the plane.");
  s.vector3("normal", "0, 0, 1", "-", "Normal of the plane, pointing towards the balls (normalised).");
  s.vector3("velocity", "0, 0, 0", "m/s", "Constant velocity of the plane.");
  declare_wall_properties(s, 1.2e7, 0, 0);
}

void declare_cylinder(DeckSchema &s)
{
  s.flag("enabled", true, "Whether this cylindrical wall exists (false keeps it in the deck, switched off).");
  s.vector3("axis point", "0, 0, 0", "m", "A point on the axis.");
  s.vector3("axis", "0, 0, 1", "-", "Direction of the axis (normalised).");
  s.real("radius", 0.01, 0, inf, "m", "Inner radius.", Interval::open_below);
  s.real("radial velocity", 0, -inf, inf, "m/s", "Rate of change of the radius (> 0 expands).");
  declare_wall_properties(s, 1.2e7, 0, 0);
}

/// The wall's name in the series columns: the label, or keyword + label
/// when the label is a number ("plane 2" -> plane2) or absent.
std::string wall_name(const std::string &section, const std::string &keyword)
{
  const std::string label = section.size() > keyword.size() ? section.substr(keyword.size() + 1) : "";
  const bool numeric = !label.empty() && label.find_first_not_of("0123456789") == std::string::npos;
  return label.empty() || numeric ? keyword + label : label;
}
} // namespace

void declare_scene(DeckSchema &s)
{
  s.text("title", "", "One line saying what this scene is for (copied to summary.json).");
  s.enter("particles");
  s.file("file", "particles.csv",
         "CSV of balls, relative to the deck: x_m,y_m,z_m,radius_m [m] and optional vx_mps,vy_mps,vz_mps "
         "[m/s], wx_radps,wy_radps,wz_radps [rad/s], hold_velocity, hold_spin (0/1: keep the given "
         "velocity / spin whatever the forces), density_kgpm3 [kg/m^3], kn_npm, ks_npm [N/m], friction "
         "[-] (these four override the balls section per ball).  Every value must be a finite number, every "
         "column one of these (once), and no two balls may start overlapping by more than half the smaller "
         "radius.");
  s.leave();
  declare_ball_properties(s);
  declare_contact_law(s);
  declare_bonds(s, {"none", "touching", "list"});
  s.enter("walls");
  s.real("resting overlap", 1e-3, 0, 0.1, "-",
         "Largest ball-wall overlap accepted at the start, as a fraction of the ball radius (a ball "
         "resting on a wall); larger overlaps are refused as input errors.");
  s.repeated("plane", &declare_plane,
             "a plane wall; its forces go to series.csv as NAME_force_x_n ... (a numeric NAME k gives planek)");
  s.repeated("cylinder", &declare_cylinder,
             "a cylindrical wall that confines the balls to its inside; its forces go to series.csv as "
             "NAME_force_x_n ... (the bare 'cylinder' gives cylinder)");
  s.leave();
  declare_rate(s);
  declare_motion(s, "0, 0, 0", 0.7);
  s.enter("run");
  s.real("duration", 1e-3, 0, inf, "s", "Simulated time.", Interval::open_below);
  s.leave();
  s.enter("output");
  // A row costs about half a step (energies, counts, coordination): rows
  // 1e-5 s apart are 100 per millisecond, and with the steps of millimetre
  // grains (1e-7 s and longer) cost at most half a percent of a run.
  s.real("interval", 1e-5, 0, inf, "s",
         "Time between output rows; 0 writes every step.  The energy ledger and the overlap guard are checked "
         "at every row.");
  s.text("track particles", "",
         "Balls whose motion goes to particles.csv: rows of the particle file, from 0, comma separated.");
  s.text("track pairs", "", "Pairs whose contact goes to contacts.csv: 'i-j' items, comma separated.");
  s.flag("paraview", false, "Write ParaView files (particles, contact forces, broken bonds) to paraview/.");
  s.real("paraview interval", 0, 0, inf, "s", "Time between ParaView frames; 0 uses the output interval.");
  declare_checkpoint_interval(s);
  s.leave();
}

namespace
{
std::vector<std::string> items(const std::string &list)
{
  std::vector<std::string> out;
  std::string item;
  std::istringstream in(list);
  while (std::getline(in, item, ','))
  {
    const auto b = item.find_first_not_of(" \t");
    if (b == std::string::npos)
      continue;
    out.push_back(item.substr(b, item.find_last_not_of(" \t") - b + 1));
  }
  return out;
}

dem::Index parse_index(const Deck &deck, const std::string &key, const std::string &text, dem::Index n)
{
  char *end = nullptr;
  const long v = std::strtol(text.c_str(), &end, 10);
  if (text.empty() || *end != '\0' || v < 0 || v >= n)
    deck.fail(key, "expected ball indices in [0, " + std::to_string(n - 1) + "], found '" + text + "'");
  return static_cast<dem::Index>(v);
}

/// Balls that start overlapping by more than half the smaller radius are
/// refused: such a contact stores a spring energy the linear law was never
/// meant for (it is released in the first steps and flings the balls apart),
/// and balls at one point have no contact normal at all.  Half a radius is
/// also the displacement per step the engine calls runaway motion.
/// Deliberately pre-compressed pairs (a fraction of a percent) pass.
void check_overlaps(const CsvTable &t, const dem::ParticleStore &p)
{
  const std::optional<dem::DeepOverlap> deep = dem::first_deep_overlap(p, 0.5);
  if (!deep)
    return;
  const auto [i, j] = deep->pair;
  std::ostringstream what;
  what << "particle " << j << " overlaps particle " << i << " (line " << t.line(static_cast<std::size_t>(i)) << ") by "
       << deep->overlap << " m at the start: expected balls that overlap by at most half the smaller "
       << "radius (" << 0.5 * std::min(p.radius[i], p.radius[j]) << " m)";
  t.fail(static_cast<std::size_t>(j), "x_m", what.str());
}

dem::ParticleStore parse_particles(const Deck &deck)
{
  const CsvTable t = CsvTable::read(deck.input_file("particles/file"));
  t.allow_only({"x_m", "y_m", "z_m", "radius_m", "vx_mps", "vy_mps", "vz_mps", "wx_radps", "wy_radps", "wz_radps",
                "density_kgpm3", "kn_npm", "ks_npm", "friction", "hold_velocity", "hold_spin"},
               "a particle file");
  if (t.rows() == 0)
    throw DeckError(t.path() + ": no particles: expected at least one row after the header");
  for (const char *c : {"x_m", "y_m", "z_m", "radius_m"})
    if (!t.has(c))
      throw DeckError(t.path() + ": column '" + std::string(c) +
                      "' is missing: expected a header with x_m,y_m,z_m,radius_m");
  check_memory(dem::estimated_memory_bytes(double(t.rows()), int(deck.instances("walls", "plane").size() +
                                                                 deck.instances("walls", "cylinder").size())),
               std::to_string(t.rows()) + " balls", t.path(), "rows", std::to_string(t.rows()), "expected fewer balls");
  const dem::BallSpec common = parse_ball_properties(deck);
  dem::ParticleStore p;
  p.reserve(static_cast<dem::Index>(t.rows()));
  for (std::size_t r = 0; r < t.rows(); ++r)
  {
    dem::BallSpec b = common;
    b.position = {t.get(r, "x_m"), t.get(r, "y_m"), t.get(r, "z_m")};
    b.radius = t.get(r, "radius_m");
    b.velocity = {t.get(r, "vx_mps", 0), t.get(r, "vy_mps", 0), t.get(r, "vz_mps", 0)};
    b.spin = {t.get(r, "wx_radps", 0), t.get(r, "wy_radps", 0), t.get(r, "wz_radps", 0)};
    b.density = t.get(r, "density_kgpm3", b.density);
    b.kn = t.get(r, "kn_npm", b.kn);
    b.ks = t.get(r, "ks_npm", b.ks);
    b.friction = t.get(r, "friction", b.friction);
    // The table holds finite numbers only (csv_input.h); the deck's balls
    // section is checked by its patterns.
    if (!(b.radius > 0))
      t.fail(r, "radius_m", "expected a radius > 0 m");
    if (!(b.density > 0))
      t.fail(r, "density_kgpm3", "expected a density > 0 kg/m^3");
    if (!(b.kn > 0))
      t.fail(r, "kn_npm", "expected a normal stiffness > 0 N/m");
    if (!(b.ks >= 0))
      t.fail(r, "ks_npm", "expected a shear stiffness >= 0 N/m");
    if (!(b.friction >= 0))
      t.fail(r, "friction", "expected a friction coefficient >= 0");
    for (const char *flag : {"hold_velocity", "hold_spin"})
    {
      const double v = t.get(r, flag, 0);
      if (v != 0 && v != 1)
        t.fail(r, flag, "expected 0 or 1");
    }
    b.hold_velocity = t.get(r, "hold_velocity", 0) == 1;
    b.hold_spin = t.get(r, "hold_spin", 0) == 1;
    for (int k = 0; k < 3; ++k)
      if (!std::isfinite(b.position[k]) || !std::isfinite(b.velocity[k]) || !std::isfinite(b.spin[k]))
        throw DeckError(t.path() + ":" + std::to_string(t.line(r)) + ": non-finite position, velocity or spin");
    const dem::Index i = p.add(b);
    // The step bound divides by the mass and the moment of inertia: both
    // must be normal numbers, neither 0 by underflow nor infinite.
    const auto normal = [](double v) { return v >= std::numeric_limits<double>::min() && std::isfinite(v); };
    if (!normal(p.mass[i]) || !normal(p.inertia[i]))
      t.fail(r, "radius_m",
             "gives a ball of mass " + format_number(p.mass[i]) + " kg and moment of inertia " +
               format_number(p.inertia[i]) +
               " kg m^2: expected a radius whose mass and moment of inertia are "
               "finite and above 2.2e-308");
  }
  check_overlaps(t, p);
  return p;
}

/// The walls in the order the deck names them, planes first, and for each
/// wall the deck key that places it (for errors found later).
dem::WallSet parse_walls(const Deck &deck, std::vector<std::string> &placing_key)
{
  dem::WallSet walls;
  for (const std::string &section : deck.instances("walls", "plane"))
  {
    const std::string sec = "walls/" + section;
    if (!deck.flag(sec + "/enabled"))
      continue;
    dem::Wall w;
    w.name = wall_name(section, "plane");
    w.shape = dem::WallShape::plane;
    w.point = parse_vec3(deck, sec + "/point");
    w.direction = parse_vec3(deck, sec + "/normal", true);
    w.velocity = parse_vec3(deck, sec + "/velocity");
    w.props = parse_wall_properties(deck, sec);
    walls.add(w);
    placing_key.push_back(sec + "/point");
  }
  for (const std::string &section : deck.instances("walls", "cylinder"))
  {
    const std::string sec = "walls/" + section;
    if (!deck.flag(sec + "/enabled"))
      continue;
    dem::Wall w;
    w.name = wall_name(section, "cylinder");
    w.shape = dem::WallShape::cylinder;
    w.point = parse_vec3(deck, sec + "/axis point");
    w.direction = parse_vec3(deck, sec + "/axis", true);
    w.radius = deck.real(sec + "/radius");
    w.radial_velocity = deck.real(sec + "/radial velocity");
    w.props = parse_wall_properties(deck, sec);
    walls.add(w);
    placing_key.push_back(sec + "/radius");
  }
  for (dem::WallIndex a = 0; a < walls.size(); ++a)
    for (dem::WallIndex b = 0; b < a; ++b)
      if (walls[a].name == walls[b].name)
        deck.fail(placing_key[a], "two walls are both named '" + walls[a].name + "': expected distinct names");
  return walls;
}

/// A wall that starts inside a ball would fling it away: bad input.
void check_walls_clear(const Deck &deck, const dem::ParticleStore &p, const dem::WallSet &walls,
                       const std::vector<std::string> &placing_key)
{
  const double resting = deck.real("walls/resting overlap");
  for (dem::WallIndex w = 0; w < walls.size(); ++w)
    for (dem::Index b = 0; b < p.size(); ++b)
    {
      const double clearance = walls.clearance(w, p.position[b]);
      if (clearance < p.radius[b] * (1 - resting))
      {
        std::ostringstream msg;
        msg << "wall '" << walls[w].name << "' overlaps particle " << b << " at the start (clearance " << clearance
            << " m, radius " << p.radius[b] << " m): expected every ball clear of every wall, up to "
            << "the resting overlap of walls/resting overlap";
        deck.fail(placing_key[w], msg.str());
      }
    }
}

/// The bonds of a list file: each pair once, between balls that touch
/// within bonds/touch tolerance, as install = touching has them (a contact
/// bond joins a contact, thesis §3.4; one across a gap would pull the balls
/// together with the full stiffness of the gap).
std::vector<ListedBond> parse_bond_list(const BondSpec &bonds, const dem::ParticleStore &p)
{
  const dem::Index n = p.size();
  std::vector<ListedBond> out;
  std::map<dem::Pair, std::size_t> listed; // pair -> row
  if (bonds.install != "list")
    return out;
  const CsvTable t = CsvTable::read(bonds.list_file);
  t.allow_only({"first", "second", "normal_strength_n", "shear_strength_n"}, "a bond list");
  for (std::size_t r = 0; r < t.rows(); ++r)
  {
    for (const char *c : {"first", "second"})
    {
      const double v = t.get(r, c);
      if (v < 0 || v >= n || v != std::floor(v) || (std::string(c) == "second" && v == t.get(r, "first")))
        t.fail(r, c, "expected a ball index in [0, " + std::to_string(n - 1) + "], distinct from the other");
    }
    ListedBond b;
    b.first = static_cast<dem::Index>(t.get(r, "first"));
    b.second = static_cast<dem::Index>(t.get(r, "second"));
    const dem::Pair pair{std::min(b.first, b.second), std::max(b.first, b.second)};
    if (const auto [at, added] = listed.emplace(pair, r); !added)
      t.fail(r, "second",
             "the pair is listed again (first at line " + std::to_string(t.line(at->second)) +
               "): expected each bond once");
    const double gap = (p.position[b.second] - p.position[b.first]).norm() - p.radius[b.first] - p.radius[b.second];
    if (gap > bonds.settings.touch_tolerance * std::min(p.radius[b.first], p.radius[b.second]))
    {
      std::ostringstream what;
      what << "balls " << b.first << " and " << b.second << " are " << gap
           << " m apart: expected a bond between balls that touch";
      t.fail(r, "second", what.str());
    }
    b.normal_strength = t.get(r, "normal_strength_n", bonds.settings.normal_strength);
    b.shear_strength = t.get(r, "shear_strength_n", bonds.settings.shear_strength);
    if (!(b.normal_strength > 0))
      t.fail(r, "normal_strength_n", "expected a strength > 0 N");
    if (!(b.shear_strength > 0))
      t.fail(r, "shear_strength_n", "expected a strength > 0 N");
    out.push_back(b);
  }
  return out;
}

/// Renumbers the balls along the Morton curve (dem/spatial_order.h) once
/// every check has named them by their file rows, and the bonds and tracked
/// balls with them: the same balls in any file order run alike.
void number_along_curve(SceneSpec &spec)
{
  spec.file_row = dem::morton_order(spec.particles);
  spec.particles = dem::renumbered(spec.particles, spec.file_row);
  const std::vector<dem::Index> index_of = dem::inverse_permutation(spec.file_row);
  for (ListedBond &b : spec.bond_list)
  {
    b.first = index_of[b.first];
    b.second = index_of[b.second];
  }
  for (dem::Index &p : spec.tracked)
    p = index_of[p];
  for (dem::Pair &pr : spec.tracked_pairs)
    pr = {std::min(index_of[pr.first], index_of[pr.second]), std::max(index_of[pr.first], index_of[pr.second])};
}

dem::BondReport install_bonds(const SceneSpec &spec, dem::Simulation &sim)
{
  dem::BondReport report;
  if (spec.bonds.install == "none")
    return report;
  sim.refresh_contacts();
  if (spec.bonds.install == "touching")
    return dem::bond_touching_pairs(sim.contacts(), sim.particles(), spec.bonds.settings);
  for (const ListedBond &b : spec.bond_list)
  {
    dem::bond_pair(sim.contacts(), sim.particles(), b.first, b.second, b.normal_strength, b.shear_strength);
    ++report.bonded;
  }
  return report;
}

std::vector<std::string> series_columns(const dem::WallSet &walls)
{
  std::vector<std::string> c = {"time_s",
                                "step",
                                "time_step_s",
                                "kinetic_energy_j",
                                "strain_energy_j",
                                "friction_dissipated_j",
                                "damping_dissipated_j",
                                "bond_energy_released_j",
                                "boundary_work_j",
                                "gravity_work_j",
                                "energy_residual_j",
                                "contacts",
                                "bonds_intact",
                                "bonds_broken_tension",
                                "bonds_broken_shear",
                                "bonds_broken_displacement",
                                "coordination_number",
                                "unbalanced_force_ratio"};
  for (dem::WallIndex w = 0; w < walls.size(); ++w)
    for (const char *axis : {"x", "y", "z"})
      c.push_back(walls[w].name + "_force_" + axis + "_n");
  return c;
}

/// A scene as the DEM driver runs it: nothing moves but what the deck
/// prescribes; rows record energies, counts and wall forces, and the
/// tracked balls and pairs.
class SceneProtocol final : public DemProtocol
{
public:
  SceneProtocol(const SceneSpec &spec, SceneResult &result) : spec_(spec), result_(result) {}

  std::string label() const override { return "scene " + spec_.deck.name; }
  std::string clock_name() const override { return "time_s"; }
  double clock(const dem::Simulation &sim) const override { return sim.time(); }
  double fraction_done(const dem::Simulation &sim) const override { return sim.time() / spec_.duration; }
  bool finished(const dem::Simulation &sim) const override { return sim.time() >= spec_.duration; }
  double time_left(const dem::Simulation &sim) const override { return spec_.duration - sim.time(); }
  [[noreturn]] void refuse_duration(const std::string &expected) const override
  {
    spec_.deck.fail("run/duration", format_number(spec_.duration), expected);
  }
  std::string state_text(const dem::Simulation &sim) const override
  {
    char text[64];
    std::snprintf(text, sizeof text, "t = %.4g s", sim.time());
    return text;
  }

  void measure(const dem::Simulation &sim) override
  {
    const double t = sim.time();
    const dem::ParticleStore &P = sim.particles();
    for (dem::Index p : spec_.tracked)
      result_.particles.add({t, double(row_of(p)), P.position[p].x(), P.position[p].y(), P.position[p].z(),
                             P.velocity[p].x(), P.velocity[p].y(), P.velocity[p].z(), P.spin[p].x(), P.spin[p].y(),
                             P.spin[p].z(), P.force[p].x(), P.force[p].y(), P.force[p].z()});
    for (const dem::Pair &pr : spec_.tracked_pairs)
    {
      const dem::Contact *c = sim.contacts().find(pr.first, pr.second);
      const dem::ContactState s = c ? c->state : dem::ContactState{};
      const double gap =
        (P.position[pr.second] - P.position[pr.first]).norm() - P.radius[pr.first] - P.radius[pr.second];
      // Written by file rows, smaller first, the shear force on the second:
      // where the run's numbering swaps the pair, so does the force's sign.
      const dem::Index a = row_of(pr.first), b = row_of(pr.second);
      const dem::Vec3 shear = a < b ? s.shear_force : dem::Vec3(dem::Vec3::Zero() - s.shear_force); // no -0
      result_.contacts.add({t, double(std::min(a, b)), double(std::max(a, b)), s.touching() ? s.overlap : -gap,
                            s.normal_force, shear.norm(), shear.x(), shear.y(), shear.z(), c && c->bonded ? 1.0 : 0.0,
                            s.touching() ? 1.0 : 0.0});
    }
  }

  void record(const dem::Simulation &sim) override
  {
    const dem::EnergyLedger e = sim.energy();
    std::size_t touching = 0, intact = 0;
    for (const dem::Contact &c : sim.contacts().entries())
    {
      touching += c.state.touching() ? 1 : 0;
      intact += c.bonded ? 1 : 0;
    }
    std::vector<double> row = {sim.time() - sim.time_step(),
                               double(sim.steps() - 1),
                               sim.time_step(),
                               e.kinetic,
                               e.strain,
                               e.friction,
                               e.damping,
                               e.bond_released,
                               e.boundary_work,
                               e.body_work,
                               e.residual(),
                               double(touching),
                               double(intact),
                               double(sim.bonds_broken(dem::BreakMode::tension)),
                               double(sim.bonds_broken(dem::BreakMode::shear)),
                               double(sim.bonds_broken(dem::BreakMode::displacement)),
                               dem::coordination_number(sim.particles(), sim.contacts()),
                               dem::unbalanced_force_ratio(sim.particles(), sim.contacts())};
    for (dem::WallIndex w = 0; w < sim.walls().size(); ++w)
    {
      const dem::Vec3 f = sim.wall_force(w);
      row.insert(row.end(), {f.x(), f.y(), f.z()});
    }
    result_.series.add(std::move(row));
  }

  std::vector<SeriesFile> series_files() override
  {
    const std::string convention = "demvv scene '" + spec_.deck.name + "': SI units, compression positive";
    std::vector<SeriesFile> files = {{&result_.series, "series.csv", convention}};
    if (!spec_.tracked.empty())
      files.push_back({&result_.particles, "particles.csv", convention + "; velocities at t - dt/2"});
    if (!spec_.tracked_pairs.empty())
      files.push_back({&result_.contacts, "contacts.csv",
                       convention + "; normal force > 0 in compression, force on the second ball"});
    return files;
  }

  bool resolves_contact_dynamics() const override { return true; }

  nlohmann::json summary(const dem::Simulation &sim, const RunStatus &status, const ContactResolution &resolution,
                         const RunDirectory * /*dir*/) const override
  {
    const dem::EnergyLedger e = sim.energy();
    const dem::Index n = sim.particles().size();
    return {
      {"kind", "scene"},
      {"title", spec_.title},
      {"contact_law", std::string(sim.model().name())},
      {"rate", spec_.rate.to_json()},
      {"particles", n},
      {"steps", sim.steps()},
      {"final_time_s", sim.time()},
      {"last_time_step_s", sim.time_step()},
      {"critical_time_step_bound_s", resolution.smallest_bound_json()},
      {"contact_resolution", resolution.to_json()},
      {"neighbour_rebuilds", sim.neighbors().rebuilds()},
      {"contacts_in_lanes", sim.contacts_in_lanes()},
      {"bonds",
       {{"installed", result_.bonds.bonded},
        {"removed", result_.bonds.removed},
        {"truncated_strength_draws", result_.bonds.truncated_draws},
        {"broken_tension", sim.bonds_broken(dem::BreakMode::tension)},
        {"broken_shear", sim.bonds_broken(dem::BreakMode::shear)},
        {"broken_displacement", sim.bonds_broken(dem::BreakMode::displacement)}}},
      {"energy_j",
       {{"kinetic", e.kinetic},
        {"strain", e.strain},
        {"friction", e.friction},
        {"damping", e.damping},
        {"bond_released", e.bond_released},
        {"boundary_work", e.boundary_work},
        {"gravity_work", e.body_work},
        {"initial", e.initial},
        {"residual", e.residual()}}},
      {"wall_seconds", status.wall_seconds},
      {"particle_steps_per_second", status.wall_seconds > 0 ? double(n) * sim.steps() / status.wall_seconds : 0.0}};
  }

private:
  /// Ball k's row in the particle file (k itself for a spec whose balls
  /// were never renumbered).
  dem::Index row_of(dem::Index k) const { return dem::file_row(spec_.file_row, k); }

  const SceneSpec &spec_;
  SceneResult &result_;
};
} // namespace

SceneSpec parse_scene(const Deck &deck)
{
  SceneSpec spec;
  spec.deck = DeckRecord(deck);
  spec.title = deck.text("title");
  spec.particles = parse_particles(deck);
  std::vector<std::string> placing_key;
  spec.walls = parse_walls(deck, placing_key);
  check_walls_clear(deck, spec.particles, spec.walls, placing_key);
  spec.law = LawSpec::parse(deck);
  spec.rate = RateSpec::parse(deck).scaling(0);
  spec.motion = parse_motion(deck);
  spec.bonds = BondSpec::parse(deck);
  spec.bond_list = parse_bond_list(spec.bonds, spec.particles);
  // Without bonds nearly every contact is ordinary and the linear law's
  // blocks of eight pay; where bonds break they cost (BENCHMARKS.md, "Eight
  // contacts per instruction").
  spec.motion.contacts_in_lanes = spec.bonds.install == "none";
  spec.duration = deck.real("run/duration");
  spec.output.interval = deck.real("output/interval");
  spec.output.paraview = deck.flag("output/paraview");
  spec.output.paraview_interval = deck.real("output/paraview interval");
  spec.output.checkpoint_interval = deck.real("output/checkpoint interval");
  const dem::Index n = spec.particles.size();
  std::set<dem::Index> tracked;
  for (const auto &item : items(deck.text("output/track particles")))
  {
    spec.tracked.push_back(parse_index(deck, "output/track particles", item, n));
    if (!tracked.insert(spec.tracked.back()).second)
      deck.fail("output/track particles", "ball " + item + " is named twice: expected each ball once");
  }
  std::set<dem::Pair> pairs;
  for (const auto &item : items(deck.text("output/track pairs")))
  {
    const auto dash = item.find('-');
    if (dash == std::string::npos)
      deck.fail("output/track pairs", "expected items of the form i-j, found '" + item + "'");
    dem::Index i = parse_index(deck, "output/track pairs", item.substr(0, dash), n);
    dem::Index j = parse_index(deck, "output/track pairs", item.substr(dash + 1), n);
    if (i == j)
      deck.fail("output/track pairs", "expected two different balls in '" + item + "'");
    if (!pairs.insert({std::min(i, j), std::max(i, j)}).second)
      deck.fail("output/track pairs", "the pair '" + item + "' is named twice: expected each pair once");
    spec.tracked_pairs.emplace_back(i, j);
  }
  number_along_curve(spec);
  return spec;
}

SceneResult run_scene(const SceneSpec &spec, const RunOptions &options)
{
  const int threads = apply_threads(options);
  dem::ParticleStore particles = spec.particles;
  spec.rate.scale_ball_stiffness(particles);
  SceneResult result;
  result.sim =
    std::make_unique<dem::Simulation>(std::move(particles), spec.walls, spec.law.make(spec.rate), spec.motion);
  dem::Simulation &sim = *result.sim;
  result.bonds = install_bonds(spec, sim);
  spec.bonds.finish(sim.contacts(), sim.particles(), spec.rate);

  result.series = Series(series_columns(sim.walls()));
  result.particles = Series({"time_s", "particle", "x_m", "y_m", "z_m", "vx_mps", "vy_mps", "vz_mps", "wx_radps",
                             "wy_radps", "wz_radps", "fx_n", "fy_n", "fz_n"});
  result.contacts = Series({"time_s", "first", "second", "overlap_m", "normal_force_n", "shear_force_n", "shear_x_n",
                            "shear_y_n", "shear_z_n", "bonded", "touching"});
  const std::string convention = "demvv scene '" + spec.deck.name + "': SI units, compression positive";
  RunFiles files(options, spec.deck, threads, static_cast<long long>(spec.bonds.settings.seed), convention,
                 spec.output.paraview);
  files.set_ball_ids(spec.file_row);
  SceneProtocol protocol(spec, result);
  result.status = run_dem(sim, protocol, files, spec.output, options).status;
  return result;
}

SceneResult run_scene(const Deck &deck, const RunOptions &options) { return run_scene(parse_scene(deck), options); }
} // namespace demvv
