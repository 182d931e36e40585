#include "dem/simulation.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace dem
{
NumericalFault::NumericalFault(long step_, double time_, Index particle_, const std::string &what)
  : std::runtime_error(what), step(step_), time(time_), particle(particle_)
{
}

Simulation::Simulation(ParticleStore particles, WallSet walls, std::unique_ptr<ContactModel> model,
                       SimulationSettings settings)
  : particles_(std::move(particles)), walls_(std::move(walls)), model_(std::move(model)), settings_(settings)
{
  const auto n = static_cast<std::size_t>(particles_.size());
  contacts_.keeps_law_states(model_->keeps_law_state());
  walls_.resize_history(particles_.size());
  row_bound_.assign(n, 0);
  active_walls_.reserve(static_cast<std::size_t>(walls_.size()));
  wall_power_.assign(n, 0);
  ball_energy_.assign(n, BallEnergy{});
  breaks_.reserve(1024);
}

namespace
{
WallSet assemble_walls(const std::vector<Wall> &walls)
{
  WallSet set;
  for (const Wall &w : walls)
    set.add(w);
  return set;
}
} // namespace

Simulation::Simulation(Snapshot snap, std::unique_ptr<ContactModel> model, SimulationSettings settings)
  : Simulation(std::move(snap.particles), assemble_walls(snap.walls), std::move(model), settings)
{
  // Restored here, not among the delegated constructor's arguments: those
  // are evaluated in an unspecified order (clang moves snap.particles out
  // before a later argument reads its size), while here the history is
  // laid out for particles_.size() balls.
  walls_.restore_history(snap.wall_contacts);
  std::vector<LawState> law_states;
  if (snap.contact_law == model_->name())
    law_states = std::move(snap.law_states);
  contacts_.assign(snap.contacts, std::move(law_states), particles_, snap.clock.retired);
  const SimulationClock &c = snap.clock;
  time_ = c.time;
  step_ = c.steps;
  dt_prev_ = c.last_time_step;
  if (c.ball_energy.size() == ball_energy_.size())
    ball_energy_ = c.ball_energy;
  initial_energy_ = c.initial_energy;
  initial_recorded_ = c.initial_recorded;
  removed_wall_strain_ = c.removed_wall_strain;
  removed_wall_friction_ = c.removed_wall_friction;
  broken_tension_ = c.broken_tension;
  broken_shear_ = c.broken_shear;
  broken_displacement_ = c.broken_displacement;
}

Snapshot Simulation::snapshot() const
{
  Snapshot s;
  s.particles = particles_;
  for (WallIndex w = 0; w < walls_.size(); ++w)
    s.walls.push_back(walls_[w]);
  s.wall_contacts = walls_.contacts();
  s.contacts = contacts_.records();
  s.contact_law = model_->name();
  s.law_states = contacts_.law_states();
  SimulationClock &c = s.clock;
  c.time = time_;
  c.steps = step_;
  c.last_time_step = dt_prev_;
  c.ball_energy = ball_energy_;
  c.initial_energy = initial_energy_;
  c.initial_recorded = initial_recorded_;
  c.removed_wall_strain = removed_wall_strain_;
  c.removed_wall_friction = removed_wall_friction_;
  c.broken_tension = broken_tension_;
  c.broken_shear = broken_shear_;
  c.broken_displacement = broken_displacement_;
  c.retired = contacts_.retired();
  return s;
}

void Simulation::restore(Snapshot snapshot)
{
  std::unique_ptr<ContactModel> model = std::move(model_);
  *this = Simulation(std::move(snapshot), std::move(model), settings_);
}

void Simulation::step()
{
  compute_forces();
  integrate(false);
}

bool Simulation::step(StepHooks &hooks)
{
  hooks.before_forces(*this);
  compute_forces();
  const ForceTimeAction action = hooks.at_force_time(*this);
  if (action.stop)
    return false;
  integrate(action.measure_kinetic);
  hooks.after_integration(*this);
  return true;
}

namespace
{
/// Row bound of ball p against one fixed partner with its own stiffness
/// [1/s^2] (real mass and inertia, so that held balls count too).
double lone_bound(const ParticleStore &P, Index p)
{
  const double own = std::max(P.kn[p], P.ks[p] * (1.0 + P.mass[p] * P.radius[p] * P.radius[p] / P.inertia[p]));
  return own / P.mass[p];
}
} // namespace

Index stiffest_ball(const ParticleStore &particles)
{
  Index stiffest = -1;
  double largest = -1;
  for (Index p = 0; p < particles.size(); ++p)
    if (const double b = lone_bound(particles, p); b > largest)
    {
      largest = b;
      stiffest = p;
    }
  return stiffest;
}

namespace
{
/// The largest stability row bound of one contact with a ball's own
/// stiffness [1/s^2]; 0 for no balls.
double lone_contact_bound(const ParticleStore &P)
{
  const Index b = stiffest_ball(P);
  return b < 0 ? 0.0 : lone_bound(P, b);
}
} // namespace

double estimated_memory_bytes(double particles, int walls)
{
  constexpr double pairs_per_ball = 8;
  const double ball = 5 * sizeof(Vec3) + 12 * sizeof(double) + 1                   // ParticleStore
                      + 2 * sizeof(double) + sizeof(BallEnergy)                    // step scratch, energy ledger
                      + sizeof(Vec3) + 14 * sizeof(Index)                          // neighbour reference and cells
                      + 2 * sizeof(EntryIndex)                                     // contact table adjacency
                      + double(walls) * sizeof(std::int32_t) + sizeof(WallContact) // wall histories
                      + sizeof(std::uint64_t);                                     // near-wall marks
  constexpr double load_record = 9 * sizeof(double); // the force pass's loads of a pair (contact_model.h)
  const double pair = sizeof(Pair) + sizeof(Contact) + sizeof(LawState) + sizeof(EntryIndex) + load_record;
  return 1.5 * particles * (ball + pairs_per_ball * pair);
}

double least_steps(const ParticleStore &particles, const SimulationSettings &settings, double duration)
{
  const double largest_step =
    settings.fixed_time_step > 0
      ? settings.fixed_time_step
      : settings.time_step_safety *
          critical_step(damped_row_bound(lone_contact_bound(particles), settings.local_damping));
  return largest_step > 0 ? duration / largest_step : infinity;
}

void Simulation::refresh_contacts()
{
  // A ball without contacts still gets the step of one contact with its own
  // stiffness, so that a first impact is resolved; real mass and inertia are
  // used so that a scene of held balls still has a step.  Radii only change
  // before a refresh, so this is computed here, not every step.
  lone_bound_max_ = lone_contact_bound(particles_);
  neighbors_.set_skin(skin_for_rebuild());
  built_at_step_ = step_;
  // The rebuild's scratch (candidates, cells) and the force pass's (load
  // records) are never needed at once: each is freed before the other is
  // made, so that peak memory holds only the larger.
  model_->release_scratch();
  neighbors_.rebuild(particles_);
  walls_.mark_near(neighbors_.reference(), particles_.radius, neighbors_.skin());
  contacts_.rebuild(neighbors_.pairs(), particles_);
  neighbors_.release_candidates();
  rebuild_requested_ = false;
}

double Simulation::skin_for_rebuild() const
{
  // A wider skin makes every force pass test more candidates that do not
  // touch; a narrower one makes rebuilds more frequent.  With balls moving
  // at most u per step (the farthest one since the last build, over the
  // steps it took), a skin s lasts s / (2 u) steps: the skin taken is the
  // one that lasts about `lasting` steps, never wider than the deck's (fast
  // balls: packing, impacts, breakage) and never below 1 % of the largest
  // radius.  A build costs about 2.7 force passes on one thread and twice
  // that on two (it is serial; BENCHMARKS.md, Adaptive neighbour skin), so
  // the rebuilds this adds cost at most about 1 % of a run, while a slow
  // compression stops testing the pairs that do not touch (about an eighth
  // of its step on the identical-work packing).  Candidates left out cannot
  // touch before the next build, so the motion does not depend on the skin;
  // the rule reads positions only (not clocks), so the rebuild steps are
  // the same on any thread count too.
  constexpr double lasting = 500, narrowest = 0.01;
  const double radius = particles_.max_radius(), widest = settings_.skin_fraction * radius;
  if (!settings_.adaptive_skin)
    return widest;
  // u from the motion since the last build; at the first build (or after
  // balls were added) from the fastest ball over the last step, and a run
  // that starts with every ball at rest starts narrow.
  const long steps = step_ - built_at_step_;
  double per_step = 0;
  if (steps > 0 && !neighbors_.stale(particles_))
    per_step = neighbors_.largest_displacement(particles_) / double(steps);
  else
  {
    double fastest = 0;
    for (const Vec3 &v : particles_.velocity)
      fastest = std::max(fastest, v.squaredNorm());
    if (dt_prev_ > 0)
      per_step = std::sqrt(fastest) * dt_prev_;
    else if (fastest > 0)
      return widest;
  }
  return std::clamp(2 * lasting * per_step, std::min(narrowest * radius, widest), widest);
}

void Simulation::compute_forces()
{
  if (rebuild_requested_ || neighbors_.stale(particles_))
    refresh_contacts();
  else if (walls_.near_stale())
  {
    // The walls moved a quarter skin since the marks: marked anew from the
    // centres the neighbour list measures from (walls.h), which no ball has
    // left by more than half a skin.
    walls_.mark_near(neighbors_.reference(), particles_.radius, neighbors_.skin());
  }
  if (contacts_.take_changed())
  {
    // Pairs were added (ensure) or the table rebuilt: the precomputed pair
    // constants are refreshed.
    model_->update_stability_terms(particles_, contacts_);
  }
  active_walls_.clear();
  for (WallIndex w = 0; w < walls_.size(); ++w)
    if (walls_[w].enabled)
      active_walls_.push_back(w);
  const BallForces balls{particles_, walls_,      active_walls_, settings_.gravity,          dt_prev_,
                         row_bound_, wall_power_, ball_ranges_,  settings_.contacts_in_lanes};
  broken_.clear();
  walls_.open_pass(omp_get_max_threads());
  // The bound of the contacts that exist; infinite when none carries force.
  dt_critical_ =
    critical_step(damped_row_bound(model_->resolve_and_sum(contacts_, balls, broken_), settings_.local_damping));
  walls_.close_pass();
  record_breaks();
  choose_time_step();
  if (!initial_recorded_)
  {
    double kinetic = 0;
    for (Index p = 0; p < particles_.size(); ++p)
      kinetic += 0.5 * particles_.mass[p] * particles_.velocity[p].squaredNorm() +
                 0.5 * particles_.inertia[p] * particles_.spin[p].squaredNorm();
    initial_energy_ = kinetic + energy().strain;
    initial_recorded_ = true;
  }
  forces_current_ = true;
}

void Simulation::record_breaks()
{
  for (const BrokenBond &b : broken_)
  {
    const Contact &k = contacts_[b.contact];
    breaks_.push_back({time_, k.first, k.second, b.mode, b.trial.normal, b.trial.shear,
                       centre_line_point(particles_, k.first, k.second)});
    ++broken_count(b.mode);
  }
}

void Simulation::choose_time_step()
{

  if (settings_.fixed_time_step > 0)
  {
    dt_ = settings_.fixed_time_step;
    if (dt_ > dt_critical_ && !settings_.allow_unstable_step)
    {
      std::ostringstream msg;
      msg << "fixed time step " << dt_ << " s exceeds the critical step bound " << dt_critical_
          << " s set by this particle";
      fail(critical_particle(), msg.str());
    }
  }
  else
  {
    // The automatic step also respects the step of a single contact of each
    // ball, so that a ball flying towards another resolves its first impact.
    dt_ = settings_.time_step_safety *
          std::min(dt_critical_, critical_step(damped_row_bound(lone_bound_max_, settings_.local_damping)));
    if (!std::isfinite(dt_))
      fail(-1, "no particle has a finite critical time step (every ball has zero stiffness)");
  }
}

template <bool damped, bool weighted, bool kinetic>
Simulation::BallAdvance Simulation::advance_balls()
{
  const Index n = particles_.size();
  const double dt = dt_;
  // Velocities live at half steps; with a varying step the kick spans the
  // mean of the two neighbouring steps (dt_prev = 0 at the first step gives
  // the half kick that starts the scheme from v(0)).
  const double kick = 0.5 * (dt_prev_ + dt);
  const bool first_step = dt_prev_ == 0;
  const double alpha = settings_.local_damping;
  const Vec3 gravity = settings_.gravity;
  ParticleStore &P = particles_;
  Index first_bad = n;
  bool moved = false;

  // Raw views of the ball arrays: the loop below is the hottest per-ball
  // code, written component by component so that it compiles to plain
  // arithmetic.  Vec3 arrays are contiguous x, y, z triples.
  double *const x = P.position.front().data();
  double *const v = P.velocity.front().data();
  double *const w = P.spin.front().data();
  const double *const f = P.force.front().data();
  const double *const t = P.torque.front().data();

  // Each thread advances the balls whose resultants it summed in the pass
  // (BallForces::ranges); the arithmetic of a ball does not depend on the
  // thread.  Without a pass over these balls (none yet), equal shares.
  // The lines of a ball near the other thread's balls were read by the other
  // core in the pass; writing them waits for that core to let them go, so
  // the loop asks for them, to write, some balls ahead (the force pass's
  // prefetches, contact_model.h, say why and what it gained).
  constexpr Index balls_ahead = 16;
  if (ball_ranges_.items() != static_cast<std::size_t>(n) || ball_ranges_.ranges() == 0)
    ball_ranges_.prepare(static_cast<std::size_t>(n), omp_get_max_threads());
  const BalancedRanges &ranges = ball_ranges_;
#pragma omp parallel reduction(min : first_bad) reduction(|| : moved)
  {
    const int team = omp_get_num_threads();
    for (int r = omp_get_thread_num(); r < ranges.ranges(); r += team)
    {
      const auto last = static_cast<Index>(ranges.end(r));
      for (auto p = static_cast<Index>(ranges.begin(r)); p < last; ++p)
      {
        BallEnergy &e = ball_energy_[p];
        const std::size_t b = 3 * static_cast<std::size_t>(p);
        if (p + balls_ahead < last)
          for (double *motion : {x, v, w})
            __builtin_prefetch(motion + b + 3 * balls_ahead, 1);
        // A held ball has zero inverse mass (inertia), so the kick leaves it
        // alone; the flags below only route its energy to the boundary work its
        // constraint does.
        const double free_v = P.holds_velocity(p) ? 0.0 : 1.0, free_w = P.holds_spin(p) ? 0.0 : 1.0;
        const double im = P.inv_mass[p] * kick, ii = P.inv_inertia[p] * kick, m = P.mass[p];
        double power = wall_power_[p], damping = 0, body = 0, held = 0, energy = 0, speed2 = 0, spin2 = 0;
        for (int k = 0; k < 3; ++k)
        {
          const double vo = v[b + k], wo = w[b + k];
          // PFC local damping: the component loses alpha |F| against the sign of
          // its velocity, nothing at zero velocity.  Two one-sided selects
          // compile to masks, not branches (a velocity's sign is a coin toss for
          // the branch predictor).  Undamped, f_damp = 0 and its terms vanish.
          double f_damp = 0, t_damp = 0;
          if constexpr (damped)
          {
            const double fd = alpha * std::abs(f[b + k]), td = alpha * std::abs(t[b + k]);
            f_damp = (vo > 0 ? fd : 0.0) - (vo < 0 ? fd : 0.0);
            t_damp = (wo > 0 ? td : 0.0) - (wo < 0 ? td : 0.0);
          }
          const double vn = vo + (f[b + k] - f_damp) * im;
          const double wn = wo + (t[b + k] - t_damp) * ii;
          const double vm = 0.5 * (vo + vn), wm = 0.5 * (wo + wn);
          if constexpr (damped)
            damping += free_v * f_damp * vm + free_w * t_damp * wm;
          if constexpr (weighted)
            body += free_v * m * gravity[k] * vm;
          // A held ball's constraint does the work the resultant would have done.
          const double resultant = weighted ? f[b + k] - m * gravity[k] : f[b + k];
          held += (1.0 - free_v) * resultant * vo + (1.0 - free_w) * t[b + k] * wo;
          if constexpr (kinetic)
            energy += 0.5 * m * vo * (first_step ? vo : vn) + 0.5 * P.inertia[p] * wo * (first_step ? wo : wn);
          v[b + k] = vn;
          w[b + k] = wn;
          x[b + k] += vn * dt;
          speed2 += vn * vn;
          spin2 += wn * wn;
        }
        power -= held;
        e.boundary += power * kick;
        if constexpr (damped)
          e.damping += damping * kick;
        if constexpr (weighted)
          e.body += body * kick;
        if constexpr (kinetic)
          e.kinetic = energy;
        const double half_radius = 0.5 * P.radius[p];
        if (!(speed2 * dt * dt <= half_radius * half_radius) || !std::isfinite(spin2))
          first_bad = std::min(first_bad, p);
        moved = moved || neighbors_.moved_too_far(p, P.position[p]);
      }
    }
  }
  return {first_bad, moved};
}

void Simulation::integrate(bool measure_kinetic)
{
  if (!forces_current_)
    compute_forces();
  forces_current_ = false;
  // The ball loop is compiled for each combination of three switches that
  // hold for the whole step, so that a step without damping, gravity or a
  // kinetic-energy measure does none of the arithmetic whose terms are
  // zero (the same values to the bit: those terms add exact zeros).
  using Loop = BallAdvance (Simulation::*)();
  static constexpr Loop loops[2][2][2] = {
    {{&Simulation::advance_balls<false, false, false>, &Simulation::advance_balls<false, false, true>},
     {&Simulation::advance_balls<false, true, false>, &Simulation::advance_balls<false, true, true>}},
    {{&Simulation::advance_balls<true, false, false>, &Simulation::advance_balls<true, false, true>},
     {&Simulation::advance_balls<true, true, false>, &Simulation::advance_balls<true, true, true>}}};
  const bool damped = settings_.local_damping != 0, weighted = !settings_.gravity.isZero(0);
  const BallAdvance advanced = (this->*loops[damped][weighted][measure_kinetic])();
  ball_ranges_.rebalance();
  const Index n = particles_.size(), first_bad = advanced.first_bad;
  const double dt = dt_;
  const ParticleStore &P = particles_;

  walls_.advance(dt);
  time_ += dt;
  ++step_;
  dt_prev_ = dt;
  rebuild_requested_ = rebuild_requested_ || advanced.moved;
  if (first_bad < n)
  {
    std::ostringstream msg;
    const double speed = P.velocity[first_bad].norm();
    if (std::isfinite(speed))
      msg << "runaway motion: the particle moved " << speed * dt << " m in one step of " << dt
          << " s (more than half its radius " << P.radius[first_bad] << " m)";
    else
      msg << "non-finite velocity or spin (NaN or infinity)";
    fail(first_bad, msg.str());
  }
}

Index Simulation::critical_particle() const
{
  const auto it = std::max_element(row_bound_.begin(), row_bound_.end());
  return it == row_bound_.end() || *it <= 0 ? -1 : static_cast<Index>(it - row_bound_.begin());
}

void Simulation::fail(Index particle, const std::string &what) const
{
  throw NumericalFault(step_, time_, particle, what);
}

EnergyLedger Simulation::energy() const
{
  EnergyLedger e;
  for (const BallEnergy &b : ball_energy_)
  {
    e.kinetic += b.kinetic;
    e.boundary_work += b.boundary;
    e.body_work += b.body;
    e.damping += b.damping;
  }
  e.strain = model_->stored_energy(contacts_);
  e.friction = contacts_.retired().friction_work;
  e.bond_released = contacts_.retired().bond_energy;
  for (const Contact &c : contacts_.entries())
  {
    e.friction += c.state.friction_work;
    e.bond_released += c.state.bond_energy;
  }
  for (WallIndex w = 0; w < walls_.size(); ++w)
  {
    const auto [strain, friction] = wall_energy(w);
    e.strain += strain;
    e.friction += friction;
  }
  e.friction += removed_wall_friction_;
  e.boundary_work -= removed_wall_strain_;
  e.initial = initial_energy_;
  return e;
}

void Simulation::check_energy_ledger(const LedgerLimits &limits) const
{
  // The kinetic energy at the force time, 1/2 m v(t - dt/2).v(t + dt/2), is
  // negative when contacts oscillate at a coarse resolution: the scheme's
  // invariant (kinetic + strain) stays constant while the strain energy
  // overshoots it, so a stable undamped contact at omega dt = 1.6 shows
  // -1.8 times its energy.  It is no symptom on its own; its positive part
  // counts towards the runaway.
  const EnergyLedger e = energy();
  const double held = std::max(0.0, e.kinetic) + e.strain;
  const double supplied = e.initial + std::max(0.0, e.boundary_work) + std::max(0.0, e.body_work);
  const auto most_kinetic = [&]
  {
    const auto it = std::max_element(ball_energy_.begin(), ball_energy_.end(),
                                     [](const BallEnergy &a, const BallEnergy &b) { return a.kinetic < b.kinetic; });
    return it == ball_energy_.end() ? Index(-1) : static_cast<Index>(it - ball_energy_.begin());
  };
  std::ostringstream msg;
  if (held > limits.runaway * supplied)
  {
    msg << "runaway energy: kinetic + strain energy " << held << " J is more than " << limits.runaway
        << " times the energy supplied (initial + boundary and gravity work) " << supplied
        << " J: the time step does not resolve the contacts (it is above the stability limit, or within a few "
           "percent of it)";
    fail(most_kinetic(), msg.str());
  }
  if (e.damping < -limits.negative_damping * supplied)
  {
    const auto most = std::min_element(ball_energy_.begin(), ball_energy_.end(),
                                       [](const BallEnergy &a, const BallEnergy &b) { return a.damping < b.damping; });
    msg << "local damping gave energy: its cumulative dissipation is " << e.damping << " J, below -"
        << limits.negative_damping << " times the energy supplied " << supplied
        << " J: the fastest mode reverses at nearly every step, which the step does not resolve (the damping feeds the "
           "mode, or its work cannot be booked); lower motion/time step safety or motion/fixed time step";
    fail(static_cast<Index>(most - ball_energy_.begin()), msg.str());
  }
  if (step_ >= limits.residual_from_step && settings_.local_damping == 0 && model_->books_every_dissipation() &&
      std::abs(e.residual()) > limits.residual * supplied)
  {
    msg << "energy balance broken: the residual " << e.residual() << " J is more than " << limits.residual
        << " times the energy supplied " << supplied
        << " J (the contact law books every dissipation): the integration is not resolving the contacts";
    fail(most_kinetic(), msg.str());
  }
}

void Simulation::check_contact_overlaps(double fraction) const
{
  const ParticleStore &P = particles_;
  const auto refuse = [&](Index ball, double overlap, double radius, const std::string &with)
  {
    std::ostringstream msg;
    msg << "contact overlap beyond the law's meaning: the particle overlaps " << with << " by " << overlap
        << " m, more than " << fraction << " of the radius " << radius
        << " m (a load the contact stiffness cannot carry, or balls pressed through one another)";
    fail(ball, msg.str());
  };
  for (const Contact &c : contacts_.entries())
  {
    const double smaller = std::min(P.radius[c.first], P.radius[c.second]);
    if (c.state.touching() && c.state.overlap > fraction * smaller)
    {
      std::ostringstream ball;
      ball << "the ball at (" << P.position[c.second].x() << ", " << P.position[c.second].y() << ", "
           << P.position[c.second].z() << ") m";
      refuse(c.first, c.state.overlap, smaller, ball.str());
    }
  }
  for (WallIndex w = 0; w < walls_.size(); ++w)
    for (Index p = 0; p < P.size(); ++p)
    {
      const ContactState &s = walls_.state(w, p);
      if (s.touching() && s.overlap > fraction * P.radius[p])
        refuse(p, s.overlap, P.radius[p], "wall " + std::to_string(w));
    }
}

std::pair<double, double> Simulation::wall_energy(WallIndex w) const
{
  const LinearLaw wall_law;
  const WallProps &wp = walls_[w].props;
  double strain = 0, friction = 0;
  for (Index p = 0; p < particles_.size(); ++p)
  {
    const ContactState &s = walls_.state(w, p);
    friction += s.friction_work;
    if (!s.touching())
      continue;
    const ContactParams params{in_series(particles_.kn[p], wp.kn), in_series(particles_.ks[p], wp.ks), 0};
    strain += wall_law.stored_energy(params, s.normal_force, s.shear_force, {});
  }
  return {strain, friction};
}

void Simulation::set_wall_enabled(WallIndex w, bool enabled)
{
  // The springs of a removed wall vanish with their energy: booked as work
  // the wall takes out, so the energy balance stays closed.
  const auto [strain, friction] = wall_energy(w);
  removed_wall_strain_ += strain;
  removed_wall_friction_ += friction;
  walls_.set_enabled(w, enabled);
}

Vec3 Simulation::wall_force(WallIndex w) const
{
  Vec3 f = Vec3::Zero();
  for (Index p = 0; p < particles_.size(); ++p)
  {
    const ContactState &s = walls_.state(w, p);
    if (s.touching())
      f -= s.normal_force * s.normal + s.shear_force;
  }
  return f;
}

std::vector<BondBreak> Simulation::take_breaks()
{
  std::vector<BondBreak> out;
  if (breaks_.empty())
    return out; // no allocation on the common path
  out.swap(breaks_);
  breaks_.reserve(1024);
  return out;
}

std::size_t &Simulation::broken_count(BreakMode mode)
{
  return mode == BreakMode::tension ? broken_tension_ : mode == BreakMode::shear ? broken_shear_ : broken_displacement_;
}

std::size_t Simulation::bonds_broken(BreakMode mode) const
{
  return mode == BreakMode::tension ? broken_tension_ : mode == BreakMode::shear ? broken_shear_ : broken_displacement_;
}
} // namespace dem
