// MPI ranks sharing one directory: rank 0 claims it, every rank takes its
// verdict (a run of a kind that runs on every rank, a sweep, a calibration).
#pragma once

#include <functional>

namespace demvv
{
/// Runs `claim` (which may throw a one-line error) on MPI rank 0 alone when
/// `every_rank`, and gives every rank its verdict: all go on, or all throw
/// the same error (DeckError, exit 2; OutputError, exit 4).  No rank goes
/// on before rank 0 is done, so none writes into a directory that rank 0 is
/// still emptying, and no rank waits for one that has quit.  Without
/// `every_rank`, runs `claim` here.
void on_rank_zero_for_all(bool every_rank, const std::function<void()> &claim);
} // namespace demvv
