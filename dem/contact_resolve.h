// The contact resolver: one contact, one step, any law.
//
//   1. a contact exists when the entities overlap (U > 0) or a bond joins
//      them; otherwise its history is cleared (thesis §3.3.2: a new contact
//      starts with zero shear force);
//   2. the old shear force is rotated with the contact plane, and the shear
//      displacement increment is the relative velocity of the contact points
//      times dt, with the lever arms taken along the mean of the old and new
//      normals: velocities live at t - dt/2, so the geometry they act on is
//      taken there too.  With the new normal instead, a rigid rotation by
//      dtheta per step would create a spurious shear increment
//      d dtheta^2 / 2 per step (first-order error); with the mean it is
//      O(dtheta^3) (second order, check V04);
//   3. the law gives trial normal and shear forces (law_*.h);
//   4. the PFC3D contact bond and slip rules of thesis §3.4.2 apply:
//        bonded:   tension allowed; if -F_n >= phi_n the bond breaks and both
//                  forces are set to zero; if |F_s| >= phi_s the bond breaks
//                  and the forces stay unless they exceed the slip limit;
//        unbonded: no tension; |F_s| <= mu F_n (Coulomb slip, the excess is
//                  dissipated as friction work).
//      A bond never breaks in compression under the normal criterion.
//      Displacement criterion (appendix A): a bond also breaks, with both
//      forces set to zero, when the centre distance exceeds its break
//      distance (distance when bonded + delta_c; infinite when unused).
//
// Energy: friction work is F_s,new . (F_trial - F_s,new) / K^s per slipping
// step (the slip displacement times the force that resists it); a break
// releases the stored energy the forces lose at that step.
#pragma once

#include "dem/contact.h"

#include <algorithm>

namespace dem
{
struct ResolvedContact
{
  Vec3 force = Vec3::Zero(); ///< N, on the second entity
  Vec3 shear = Vec3::Zero(); ///< N, its shear part F_s (the new state's shear force)
  BreakMode broke = BreakMode::none;
  bool touching = false;
  BreakForces trial; ///< the law's forces at a break (set only when broke)
};

template <class Law>
DEM_HOT_INLINE ResolvedContact resolve_contact(const Law &law, const ContactParams &params, bool &bonded,
                                               const ContactBond &bond, ContactState &state,
                                               typename Law::History &history, const ContactGeometry &g, double dt)
{
  ResolvedContact out;
  if (g.overlap <= 0 && !bonded)
  {
    state.shear_force.setZero();
    state.normal.setZero();
    state.normal_force = 0;
    state.overlap = g.overlap;
    history = typename Law::History{};
    return out;
  }

  const bool new_contact = !state.touching();
  const Vec3 mid_normal = new_contact ? g.normal : Vec3(0.5 * (state.normal + g.normal));
  // Contact-point velocities: v + omega x (arm n) for the first entity and
  // v - omega x (arm n) for the second, along the mean normal.
  const Vec3 relative_velocity =
    g.velocity_difference - cross(g.arm_second * g.spin_second + g.arm_first * g.spin_first, mid_normal);
  Vec3 shear = state.shear_force;
  if (!new_contact)
  {
    const double twist = 0.5 * (g.spin_first + g.spin_second).dot(mid_normal) * dt;
    shear = rotate_with_contact_plane(shear, state.normal, g.normal, twist);
    law.rotate_history(history, state.normal, g.normal, twist);
  }
  const Vec3 shear_before = shear;
  const Vec3 shear_increment = (relative_velocity - relative_velocity.dot(g.normal) * g.normal) * dt;

  double fn = law.normal_force(params, g.overlap, history, dt);
  shear = law.shear_force(params, shear, shear_increment, history, dt);

  const auto limit_by_friction = [&](double normal_force)
  {
    const double limit = params.friction * std::max(normal_force, 0.0);
    // Most contacts stick: a shear whose square is clearly below the
    // limit's (by far more than the round-off of either square, which is
    // relative while the limit's square is a normal number) is inside the
    // cone without the square root; the root decides the rest, as before.
    const double squared = shear.squaredNorm(), limit_squared = limit * limit;
    if (limit_squared > 1e-290 && squared < (1.0 - 1e-12) * limit_squared)
      return;
    const double magnitude = std::sqrt(squared);
    if (magnitude > limit)
    {
      const Vec3 limited = magnitude > 0 ? Vec3(shear * (limit / magnitude)) : Vec3::Zero();
      if (params.ks > 0)
        state.friction_work += limited.dot(shear - limited) / params.ks;
      shear = limited;
    }
  };

  if (bonded)
  {
    const auto record_trial = [&] { out.trial = {fn, shear.norm()}; };
    if (g.arm_first + g.arm_second > bond.break_distance)
    {
      state.bond_energy += law.stored_energy(params, fn, shear, history);
      record_trial();
      bonded = false;
      out.broke = BreakMode::displacement;
      fn = 0;
      shear.setZero();
    }
    else if (fn < 0 && -fn >= bond.normal_strength)
    {
      state.bond_energy += law.stored_energy(params, fn, shear, history);
      record_trial();
      bonded = false;
      out.broke = BreakMode::tension;
      fn = 0;
      shear.setZero();
    }
    else if (shear.squaredNorm() >= bond.shear_strength * bond.shear_strength)
    {
      const double before = law.stored_energy(params, fn, shear, history);
      record_trial();
      bonded = false;
      out.broke = BreakMode::shear;
      if (fn < 0)
      {
        fn = 0;
        shear.setZero();
      }
      else
      {
        const double limit = params.friction * fn;
        const double magnitude = shear.norm();
        if (magnitude > limit)
          shear *= limit / magnitude;
      }
      state.bond_energy += before - law.stored_energy(params, fn, shear, history);
    }
  }
  else
  {
    fn = std::max(fn, 0.0);
    limit_by_friction(fn);
  }

  law.commit(history, g.overlap, fn, shear_before, shear, dt);
  // A bond that broke apart (no overlap) leaves the contact without force.
  out.touching = g.overlap > 0 || bonded;
  state.normal = out.touching ? g.normal : Vec3(Vec3::Zero());
  state.normal_force = fn;
  state.overlap = g.overlap;
  state.shear_force = shear;
  out.force = fn * g.normal + shear;
  out.shear = shear;
  return out;
}

/// resolve_contact for an unbonded contact whose pair has no shear
/// stiffness (K^s = 0) and which carries no shear force: the shear force
/// stays zero (every increment is K^s V_s dt = 0, and a turned zero is
/// zero), no friction work is done, and only the normal force of the linear
/// law remains, F = max(K^n U, 0) n (eq. 3.2), while U > 0.  The same
/// state and force as resolve_contact with the linear law, to the bit but
/// for the sign of a zero (a test compares them).  Used for ball-wall
/// contacts, where K^s = 0 is the default (frictionless platens).
DEM_HOT_INLINE ResolvedContact resolve_shear_free_contact(const ContactParams &params, ContactState &state,
                                                          const ContactGeometry &g)
{
  ResolvedContact out;
  state.shear_force.setZero();
  state.overlap = g.overlap;
  if (!(g.overlap > 0)) // apart (and, as resolve_contact has it, not touching at a NaN overlap)
  {
    state.normal.setZero();
    state.normal_force = 0;
    return out;
  }
  const double fn = std::max(params.kn * g.overlap, 0.0);
  out.touching = true;
  state.normal = g.normal;
  state.normal_force = fn;
  out.force = fn * g.normal;
  return out;
}
} // namespace dem
