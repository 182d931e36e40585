// Run outputs: files that stay valid whatever happens to the run.
//
//  - write_atomically(): whole files (summary.json, deck.prm, ParaView
//    frames) are written to a temporary name and renamed, so a reader sees
//    the old file or the new one, never half of one.
//  - CsvSeries: time series (series.csv, particles.csv, ...) are appended one
//    complete row per write(2) call and flushed at once, so an interrupted
//    run leaves every row written so far, each row whole.
//  - Progress: a throttled one-line progress display on stderr, only when
//    stderr is a terminal.
#pragma once

#include <nlohmann/json.hpp>

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

namespace demvv
{
/// An output could not be written (a full disk, a quota, an I/O error): the
/// message names the file and the system's reason; demvv exits with code 4.
class OutputError : public std::runtime_error
{
public:
  using std::runtime_error::runtime_error;
};

/// Writes `content` to `path` via a temporary file and rename(2); on failure
/// the old file stays as it was and OutputError says why.  The temporary
/// file is created exclusively beside `path` (never through a link, never
/// over another file); a `path` that is a symbolic link or not a regular
/// file (a directory, a device, a pipe) is refused, never replaced.
void write_atomically(const std::string &path, const std::string &content);

/// An output file the user named (--out FILE): "-" is standard output; a
/// character device or a pipe (/dev/null, a FIFO) is written through, never
/// replaced; anything else as write_atomically().
void write_named_output(const std::string &path, const std::string &content);

/// Flushes a written file to the disk (fsync(2)); OutputError when the
/// system cannot, nothing when the file does not exist.
void sync_file(const std::string &path);

/// Removes `path` when it is a regular file (a link, a directory or a
/// device there is left alone); nothing when there is none.
void remove_regular_file(const std::string &path);

/// Creates a directory and its parents; throws DeckError-free std::runtime_error on failure.
void make_directories(const std::string &path);

class CsvSeries
{
public:
  /// Creates (truncates) the file and writes a comment line and the header.
  CsvSeries(const std::string &path, const std::string &comment, const std::vector<std::string> &columns);
  /// Continues a file written earlier: cuts it back to its first `keep`
  /// bytes (whole rows, as a checkpoint recorded them) and appends; a file
  /// shorter than `keep` (cut since) is refused, never padded.
  CsvSeries(const std::string &path, std::size_t columns, std::uintmax_t keep);
  ~CsvSeries();
  CsvSeries(const CsvSeries &) = delete;
  CsvSeries &operator=(const CsvSeries &) = delete;

  /// Appends one row (as many values as columns), flushed; a row the disk
  /// cannot take is cut off whole (the file ends at the previous row) and
  /// OutputError says why.
  void write(const std::vector<double> &row);
  std::size_t columns() const { return columns_; }

private:
  std::FILE *file_ = nullptr;
  std::size_t columns_;
  std::string path_;
  std::string buffer_;
};

/// The one-line progress display of a long run: percent done, a few words
/// of state, time left.  Shown only when standard output and standard error
/// are terminals (and the run wants it); redrawn at most four times a second.
class Progress
{
public:
  /// `done_at_start`: the fraction already done when this display starts
  /// (a resumed run), so that the time left is estimated from this leg.
  explicit Progress(std::string label, bool wanted = true, double done_at_start = 0);
  /// True when update() would redraw: callers compose the text only then.
  bool due() const;
  /// fraction in [0, 1]; the text follows the percentage.
  void update(double fraction, const std::string &text);
  /// Seconds since the display started.
  double elapsed() const;
  void finish();

private:
  std::string label_;
  bool enabled_;
  double done_at_start_;
  std::chrono::steady_clock::time_point start_, last_;
};

/// Provenance of a run: version, git SHA, the sources' hash, compiler, flags
/// and the instruction sets they resolved to, host and processor model,
/// threads, seed, input.
nlohmann::json provenance(int threads, long long seed, const std::string &deck_text);

/// What makes this build's results what they are: the hash of demvv's
/// sources, the compiler, the build type, the engine's flags and the
/// instruction sets they resolved to (keys as in provenance).  Part of a
/// cached sample's key, so that a sample prepared by another build (other
/// sources, other arithmetic) is never served, and of a checkpoint's.
nlohmann::json build_identity();
/// Whether `record` (a provenance, or a build_identity()) names this build.
bool made_by_this_build(const nlohmann::json &record);

/// FNV-1a 64-bit hash of a text (the standard offset basis and prime, so any
/// FNV-1a tool reproduces it), as 16 hex digits (identifies inputs; not cryptographic).
std::string fnv1a_hex(const std::string &text);

/// Reads a whole file; throws std::runtime_error if it cannot.
std::string read_file(const std::string &path);

/// JSON text of an output document (summary, sample, checkpoint).  Strings
/// that are not valid UTF-8 (a path or argument in another encoding; deck
/// text is refused at parse, app/decks/deck.h) are written with U+FFFD
/// in place of the bad bytes instead of aborting the write at the end of a
/// run.  indent < 0: one line.
std::string json_text(const nlohmann::json &doc, int indent = -1);
} // namespace demvv
