#include "app/decks/deck.h"

#include "app/io/input.h"

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/patterns.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <map>
#include <set>
#include <sstream>

namespace demvv
{
namespace Patterns = dealii::Patterns;

namespace
{
std::vector<std::string> split(const std::string &s, char sep)
{
  std::vector<std::string> out;
  std::string item;
  std::istringstream in(s);
  while (std::getline(in, item, sep))
    out.push_back(trimmed(item));
  if (!s.empty() && s.back() == sep)
    out.emplace_back();
  return out;
}

/// Levenshtein distance, for "did you mean" hints.
std::size_t edit_distance(const std::string &a, const std::string &b)
{
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j)
    row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i)
  {
    std::size_t diag = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j)
    {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diag = up;
    }
  }
  return row[b.size()];
}

/// True unless the text is a number a double cannot hold as a normal value
/// (1e-400, the subnormal 1e-310, 1e400): such numbers would be silently
/// rounded, or abort std::stod later.  Text that is no number at all is left
/// to the pattern, which names what was expected.
bool normal_double(const std::string &text)
{
  char *end = nullptr;
  errno = 0;
  const double v = std::strtod(text.c_str(), &end);
  if (end == text.c_str())
    return true;
  if (errno == ERANGE)
    return false;
  return v == 0 || !std::isfinite(v) || std::abs(v) >= std::numeric_limits<double>::min();
}

/// Where a value came from, for error messages: "deck.prm:12" or "--set".
struct Origin
{
  std::string where;
};
} // namespace

struct Deck::Impl final : DeckSchema
{
  struct Entry
  {
    std::unique_ptr<Patterns::PatternBase> pattern;
    std::string expected; // human description of the allowed values
    std::string value;
    bool open_min = false; // a real whose interval leaves out its lower end
    bool open_max = false; // ... its upper end
    double min = 0;
    double max = 0;
    bool assigned = false;     // set by the deck or an override (not the default)
    mutable bool read = false; // asked for by a typed accessor (the kind's parse uses it)
    bool list = false;         // a vector or list of numbers (comma-separated)
    bool numeric = false;      // real, vector or list of reals: every item must be a normal double
    bool file = false;         // a file name, relative to the deck's folder unless absolute
    std::string unit;          // of a number, vector or list ("-": dimensionless; "": not a number)
  };

  /// A repeated section: where it may appear and how an instance is declared.
  struct Repeated
  {
    std::string parent; ///< "walls" (sections joined by '/'; "" at the top)
    std::string keyword;
    void (*declare)(DeckSchema &);
    std::string help;
    std::vector<std::string> instances; ///< section names, in order of appearance
  };

  dealii::ParameterHandler prm;
  std::map<std::string, Entry> entries;
  std::vector<Repeated> repeats;
  std::vector<std::string> stack;
  std::string kind;
  const DeckKinds *kinds = nullptr; ///< the table the deck was read with
  const DeckKind *row = nullptr;    ///< its kind's row in it
  std::string path;
  std::vector<std::string> overrides; // the --set values it was read with, in order

  std::string full(const std::string &name) const
  {
    std::string key;
    for (const auto &s : stack)
      key += s + "/";
    return key + name;
  }

  void add(const std::string &name, const std::string &value, std::unique_ptr<Patterns::PatternBase> pattern,
           std::string expected, const std::string &help)
  {
    prm.declare_entry(name, value, *pattern, help);
    Entry e;
    e.pattern = std::move(pattern);
    e.expected = std::move(expected);
    e.value = value;
    entries[full(name)] = std::move(e);
  }

