#include "dem/prep_packing.h"

#include "dem/measure.h"
#include "dem/neighbors.h"
#include "dem/servo.h"

#include <Eigen/Eigenvalues>
#include <gsl/gsl_rng.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>
#include <unordered_map>

namespace dem
{
namespace
{
constexpr double densest_packing = 0.7404804896930610; // pi / (3 sqrt 2), Kepler

double ball_volume(double r) { return 4.0 / 3.0 * pi * r * r * r; }

std::string fmt(double v)
{
  std::ostringstream o;
  o.precision(4);
  o << v;
  return o.str();
}

/// The state of the preparation: the simulation, its cell, the log.
class Preparation
{
public:
  Preparation(const PackingSettings &s, const std::function<void(const std::string &)> &log,
              const std::function<bool()> &stop_requested, const StageView &at_stage)
    : s_(s), log_(log), stop_requested_(stop_requested), at_stage_(at_stage)
  {
  }

  PreparedSample run();

private:
  void generate();
  void grow();
  StageReport equilibrate(const std::string &name, bool servo, double ratio);
  void reduce_stress();
  void expand_rattlers();
  void bond_and_release();
  void restore_friction();
  std::vector<Index> short_of_contacts() const;
  void finish(PackingReport &r);

  StageReport measure(const std::string &name, long cycles, bool converged) const;
  double cell_volume() const;
  /// The cell's six bands of equal volume, from its walls now.
  CylinderBands cell_bands() const;
  double solid_fraction() const;
  void scale_radii(double factor);
  void say(const std::string &line) const
  {
    if (log_)
      log_(line);
  }
  /// Throws PreparationStopped when a stop was asked for (looked at every
  /// 128 steps: a step of 12 000 balls is about a millisecond).
  void poll_stop(long cycle) const
  {
    if (cycle % 128 == 0 && stop_requested_ && stop_requested_())
      throw PreparationStopped("sample preparation stopped at step " + std::to_string(sim_->steps()) +
                               " (cycle " + std::to_string(cycle) + " of a stage): a stop was asked for");
  }
  void show(const std::string &stage) const
  {
    if (at_stage_)
      at_stage_(*sim_, stage);
  }
  void record(const StageReport &st)
  {
    report_.stages.push_back(st);
    show(st.name);
    say(st.name + ": " + std::to_string(st.cycles) + " cycles" + (st.converged ? "" : " (NOT converged)") +
        ", mean stress " + fmt(st.mean_stress) + " Pa, unbalanced-force ratio " + fmt(st.unbalanced_ratio) +
        ", solid fraction " + fmt(st.solid_fraction) + ", coordination " + fmt(st.coordination));
  }

