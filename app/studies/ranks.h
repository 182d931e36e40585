// MPI ranks sharing one directory: rank 0 claims it, every rank takes its
// verdict (a run of a kind that runs on every rank, a sweep, a calibration).
//
// A study that runs alone (no mpirun) does not start MPI: it needs none,
// and Open MPI cannot start where demvv's own outputs would stop cleanly
// (a small file-size limit: exit 4 with one line, not an abort in MPI's
// start-up).  A continuum member still starts it, as `demvv run` does.
#pragma once

#include "continuum/cylinder.h"

#include <functional>

namespace demvv
{
/// This process's rank and the launch's count: MPI's under mpirun (its
/// environment says so; MPI started here if need be) or once MPI runs, else
/// rank 0 of 1 without starting MPI.
continuum::ParallelInfo study_ranks();

/// Every rank waits here for all the others (nothing to wait for without
/// MPI).
void wait_for_all_ranks();

/// The largest of every rank's `value` (its own without MPI).
int largest_over_ranks(int value);

/// Runs `claim` (which may throw a one-line error) on MPI rank 0 alone when
/// `every_rank`, and gives every rank its verdict: all go on, or all throw
/// the same error (DeckError, exit 2; OutputError, exit 4).  No rank goes
/// on before rank 0 is done, so none writes into a directory that rank 0 is
/// still emptying, and no rank waits for one that has quit.  Without
/// `every_rank`, runs `claim` here.
void on_rank_zero_for_all(bool every_rank, const std::function<void()> &claim);
} // namespace demvv