  // --- DeckSchema -------------------------------------------------------
  void enter(const std::string &section) override
  {
    prm.enter_subsection(section);
    stack.push_back(section);
  }
  void leave() override
  {
    prm.leave_subsection();
    stack.pop_back();
  }
  void real(const std::string &name, double value, double min, double max, const std::string &unit,
            const std::string &help, Interval ends) override
  {
    const bool open_min = ends == Interval::open_below || ends == Interval::open;
    const bool open_max = ends == Interval::open_above || ends == Interval::open;
    const double lo = std::isinf(min) ? -std::numeric_limits<double>::max() : min;
    const double hi = std::isinf(max) ? std::numeric_limits<double>::max() : max;
    std::string expected = "a number " + std::string(open_min ? "> " : ">= ") + format_number(min);
    if (!std::isinf(max))
      expected += std::string(open_max ? " and < " : " and <= ") + format_number(max);
    if (!unit.empty() && unit != "-")
      expected += " (" + unit + ")";
    add(name, format_number(value), std::make_unique<Patterns::Double>(lo, hi), expected, help + " [" + unit + "]");
    Entry &e = entries[full(name)];
    e.open_min = open_min;
    e.open_max = open_max;
    e.min = min;
    e.max = max;
    e.numeric = true;
    e.unit = unit;
  }
  void integer(const std::string &name, long value, long min, long max, const std::string &help) override
  {
    add(name, std::to_string(value), std::make_unique<Patterns::Integer>(static_cast<int>(min), static_cast<int>(max)),
        "an integer in [" + std::to_string(min) + ", " + std::to_string(max) + "]", help + " [-]");
    entries[full(name)].unit = "-";
  }
  void choice(const std::string &name, const std::string &value, const std::vector<std::string> &options,
              const std::string &help) override
  {
    std::string joined;
    for (const auto &o : options)
      joined += (joined.empty() ? "" : "|") + o;
    add(name, value, std::make_unique<Patterns::Selection>(joined), "one of " + joined,
        help + " Allowed: " + joined + ".");
  }
  void flag(const std::string &name, bool value, const std::string &help) override
  {
    add(name, value ? "true" : "false", std::make_unique<Patterns::Bool>(), "true or false", help);
  }
  void text(const std::string &name, const std::string &value, const std::string &help) override
  {
    add(name, value, std::make_unique<Patterns::Anything>(), "any text", help);
  }
  void file(const std::string &name, const std::string &value, const std::string &help) override
  {
    add(name, value, std::make_unique<Patterns::Anything>(), "a file name (relative to the deck's folder)",
        help + " [file, relative to the deck's folder unless absolute]");
    entries[full(name)].file = true;
  }
  void vector3(const std::string &name, const std::string &value, const std::string &unit,
               const std::string &help) override
  {
    add(name, value, std::make_unique<Patterns::List>(Patterns::Double(), 3, 3, ","),
        "three comma-separated numbers (" + unit + ")", help + " [" + unit + "]");
    entries[full(name)].list = true;
    entries[full(name)].numeric = true;
    entries[full(name)].unit = unit;
  }
  void real_list(const std::string &name, const std::string &value, unsigned min_len, unsigned max_len,
                 const std::string &unit, const std::string &help) override
  {
    add(name, value, std::make_unique<Patterns::List>(Patterns::Double(), min_len, max_len, ","),
        "a comma-separated list of " + std::to_string(min_len) + " to " + std::to_string(max_len) + " numbers (" +
          unit + ")",
        help + " [" + unit + "]");
    entries[full(name)].list = true;
    entries[full(name)].numeric = true;
    entries[full(name)].unit = unit;
  }

  void repeated(const std::string &keyword, void (*declare)(DeckSchema &), const std::string &help) override
  {
    std::string parent;
    for (const auto &s : stack)
      parent += (parent.empty() ? "" : "/") + s;
    repeats.push_back({parent, keyword, declare, help, {}});
  }

  /// Declares the instance of a repeated section that `key` lies in, if
  /// any and not yet declared; true if it did.
  bool declare_instance(const std::string &key)
  {
    const auto parts = split(key, '/');
    std::string parent;
    for (std::size_t k = 0; k + 1 < parts.size(); ++k)
    {
      const std::string &section = parts[k];
      for (Repeated &r : repeats)
      {
        const bool named = section == r.keyword || section.rfind(r.keyword + " ", 0) == 0;
        if (r.parent != parent || !named ||
            std::find(r.instances.begin(), r.instances.end(), section) != r.instances.end())
          continue;
        const std::vector<std::string> saved = stack;
        stack.clear();
        for (std::size_t j = 0; j < k; ++j)
          enter(parts[j]);
        enter(section);
        r.declare(*this);
        leave();
        for (std::size_t j = 0; j < k; ++j)
          leave();
        stack = saved;
        r.instances.push_back(section);
        return true;
      }
      parent += (parent.empty() ? "" : "/") + section;
    }
    return false;
  }

