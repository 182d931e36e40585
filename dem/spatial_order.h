// Spatial order: balls numbered along a space-filling (Morton, Z-order) curve.
//
// Every step reads, for each ball, the balls it touches, and hands each
// thread a contiguous range of ball indices.  When neighbours in space are
// neighbours in memory those reads stay in cache and each thread's range is
// a compact region of space; when they are not (a file in generation order,
// consecutive balls a box apart) every contact is a cache miss and the two
// threads write to the same cache lines.  On the same 6000-ball packing the
// second thread gained 1.0x in generation order and 1.9x on a Morton curve.
//
// The order is canonical: it depends on the balls' positions only, never on
// the order they were listed in.  Cells one largest diameter wide are
// visited along the Morton curve of their integer coordinates; balls of one
// cell follow by (z, y, x), then by radius (two balls at one point are
// refused by every loader, so ties end there).  The same balls listed in any
// order are numbered alike and give the same results to the last bit.
#pragma once

#include "dem/particles.h"

#include <vector>

namespace dem
{
/// The permutation that numbers the balls along the Morton curve:
/// order[k] is the index (in `p`) of the k-th ball of the new numbering.
std::vector<Index> morton_order(const ParticleStore &p);

/// The balls of `p` renumbered: ball k of the result is ball order[k] of p,
/// every per-ball array moved with it.  `order` must be a permutation.
ParticleStore renumbered(const ParticleStore &p, const std::vector<Index> &order);

/// The inverse permutation: inverse[order[k]] = k.
std::vector<Index> inverse_permutation(const std::vector<Index> &order);

/// Ball k's row in the file it was read from, given `rows` (rows[k], the
/// order a renumbering used); empty `rows`: never renumbered, k itself.
inline Index file_row(const std::vector<Index> &rows, Index k) { return rows.empty() ? k : rows[k]; }
} // namespace dem
