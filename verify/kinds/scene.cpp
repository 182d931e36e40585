#include "verify/kinds/scene.h"

#include "verify/decks/csv_input.h"
#include "verify/decks/deck_sections.h"
#include "verify/io/paraview.h"

#include "dem/measure.h"

#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>

namespace verify
{
namespace
{
constexpr double inf = std::numeric_limits<double>::infinity();
constexpr int plane_slots = 4;

std::string plane_section(int k) { return "walls/plane " + std::to_string(k); }
} // namespace

void declare_scene(DeckSchema &s)
{
  s.text("title", "", "One line saying what this scene is for (copied to summary.json).");
  s.enter("particles");
  s.text("file", "particles.csv",
         "CSV of balls, relative to the deck: x_m,y_m,z_m,radius_m [m] and optional vx_mps,vy_mps,vz_mps "
         "[m/s], wx_radps,wy_radps,wz_radps [rad/s], hold_velocity, hold_spin (0/1: keep the given "
         "velocity / spin whatever the forces), density_kgpm3 [kg/m^3], kn_npm, ks_npm [N/m], friction "
         "[-] (these four override the balls section per ball).");
  s.leave();
  declare_ball_properties(s);
  declare_contact_law(s);
  declare_bonds(s, {"none", "touching", "list"});
  s.enter("walls");
  s.real("resting overlap", 1e-3, 0, 0.1, "-",
         "Largest ball-wall overlap accepted at the start, as a fraction of the ball radius (a ball "
         "resting on a wall); larger overlaps are refused as input errors.");
  for (int k = 1; k <= plane_slots; ++k)
  {
    s.enter("plane " + std::to_string(k));
    s.flag("enabled", false, "Whether this plane wall exists.");
    s.vector3("point", "0, 0, 0", "m", "A point on the plane.");
    s.vector3("normal", "0, 0, 1", "-", "Normal of the plane, pointing towards the balls (normalised).");
    s.vector3("velocity", "0, 0, 0", "m/s", "Constant velocity of the plane.");
    declare_wall_properties(s, 1.2e7, 0, 0);
    s.leave();
  }
  s.enter("cylinder");
  s.flag("enabled", false, "Whether the cylindrical wall exists (balls are confined to its inside).");
  s.vector3("axis point", "0, 0, 0", "m", "A point on the axis.");
  s.vector3("axis", "0, 0, 1", "-", "Direction of the axis (normalised).");
  s.real("radius", 0.01, 0, inf, "m", "Inner radius.", true);
  s.real("radial velocity", 0, -inf, inf, "m/s", "Rate of change of the radius (> 0 expands).");
  declare_wall_properties(s, 1.2e7, 0, 0);
  s.leave();
  s.leave();
  declare_rate(s);
  declare_motion(s, "0, 0, 0", 0.7);
  s.enter("run");
  s.real("duration", 1e-3, 0, inf, "s", "Simulated time.", true);
  s.leave();
  s.enter("output");
  s.real("interval", 0, 0, inf, "s", "Time between output rows; 0 writes every step.");
  s.text("track particles", "", "Balls whose motion goes to particles.csv: indices from 0, comma separated.");
  s.text("track pairs", "", "Pairs whose contact goes to contacts.csv: 'i-j' items, comma separated.");
  s.flag("paraview", false, "Write ParaView files (particles, contact forces, broken bonds) to paraview/.");
  s.real("paraview interval", 0, 0, inf, "s", "Time between ParaView frames; 0 uses the output interval.");
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

dem::ParticleStore read_particles(const Deck &deck)
{
  const CsvTable t = CsvTable::read(deck.file("particles/file"));
  if (t.rows() == 0)
    throw DeckError(t.path() + ": no particles: expected at least one row after the header");
  for (const char *c : {"x_m", "y_m", "z_m", "radius_m"})
    if (!t.has(c))
      throw DeckError(t.path() + ": column '" + std::string(c) +
                      "' is missing: expected a header with x_m,y_m,z_m,radius_m");
  dem::ParticleStore p;
  p.reserve(t.rows());
  for (std::size_t r = 0; r < t.rows(); ++r)
  {
    dem::BallSpec b;
    apply_ball_properties(deck, b);
    b.position = {t.get(r, "x_m"), t.get(r, "y_m"), t.get(r, "z_m")};
    b.radius = t.get(r, "radius_m");
    b.velocity = {t.get(r, "vx_mps", 0), t.get(r, "vy_mps", 0), t.get(r, "vz_mps", 0)};
    b.spin = {t.get(r, "wx_radps", 0), t.get(r, "wy_radps", 0), t.get(r, "wz_radps", 0)};
    b.density = t.get(r, "density_kgpm3", b.density);
    b.kn = t.get(r, "kn_npm", b.kn);
    b.ks = t.get(r, "ks_npm", b.ks);
    b.friction = t.get(r, "friction", b.friction);
    if (!(b.radius > 0))
      t.fail(r, "radius_m", "expected a radius > 0 m");
    if (!(b.density > 0))
      t.fail(r, "density_kgpm3", "expected a density > 0 kg/m^3");
    if (!(b.kn > 0))
      t.fail(r, "kn_npm", "expected a normal stiffness > 0 N/m");
    if (b.ks < 0)
      t.fail(r, "ks_npm", "expected a shear stiffness >= 0 N/m");
    if (b.friction < 0)
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
    p.add(b);
  }
  return p;
}

dem::WallSet read_walls(const Deck &deck)
{
  dem::WallSet walls;
  for (int k = 1; k <= plane_slots; ++k)
  {
    const std::string sec = plane_section(k);
    if (!deck.flag(sec + "/enabled"))
      continue;
    dem::Wall w;
    w.name = "plane" + std::to_string(k);
    w.shape = dem::WallShape::plane;
    w.point = read_vec3(deck, sec + "/point");
    w.direction = read_vec3(deck, sec + "/normal");
    if (w.direction.norm() == 0)
      deck.fail(sec + "/normal", "expected a non-zero normal vector");
    w.velocity = read_vec3(deck, sec + "/velocity");
    w.props = read_wall_properties(deck, sec);
    walls.add(w);
  }
  if (deck.flag("walls/cylinder/enabled"))
  {
    dem::Wall w;
    w.name = "cylinder";
    w.shape = dem::WallShape::cylinder;
    w.point = read_vec3(deck, "walls/cylinder/axis point");
    w.direction = read_vec3(deck, "walls/cylinder/axis");
    if (w.direction.norm() == 0)
      deck.fail("walls/cylinder/axis", "expected a non-zero axis vector");
    w.radius = deck.real("walls/cylinder/radius");
    w.radial_velocity = deck.real("walls/cylinder/radial velocity");
    w.props = read_wall_properties(deck, "walls/cylinder");
    walls.add(w);
  }
  return walls;
}

/// A wall that starts inside a ball would fling it away: bad input.
void check_walls_clear(const Deck &deck, const dem::ParticleStore &p, const dem::WallSet &walls)
{
  const double resting = deck.real("walls/resting overlap");
  for (dem::WallIndex w = 0; w < walls.size(); ++w)
    for (dem::Index b = 0; b < p.size(); ++b)
    {
      const double clearance = walls.clearance(w, p.position[b]);
      if (clearance < p.radius[b] * (1 - resting))
      {
        const std::string name = walls[w].name;
        const std::string key = name == "cylinder" ? "walls/cylinder/radius"
                                                   : plane_section(std::stoi(name.substr(5))) + "/point";
        std::ostringstream msg;
        msg << "wall '" << name << "' overlaps particle " << b << " at the start (clearance " << clearance
            << " m, radius " << p.radius[b] << " m): expected every ball clear of every wall, up to the "
            << "resting overlap of walls/resting overlap";
        deck.fail(key, msg.str());
      }
    }
}

void install_bonds(const Deck &deck, dem::Simulation &sim, dem::BondReport &report)
{
  const std::string mode = deck.text("bonds/install");
  if (mode == "none")
    return;
  sim.refresh_contacts();
  const dem::BondSettings settings = read_bond_settings(deck);
  if (mode == "touching")
  {
    report = dem::bond_touching_pairs(sim.contacts(), sim.particles(), settings);
    return;
  }
  if (deck.text("bonds/list file").empty())
    deck.fail("bonds/list file", "expected a CSV file of bonded pairs when install = list");
  const CsvTable t = CsvTable::read(deck.file("bonds/list file"));
  const dem::Index n = sim.particles().size();
  for (std::size_t r = 0; r < t.rows(); ++r)
  {
    for (const char *c : {"first", "second"})
    {
      const double v = t.get(r, c);
      if (v < 0 || v >= n || v != std::floor(v) || (std::string(c) == "second" && v == t.get(r, "first")))
        t.fail(r, c, "expected a ball index in [0, " + std::to_string(n - 1) + "], distinct from the other");
    }
    const double fn = t.get(r, "normal_strength_n", settings.normal_strength);
    const double fs = t.get(r, "shear_strength_n", settings.shear_strength);
    if (!(fn > 0))
      t.fail(r, "normal_strength_n", "expected a strength > 0 N");
    if (!(fs > 0))
      t.fail(r, "shear_strength_n", "expected a strength > 0 N");
    dem::bond_pair(sim.contacts(), sim.particles(), static_cast<dem::Index>(t.get(r, "first")),
                   static_cast<dem::Index>(t.get(r, "second")), fn, fs);
    ++report.bonded;
  }
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
} // namespace

SceneResult run_scene(const Deck &deck, const RunOptions &options)
{
  const int threads = apply_threads(options);
  dem::ParticleStore particles = read_particles(deck);
  dem::WallSet walls = read_walls(deck);
  check_walls_clear(deck, particles, walls);

  const RateScaling rate = read_rate(deck, 0);
  rate.scale_ball_stiffness(particles);
  SceneResult result;
  result.sim = std::make_unique<dem::Simulation>(std::move(particles), std::move(walls),
                                                 read_contact_law(deck, rate), read_motion(deck));
  dem::Simulation &sim = *result.sim;
  install_bonds(deck, sim, result.bonds);
  finish_bonds(deck, sim.contacts(), sim.particles(), rate);

  const dem::Index n = sim.particles().size();
  std::vector<dem::Index> tracked;
  for (const auto &item : items(deck.text("output/track particles")))
    tracked.push_back(parse_index(deck, "output/track particles", item, n));
  std::vector<dem::Pair> pairs;
  for (const auto &item : items(deck.text("output/track pairs")))
  {
    const auto dash = item.find('-');
    if (dash == std::string::npos)
      deck.fail("output/track pairs", "expected items of the form i-j, found '" + item + "'");
    dem::Index i = parse_index(deck, "output/track pairs", item.substr(0, dash), n);
    dem::Index j = parse_index(deck, "output/track pairs", item.substr(dash + 1), n);
    if (i == j)
      deck.fail("output/track pairs", "expected two different balls in '" + item + "'");
    pairs.emplace_back(std::min(i, j), std::max(i, j));
  }

  result.series = Series(series_columns(sim.walls()));
  result.particles = Series({"time_s", "particle", "x_m", "y_m", "z_m", "vx_mps", "vy_mps", "vz_mps",
                             "wx_radps", "wy_radps", "wz_radps", "fx_n", "fy_n", "fz_n"});
  result.contacts = Series({"time_s", "first", "second", "overlap_m", "normal_force_n", "shear_force_n",
                            "shear_x_n", "shear_y_n", "shear_z_n", "bonded", "touching"});
  const std::string convention = "demvv scene '" + deck.name() + "': SI units, compression positive";
  RunFiles files(options, deck, threads, deck.integer("bonds/seed"), convention, deck.flag("output/paraview"));
  RunDirectory *dir = files.directory();
  ParaviewWriter *paraview = files.paraview();
  if (dir)
  {
    result.series.stream_to(dir->path("series.csv"), convention);
    if (!tracked.empty())
      result.particles.stream_to(dir->path("particles.csv"), convention + "; velocities at t - dt/2");
    if (!pairs.empty())
      result.contacts.stream_to(dir->path("contacts.csv"),
                                convention + "; normal force > 0 in compression, force on the second ball");
  }

  const double duration = deck.real("run/duration");
  const double interval = deck.real("output/interval");
  const double pv_interval = deck.real("output/paraview interval") > 0 ? deck.real("output/paraview interval") : interval;
  double next_output = 0, next_frame = 0;
  Progress progress("scene " + deck.name());
  const auto start = std::chrono::steady_clock::now();

  const auto record = [&](bool final_row) {
    const double t = sim.time();
    const dem::ParticleStore &P = sim.particles();
    for (dem::Index p : tracked)
      result.particles.add({t, double(p), P.position[p].x(), P.position[p].y(), P.position[p].z(),
                            P.velocity[p].x(), P.velocity[p].y(), P.velocity[p].z(), P.spin[p].x(),
                            P.spin[p].y(), P.spin[p].z(), P.force[p].x(), P.force[p].y(), P.force[p].z()});
    for (const dem::Pair &pr : pairs)
    {
      const dem::Contact *c = sim.contacts().find(pr.first, pr.second);
      const dem::ContactState s = c ? c->state : dem::ContactState{};
      const double gap = (P.position[pr.second] - P.position[pr.first]).norm() - P.radius[pr.first] - P.radius[pr.second];
      result.contacts.add({t, double(pr.first), double(pr.second), s.touching ? s.overlap : -gap, s.normal_force,
                           s.shear_force.norm(), s.shear_force.x(), s.shear_force.y(), s.shear_force.z(),
                           c && c->bond.intact ? 1.0 : 0.0, s.touching ? 1.0 : 0.0});
    }
    if (paraview && (final_row || t >= next_frame))
    {
      paraview->write_frame(sim, t);
      next_frame = t + pv_interval;
    }
  };
  const auto record_energy = [&]() {
    const dem::EnergyLedger e = sim.energy();
    std::size_t touching = 0, intact = 0;
    for (const dem::Contact &c : sim.contacts().entries())
    {
      touching += c.state.touching ? 1 : 0;
      intact += c.bond.intact ? 1 : 0;
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
    result.series.add(std::move(row));
  };

  try
  {
    for (;;)
    {
      sim.compute_forces();
      files.drain_breaks(sim);
      const bool last = sim.time() >= duration;
      const bool due = last || sim.time() >= next_output;
      if (due)
      {
        record(last);
        next_output = sim.time() + interval;
      }
      sim.integrate(due);
      if (due)
        record_energy();
      if (last)
        break;
      progress.update(sim.time() / duration, "t = " + std::to_string(sim.time()) + " s");
    }
  }
  catch (const dem::NumericalFault &f)
  {
    record_fault(result.status, f);
  }
  progress.finish();
  result.status.steps = sim.steps();
  result.status.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  if (dir)
  {
    const dem::EnergyLedger e = sim.energy();
    nlohmann::json summary = {
      {"kind", "scene"},
      {"title", deck.text("title")},
      {"status", result.status.to_json()},
      {"contact_law", std::string(sim.model().name())},
      {"rate", rate.to_json()},
      {"particles", n},
      {"steps", sim.steps()},
      {"final_time_s", sim.time()},
      {"last_time_step_s", sim.time_step()},
      {"critical_time_step_bound_s", sim.critical_time_step()},
      {"neighbour_rebuilds", sim.neighbors().rebuilds()},
      {"bonds", {{"installed", result.bonds.bonded},
                 {"removed", result.bonds.removed},
                 {"truncated_strength_draws", result.bonds.truncated_draws},
                 {"broken_tension", sim.bonds_broken(dem::BreakMode::tension)},
                 {"broken_shear", sim.bonds_broken(dem::BreakMode::shear)},
                 {"broken_displacement", sim.bonds_broken(dem::BreakMode::displacement)}}},
      {"energy_j", {{"kinetic", e.kinetic},
                    {"strain", e.strain},
                    {"friction", e.friction},
                    {"damping", e.damping},
                    {"bond_released", e.bond_released},
                    {"boundary_work", e.boundary_work},
                    {"gravity_work", e.body_work},
                    {"initial", e.initial},
                    {"residual", e.residual()}}},
      {"wall_seconds", result.status.wall_seconds},
      {"particle_steps_per_second",
       result.status.wall_seconds > 0 ? double(n) * sim.steps() / result.status.wall_seconds : 0.0}};
    dir->write_summary(summary);
  }
  return result;
}
} // namespace verify
