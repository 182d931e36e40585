// The demvv sub-commands, callable from main() and from tests.
#pragma once

#include "verify/run/run.h"

#include <functional>
#include <string>
#include <vector>

namespace verify
{
/// demvv run: returns the exit code (0 ok, 3 numerical fault); throws DeckError on bad input.
int command_run(const std::string &deck_path, const std::vector<std::string> &overrides,
                const RunOptions &options);

/// Runs `claim` (which may throw a one-line error) on MPI rank 0 alone when
/// `every_rank`, and gives every rank its verdict: all go on, or all throw
/// the same error (DeckError, exit 2; OutputError, exit 4).  No rank goes
/// on before rank 0 is done, so none writes into a directory that rank 0 is
/// still emptying, and no rank waits for one that has quit.  Without
/// `every_rank`, runs `claim` here.
void on_rank_zero_for_all(bool every_rank, const std::function<void()> &claim);

/// demvv plot: (re)draws the figures of a run directory into RUN_DIR/plots;
/// returns 0 (figures gnuplot could not draw are listed, not fatal).
int command_plot(const std::string &run_dir);

/// demvv defaults: prints the documented deck of a kind.
int command_defaults(const std::string &kind);

/// demvv verify: runs the checks, writes report.md and report.json to
/// out_dir; returns 1 if any check fails.
int command_verify(bool full, const std::string &only, const std::string &out_dir, const std::string &cases_dir,
                   int threads);

/// demvv catalogue: writes the verification catalogue generated from the
/// check registry to out_file, or to standard output when it is empty.
int command_catalogue(const std::string &out_file);
} // namespace verify