  /// The name of a repeated section ("plane NAME") becomes a column name
  /// of series.csv and a word of figure titles: letters, digits, '_', '-'
  /// and '.' only.
  void check_instance_names(const std::string &key, const Origin &o) const
  {
    static const std::string allowed = "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-.";
    for (const std::string &section : split(key, '/'))
      for (const Repeated &r : repeats)
        if (section.size() > r.keyword.size() + 1 && section.rfind(r.keyword + " ", 0) == 0)
        {
          const std::string name = section.substr(r.keyword.size() + 1);
          if (name.find_first_not_of(allowed) != std::string::npos)
            reject(o, "section '" + escaped(section) + "': the name '" + escaped(name) +
                        "' becomes a column of series.csv: expected letters, digits, '_', '-' or '.'");
        }
  }

  /// A section the deck opens must be one of the kind's (or an instance of
  /// a repeated one, declared here with its defaults if nothing in it was
  /// set): an empty section of another name would be dropped unseen.
  void open_section(const std::string &section, const Origin &o)
  {
    check_instance_names(section, o);
    const std::string prefix = section + "/";
    const auto known = [&]
    {
      const auto it = entries.lower_bound(prefix);
      return it != entries.end() && it->first.compare(0, prefix.size(), prefix) == 0;
    };
    if (!known())
      declare_instance(prefix + "entry");
    if (!known())
      reject(o, "unknown section '" + escaped(section) + "'; `demvv defaults " + kind + "` lists the sections of a " +
                  kind + " deck");
  }

  // --- assignment --------------------------------------------------------
  [[noreturn]] void reject(const Origin &o, const std::string &message) const
  {
    throw DeckError(o.where + ": " + message);
  }

  std::string suggestion(const std::string &key) const
  {
    std::string best;
    std::size_t best_d = 4;
    for (const auto &[k, e] : entries)
    {
      const std::size_t d = edit_distance(k, key);
      if (d < best_d)
      {
        best_d = d;
        best = k;
      }
    }
    return best.empty() ? "" : " (did you mean '" + best + "'?)";
  }

  void assign(const std::string &key, const std::string &raw, const Origin &o)
  {
    for (const std::string &part : split(key, '/'))
      if (const std::size_t bad = control_character(part); bad != std::string::npos)
        reject(o, "key or section '" + escaped(key) + "' holds a control character (" +
                    escaped(part.substr(bad, static_cast<unsigned char>(part[bad]) == 0xC2 ? 2 : 1)) +
                    "): expected printable text (control characters would rewrite the run's own records)");
    check_instance_names(key, o);
    if (entries.find(key) == entries.end())
      declare_instance(key);
    const auto it = entries.find(key);
    if (it == entries.end())
      reject(o, "unknown key '" + key + "'" + suggestion(key) + "; `demvv defaults " + kind + "` lists the keys of a " +
                  kind + " deck");
    Entry &e = it->second;
    const std::string value = trimmed(raw);
    if (!valid_utf8(value))
      reject(o, "key '" + key + "' has value '" + escaped(value) +
                  "': not UTF-8 text: expected UTF-8 (save the deck as UTF-8; summaries and sample files are JSON, "
                  "which holds only UTF-8)");
    if (const std::size_t bad = control_character(value); bad != std::string::npos)
      reject(o, "key '" + key + "' has value '" + escaped(value) + "' with a control character (" +
                  escaped(value.substr(bad, static_cast<unsigned char>(value[bad]) == 0xC2 ? 2 : 1)) +
                  "): expected one line of printable text (a newline or escape would be written into deck.prm, "
                  "CSV headers and scripts)");
    if (value.find('#') != std::string::npos)
      reject(o, "key '" + key + "' has value '" + escaped(value) +
                  "' with '#': expected text without '#' (it starts a comment in a .prm deck, so deck.prm would "
                  "read back another value)");
    if (e.numeric)
      for (const std::string &item : split(value, ','))
        if (!item.empty() && !normal_double(item))
          reject(o, "key '" + key + "' has value '" + value + "': '" + item +
                      "' is not a normal double (0, or a magnitude between 2.2e-308 and 1.8e308): expected " +
                      e.expected);
    bool ok = e.pattern->match(value);
    if (ok && e.open_min)
      ok = std::stod(value) > e.min;
    if (ok && e.open_max)
      ok = std::stod(value) < e.max;
    if (!ok)
      reject(o, "key '" + key + "' has value '" + value + "': expected " + e.expected);
    e.value = value;
    e.assigned = true;
    store(key, value);
  }

