// Neighbour search: linked cells plus a skin (Verlet list).
//
// A pair (i, j), i < j, is a candidate when its centre distance is below
// R_i + R_j + skin.  While no ball has moved more than skin/2 since the last
// build, no pair outside the list can touch, so the list is rebuilt only
// when some ball has; the cell build is O(N) for a bounded density.
// Candidates come sorted by (first, second): the contact table merges its
// history into a new list by a linear walk, with no hashing.
//
// The skin is the caller's to choose at each build (Simulation narrows it
// while balls move slowly: fewer candidates that do not touch); any skin
// gives the same contacts, so results never depend on it.
//
// brute_force_pairs() is the O(N^2) oracle the tests compare against.
#pragma once

#include "dem/particles.h"

#include <optional>
#include <utility>
#include <vector>

namespace dem
{
using Pair = std::pair<Index, Index>;

class NeighborList
{
public:
  explicit NeighborList(double skin = 0) : skin_(skin) {}

  double skin() const { return skin_; }
  void set_skin(double skin) { skin_ = skin; }

  /// Builds the candidate list for the current positions and radii.
  void rebuild(const ParticleStore &particles);

  /// True when ball p at x has moved more than skin/2 since the last build.
  bool moved_too_far(Index p, const Vec3 &x) const { return (x - reference_[p]).squaredNorm() > quarter_skin_sq_; }

  /// The farthest any ball has moved since the last build [m]; 0 when the
  /// list is stale.  Exact (a maximum), so the same on any thread count.
  double largest_displacement(const ParticleStore &particles) const;

  /// True when the list cannot be used at all (never built, or the particle
  /// count changed).  Whoever changes radii must ask for a rebuild
  /// (Simulation::invalidate_neighbors).
  bool stale(const ParticleStore &particles) const;

  const std::vector<Pair> &pairs() const { return pairs_; }
  /// The ball centres at the last build [m], from which moved_too_far()
  /// measures.
  const std::vector<Vec3> &reference() const { return reference_; }
  std::size_t rebuilds() const { return rebuilds_; }

  /// Frees the candidates and the cells once their user has taken the
  /// candidates (the next build makes them anew); the reference positions,
  /// which say when that is due, stay.
  void release_candidates();

private:
  double skin_;
  double quarter_skin_sq_ = 0;
  std::vector<Vec3> reference_;
  std::vector<Pair> pairs_;
  std::vector<Index> cell_start_, cell_members_, cell_of_, cell_fill_, partners_;
  std::size_t rebuilds_ = 0;
};

/// The first pair (i, j), i < j, whose overlap R_i + R_j - |x_i - x_j|
/// exceeds `fraction` of the smaller radius, with that overlap, or none.  It stops at the first
/// such pair, so balls piled on one point are found in the time of one cell
/// build (a full candidate list of N coincident balls has N^2/2 pairs).
struct DeepOverlap
{
  Pair pair;
  double overlap = 0; ///< m
};
std::optional<DeepOverlap> first_deep_overlap(const ParticleStore &particles, double fraction);

/// All pairs i < j with |x_i - x_j| < R_i + R_j + skin, sorted.  O(N^2).
std::vector<Pair> brute_force_pairs(const ParticleStore &particles, double skin);
} // namespace dem
