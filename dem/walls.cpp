#include "dem/walls.h"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <tuple>

namespace dem
{
namespace
{
bool wall_then_ball(const WallContact &a, const WallContact &b)
{
  return std::tie(a.wall, a.ball) < std::tie(b.wall, b.ball);
}
} // namespace

WallIndex WallSet::add(Wall w)
{
  w.direction.normalize();
  walls_.push_back(std::move(w));
  slot_.resize(stride_ * walls_.size(), -1);
  return static_cast<WallIndex>(walls_.size() - 1);
}

WallIndex WallSet::find(const std::string &name) const
{
  for (WallIndex w = 0; w < size(); ++w)
    if (walls_[w].name == name)
      return w;
  return -1;
}

// The radial distance alone (no unit vector), the same rho as radial_of's.
double WallSet::cylinder_clearance(const Wall &c, const Vec3 &x) { return c.radius - radial_offset(c, x).norm(); }

void WallSet::set_enabled(WallIndex w, bool enabled)
{
  walls_[w].enabled = enabled;
  kept_.erase(std::remove_if(kept_.begin(), kept_.end(), [w](const WallContact &c) { return c.wall == w; }),
              kept_.end());
  index_kept();
}

void WallSet::advance(double dt)
{
  for (auto &w : walls_)
  {
    w.point += w.velocity * dt;
    w.radius += w.radial_velocity * dt;
  }
}

void WallSet::mark_near(const std::vector<Vec3> &centres, const std::vector<double> &radii, double reach)
{
  near_.assign(centres.size(), 0);
  const WallIndex marked = std::min(size(), marked_walls);
  for (std::size_t p = 0; p < centres.size(); ++p)
    for (WallIndex w = 0; w < marked; ++w)
      if (clearance(w, centres[p]) < radii[p] + reach)
        near_[p] |= std::uint64_t(1) << w;
  marked_at_ = walls_;
  near_reach_ = reach;
  ++near_marks_;
}

bool WallSet::near_stale() const
{
  if (marked_at_.size() != walls_.size())
    return true;
  const double allowed = 0.25 * near_reach_;
  for (std::size_t w = 0; w < walls_.size(); ++w)
  {
    const Wall &now = walls_[w], &then = marked_at_[w];
    if (now.shape != then.shape || now.direction != then.direction ||
        !((now.point - then.point).norm() + std::abs(now.radius - then.radius) <= allowed))
      return true;
  }
  return false;
}

void WallSet::index_kept()
{
  std::fill(slot_.begin(), slot_.end(), -1);
  for (std::size_t k = 0; k < kept_.size(); ++k)
    slot_[slot(kept_[k].wall, kept_[k].ball)] = static_cast<std::int32_t>(k);
}

void WallSet::open_pass(int threads)
{
  new_.resize(static_cast<std::size_t>(std::max(threads, 1)));
  for (std::vector<WallContact> &list : new_)
    list.clear();
}

void WallSet::keep_new_contact(WallIndex w, Index p, const ContactState &state)
{
  new_[static_cast<std::size_t>(omp_get_thread_num())].push_back({w, p, state});
}

void WallSet::close_pass()
{
  const std::size_t first = kept_.size();
  for (const std::vector<WallContact> &list : new_)
    kept_.insert(kept_.end(), list.begin(), list.end());
  // The order of the lists depends on the threads; the order kept does not.
  std::sort(kept_.begin() + static_cast<std::ptrdiff_t>(first), kept_.end(), wall_then_ball);
  for (std::size_t k = first; k < kept_.size(); ++k)
    slot_[slot(kept_[k].wall, kept_[k].ball)] = static_cast<std::int32_t>(k);
}

std::vector<WallContact> WallSet::contacts() const
{
  std::vector<WallContact> out = kept_;
  std::sort(out.begin(), out.end(), wall_then_ball);
  return out;
}

void WallSet::restore_history(const std::vector<WallContact> &contacts)
{
  for (const WallContact &c : contacts)
    if (c.wall < 0 || c.wall >= size() || c.ball < 0 || static_cast<std::size_t>(c.ball) >= stride_)
      throw std::invalid_argument("a wall contact history names wall " + std::to_string(c.wall) + " and ball " +
                                  std::to_string(c.ball) + ": expected one of " + std::to_string(size()) +
                                  " walls and " + std::to_string(stride_) + " balls");
  for (const WallContact &c : contacts)
  {
    if (ContactState *kept = history_of(c.wall, c.ball))
      *kept = c.state;
    else
    {
      slot_[slot(c.wall, c.ball)] = static_cast<std::int32_t>(kept_.size());
      kept_.push_back(c);
    }
  }
}

void WallSet::resize_history(Index particles)
{
  if (stride_ == static_cast<std::size_t>(particles) && slot_.size() == stride_ * walls_.size())
    return; // already laid out for these balls: keep the histories
  stride_ = static_cast<std::size_t>(particles);
  kept_.clear();
  slot_.assign(stride_ * walls_.size(), -1);
}
} // namespace dem