  /// Gives deal.II's copy of the entry `key` ("section/key") its value.
  void store(const std::string &key, const std::string &value)
  {
    const auto parts = split(key, '/');
    for (std::size_t k = 0; k + 1 < parts.size(); ++k)
      prm.enter_subsection(parts[k]);
    prm.set(parts.back(), value);
    for (std::size_t k = 0; k + 1 < parts.size(); ++k)
      prm.leave_subsection();
  }

  /// The value of `key`, marked as read.
  const std::string &value_of(const std::string &key) const
  {
    const Entry &e = at(key);
    e.read = true;
    return e.value;
  }

  const Entry &at(const std::string &key) const
  {
    const auto it = entries.find(key);
    if (it == entries.end())
      throw std::logic_error("demvv bug: deck key '" + key + "' is not declared for kind " + kind);
    return it->second;
  }
};

const DeckKind *find_deck_kind(const DeckKinds &kinds, std::string_view name)
{
  for (const DeckKind &k : kinds)
    if (k.name == name)
      return &k;
  return nullptr;
}

namespace
{
std::string kind_names(const DeckKinds &kinds)
{
  std::string names;
  for (const DeckKind &k : kinds)
    names += (names.empty() ? "" : "|") + std::string(k.name);
  return names;
}

const DeckKind &find_kind(const DeckKinds &kinds, const std::string &name, const std::string &where)
{
  if (const DeckKind *k = find_deck_kind(kinds, name))
    return *k;
  throw DeckError(where + ": key 'kind' has value '" + escaped(name) + "': expected one of " + kind_names(kinds));
}

std::unique_ptr<Deck::Impl> make_impl(const DeckKinds &kinds, const std::string &kind, const std::string &where)
{
  const DeckKind &k = find_kind(kinds, kind, where);
  auto impl = std::make_unique<Deck::Impl>();
  impl->kind = kind;
  impl->kinds = &kinds;
  impl->row = &k;
  std::vector<std::string> names;
  for (const DeckKind &d : kinds)
    names.emplace_back(d.name);
  impl->choice("kind", kind, names, "What this deck describes (fixed once the deck is read).");
  k.declare(*impl);
  return impl;
}

/// A parsed line of a .prm file.
struct PrmAssignment
{
  std::string key;
  std::string value;
  int line;
};

/// A deck's assignments and the sections it opens (path, line; 0 in JSON).
struct DeckText
{
  std::vector<PrmAssignment> assignments;
  std::vector<std::pair<std::string, int>> sections;
  std::set<std::string> named; ///< every key and section path so far (JSON: one may come twice)
};

DeckText read_prm(const std::string &path, std::istream &in)
{
  DeckText out;
  std::vector<std::string> stack;
  // Where each section and key was first written: a second one would merge
  // into the first (two 'subsection plane a') or silently win over it.
  std::map<std::string, int> opened, written;
  const auto path_of = [&stack]()
  {
    std::string p;
    for (const auto &sec : stack)
      p += (p.empty() ? "" : "/") + sec;
    return p;
  };
  std::string raw;
  int line = 0;
  while (std::getline(in, raw))
  {
    ++line;
    const auto hash = raw.find('#');
    // A tab separates words as a space does (editors insert either).
    std::string s = trimmed(hash == std::string::npos ? raw : raw.substr(0, hash));
    for (const std::string_view word : {"set", "subsection"})
      if (s.size() > word.size() && s.compare(0, word.size(), word) == 0 && s[word.size()] == '\t')
        s[word.size()] = ' ';
    if (s.empty())
      continue;
    const std::string where = path + ":" + std::to_string(line);
    if (s.rfind("subsection ", 0) == 0)
    {
      stack.push_back(trimmed(s.substr(11)));
      if (const auto [first, fresh] = opened.emplace(path_of(), line); !fresh)
        throw DeckError(where + ": subsection '" + escaped(first->first) + "' is opened again (first at line " +
                        std::to_string(first->second) +
                        "): expected each section once (its entries would merge into the first one's)");
      out.sections.emplace_back(path_of(), line);
    }
    else if (s == "end")
    {
      if (stack.empty())
        throw DeckError(where + ": 'end' without a matching 'subsection'");
      stack.pop_back();
    }
    else if (s.rfind("set ", 0) == 0)
    {
      const auto eq = s.find('=');
      if (eq == std::string::npos)
        throw DeckError(where + ": cannot read '" + escaped(s) + "': expected 'set KEY = VALUE'");
      std::string key;
      for (const auto &sec : stack)
        key += sec + "/";
      key += trimmed(s.substr(4, eq - 4));
      // A second 'set kind' has its own message (from_file).
      if (const auto [first, fresh] = written.emplace(key, line); !fresh && key != "kind")
        throw DeckError(where + ": key '" + escaped(key) + "' is set again (first at line " +
                        std::to_string(first->second) + "): expected each key once (the last would win silently)");
      out.assignments.push_back({key, trimmed(s.substr(eq + 1)), line});
    }
    else
      throw DeckError(where + ": cannot read '" + escaped(s) +
                      "': expected 'set KEY = VALUE', 'subsection NAME' or 'end'");
  }
  if (!stack.empty())
    throw DeckError(path + ": subsection '" + stack.back() + "' is never closed with 'end'");
  return out;
}

void flatten_json(const nlohmann::json &j, const std::string &prefix, DeckText &out, const std::string &path)
{
  for (const auto &[k, v] : j.items())
  {
    const std::string key = prefix.empty() ? k : prefix + "/" + k;
    // {"a": {"b": 1}} and {"a/b": 2} name one key: the last would win.
    if (!out.named.insert(key).second)
      throw DeckError(path + ": key '" + escaped(key) +
                      "' is given twice (as a nested object and as a path with '/'): expected each key once");
    if (v.is_object())
    {
      out.sections.emplace_back(key, 0);
      flatten_json(v, key, out, path);
    }
    else if (v.is_string())
      out.assignments.push_back({key, v.get<std::string>(), 0});
    else if (v.is_boolean())
      out.assignments.push_back({key, v.get<bool>() ? "true" : "false", 0});
    else if (v.is_number())
      out.assignments.push_back({key, v.dump(), 0}); // shortest text that reads back to the same number
    else
      throw DeckError(path + ": key '" + key + "' has a JSON " + std::string(v.type_name()) +
                      ": expected a string, number or boolean");
  }
}
} // namespace

