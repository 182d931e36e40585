// Decks: input files that declare themselves (deal.II step-44 pattern).
//
// A deck is a deal.II ParameterHandler file (.prm) or the same tree in JSON.
// Its top-level entry `kind` selects a schema (deck_kinds.cpp); every entry
// of the schema is declared with a default, a pattern, a unit and a help
// string, so `demvv defaults KIND` prints a complete, documented deck and a
// run writes the resolved deck (every default filled in) to deck.prm.
//
// Errors are one line naming the file (and line), the key, the value and
// what was expected; the caller turns DeckError into exit code 2.  The
// parser is demvv's own (so that it can say all of that); deal.II stores
// and prints the values and its Patterns check them.
//
// This header does not include deal.II: only deck.cpp sees it.
#pragma once

#include "app/io/text.h"

#include <nlohmann/json_fwd.hpp>

#include <array>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace demvv
{
/// Which ends of a real entry's [min, max] are allowed.
enum class Interval
{
  closed,     ///< [min, max]
  open_below, ///< (min, max]
  open_above, ///< [min, max)
  open        ///< (min, max)
};

/// How a kind declares its entries (implemented over deal.II in deck.cpp).
class DeckSchema
{
public:
  virtual ~DeckSchema() = default;
  virtual void enter(const std::string &section) = 0;
  virtual void leave() = 0;
  /// A real number in [min, max], or with the ends the interval leaves out.
  virtual void real(const std::string &name, double value, double min, double max, const std::string &unit,
                    const std::string &help, Interval ends = Interval::closed) = 0;
  virtual void integer(const std::string &name, long value, long min, long max, const std::string &help) = 0;
  virtual void choice(const std::string &name, const std::string &value, const std::vector<std::string> &options,
                      const std::string &help) = 0;
  virtual void flag(const std::string &name, bool value, const std::string &help) = 0;
  /// Free text (titles, keywords).
  virtual void text(const std::string &name, const std::string &value, const std::string &help) = 0;
  /// A file name, relative to the deck's folder or absolute (read with
  /// Deck::file).  The resolved deck writes it absolute, so that a run
  /// directory's deck.prm runs again from any folder.
  virtual void file(const std::string &name, const std::string &value, const std::string &help) = 0;
  /// Three comma-separated reals.
  virtual void vector3(const std::string &name, const std::string &value, const std::string &unit,
                       const std::string &help) = 0;
  /// A comma-separated list of reals (possibly empty) of length in [min_len, max_len].
  virtual void real_list(const std::string &name, const std::string &value, unsigned min_len, unsigned max_len,
                         const std::string &unit, const std::string &help) = 0;
  /// A section that may appear any number of times, each instance named
  /// by the keyword and a label ('subsection plane top', 'subsection plane
  /// 2'; the bare keyword is an instance too).  `declare` declares the
  /// entries of one instance; instances exist only where a deck writes them.
  virtual void repeated(const std::string &keyword, void (*declare)(DeckSchema &), const std::string &help) = 0;
};

struct RunOptions;
struct RunStatus;
struct Figure;
class Deck;

/// A deck parsed into its kind's typed spec, ready to run: the spec lives in
/// the closure, so that a run parses its deck once (the parse that claims
/// the run directory is the one that runs).
using ParsedRun = std::function<RunStatus(const RunOptions &)>;

/// One deck kind, whole: its keyword, what it is for (one line), its
/// schema, the parse into its typed spec (throws DeckError, runs nothing)
/// that gives the run, and the figures `demvv run` and
/// `demvv plot` draw from its run directory.  `demvv run`, `demvv
/// defaults`, `demvv plot` and `--help` all read one table of these
/// (app/kinds/deck_kinds.cpp), handed to the deck reader.  A kind that runs
/// on every rank of an MPI job (`mpirun -np N demvv run`) says so: its run
/// directory is then claimed on rank 0 alone, and every rank takes rank
/// 0's verdict before any writes.
struct DeckKind
{
  std::string_view name;
  std::string_view summary;
  void (*declare)(DeckSchema &);
  ParsedRun (*parse)(const Deck &);
  /// Appends the figures of a run directory of this kind (its summary.json
  /// already read); nullptr for a kind without figures.
  void (*figures)(const std::string &run_dir, const nlohmann::json &summary, std::vector<Figure> &out) = nullptr;
  bool on_every_mpi_rank = false;
  bool pauses = false; ///< --pause-after and --resume work (a DEM time loop with checkpoints)
};

/// A table of deck kinds: the deck reader knows the kinds it is handed.
using DeckKinds = std::vector<DeckKind>;

/// The row of `kinds` named `name`, or nullptr.
const DeckKind *find_deck_kind(const DeckKinds &kinds, std::string_view name);

class Deck;

/// What a run keeps of its deck once the deck is parsed into a spec: where
/// it came from and its resolved text (deck.prm, provenance, resume), and a
/// way to name a key of it in a one-line error found later in the run.
struct DeckRecord
{
  std::string path;                   ///< "" for a defaults deck
  std::string name;                   ///< Deck::name()
  std::string resolved;               ///< Deck::resolved()
  std::vector<std::string> overrides; ///< Deck::overrides()
  std::vector<std::string> inputs;    ///< Deck::input_files()

  DeckRecord() = default;
  DeckRecord(const Deck &deck); // NOLINT: a deck is a record of itself
  [[noreturn]] void fail(const std::string &key, const std::string &value, const std::string &expected) const;
};

/// Throws a DeckError when two of a command line's overrides
/// ("section/key=value", as --set) name the same key: the last would win
/// unseen.  (Deck::from_file() applies a repeated key in order, as sweeps
/// use it; a user's command line may not.)
void refuse_repeated_overrides(const std::vector<std::string> &overrides);

class Deck
{
public:
  /// Reads a deck file of one of `kinds` and applies overrides of the form
  /// "section/key=value".  The deck keeps a reference to `kinds`.
  static Deck from_file(const DeckKinds &kinds, const std::string &path,
                        const std::vector<std::string> &overrides = {});
  /// A deck of the given kind with every default.
  static Deck defaults(const DeckKinds &kinds, const std::string &kind);

  Deck(Deck &&) noexcept;
  Deck &operator=(Deck &&) noexcept;
  ~Deck();

  const std::string &kind() const;
  /// The row of this deck's kind, and the table it was read with (a deck
  /// that names another deck reads it with the same table).
  const DeckKind &kind_row() const;
  const DeckKinds &kinds() const;
  /// The deck file ("" for a defaults deck).
  const std::string &path() const;
  /// The overrides ("section/key=value", as --set) from_file() applied, in
  /// order; set() adds none.
  const std::vector<std::string> &overrides() const;
  /// Directory relative file names in the deck are resolved against.
  std::string directory() const;
  /// A short name for run directories: the file stem, or the parent
  /// directory's name when the file is called case.prm.
  std::string name() const;

  /// Sets an entry as --set does ("section/key", value), with validation.
  void set(const std::string &key, const std::string &value);

  std::string text(const std::string &key) const;
  /// The unit a numeric entry is declared in ("m/s"; "-": dimensionless;
  /// "" for an entry that is not a number).
  std::string unit(const std::string &key) const;
  /// Whether the entry is a vector or list of numbers (comma-separated).
  bool holds_list(const std::string &key) const;
  double real(const std::string &key) const;
  long integer(const std::string &key) const;
  bool flag(const std::string &key) const;
  std::array<double, 3> vector3(const std::string &key) const;
  std::vector<double> real_list(const std::string &key) const;
  /// A relative file name from the deck resolved against directory().
  std::string file(const std::string &key) const;
  /// file(key), refused (fail) unless something exists at that name;
  /// the message says when the name is the key's default.
  std::string input_file(const std::string &key) const;
  /// Every file the deck's entries name (a sample, a particle CSV, ...),
  /// absolute (links and ".." resolved where the file exists).
  std::vector<std::string> input_files() const;
  /// The instances of a repeated section, e.g. instances("walls", "plane")
  /// gives {"plane 1", "plane top"}, in the order the deck first names them.
  std::vector<std::string> instances(const std::string &section, const std::string &keyword) const;

  /// Whether a typed accessor (text, real, file, ...) has asked for `key`:
  /// after the kind's parse, whether the run uses it.
  bool was_read(const std::string &key) const;

  /// Throws a DeckError naming this deck, the key and its value.
  [[noreturn]] void fail(const std::string &key, const std::string &expected) const;

  /// The resolved deck in .prm form (every entry, declaration order; file
  /// names absolute, so that it reads the same files from any folder).
  std::string resolved() const;
  /// The documented defaults in .prm form (help, unit, allowed values).
  std::string documented() const;

  struct Impl;

private:
  explicit Deck(std::unique_ptr<Impl> impl);
  /// A file name as written, resolved against directory().
  std::string beside_deck(const std::string &name) const;
  std::unique_ptr<Impl> impl_;
};

/// True when a deck of this kind declares `key`.
bool deck_declares(const Deck &deck, const std::string &key);
} // namespace demvv
