// The demvv sub-commands, callable from main() and from tests.
#pragma once

#include "app/run/run.h"

#include <functional>
#include <string>
#include <vector>

namespace demvv
{
/// demvv run: returns the exit code (0 ok, 3 numerical fault); throws DeckError on bad input.
int command_run(const std::string &deck_path, const std::vector<std::string> &overrides, const RunOptions &options);

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
} // namespace demvv