Deck::Deck(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Deck::Deck(Deck &&) noexcept = default;
Deck &Deck::operator=(Deck &&) noexcept = default;
Deck::~Deck() = default;

Deck Deck::defaults(const DeckKinds &kinds, const std::string &kind)
{
  return Deck(make_impl(kinds, kind, "demvv defaults"));
}

void refuse_repeated_overrides(const std::vector<std::string> &overrides)
{
  std::map<std::string, std::string> set_by;
  for (const std::string &o : overrides)
  {
    const std::string key = o.substr(0, o.find('='));
    const auto first = key.find_first_not_of(" \t");
    const std::string name =
      first == std::string::npos ? key : key.substr(first, key.find_last_not_of(" \t") + 1 - first);
    if (const auto [at, added] = set_by.emplace(name, o); !added)
      throw DeckError("--set '" + o + "': the key is set again (first by --set '" + at->second +
                      "'): expected each key once");
  }
}

Deck Deck::from_file(const DeckKinds &kinds, const std::string &path, const std::vector<std::string> &overrides)
{
  const std::string text = read_input(path, "deck file", max_deck_bytes);
  DeckText parsed;
  const bool json = path.size() > 5 && path.compare(path.size() - 5, 5, ".json") == 0;
  if (json)
  {
    const nlohmann::json j = parse_json_input(text, path, "deck");
    if (!j.is_object())
      throw DeckError(path + ": expected a JSON object at the top level");
    flatten_json(j, "", parsed, path);
  }
  else
  {
    std::istringstream in(text);
    parsed = read_prm(path, in);
  }
  const std::vector<PrmAssignment> &lines = parsed.assignments;

  const auto kind_line = std::find_if(lines.begin(), lines.end(), [](const auto &a) { return a.key == "kind"; });
  if (kind_line == lines.end())
    throw DeckError(path + ": key 'kind' is missing: expected 'set kind = " + kind_names(kinds) + "' at the top level");
  const std::string where = kind_line->line > 0 ? path + ":" + std::to_string(kind_line->line) : path;
  // The kind selects the schema: a second 'set kind' would be recorded in
  // deck.prm while the first one runs.
  const auto second_kind = std::find_if(kind_line + 1, lines.end(), [](const auto &a) { return a.key == "kind"; });
  if (second_kind != lines.end())
    throw DeckError(path + ":" + std::to_string(second_kind->line) + ": key 'kind' has value '" + second_kind->value +
                    "': the kind is already set to '" + kind_line->value + "' at " + where +
                    ": expected one 'set kind' per deck");
  auto impl = make_impl(kinds, kind_line->value, where);
  impl->path = path;
  for (const auto &a : lines)
    impl->assign(a.key, a.value, {a.line > 0 ? path + ":" + std::to_string(a.line) : path});
  for (const auto &[section, line] : parsed.sections)
    impl->open_section(section, {line > 0 ? path + ":" + std::to_string(line) : path});
  Deck deck(std::move(impl));
  for (const auto &o : overrides)
  {
    const auto eq = o.find('=');
    if (eq == std::string::npos)
      throw DeckError("--set '" + o + "': expected SECTION/KEY=VALUE");
    const std::string key = trimmed(o.substr(0, eq));
    if (key == "kind")
      throw DeckError("--set '" + o + "': the kind of a deck cannot be overridden");
    deck.impl_->assign(key, o.substr(eq + 1), {"--set " + key});
  }
  deck.impl_->overrides = overrides;
  return deck;
}

const std::string &Deck::kind() const { return impl_->kind; }
const DeckKind &Deck::kind_row() const { return *impl_->row; }
const DeckKinds &Deck::kinds() const { return *impl_->kinds; }
const std::string &Deck::path() const { return impl_->path; }
const std::vector<std::string> &Deck::overrides() const { return impl_->overrides; }

std::string Deck::directory() const
{
  const auto slash = impl_->path.find_last_of('/');
  return slash == std::string::npos ? "." : impl_->path.substr(0, slash);
}

std::string Deck::name() const
{
  if (impl_->path.empty())
    return impl_->kind;
  const auto slash = impl_->path.find_last_of('/');
  std::string file = slash == std::string::npos ? impl_->path : impl_->path.substr(slash + 1);
  const auto dot = file.find_last_of('.');
  std::string stem = dot == std::string::npos ? file : file.substr(0, dot);
  if (stem == "case" || stem == "deck")
  {
    const std::string dir = directory();
    const auto s2 = dir.find_last_of('/');
    const std::string parent = s2 == std::string::npos ? dir : dir.substr(s2 + 1);
    if (!parent.empty() && parent != ".")
      return parent;
  }
  return stem;
}

void Deck::set(const std::string &key, const std::string &value) { impl_->assign(key, value, {"override " + key}); }

std::string Deck::text(const std::string &key) const { return impl_->value_of(key); }
std::string Deck::unit(const std::string &key) const { return impl_->at(key).unit; }
double Deck::real(const std::string &key) const { return std::stod(impl_->value_of(key)); }
long Deck::integer(const std::string &key) const { return std::stol(impl_->value_of(key)); }
bool Deck::was_read(const std::string &key) const { return impl_->at(key).read; }
bool Deck::holds_list(const std::string &key) const { return impl_->at(key).list; }
bool Deck::flag(const std::string &key) const
{
  const std::string &v = impl_->value_of(key);
  return v == "true" || v == "yes";
}

std::vector<double> Deck::real_list(const std::string &key) const
{
  std::vector<double> out;
  const std::string &v = impl_->value_of(key);
  if (trimmed(v).empty())
    return out;
  for (const auto &item : split(v, ','))
    out.push_back(std::stod(item));
  return out;
}

std::array<double, 3> Deck::vector3(const std::string &key) const
{
  const auto v = real_list(key);
  return {{v.at(0), v.at(1), v.at(2)}};
}

DeckRecord::DeckRecord(const Deck &deck)
  : path(deck.path()), name(deck.name()), resolved(deck.resolved()), overrides(deck.overrides()),
    inputs(deck.input_files())
{
}

void DeckRecord::fail(const std::string &key, const std::string &value, const std::string &expected) const
{
  fail_key(path, key, value, expected);
}

std::vector<std::string> Deck::instances(const std::string &section, const std::string &keyword) const
{
  for (const Impl::Repeated &r : impl_->repeats)
    if (r.parent == section && r.keyword == keyword)
      return r.instances;
  throw std::logic_error("demvv bug: no repeated section '" + keyword + "' in '" + section + "'");
}

std::string Deck::file(const std::string &key) const { return beside_deck(text(key)); }

std::string Deck::beside_deck(const std::string &f) const
{
  if (f.empty() || f.front() == '/')
    return f;
  return directory() + "/" + f;
}

namespace
{
/// The absolute form of a file name read by Deck::file (symbolic links and
/// ".." resolved as the system would, where the path exists).
std::string absolute_file(const std::string &file)
{
  std::error_code ec;
  const std::filesystem::path absolute = std::filesystem::absolute(file, ec);
  if (ec)
    return file;
  const std::filesystem::path canonical = std::filesystem::weakly_canonical(absolute, ec);
  return (ec ? absolute.lexically_normal() : canonical).string();
}
} // namespace

std::string Deck::input_file(const std::string &key) const
{
  const std::string f = file(key);
  std::error_code ec;
  if (!std::filesystem::exists(f, ec))
    fail(key, (impl_->at(key).assigned ? "" : "(the default: the deck does not set this key) ") +
                std::string("no file '") + escaped(f) +
                "': expected an existing file (relative names are read beside the deck)");
  return f;
}

void Deck::fail(const std::string &key, const std::string &expected) const
{
  fail_key(impl_->path, key, impl_->at(key).value, expected);
}

std::string Deck::resolved() const
{
  // File names are printed absolute, then given back their text as written
  // (what errors and descriptions quote).
  std::vector<std::pair<std::string, std::string>> relative;
  for (const auto &[key, e] : impl_->entries)
    if (e.file && !e.value.empty() && e.value.front() != '/' && !impl_->path.empty())
    {
      relative.emplace_back(key, e.value);
      impl_->store(key, absolute_file(beside_deck(e.value)));
    }
  std::ostringstream out;
  out << "# demvv resolved deck: every entry, defaults filled in (SI units).\n";
  impl_->prm.print_parameters(out,
                              static_cast<dealii::ParameterHandler::OutputStyle>(
                                dealii::ParameterHandler::ShortPRM | dealii::ParameterHandler::KeepDeclarationOrder));
  for (const auto &[key, value] : relative)
    impl_->store(key, value);
  return out.str();
}

std::vector<std::string> Deck::input_files() const
{
  std::vector<std::string> files;
  for (const auto &[key, e] : impl_->entries)
    if (e.file && !e.value.empty())
      files.push_back(absolute_file(beside_deck(e.value)));
  return files;
}

std::string Deck::documented() const
{
  std::ostringstream out;
  out << "# demvv deck of kind '" << impl_->kind << "': every entry with its default.\n"
      << "# Units in brackets; SI throughout; compression positive.\n";
  impl_->prm.print_parameters(out, static_cast<dealii::ParameterHandler::OutputStyle>(
                                     dealii::ParameterHandler::PRM | dealii::ParameterHandler::KeepDeclarationOrder));
  for (const Impl::Repeated &r : impl_->repeats)
  {
    // One instance of each repeated section, commented out, as an example.
    Impl example;
    example.enter(r.keyword + " NAME");
    r.declare(example);
    example.leave();
    std::ostringstream text;
    example.prm.print_parameters(text,
                                 static_cast<dealii::ParameterHandler::OutputStyle>(
                                   dealii::ParameterHandler::PRM | dealii::ParameterHandler::KeepDeclarationOrder));
    out << "\n# Repeatable section '" << r.keyword << "'" << (r.parent.empty() ? "" : " inside '" + r.parent + "'")
        << ": " << r.help << "\n# Write it once per item, each with its own NAME, e.g.:\n";
    std::istringstream lines(text.str());
    std::string line;
    while (std::getline(lines, line))
      out << "#   " << line << "\n";
  }
  return out.str();
}

bool deck_declares(const Deck &deck, const std::string &key)
{
  try
  {
    deck.text(key);
    return true;
  }
  catch (const std::logic_error &)
  {
    return false;
  }
}
} // namespace demvv
