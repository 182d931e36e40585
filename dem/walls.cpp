#include "dem/walls.h"

#include <algorithm>
#include <cmath>

namespace dem
{
WallIndex WallSet::add(Wall w)
{
  w.direction.normalize();
  walls_.push_back(std::move(w));
  history_.resize(stride_ * walls_.size());
  engaged_.resize(stride_ * walls_.size(), 0);
  return static_cast<WallIndex>(walls_.size() - 1);
}

WallIndex WallSet::find(const std::string &name) const
{
  for (WallIndex w = 0; w < size(); ++w)
    if (walls_[w].name == name)
      return w;
  return -1;
}

namespace
{
/// Outward radial unit vector and radial distance of x from a cylinder axis.
std::pair<Vec3, double> radial_of(const Wall &c, const Vec3 &x)
{
  const Vec3 d = x - c.point;
  const Vec3 radial = d - d.dot(c.direction) * c.direction;
  const double rho = radial.norm();
  // On the axis every direction is radial; pick one that is normal to it.
  const Vec3 outward = rho > 0 ? Vec3(radial / rho) : c.direction.unitOrthogonal();
  return {outward, rho};
}
} // namespace

double WallSet::cylinder_clearance(const Wall &c, const Vec3 &x)
{
  return c.radius - radial_of(c, x).second;
}

ContactGeometry WallSet::geometry(WallIndex w, const Vec3 &x, double r, const Vec3 &v,
                                  const Vec3 &omega) const
{
  const Wall &wall = walls_[w];
  ContactGeometry g;
  Vec3 wall_velocity = wall.velocity;
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
  return g;
}

Vec3 WallSet::surface_velocity(WallIndex w, const Vec3 &x) const
{
  const Wall &wall = walls_[w];
  if (wall.shape == WallShape::plane)
    return wall.velocity;
  return wall.velocity + wall.radial_velocity * radial_of(wall, x).first;
}

void WallSet::set_enabled(WallIndex w, bool enabled)
{
  walls_[w].enabled = enabled;
  std::fill(history_.begin() + static_cast<std::ptrdiff_t>(slot(w, 0)),
            history_.begin() + static_cast<std::ptrdiff_t>(slot(w, 0) + stride_), ContactState{});
  std::fill(engaged_.begin() + static_cast<std::ptrdiff_t>(slot(w, 0)),
            engaged_.begin() + static_cast<std::ptrdiff_t>(slot(w, 0) + stride_), 0);
}

void WallSet::advance(double dt)
{
  for (auto &w : walls_)
  {
    w.point += w.velocity * dt;
    w.radius += w.radial_velocity * dt;
  }
}

void WallSet::restore_history(std::vector<ContactState> history)
{
  if (history.size() != history_.size())
    return; // a snapshot from another layout: start without wall history
  history_ = std::move(history);
  for (std::size_t k = 0; k < history_.size(); ++k)
    engaged_[k] = history_[k].touching ? 1 : 0;
}

void WallSet::resize_history(Index particles)
{
  if (stride_ == static_cast<std::size_t>(particles) && history_.size() == stride_ * walls_.size())
    return; // already laid out for these balls: keep the history
  stride_ = static_cast<std::size_t>(particles);
  history_.assign(stride_ * walls_.size(), ContactState{});
  engaged_.assign(stride_ * walls_.size(), 0);
}
} // namespace dem
