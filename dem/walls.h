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
#include <utility>
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

/// Outward radial unit vector and radial distance of x from a cylinder axis.
DEM_HOT_INLINE std::pair<Vec3, double> radial_of(const Wall &c, const Vec3 &x)
{
  const Vec3 radial = radial_offset(c, x);
  const double rho = radial.norm();
  // On the axis every direction is radial; pick one that is normal to it.
  const Vec3 outward = rho > 0 ? Vec3(radial / rho) : c.direction.unitOrthogonal();
  return {outward, rho};
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
  /// clearance(w, x) >= r; every ball near a cylinder (near_walls) asks it
  /// at every step, so a ball inside it is answered without the square root: its
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

  /// A ball's contact with a wall: its geometry (the wall is the first
  /// entity) and the velocity of the wall's surface at the point nearest
  /// the ball's centre [m/s], which the boundary work needs; one radial
  /// direction serves both.
  struct Touch
  {
    ContactGeometry geometry;
    Vec3 surface_velocity;
  };
  /// The contact of a ball (centre x, radius r, velocity v, spin omega)
  /// with wall w.
  DEM_HOT_INLINE Touch touch(WallIndex w, const Vec3 &x, double r, const Vec3 &v, const Vec3 &omega) const
  {
    const Wall &wall = walls_[w];
    Touch t;
    ContactGeometry &g = t.geometry;
    Vec3 &wall_velocity = t.surface_velocity;
    wall_velocity = wall.velocity;
    double gap;
    if (wall.shape == WallShape::plane)
    {
      g.normal = wall.direction;
      gap = (x - wall.point).dot(wall.direction);
    }
    else
    {
      const auto [outward, rho] = radial_of(wall, x);
      g.normal = -outward;
      gap = wall.radius - rho;
      wall_velocity += wall.radial_velocity * outward;
    }
    g.overlap = r - gap;
    g.arm_first = 0;
    g.arm_second = r - 0.5 * g.overlap;
    g.velocity_difference = v - wall_velocity;
    g.spin_first = Vec3::Zero();
    g.spin_second = omega;
    return t;
  }

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
  /// The walls' side of the neighbour list (neighbors.h).  mark_near()
  /// marks, for every ball, the walls whose surface lies within its radius
  /// plus `reach` of its centre [m], and records where each wall stands;
  /// it is given the centres the neighbour list measures its skin from.
  /// While no ball has moved reach/2 from them (the neighbour list's own
  /// rule) and no wall reach/4 since the marks (near_stale), a ball is
  /// clear of every wall not marked for it: a ball's clearance changes by
  /// at most the distance its centre moves plus the distance the wall's
  /// point moves plus the change of a cylinder's radius, so it has lost at
  /// most 3/4 of the reach; the quarter left over is far above the
  /// round-off.  A force pass then asks only the marked walls
  /// (ball_forces.h).  Walls from the 64th on are asked by every ball.
  void mark_near(const std::vector<Vec3> &centres, const std::vector<double> &radii, double reach);
  /// Bit w set: ball p may touch wall w before the next mark_near().
  std::uint64_t near_walls(Index p) const
  {
    return static_cast<std::size_t>(p) < near_.size() ? near_[static_cast<std::size_t>(p)] : ~std::uint64_t(0);
  }
  static constexpr WallIndex marked_walls = 64;
  /// Whether the marks no longer hold: never made, a wall added, a wall
  /// turned, or moved more than reach/4 (its point, or a cylinder's radius).
  bool near_stale() const;
  /// How many times the marks were made.
  std::size_t near_marks() const { return near_marks_; }

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
  std::vector<std::uint64_t> near_; ///< per ball, the walls it may touch (mark_near)
  std::vector<Wall> marked_at_;     ///< the walls where mark_near() found them
  double near_reach_ = 0;           ///< m, the reach of the marks
  std::size_t near_marks_ = 0;
};
} // namespace dem
