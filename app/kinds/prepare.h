// Prepare decks: numerical sample preparation (thesis ch. 5, dem/prep_packing.h).
//
// A prepare deck says how many balls (or which cell), their properties, the
// preparation targets and the bonds; running it writes the sample file
// (sample_file.h) with the preparation report, a ParaView view of the
// sample, summary.json and deck.prm.  Uniaxial decks load the sample file,
// or name the prepare deck itself: the sample is then prepared once and
// cached beside that deck, in samples/<deck>-<hash>/ (keyed by the resolved
// deck and the build: the sources' hash, compiler, flags and instruction
// sets, output.h's build_identity()), whatever the current folder; the
// environment variable DEMVV_CACHE, when set, names another folder for it.
// The cache keeps the samples of the few builds used most recently
// (prune_sample_cache), so that it does not grow with every rebuild.
#pragma once

#include "app/decks/deck.h"
#include "app/io/sample_file.h"
#include "app/run/run.h"
#include "dem/prep_packing.h"

#include <chrono>
#include <cstddef>
#include <string>
#include <vector>

namespace demvv
{
void declare_prepare(DeckSchema &s);

struct PrepareResult
{
  SampleFile sample;
  RunStatus status;
};

/// The preparation a deck describes, validated (an impossible packing is
/// refused here, before any file is written).
dem::PackingSettings parse_prepare(const Deck &deck);

/// A prepare deck parsed: the preparation and what the run directory keeps
/// of the deck.
struct PrepareSpec
{
  DeckRecord deck;
  dem::PackingSettings settings;
  std::string title;
  long long seed = 0;           ///< sample/seed
  double stress_target_pa = 0;  ///< preparation/stress target [Pa]
  bool paraview = false;        ///< output/paraview
  bool paraview_stages = false; ///< output/paraview stages
};

/// parse_prepare, kept with the deck's record.
PrepareSpec parse_prepare_spec(const Deck &deck);

/// Prepares the sample of a parsed prepare deck; with options.out_dir set,
/// writes the run directory (sample.json among it).
PrepareResult run_prepare(const PrepareSpec &spec, const RunOptions &options);
/// parse_prepare then run_prepare.
PrepareResult run_prepare(const Deck &deck, const RunOptions &options);

/// The folder where the samples of prepare decks are cached: $DEMVV_CACHE
/// when set and not empty, else samples/ beside the deck at `deck_path`.
std::string sample_cache_dir(const std::string &deck_path);

/// The cached sample file (sample.json) of the prepare deck at `path` with
/// `overrides` ("section/key=value", as --set), prepared on first use: a
/// sweep gives each seed its own sample this way.  A deck of another kind
/// is refused (DeckError), a preparation that stops on a fault is a
/// std::runtime_error.
std::string cached_sample_file(const std::string &path, const std::vector<std::string> &overrides, bool progress);

/// The 12 hex digits that end the name of the cache entry of a prepare
/// deck (its resolved text) made by a build (a build_identity()).
std::string sample_cache_hash(const std::string &resolved_deck, const nlohmann::json &build);

/// How many builds' samples the cache keeps, and how long any sample stays
/// after its last use whatever its build (a sweep of an older build may
/// still be reading it): cached_sample_file() prunes the rest after each
/// preparation.
constexpr std::size_t cached_builds = 3;
constexpr std::chrono::hours cache_grace{24 * 7};

/// Removes from the sample cache folder `dir` the entries made by builds
/// other than this one and the `keep` most recently used, and not used for
/// `grace`.  An entry's last use is the time of its sample.json, which
/// cached_sample_file() renews (of its summary.json if its preparation
/// failed); a build's is that of its most recently used entry.  Only
/// folders proved to be cache entries are touched: a finished prepare run
/// whose name ends in sample_cache_hash() of its deck.prm and its build.
/// Entries being prepared, entries of builds that named them otherwise,
/// and anything else are left alone.  `grace` is at most a few years (the
/// file clock's range).
void prune_sample_cache(const std::string &dir, std::size_t keep, std::chrono::hours grace);

/// Where cached_sample_file() keeps that sample, prepared or not.
std::string cached_sample_file_name(const std::string &path, const std::vector<std::string> &overrides);

/// Reads a sample: a .json sample file, or a prepare deck (.prm) whose
/// sample is prepared on first use and cached in sample_cache_dir(),
/// showing its progress when `progress`.
SampleFile load_or_prepare_sample(const std::string &path, bool progress);
} // namespace demvv