  const PackingSettings &s_;
  const std::function<void(const std::string &)> &log_;
  const std::function<bool()> &stop_requested_;
  const StageView &at_stage_;
  CellSize size_{};
  Specimen cell_;
  std::unique_ptr<Simulation> sim_;
  PackingReport report_;
};

CylinderBands Preparation::cell_bands() const
{
  const WallSet &w = sim_->walls();
  CylinderBands b;
  b.axis = w[cell_.bottom].direction;
  b.base = w[cell_.lateral].point + b.axis * (w[cell_.bottom].point - w[cell_.lateral].point).dot(b.axis);
  b.height = (w[cell_.top].point - w[cell_.bottom].point).dot(b.axis);
  b.radius = w[cell_.lateral].radius;
  return b;
}

double Preparation::cell_volume() const
{
  const WallSet &w = sim_->walls();
  const double r = w[cell_.lateral].radius;
  const double h = (w[cell_.top].point - w[cell_.bottom].point).dot(w[cell_.bottom].direction);
  return pi * r * r * h;
}

double Preparation::solid_fraction() const
{
  double v = 0;
  for (double r : sim_->particles().radius)
    v += ball_volume(r);
  return v / cell_volume();
}

StageReport Preparation::measure(const std::string &name, long cycles, bool converged) const
{
  StageReport st;
  st.name = name;
  st.cycles = cycles;
  st.converged = converged;
  st.mean_stress = mean_stress(*sim_, cell_volume());
  st.unbalanced_ratio = unbalanced_force_ratio(sim_->particles(), sim_->contacts());
  st.solid_fraction = solid_fraction();
  st.coordination = coordination_number(sim_->particles(), sim_->contacts());
  return st;
}

void Preparation::scale_radii(double factor)
{
  ParticleStore &p = sim_->particles();
  for (Index b = 0; b < p.size(); ++b)
    p.set_radius(b, p.radius[b] * factor);
  sim_->invalidate_neighbors();
}

void Preparation::generate()
{
  size_ = cell_size(s_);
  report_.particles = size_.particles;
  const double r0 = 0.5 * s_.radius;
  const double rho_max = 0.5 * size_.diameter - r0;
  std::unique_ptr<gsl_rng, void (*)(gsl_rng *)> rng(gsl_rng_alloc(gsl_rng_mt19937), &gsl_rng_free);
  gsl_rng_set(rng.get(), static_cast<unsigned long>(s_.seed));

  // Random sequential addition with a hash grid of cell 2 r0: a candidate
  // only needs the 27 cells around it.
  const double h = 2 * r0;
  const auto key = [h](const Vec3 &x)
  {
    const auto c = [h](double v) { return static_cast<long long>(std::floor(v / h)) & 0x1fffff; };
    return (c(x.x()) << 42) | (c(x.y()) << 21) | c(x.z());
  };
  std::unordered_multimap<long long, Vec3> grid;
  std::vector<Vec3> centres;
  centres.reserve(static_cast<std::size_t>(size_.particles));
  const long budget = 1000 * size_.particles + 100000;
  long attempts = 0;
  while (static_cast<long>(centres.size()) < size_.particles)
  {
    if (++attempts > budget)
      throw PackingError("particles", "could not place " + std::to_string(size_.particles) +
                                        " balls at half radius without overlap in the cell (placed " +
                                        std::to_string(centres.size()) + ")");
    const double rho = rho_max * std::sqrt(gsl_rng_uniform(rng.get()));
    const double angle = 2 * pi * gsl_rng_uniform(rng.get());
    const Vec3 x(rho * std::cos(angle), rho * std::sin(angle),
                 r0 + (size_.height - 2 * r0) * gsl_rng_uniform(rng.get()));
    bool clear = true;
    for (int dx = -1; dx <= 1 && clear; ++dx)
      for (int dy = -1; dy <= 1 && clear; ++dy)
        for (int dz = -1; dz <= 1 && clear; ++dz)
        {
          const auto range = grid.equal_range(key(x + h * Vec3(dx, dy, dz)));
          for (auto it = range.first; it != range.second && clear; ++it)
            clear = (it->second - x).squaredNorm() >= h * h;
        }
    if (!clear)
      continue;
    centres.push_back(x);
    grid.emplace(key(x), x);
  }

  // Number the balls in the order of a grid of cells one final diameter
  // wide (z, then y, then x): neighbours in space are neighbours in memory,
  // which the force and integration loops (and every later test on this
  // sample) read far faster than a random order.
  const double cell = 2 * s_.radius;
  const auto cell_of = [cell](const Vec3 &x)
  {
    return std::array<long, 3>{static_cast<long>(std::floor(x.z() / cell)), static_cast<long>(std::floor(x.y() / cell)),
                               static_cast<long>(std::floor(x.x() / cell))};
  };
  std::stable_sort(centres.begin(), centres.end(),
                   [&](const Vec3 &a, const Vec3 &b) { return cell_of(a) < cell_of(b); });

  WallProps frictionless = s_.walls;
  frictionless.friction = 0;
  BallSpec ball = s_.ball;
  ball.friction = 0; // frictionless preparation gives the densest random packing
  cell_ = Specimen();
  for (const Vec3 &x : centres)
  {
    BallSpec b = ball;
    b.position = x;
    b.radius = r0;
    cell_.particles.add(b);
  }
  add_cell_walls(cell_, size_.diameter, size_.height, frictionless, frictionless, true);

  SimulationSettings settings;
  settings.local_damping = s_.local_damping;
  sim_ = std::make_unique<Simulation>(std::move(cell_.particles), std::move(cell_.walls),
                                      make_contact_model("linear", {}), settings);
  say("cell: D = " + fmt(size_.diameter) + " m, H = " + fmt(size_.height) + " m, " + std::to_string(size_.particles) +
      " balls (eq. 5.1 at solid fraction " + fmt(s_.target_solid_fraction) + "), placed at half radius in " +
      std::to_string(attempts) + " attempts");
}

void Preparation::grow()
{
  const double factor = std::pow(2.0, 1.0 / s_.growth_stages);
  for (int k = 1; k <= s_.growth_stages; ++k)
  {
    if (k == s_.growth_stages)
    {
      // Land exactly on the final radius.
      ParticleStore &p = sim_->particles();
      for (Index b = 0; b < p.size(); ++b)
        p.set_radius(b, s_.radius);
      sim_->invalidate_neighbors();
    }
    else
      scale_radii(factor);
    // The growth is not physical dynamics: the kinetic energy of the last
    // relaxation is removed before each increment, so that the overlaps it
    // creates cannot add up to a violent rebound.
    for (Vec3 &v : sim_->particles().velocity)
      v.setZero();
    for (Vec3 &w : sim_->particles().spin)
      w.setZero();
    for (long c = 0; c < s_.growth_cycles; ++c)
    {
      poll_stop(c);
      sim_->step();
    }
  }
  sim_->compute_forces();
  record(measure("generate: balls grown from R/2 to R in " + std::to_string(s_.growth_stages) + " stages",
                 s_.growth_stages * s_.growth_cycles, true));
}

namespace
{
/// The equilibrium stage as a step protocol: at every force time the servo
/// (if on) moves the cell walls; every 100 cycles the stage takes stock.
/// Servo phase: the wall stresses must be within 1 % of the target at five
/// checks in a row.  Settling phase: the stage ends, before integrating,
/// once the unbalanced-force ratio is below `ratio`.
class EquilibriumStage final : public StepHooks
{
public:
  EquilibriumStage(const Specimen &cell, double servo_stress, bool servo, double ratio,
                   const std::function<void(const CellStress &, long)> &report)
    : cell_(cell), servo_(servo), ratio_(ratio), report_(report)
  {
    settings_.target_stress = servo_stress;
  }

