#include "dem/neighbors.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace dem
{
namespace
{
bool within(const ParticleStore &p, Index i, Index j, double skin)
{
  const double reach = p.radius[i] + p.radius[j] + skin;
  return (p.position[i] - p.position[j]).squaredNorm() < reach * reach;
}
} // namespace

bool NeighborList::stale(const ParticleStore &particles) const
{
  return reference_.size() != static_cast<std::size_t>(particles.size());
}

double NeighborList::largest_displacement(const ParticleStore &particles) const
{
  if (stale(particles))
    return 0;
  double largest = 0;
  for (Index p = 0; p < particles.size(); ++p)
    largest = std::max(largest, (particles.position[p] - reference_[p]).squaredNorm());
  return std::sqrt(largest);
}

void NeighborList::release_candidates()
{
  std::vector<Pair>().swap(pairs_);
  for (std::vector<Index> *scratch : {&cell_start_, &cell_members_, &cell_of_, &cell_fill_, &partners_})
    std::vector<Index>().swap(*scratch);
}

namespace
{
/// Scratch of a cell build, kept by a NeighborList between builds.
struct CellScratch
{
  std::vector<Index> &cell_start, &cell_members, &cell_of, &cell_fill;
};

/// Calls visit(i, j) for every pair i < j of balls in neighbouring cells
/// (cells at least R_i + R_j + skin wide), i ascending and, for each i, the
/// candidates j in cell order; stops as soon as visit returns false.
template <class Visit>
void visit_cell_neighbours(const ParticleStore &particles, double skin, const CellScratch &s, Visit &&visit)
{
  const Index n = particles.size();
  if (n == 0)
    return;
  Vec3 lo = particles.position[0], hi = lo;
  for (const Vec3 &x : particles.position)
  {
    lo = lo.cwiseMin(x);
    hi = hi.cwiseMax(x);
  }
  // Cells at least one interaction range wide, so neighbours of a ball are
  // in the 27 cells around it; coarsened if stray balls stretch the box.
  // Cell counts are reckoned in floating point and cast to integers only
  // once they are known to fit: balls at huge coordinates (1e300 m) coarsen
  // the grid, and a box no double can measure (balls at -1e308 and 1e308,
  // or a NaN position) gets a single cell.
  double h = std::max(2.0 * particles.max_radius() + skin, std::numeric_limits<double>::min());
  const Vec3 extent = (hi - lo).cwiseMax(h);
  const double max_cells = 8.0 * double(n) + 64;
  const auto along = [&](int k) { return std::max(1.0, std::floor(extent[k] / h)); };
  std::array<long, 3> dims{1, 1, 1};
  if (extent.allFinite())
  {
    while (along(0) * along(1) * along(2) > max_cells)
      h *= 1.25;
    for (int k = 0; k < 3; ++k)
      dims[k] = static_cast<long>(along(k));
  }
  const long cells = dims[0] * dims[1] * dims[2];
  const auto coord = [&](const Vec3 &x, int k)
  {
    const double c = (x[k] - lo[k]) / h; // >= 0, or NaN
    return c < double(dims[k] - 1) ? static_cast<long>(c) : dims[k] - 1;
  };
  const auto cell_id = [&](long cx, long cy, long cz) { return (cz * dims[1] + cy) * dims[0] + cx; };

  // Counting sort of balls into cells.
  s.cell_of.resize(n);
  s.cell_start.assign(cells + 1, 0);
  for (Index p = 0; p < n; ++p)
  {
    const Vec3 &x = particles.position[p];
    s.cell_of[p] = static_cast<Index>(cell_id(coord(x, 0), coord(x, 1), coord(x, 2)));
    ++s.cell_start[s.cell_of[p] + 1];
  }
  for (long c = 0; c < cells; ++c)
    s.cell_start[c + 1] += s.cell_start[c];
  s.cell_members.resize(n);
  s.cell_fill.assign(s.cell_start.begin(), s.cell_start.end() - 1);
  for (Index p = 0; p < n; ++p)
    s.cell_members[s.cell_fill[s.cell_of[p]]++] = p;

  for (Index i = 0; i < n; ++i)
  {
    const Vec3 &x = particles.position[i];
    const long cx = coord(x, 0), cy = coord(x, 1), cz = coord(x, 2);
    for (long z = std::max(0L, cz - 1); z <= std::min(dims[2] - 1, cz + 1); ++z)
      for (long y = std::max(0L, cy - 1); y <= std::min(dims[1] - 1, cy + 1); ++y)
        for (long xx = std::max(0L, cx - 1); xx <= std::min(dims[0] - 1, cx + 1); ++xx)
        {
          const long c = cell_id(xx, y, z);
          for (Index k = s.cell_start[c]; k < s.cell_start[c + 1]; ++k)
          {
            const Index j = s.cell_members[k];
            if (j > i && !visit(i, j))
              return;
          }
        }
  }
}
} // namespace

void NeighborList::rebuild(const ParticleStore &particles)
{
  reference_ = particles.position;
  quarter_skin_sq_ = 0.25 * skin_ * skin_;
  pairs_.clear();
  ++rebuilds_;
  // Each ball's partners are gathered, then sorted, before the next ball's.
  std::vector<Index> &partners = partners_;
  partners.clear();
  Index current = 0;
  const auto flush = [&]()
  {
    std::sort(partners.begin(), partners.end());
    for (Index j : partners)
      pairs_.emplace_back(current, j);
    partners.clear();
  };
  visit_cell_neighbours(particles, skin_, {cell_start_, cell_members_, cell_of_, cell_fill_},
                        [&](Index i, Index j)
                        {
                          if (i != current)
                          {
                            flush();
                            current = i;
                          }
                          if (within(particles, i, j, skin_))
                            partners.push_back(j);
                          return true;
                        });
  flush();
}

std::optional<DeepOverlap> first_deep_overlap(const ParticleStore &particles, double fraction)
{
  std::vector<Index> cell_start, cell_members, cell_of, cell_fill;
  std::optional<DeepOverlap> found;
  visit_cell_neighbours(particles, 0.0, {cell_start, cell_members, cell_of, cell_fill},
                        [&](Index i, Index j)
                        {
                          const double overlap = particles.radius[i] + particles.radius[j] -
                                                 (particles.position[j] - particles.position[i]).norm();
                          if (overlap > fraction * std::min(particles.radius[i], particles.radius[j]))
                            found = DeepOverlap{Pair(i, j), overlap};
                          return !found;
                        });
  return found;
}

std::vector<Pair> brute_force_pairs(const ParticleStore &particles, double skin)
{
  std::vector<Pair> out;
  for (Index i = 0; i < particles.size(); ++i)
    for (Index j = i + 1; j < particles.size(); ++j)
      if (within(particles, i, j, skin))
        out.emplace_back(i, j);
  return out;
}
} // namespace dem
