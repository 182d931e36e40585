#include "simulation.h"

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
  : particles_(std::move(particles)), walls_(std::move(walls)), model_(std::move(model)),
    settings_(settings)
{
  const auto n = static_cast<std::size_t>(particles_.size());
  walls_.resize_history(particles_.size());
  row_bound_.assign(n, 0);
  lone_bound_.assign(n, 0);
  wall_power_.assign(n, 0);
  ball_energy_.assign(n, BallEnergy{});
  breaks_.reserve(1024);
}

void Simulation::step()
{
  compute_forces();
  integrate(false);
}

void Simulation::refresh_contacts()
{
  neighbors_.set_skin(settings_.skin_fraction * particles_.max_radius());
  neighbors_.rebuild(particles_);
  contacts_.rebuild(neighbors_.pairs(), particles_);
  model_->remap_history(contacts_.origin());
  rebuild_requested_ = false;
}

void Simulation::compute_forces()
{
  if (rebuild_requested_ || neighbors_.stale(particles_))
    refresh_contacts();
  if (model_->resolve_pairs(particles_, contacts_, dt_prev_) > 0)
    record_breaks();
  gather_forces();
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
  const auto &loads = contacts_.loads();
  for (std::size_t c = 0; c < loads.size(); ++c)
  {
    if (loads[c].broke == BreakMode::none)
      continue;
    const Contact &k = contacts_[c];
    breaks_.push_back({time_, k.first, k.second, loads[c].broke});
    (loads[c].broke == BreakMode::tension ? broken_tension_ : broken_shear_) += 1;
  }
}

void Simulation::gather_forces()
{
  const Index n = particles_.size();
  const auto &loads = contacts_.loads();
  const auto &second_list = contacts_.second_list();
  const LinearLaw wall_law;
  const double dt = dt_prev_;
  const int walls = walls_.size();
  ParticleStore &P = particles_;

#pragma omp parallel for schedule(static)
  for (Index p = 0; p < n; ++p)
  {
    Vec3 f = P.mass[p] * settings_.gravity;
    Vec3 t = Vec3::Zero();
    double bound = 0;
    for (std::size_t c = contacts_.first_begin(p); c < contacts_.first_begin(p + 1); ++c)
    {
      f -= loads[c].force;
      t += loads[c].torque_first;
      bound += loads[c].bound_first;
    }
    for (std::size_t k = contacts_.second_begin(p); k < contacts_.second_begin(p + 1); ++k)
    {
      const std::size_t c = second_list[k];
      f += loads[c].force;
      t += loads[c].torque_second;
      bound += loads[c].bound_second;
    }
    double power = 0;
    for (WallIndex w = 0; w < walls; ++w)
    {
      ContactState &state = walls_.state(w, p);
      if (!walls_[w].enabled || (!state.touching && walls_.clearance(w, P.position[p]) >= P.radius[p]))
        continue;
      const ContactGeometry g = walls_.geometry(w, P.position[p], P.radius[p], P.velocity[p], P.spin[p]);
      const WallProps &wp = walls_[w].props;
      const ContactParams params{in_series(P.kn[p], wp.kn), in_series(P.ks[p], wp.ks),
                                 std::min(P.friction[p], wp.friction)};
      ContactBond no_bond;
      LinearLaw::History none;
      const ResolvedContact r = resolve_contact(wall_law, params, no_bond, state, none, g, dt);
      if (!r.touching)
        continue;
      f += r.force;
      t -= g.arm_second * g.normal.cross(state.shear_force);
      const double b = shear_mobility(P.inv_mass[p], P.inv_inertia[p], g.arm_second);
      bound += stability_row_term(params.kn, params.ks, P.inv_mass[p], b, 0.0, 0.0);
      power += r.force.dot(walls_.surface_velocity(w, P.position[p]));
    }
    // A ball without contacts still gets the step of one contact with its
    // own stiffness, so that the first impact is resolved; real mass and
    // inertia are used so that a scene of held balls still has a step.
    const double alone =
      std::max(P.kn[p], P.ks[p] * (1.0 + P.mass[p] * P.radius[p] * P.radius[p] / P.inertia[p])) / P.mass[p];
    P.force[p] = f;
    P.torque[p] = t;
    row_bound_[p] = bound;
    lone_bound_[p] = alone;
    wall_power_[p] = power;
  }
}