  void start_settling() { settling_ = true, cycles_in_phase_ = 0; }
  bool servo_on_target() const { return on_target_ >= 5; }
  bool settled() const { return settled_; }

  ForceTimeAction at_force_time(Simulation &sim) override
  {
    if (servo_)
      servo_cell(sim, cell_, settings_);
    const bool stock = cycles_in_phase_ % 100 == 0 && cycles_in_phase_ > 0;
    ++cycles_in_phase_;
    if (!stock)
      return {};
    if (settling_)
    {
      settled_ = unbalanced_force_ratio(sim.particles(), sim.contacts()) < ratio_;
      return {false, settled_};
    }
    const CellStress cs = cell_stress(sim, cell_);
    on_target_ = cs.largest_error(settings_.target_stress) < 0.01 * settings_.target_stress ? on_target_ + 1 : 0;
    report_(cs, cycles_in_phase_ - 1);
    return {};
  }

private:
  const Specimen &cell_;
  ServoSettings settings_;
  bool servo_;
  double ratio_;
  const std::function<void(const CellStress &, long)> &report_;
  bool settling_ = false, settled_ = false;
  long cycles_in_phase_ = 0;
  int on_target_ = 0;
};
} // namespace

StageReport Preparation::equilibrate(const std::string &name, bool servo, double ratio)
{
  // A servo stage first brings the wall stresses within 1 % of the target
  // for five checks in a row, then settles to the equilibrium ratio with the
  // servo still on (near the target the walls hardly move): a frictionless
  // packing held by fixed walls can creep, rearrange and unjam.
  const std::function<void(const CellStress &, long)> progress = [&](const CellStress &cs, long cycles)
  {
    if (cycles % 20000 == 0)
      say(name + ": cycle " + std::to_string(cycles) + ", wall stresses bottom " + fmt(cs.bottom) + ", top " +
          fmt(cs.top) + ", lateral " + fmt(cs.lateral) + " Pa, solid fraction " + fmt(solid_fraction()));
  };
  EquilibriumStage stage(cell_, s_.servo_stress, servo, ratio, progress);
  long cycles = 0;
  while (servo && cycles < s_.max_cycles && !stage.servo_on_target())
  {
    poll_stop(cycles);
    sim_->step(stage);
    ++cycles;
  }
  const long servo_cycles = cycles;
  stage.start_settling();
  while (cycles < servo_cycles + s_.max_cycles && sim_->step(stage))
    poll_stop(++cycles);
  const bool converged = stage.settled() && (!servo || stage.servo_on_target());
  stop_walls(*sim_, cell_);
  sim_->compute_forces();
  StageReport st = measure(name, cycles, converged);
  record(st);
  return st;
}

void Preparation::reduce_stress()
{
  const double goal = 0.5 * s_.stress_target;
  double sigma = measure("", 0, true).mean_stress;
  if (sigma <= s_.stress_target)
  {
    say("reduce radii: mean stress " + fmt(sigma) + " Pa is already below the target " + fmt(s_.stress_target) + " Pa");
    return;
  }
  const double fraction_before = solid_fraction();
  report_.radius_reduction.push_back({report_.radius_change, sigma});
  // Stress grows with the overlaps; shrinking every radius by dR removes
  // 2 dR of every overlap, so the first guess removes the share of the mean
  // overlap that should go.  Then secant steps on sigma(scale), bisection
  // where the packing unjams (sigma ~ 0).
  double mean_overlap = 0;
  std::size_t touching = 0;
  for (const Contact &c : sim_->contacts().entries())
    if (c.state.touching() && c.state.overlap > 0)
    {
      mean_overlap += c.state.overlap;
      ++touching;
    }
  mean_overlap = touching ? mean_overlap / touching : 0;
  // sigma(scale) is close to linear above the jamming scale and zero below
  // it.  Keep a bracket: `top` (sigma above the target) and `bottom` (below
  // it, unknown at first).  The next scale is the secant through the two
  // latest points above the target, aimed at half the target, accepted if it
  // falls inside the bracket; otherwise bisection (or, with no bottom yet,
  // twice the last reduction).
  double top = 1, sigma_top = sigma, bottom = 0;
  double previous = 1, sigma_previous = sigma;
  double scale = 1 - (1 - goal / sigma) * mean_overlap / (2 * s_.radius);
  double total = 1;
  for (int it = 0; it < 30; ++it)
  {
    scale_radii(scale / total);
    total = scale;
    sigma = equilibrate("reduce radii: scale 1 - " + fmt(1 - scale), false, 10 * s_.equilibrium_ratio).mean_stress;
    report_.radius_reduction.push_back({report_.radius_change + scale - 1, sigma});
    // Near 1 kPa a frictionless packing relaxes very slowly and, left long
    // enough, can creep to unjamming: the first scale that brings the
    // stress into [5 %, 100 %] of the target is kept, and the bonds
    // installed next hold the network where it is.
    if (sigma <= s_.stress_target && sigma >= 0.05 * s_.stress_target)
      break;
    double next;
    if (sigma > s_.stress_target)
    {
      previous = top;
      sigma_previous = sigma_top;
      top = scale;
      sigma_top = sigma;
      next = top + (goal - sigma_top) * (top - previous) / (sigma_top - sigma_previous);
    }
    else
    {
      bottom = scale;
      next = 0.5 * (bottom + top);
    }
    if (!(next < top && next > bottom))
      next = bottom > 0 ? 0.5 * (bottom + top) : 1 - 2 * (1 - top);
    scale = next;
  }
  report_.radius_change += total - 1;
  report_.solid_fraction_cost += fraction_before - solid_fraction();
  say("reduce radii: radii x " + fmt(total) + " (change " + fmt(total - 1) + "), mean stress " + fmt(sigma) +
      " Pa, solid fraction cost " + fmt(fraction_before - solid_fraction()));
}

std::vector<Index> Preparation::short_of_contacts() const
{
  // A contact counts when the pair is within the bond touch tolerance: the
  // contacts that will be bonded.  Walls count too (thesis §5.3.3).
  const ParticleStore &p = sim_->particles();
  std::vector<int> count(static_cast<std::size_t>(p.size()), 0);
  for (const Contact &c : sim_->contacts().entries())
  {
    const double gap = (p.position[c.second] - p.position[c.first]).norm() - p.radius[c.first] - p.radius[c.second];
    if (gap <= s_.bonds.touch_tolerance * std::min(p.radius[c.first], p.radius[c.second]))
    {
      ++count[c.first];
      ++count[c.second];
    }
  }
  for (WallIndex w = 0; w < sim_->walls().size(); ++w)
    for (Index b = 0; b < p.size(); ++b)
      if (sim_->walls()[w].enabled &&
          sim_->walls().clearance(w, p.position[b]) <= p.radius[b] * (1 + s_.bonds.touch_tolerance))
        ++count[b];
  std::vector<Index> out;
  for (Index b = 0; b < p.size(); ++b)
    if (count[b] < s_.min_contacts)
      out.push_back(b);
  return out;
}

void Preparation::expand_rattlers()
{
  // Balls with too few contacts grow in steps of 0.1 % of their radius, the
  // packing re-settling in between so that they can move into a seat with
  // more neighbours, until they have min_contacts or have grown by
  // max_expansion (thesis §5.3.3: "typically less than 1 %").
  ParticleStore &p = sim_->particles();
  const std::vector<double> base = p.radius;
  std::vector<Index> short_balls = short_of_contacts();
  report_.rattlers_before = static_cast<long>(short_balls.size());
  const double step = 0.001;
  const int rounds = static_cast<int>(std::round(s_.max_expansion / step));
  for (int r = 0; r < rounds && !short_balls.empty(); ++r)
  {
    for (Index b : short_balls)
      p.set_radius(b, p.radius[b] + step * base[b]);
    sim_->invalidate_neighbors();
    // With servo walls the cell follows the packing: a frictionless packing
    // held in a fixed cell at the servo stress can rearrange and unjam.
    equilibrate("expand " + std::to_string(short_balls.size()) + " balls with < " + std::to_string(s_.min_contacts) +
                  " contacts by 0.1 %",
                s_.servo_stress > 0, 10 * s_.equilibrium_ratio);
    short_balls = short_of_contacts();
  }
  for (Index b = 0; b < p.size(); ++b)
    report_.largest_expansion = std::max(report_.largest_expansion, p.radius[b] / base[b] - 1);
  say("expand: " + std::to_string(report_.rattlers_before) + " balls had fewer than " +
      std::to_string(s_.min_contacts) + " contacts; largest growth " + fmt(100 * report_.largest_expansion) + " %; " +
      std::to_string(short_balls.size()) + " still short after the stage");
}

void Preparation::restore_friction()
{
  ParticleStore &p = sim_->particles();
  for (Index b = 0; b < p.size(); ++b)
    p.friction[b] = s_.ball.friction;
  ContactTable &table = sim_->contacts();
  for (Contact &c : table.entries())
  {
    ContactParams pair = table.params(c);
    pair.friction = std::min(p.friction[c.first], p.friction[c.second]);
    table.set_params(c, pair);
  }
}

void Preparation::bond_and_release()
{
  const std::vector<int> count = contacts_per_ball(*sim_);
  report_.fewest_contacts = count.empty() ? 0 : *std::min_element(count.begin(), count.end());
  report_.coordination_before_bonding = coordination_number(sim_->particles(), sim_->contacts());
  report_.mean_contact_force_before = contact_force_statistics(sim_->contacts()).mean;
  report_.force_bands = contact_force_bands(*sim_, cell_bands());
  const BandMeans &f = report_.force_bands;
  say("isotropic contact forces by band (bottom, middle, top; core, rim): " + [&f]
      {
        std::string s;
        for (int b = 0; b < CylinderBands::count; ++b)
          s += (b ? ", " : "") + fmt(f.mean[b] / f.overall_mean);
        return s;
      }() + " of the mean " + fmt(f.overall_mean) + " N; ANOVA p = " + fmt(f.p_value));

  ParticleStore &p = sim_->particles();
  sim_->refresh_contacts();
  if (s_.bond)
  {
    report_.bonds = bond_touching_pairs(sim_->contacts(), p, s_.bonds);
    say("bond: " + std::to_string(report_.bonds.bonded) + " contact bonds (" +
        std::to_string(report_.bonds.truncated_draws) + " strength draws raised to the floor, " +
        std::to_string(report_.bonds.removed) + " removed)");
  }
  sim_->set_wall_enabled(cell_.lateral, false);
  equilibrate("release: lateral wall removed, settled", false, s_.equilibrium_ratio);
  const ContactForceStatistics locked_in = contact_force_statistics(sim_->contacts());
  report_.locked_in_mean_force = locked_in.mean;
  report_.locked_in_max_force = locked_in.largest;
  say("locked-in forces: mean " + fmt(locked_in.mean) + " N, largest " + fmt(locked_in.largest) +
      " N, against a mean contact force of " + fmt(report_.mean_contact_force_before) + " N before bonding");
}

void Preparation::finish(PackingReport &r)
{
  const WallSet &w = sim_->walls();
  r.cell_diameter = 2 * w[cell_.lateral].radius;
  r.cell_height = (w[cell_.top].point - w[cell_.bottom].point).dot(w[cell_.bottom].direction);
  cell_.diameter = r.cell_diameter;
  cell_.height = r.cell_height;
  r.solid_fraction = solid_fraction();
  r.coordination = coordination_number(sim_->particles(), sim_->contacts());
  const double sphere_r = 0.3 * r.cell_diameter;
  for (int k = 0; k < 2; ++k)
  {
    const MeasurementSphere ms{Vec3(0, 0, r.cell_height * (k + 1) / 3.0), std::min(sphere_r, r.cell_height / 6)};
    r.sphere_porosity[k] = porosity(sim_->particles(), sim_->contacts(), ms);
    r.sphere_coordination[k] = coordination_number(sim_->particles(), sim_->contacts(), ms);
  }
  const Tensor3 fabric = fabric_tensor(sim_->particles(), sim_->contacts());
  r.fabric_deviator_norm = (fabric - Tensor3::Identity() / 3.0).norm();
  const Eigen::SelfAdjointEigenSolver<Tensor3> eig(fabric);
  for (int k = 0; k < 3; ++k)
    r.fabric_eigenvalues[k] = eig.eigenvalues()[k];
}

PreparedSample Preparation::run()
{
  const auto start = std::chrono::steady_clock::now();
  generate();
  show("placed: " + std::to_string(size_.particles) + " balls at half radius");
  grow();
  // The servo (or fixed-wall) stage only has to remove the growth's
  // overcompression: it settles to ten times the final equilibrium ratio.
  if (s_.servo_stress > 0)
    equilibrate("servo: walls to " + fmt(s_.servo_stress) + " Pa", true, 10 * s_.equilibrium_ratio);
  else
    equilibrate("equilibrate: fixed frictionless walls", false, 10 * s_.equilibrium_ratio);
  // Balls short of contacts grow while the network is well loaded (the
  // servo stress), then all radii shrink to bring the stress below the
  // target; the balls stay frictionless so that the packing stays dense.
  expand_rattlers();
  reduce_stress();
  report_.rattlers_after = static_cast<long>(short_of_contacts().size());
  report_.stress_before_bonding = measure("", 0, true).mean_stress;
  say("before bonding: mean stress " + fmt(report_.stress_before_bonding) + " Pa, " +
      std::to_string(report_.rattlers_after) + " balls with fewer than " + std::to_string(s_.min_contacts) +
      " contacts within the bond touch tolerance");
  restore_friction();
  finish(report_);
  bond_and_release();
  report_.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  PreparedSample out;
  out.cell = std::move(cell_);
  out.sim = std::move(sim_);
  out.report = report_;
  return out;
}
} // namespace

CellSize cell_size(const PackingSettings &s)
{
  if (!(s.target_solid_fraction > 0 && s.target_solid_fraction <= densest_packing))
    throw PackingError("target solid fraction",
                       "solid fraction " + fmt(s.target_solid_fraction) +
                         " is impossible: equal spheres pack to at most pi/(3 sqrt 2) = 0.7405");
  if (!(s.radius > 0))
    throw PackingError("radius", "ball radius must be positive");
  CellSize c{};
  if (s.particles > 0)
  {
    const double volume = s.particles * ball_volume(s.radius) / s.target_solid_fraction;
    c.particles = s.particles;
    c.diameter = std::cbrt(4 * volume / (pi * s.aspect));
    c.height = s.aspect * c.diameter;
  }
  else
  {
    c.diameter = s.diameter;
    c.height = s.height;
    const double volume = pi * 0.25 * s.diameter * s.diameter * s.height;
    const double count = volume * s.target_solid_fraction / ball_volume(s.radius); // eq. 5.1
    if (!(count <= double(std::numeric_limits<Index>::max())))
      throw PackingError("radius", "the cell (D = " + fmt(c.diameter) + " m, H = " + fmt(c.height) + " m) would hold " +
                                     fmt(count) + " balls of radius " + fmt(s.radius) +
                                     " m, more than a ball index counts (" +
                                     std::to_string(std::numeric_limits<Index>::max()) + ")");
    c.particles = std::lround(count);
  }
  // A cell sized from the ball count is too flat by its aspect ratio, or
  // too narrow by the count.
  const bool too_flat = s.particles > 0 && c.diameter > 2 * s.radius && !(c.height > 2 * s.radius);
  if (!(c.diameter > 2 * s.radius && c.height > 2 * s.radius) || c.particles < 1)
    throw PackingError(too_flat ? "aspect ratio" : s.particles > 0 ? "particles" : "diameter",
                       "the cell (D = " + fmt(c.diameter) + " m, H = " + fmt(c.height) +
                         " m) is too small for one ball of radius " + fmt(s.radius) + " m");
  if (c.particles < min_packing_balls)
    throw PackingError(s.particles > 0 ? "particles" : "diameter",
                       std::to_string(c.particles) + " balls: expected at least " + std::to_string(min_packing_balls) +
                         " (a smaller packing is all wall layer: no ball has a bulk neighbourhood, and the "
                         "preparation's measures mean nothing)");
  return c;
}

PreparedSample prepare_sample(const PackingSettings &settings, const std::function<void(const std::string &)> &log,
                              const std::function<bool()> &stop_requested, const StageView &at_stage)
{
  Preparation p(settings, log, stop_requested, at_stage);
  return p.run();
}
} // namespace dem
