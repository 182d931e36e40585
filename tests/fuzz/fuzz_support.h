// What every fuzz target shares: a scratch folder of its own, inputs written
// to files there (the loaders read files, through read_input's limits, as
// demvv does), and the rule that decides a finding.
//
// A finding is what `demvv` itself would not survive: a sanitizer report
// (ASan, UBSan, float-cast-overflow), a crash, a hang (libFuzzer's
// -timeout), or an exception that main() does not turn into its one-line
// error and exit code.  Every exception main() maps (DeckError, OutputError
// and other std::runtime_error: exit 2 or 4; std::bad_alloc and
// std::length_error: exit 2) is a refusal, the expected answer to most
// inputs; anything else (std::logic_error, std::out_of_range, ...) escapes
// the target, and libFuzzer reports it as a crash.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace fuzz
{
/// The scratch folder of this process (created on first use, removed at exit).
std::string scratch();

/// Writes `size` bytes to scratch()/name and returns the file's path.
std::string write_input(const std::string &name, const std::uint8_t *data, std::size_t size);
std::string write_input(const std::string &name, const std::string &text);

/// Runs `load` as `demvv run` would: the exceptions main() maps to an exit
/// code are refusals (true); everything else escapes.
bool refused(const std::function<void()> &load);

/// The `--set` checks and kind parse `demvv run` does before a run: the deck
/// at `path` read with `overrides`, then its kind's parse.
void read_and_parse(const std::string &path, const std::vector<std::string> &overrides = {});
} // namespace fuzz
