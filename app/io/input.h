// Input files: read whole, within limits, or refused with the one-line error.
//
// Every file demvv reads (decks, CSV tables, sample files, checkpoints)
// comes through read_input(), which refuses what is not a regular file
// (a directory, /dev/zero, a FIFO: read until memory runs out or forever)
// and files larger than the limit of their kind, before reading a byte.
// JSON inputs are parsed by parse_json_input(), which refuses nesting deeper
// than max_json_depth (a deck or sample file nests a few levels; thousands
// of levels would overflow the stack of every recursive walk over the tree)
// and turns every syntax error into the one-line error.
//
// The limits are far above any legitimate input and far below what would
// exhaust a workstation's memory while parsed (a JSON tree takes a few times
// its text):
//   decks              1 MiB   (a deck is a few hundred lines of text)
//   run summaries     64 MiB   (summary.json read back by demvv plot)
//   tables and samples 2 GiB   (a CSV of balls or a sample file; the thesis's
//                               largest sample of 12000 balls is about 20 MB)
// Runs whose estimated memory (dem::estimated_memory_bytes) exceeds what
// this machine has are refused by check_memory() before they allocate.
#pragma once

#include <nlohmann/json.hpp>

#include <cstdint>
#include <string>

namespace demvv
{
constexpr std::uintmax_t max_deck_bytes = std::uintmax_t{1} << 20;
constexpr std::uintmax_t max_table_bytes = std::uintmax_t{2} << 30;
/// A run's summary.json (a few kB; a study's with every level, a few hundred kB).
constexpr std::uintmax_t max_summary_bytes = std::uintmax_t{64} << 20;
constexpr int max_json_depth = 64;

/// The whole text of the regular file `path`; `what` names it in errors
/// ("deck file", "sample file", "CSV file").  DeckError if it does not exist,
/// cannot be read, is not a regular file or is larger than `max_bytes`.
std::string read_input(const std::string &path, const std::string &what, std::uintmax_t max_bytes);
/// The text of an input as demvv reads it: UTF-8 or ASCII with LF or CRLF
/// line ends.  A UTF-8 byte-order mark is dropped; UTF-16 or UTF-32 text
/// (by its byte-order mark, or NUL bytes between its first characters), and lines
/// ended by carriage returns alone, are DeckError naming the encoding
/// (read_input applies it to every file it reads).
std::string as_utf8_text(std::string text, const std::string &path, const std::string &what);

/// Parses JSON text read from `path`; DeckError naming the file on a syntax
/// error or nesting deeper than max_json_depth.
nlohmann::json parse_json_input(const std::string &text, const std::string &path, const std::string &what);

/// The number `key` of a JSON object, or NaN where it holds none (the key
/// absent, null or not a number; `j` not an object).
double json_number(const nlohmann::json &j, const char *key);

/// Memory this process may use [bytes]: the machine's physical memory, or
/// the cgroup's limit when one is set and lower.
double usable_memory_bytes();

/// Refuses with the one-line error (fail_key: `path`, `key`, `value`) a run
/// or input estimated to need `bytes` of memory when that exceeds
/// usable_memory_bytes(); `what` says what needs it ("2.7e13 balls") and
/// `expected` what would fit.
void check_memory(double bytes, const std::string &what, const std::string &path, const std::string &key,
                  const std::string &value, const std::string &expected);

/// True when `text` is valid UTF-8 (what JSON outputs can hold).
bool valid_utf8(const std::string &text);

/// The position of the first control character in `text`, npos when it has
/// none: C0 (below 0x20), DEL, and C1 (U+0080-U+009F, which a terminal
/// reads as escapes, e.g. U+009B as CSI).
std::size_t control_character(const std::string &text);

/// `text` with every byte that is not printable ASCII written as \xNN, for
/// error messages that quote input.
std::string escaped(const std::string &text);
} // namespace demvv
