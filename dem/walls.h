// Walls: planes (loading platens) and a cylinder (lateral confinement).
//
// Walls are geometry plus a prescribed velocity (thesis §3.3.1, §5.3.1).  A
// wall has its own contact properties; a ball-wall pair uses the ball's and
// the wall's stiffnesses in series (eq. 3.17-3.18) and the smaller of the two
// friction coefficients, exactly like a ball-ball pair.  Walls are rigid and
// infinitely massive: they move as prescribed whatever force acts on them,
// and the force the balls exert on each wall is recorded for stress
// measurement and for the boundary-work term of the energy balance.
//
// A plane is infinite; its direction is its unit normal, pointing into the
// region the balls occupy.  A cylinder confines balls to its inside; its
// direction is its axis.  A wall can be disabled (the lateral wall is removed
// before a uniaxial test, §5.3.4) without renumbering the others.
#pragma once

#include "dem/contact.h"

#include <cstdint>
#include <string>
#include <vector>

namespace dem
{
struct WallProps
{
  double kn = 0;       ///< N/m, wall normal stiffness
  double ks = 0;       ///< N/m, wall shear stiffness
  double friction = 0; ///< -
};

enum class WallShape
{
  plane,
  cylinder,
};

struct Wall
{
  std::string name;
  WallShape shape = WallShape::plane;
  Vec3 point = Vec3::Zero();      ///< m, a point on the plane / on the cylinder axis
  Vec3 direction = Vec3::UnitZ(); ///< unit: plane normal into the balls / cylinder axis
  double radius = 0;              ///< m, cylinder inner radius
  Vec3 velocity = Vec3::Zero();   ///< m/s, translation of the wall
  double radial_velocity = 0;     ///< m/s, cylinder radius rate (> 0 expanding)
  WallProps props;
  bool enabled = true;
};

using WallIndex = int;

/// The contact history of one ball with one wall (the wall is the first entity).
struct WallContact
{
  WallIndex wall = 0;
  Index ball = 0;
  ContactState state;
};

/// The offset of x from a cylinder's axis, normal to the axis [m].
inline Vec3 radial_offset(const Wall &c, const Vec3 &x)
{
  const Vec3 d = x - c.point;
  return d - d.dot(c.direction) * c.direction;
}

class WallSet
{
public:
  WallIndex add(Wall w);
  int size() const { return static_cast<int>(walls_.size()); }
  Wall &operator[](WallIndex w) { return walls_[w]; }
  const Wall &operator[](WallIndex w) const { return walls_[w]; }
  WallIndex find(const std::string &name) const; ///< -1 if absent

  /// Distance from point x to the wall surface, positive on the particle side.
  double clearance(WallIndex w, const Vec3 &x) const
  {
    const Wall &wall = walls_[w];
    return wall.shape == WallShape::plane ? (x - wall.point).dot(wall.direction) : cylinder_clearance(wall, x);
  }

  /// Whether a ball (centre x, radius r) is clear of wall w, exactly
  /// clearance(w, x) >= r; every ball asks every wall at every step, so a
  /// ball far inside a cylinder is answered without the square root: its
  /// squared radial distance below (R - r)^2 by a relative 2e-9, far more
  /// than the round-off of rho, R - rho and the squares (a few 1e-16 of R)
  /// while R - r > 1e-6 R, gives what the exact test would.
  bool clear_of(WallIndex w, const Vec3 &x, double r) const
  {
    const Wall &wall = walls_[w];
    if (wall.shape == WallShape::plane)
      return clearance(w, x) >= r;
    const double inside = wall.radius - r;
    if (inside > 1e-6 * wall.radius && radial_offset(wall, x).squaredNorm() < (1.0 - 2e-9) * (inside * inside))
      return true;
    return cylinder_clearance(wall, x) >= r;
  }

  /// Geometry of the contact of a ball (centre x, radius r, velocity v, spin
  /// omega) with wall w.  The wall is the first entity.
  ContactGeometry geometry(WallIndex w, const Vec3 &x, double r, const Vec3 &v, const Vec3 &omega) const;

  /// Velocity of the surface of wall w at the point nearest to x [m/s].
  Vec3 surface_velocity(WallIndex w, const Vec3 &x) const;

  /// Removes or restores wall w; a removed wall forgets its contacts.
  void set_enabled(WallIndex w, bool enabled);

  /// Moves every wall by its velocity over dt.
  void advance(double dt);

  /// The contact histories of ball-wall pairs, kept only for the balls that
  /// have touched a wall (a few per cent of a sample: the balls at its
  /// faces); every other pair reads as a contact at rest.  resize_history()
  /// lays out the index (four bytes per wall and ball) for a number of
  /// balls, and keeps the histories if already laid out so.
  void resize_history(Index particles);
  /// The contact of ball p with wall w at the last update (at rest if none).
  const ContactState &state(WallIndex w, Index p) const
  {
    const std::int32_t k = slot_[slot(w, p)];
    return k < 0 ? at_rest_ : kept_[static_cast<std::size_t>(k)].state;
  }
  /// The history a force pass updates, or nullptr when ball p has never
  /// touched wall w: the pass then starts it at rest and hands it to
  /// keep_new_contact() if it touches.
  ContactState *history_of(WallIndex w, Index p)
  {
    const std::int32_t k = slot_[slot(w, p)];
    return k < 0 ? nullptr : &kept_[static_cast<std::size_t>(k)].state;
  }
  /// Force passes: open_pass() before (a list of new contacts for each of
  /// `threads` threads), keep_new_contact() from the thread that owns ball
  /// p, close_pass() after, which keeps them in (wall, ball) order.
  void open_pass(int threads);
  void keep_new_contact(WallIndex w, Index p, const ContactState &state);
  void close_pass();

  /// The histories held, in increasing (wall, ball) order, and their
  /// restoration (snapshots), after resize_history(); a list naming a wall
  /// or ball out of range throws std::invalid_argument.
  std::vector<WallContact> contacts() const;
  void restore_history(const std::vector<WallContact> &contacts);

private:
  static double cylinder_clearance(const Wall &c, const Vec3 &x);
  std::size_t slot(WallIndex w, Index p) const { return static_cast<std::size_t>(w) * stride_ + p; }
  void index_kept();
  std::vector<Wall> walls_;
  std::vector<WallContact> kept_;             ///< the histories held, in no particular order
  std::vector<std::int32_t> slot_;            ///< (wall, ball) wall-major: entry of kept_, or -1
  std::vector<std::vector<WallContact>> new_; ///< a force pass's new contacts, one list per thread
  std::size_t stride_ = 0;
  ContactState at_rest_;
};
} // namespace dem