void Simulation::choose_time_step()
{
  const Index n = particles_.size();
  double largest = 0, lone = 0;
#pragma omp parallel for schedule(static) reduction(max : largest, lone)
  for (Index p = 0; p < n; ++p)
  {
    largest = std::max(largest, row_bound_[p]);
    lone = std::max(lone, lone_bound_[p]);
  }
  // The bound of the contacts that exist; infinite when none carries force.
  dt_critical_ = critical_step(largest);

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
    dt_ = settings_.time_step_safety * std::min(dt_critical_, critical_step(lone));
    if (!std::isfinite(dt_))
      fail(-1, "no particle has a finite critical time step (every ball has zero stiffness)");
  }
}

void Simulation::integrate(bool measure_kinetic)
{
  if (!forces_current_)
    compute_forces();
  forces_current_ = false;
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

  const auto damped = [alpha](const Vec3 &f, const Vec3 &v) {
    Vec3 out = f;
    for (int k = 0; k < 3; ++k)
      if (v[k] != 0)
        out[k] -= alpha * std::abs(f[k]) * (v[k] > 0 ? 1.0 : -1.0);
    return out;
  };

#pragma omp parallel for schedule(static) reduction(min : first_bad) reduction(|| : moved)
  for (Index p = 0; p < n; ++p)
  {
    BallEnergy &e = ball_energy_[p];
    const Vec3 f = P.force[p], t = P.torque[p];
    const Vec3 v_old = P.velocity[p], w_old = P.spin[p];
    Vec3 v_new = v_old, w_new = w_old;
    if (P.holds_velocity(p))
      e.boundary -= (f - P.mass[p] * gravity).dot(v_old) * kick;
    else
    {
      const Vec3 fd = damped(f, v_old);
      v_new = v_old + fd * (P.inv_mass[p] * kick);
      const Vec3 v_mid = 0.5 * (v_old + v_new);
      e.damping += (f - fd).dot(v_mid) * kick;
      e.body += P.mass[p] * gravity.dot(v_mid) * kick;
    }
    if (P.holds_spin(p))
      e.boundary -= t.dot(w_old) * kick;
    else
    {
      const Vec3 td = damped(t, w_old);
      w_new = w_old + td * (P.inv_inertia[p] * kick);
      e.damping += (t - td).dot(0.5 * (w_old + w_new)) * kick;
    }
    e.boundary += wall_power_[p] * kick;
    if (measure_kinetic)
    {
      const Vec3 &v_pair = first_step ? v_old : v_new;
      const Vec3 &w_pair = first_step ? w_old : w_new;
      e.kinetic = 0.5 * P.mass[p] * v_old.dot(v_pair) + 0.5 * P.inertia[p] * w_old.dot(w_pair);
    }
    P.velocity[p] = v_new;
    P.spin[p] = w_new;
    P.position[p] += v_new * dt;
    const double travel = v_new.norm() * dt;
    if (!(travel <= 0.5 * P.radius[p]) || !std::isfinite(w_new.squaredNorm()))
      first_bad = std::min(first_bad, p);
    moved = moved || neighbors_.moved_too_far(p, P.position[p]);
  }

  walls_.advance(dt);
  time_ += dt;
  ++step_;
  dt_prev_ = dt;
  rebuild_requested_ = rebuild_requested_ || moved;
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

std::pair<double, double> Simulation::wall_energy(WallIndex w) const
{
  const LinearLaw wall_law;
  const WallProps &wp = walls_[w].props;
  double strain = 0, friction = 0;
  for (Index p = 0; p < particles_.size(); ++p)
  {
    const ContactState &s = walls_.state(w, p);
    friction += s.friction_work;
    if (!s.touching)
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
    if (s.touching)
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

std::size_t Simulation::bonds_broken(BreakMode mode) const
{
  return mode == BreakMode::tension ? broken_tension_ : broken_shear_;
}
} // namespace dem
