// BallForces: the per-ball end of a step's force pass (thesis §3.3.2,
// Fig. 3.8).
//
// A ball's resultant at time t is summed in one fixed order, whatever the
// thread count:
//
//   F_p = m_p g - sum F_c (contacts c where p is first, increasing c)
//               + sum F_c (contacts c where p is second, increasing c)
//               + sum F_w (enabled walls w, increasing w)                [N]
//
// and likewise its torque [N m] and its stability row bound [1/s^2]
// (stability.h).  The contact law's pass (contact_model.h) sums the first
// two terms; this struct holds what the rest needs: the weight, the ball-wall
// contacts (always the linear law with the wall's properties, walls.h) and
// the arrays the resultants go to.  Each call touches ball p's entries only,
// so threads that own different balls never write the same memory.
#pragma once

#include "dem/balanced_ranges.h"
#include "dem/contact_resolve.h"
#include "dem/law_linear.h"
#include "dem/particles.h"
#include "dem/stability.h"
#include "dem/walls.h"

#include <algorithm>
#include <vector>

namespace dem
{
struct BallForces
{
  ParticleStore &particles;
  WallSet &walls;
  const std::vector<WallIndex> &active_walls; ///< enabled walls, increasing
  Vec3 gravity;                               ///< m/s^2
  double dt;                                  ///< s, the step that produced the displacement since the last pass
  std::vector<double> &row_bound;             ///< 1/s^2, per ball, out
  std::vector<double> &wall_power;            ///< W, per ball, sum over walls of F_wall->ball . v_wall, out
  /// The balls cut into one range per thread (balanced_ranges.h): the pass
  /// sums each range's balls and records its time; the integration that
  /// follows advances the same balls on the same thread, so that a ball's
  /// resultant, and the position it gives the next pass, stay in the cache
  /// of the core that uses them.  The step moves the cuts after both.
  BalancedRanges &ranges;
  /// Whether the linear law's ordinary contacts are resolved eight at a
  /// time (SimulationSettings::contacts_in_lanes).
  bool in_lanes;

  // The sums are kept as three doubles, not Vec3: the pass then compiles
  // to scalar multiply-adds instead of mixing two-lane and scalar halves
  // of one vector, which stalls loads that span both.

  /// The first term of the sum: the ball's weight [N].
  DEM_HOT_INLINE void weight(Index p, double (&f)[3]) const
  {
    for (int d = 0; d < 3; ++d)
      f[d] = particles.mass[p] * gravity[d];
  }

  /// Adds ball p's wall contacts to the contact sums f [N], t [N m] and
  /// bound [1/s^2], stores the resultants and returns the ball's row bound.
  DEM_HOT_INLINE double finish(Index p, double (&f)[3], double (&t)[3], double bound) const
  {
    ParticleStore &P = particles;
    double power = 0;
    const std::uint64_t near = walls.near_walls(p);
    for (const WallIndex w : active_walls)
    {
      if (w < WallSet::marked_walls && !((near >> w) & 1))
        continue; // clear of it until the next neighbour build (walls.h)
      ContactState *kept = walls.history_of(w, p);
      if (!(kept && kept->touching()) && walls.clear_of(w, P.position[p], P.radius[p]))
        continue;
      ContactState fresh; // a ball that never touched this wall starts at rest
      ContactState &state = kept ? *kept : fresh;
      const WallSet::Touch touch = walls.touch(w, P.position[p], P.radius[p], P.velocity[p], P.spin[p]);
      const ContactGeometry &g = touch.geometry;
      const WallProps &wp = walls[w].props;
      const ContactParams params{in_series(P.kn[p], wp.kn), in_series(P.ks[p], wp.ks),
                                 std::min(P.friction[p], wp.friction)};
      // A wall without shear stiffness (the default platen: frictionless)
      // never gives a contact shear force; the resolver's turn of the
      // shear, its increment and the Coulomb limit would all give zero.
      ResolvedContact r;
      if (params.ks == 0 && state.shear_force.isZero(0))
        r = resolve_shear_free_contact(params, state, g);
      else
      {
        bool unbonded = false;
        const ContactBond no_bond;
        LinearLaw::History none;
        r = resolve_contact(LinearLaw{}, params, unbonded, no_bond, state, none, g, dt);
      }
      if (!r.touching)
        continue;
      if (!kept)
        walls.keep_new_contact(w, p, fresh);
      const Vec3 lever = cross(g.normal, r.shear);
      for (int d = 0; d < 3; ++d)
      {
        f[d] += r.force[d];
        t[d] -= g.arm_second * lever[d];
      }
      const double sb = arm_factor(g.arm_second, P.inv_radius[p]) * P.sqrt_shear_mobility[p];
      bound += stability_row_term(params.kn, params.ks, P.inv_mass[p], sb * sb, 0.0, 0.0);
      power += r.force.dot(touch.surface_velocity);
    }
    P.force[p] = Vec3(f[0], f[1], f[2]);
    P.torque[p] = Vec3(t[0], t[1], t[2]);
    row_bound[p] = bound;
    wall_power[p] = power;
    return bound;
  }
};

/// A bond that broke in a force pass, for the break log.
struct BrokenBond
{
  std::size_t contact = 0; ///< entry of the contact table
  BreakMode mode = BreakMode::none;
  BreakForces trial; ///< the law's forces before the break
};
} // namespace dem
