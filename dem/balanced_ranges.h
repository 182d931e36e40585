// BalancedRanges: a loop's items cut into one contiguous range per thread,
// the cuts moved after each pass so that the ranges take equal times.
//
// A static schedule gives each thread the same count of items and keeps
// them on the same core from step to step (its caches hold them); but the
// items do not cost the same (a contact that touches against one that
// does not, a ball against a wall), so on the identical-work scene each
// thread waited at one of the force pass's two barriers for about a tenth
// of the step (BENCHMARKS.md, "LIGGGHTS at its best, and balanced
// ranges").  A dynamic schedule removed the waits and made each loop half
// again slower: the items moved between cores.  These ranges stay
// contiguous and stay with their thread, and each pass measures its
// ranges' times: the cost density of each range (its time over its items)
// gives a piecewise-constant cost of the whole loop, and each cut moves
// half way to where that cost splits equally.
// On a machine where one core is also busy, its thread's range shrinks.
//
// Which thread runs which item changes no result in the passes that use
// these ranges (each item writes only its own entries); what a pass
// collects per range (breaks, energies to retire) is kept per range, so
// taking the ranges in order is taking the items in order.
#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

namespace dem
{
class BalancedRanges
{
public:
  /// Sets the ranges for `items` items and `ranges` ranges: kept from the
  /// last pass when both are unchanged, equal shares otherwise (with a new
  /// item count, e.g. after a neighbour rebuild, the cuts keep their
  /// fractions).
  void prepare(std::size_t items, int ranges)
  {
    const auto count = static_cast<std::size_t>(std::max(ranges, 1));
    const bool fresh = cuts_.size() != count + 1 || items_ == 0;
    cuts_.resize(count + 1);
    if (fresh || items != items_)
      for (std::size_t r = 0; r <= count; ++r)
        cuts_[r] = fresh ? items * r / count : cuts_[r] * items / items_;
    items_ = items;
    seconds_.assign(count, 0.0);
  }

  int ranges() const { return static_cast<int>(seconds_.size()); }
  /// The item count the ranges cut (that of the last prepare).
  std::size_t items() const { return items_; }
  std::size_t begin(int r) const { return cuts_[static_cast<std::size_t>(r)]; }
  std::size_t end(int r) const { return cuts_[static_cast<std::size_t>(r) + 1]; }

  /// The time range r took in this pass [s] (each range's own slot: threads
  /// may record at once).
  void record(int r, double seconds) { seconds_[static_cast<std::size_t>(r)] = seconds; }

  /// Moves each cut half way to where the measured costs split the loop in
  /// equal times.  Called once after the pass, by one thread.
  void rebalance()
  {
    const std::size_t count = seconds_.size();
    double total = 0;
    for (double s : seconds_)
      total += s;
    if (count < 2 || !(total > 0) || items_ == 0)
      return;
    std::vector<std::size_t> target(cuts_);
    std::size_t r = 0;
    double before = 0; // time of the ranges before r
    for (std::size_t k = 1; k < count; ++k)
    {
      const double wanted = total * double(k) / double(count);
      while (r + 1 < count && before + seconds_[r] < wanted)
        before += seconds_[r++];
      const std::size_t width = cuts_[r + 1] - cuts_[r];
      const double within = seconds_[r] > 0 ? std::clamp((wanted - before) / seconds_[r], 0.0, 1.0) : 0.5;
      target[k] = cuts_[r] + static_cast<std::size_t>(within * double(width) + 0.5);
    }
    // Half way, rounded towards the target, so that a cut reaches it.
    for (std::size_t k = 1; k < count; ++k)
    {
      const std::size_t to = target[k], at = cuts_[k];
      const std::size_t moved = to >= at ? at + (to - at + 1) / 2 : at - (at - to + 1) / 2;
      cuts_[k] = std::clamp(moved, cuts_[k - 1], items_);
    }
  }

private:
  std::vector<std::size_t> cuts_; ///< ranges()+1 cuts, ascending, from 0 to items
  std::vector<double> seconds_;   ///< s, per range, of the last pass
  std::size_t items_ = 0;
};
} // namespace dem
