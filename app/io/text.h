// Text of inputs, outputs and their errors: the one number format, the one
// infinity, trimming, and the one-line error every bad input ends in.
//
// Every room writes numbers through format_number (decks and their errors
// with 12 significant digits, CSV tables with 10, reports with 3, gnuplot
// scripts with 17, which read back bit for bit), so that infinities read
// "inf" and "-inf" everywhere and no room keeps a formatter of its own.
// A DeckError is bad input: one line naming the file, the key, the value
// and what was expected; the command line turns it into exit code 2.
#pragma once

#include <limits>
#include <stdexcept>
#include <string>
#include <string_view>

namespace demvv
{
/// Bad input: one line, exit code 2.
class DeckError : public std::runtime_error
{
public:
  using std::runtime_error::runtime_error;
};

/// The one infinity (open bounds of deck entries, "no limit").
constexpr double inf = std::numeric_limits<double>::infinity();
/// Not a number: a quantity not measured, not estimated or not defined.
constexpr double nan = std::numeric_limits<double>::quiet_NaN();

/// `v` with `significant` significant digits as printf's %g writes it
/// ("inf", "-inf", "nan" for the non-finite).
std::string format_number(double v, int significant = 12);

/// `s` without blanks, tabs and line ends at either end.
std::string trimmed(std::string_view s);

/// `s` short enough to read: a word over 160 characters keeps its first
/// 100 and last 40 with the count left out between, and a whole text over
/// 2000 characters its first 1400 and last 400 (a one-line error that
/// echoes a 100 kB value names it, and still ends with what was expected).
std::string readable_length(std::string_view s);

/// `s` on one line, for text from elsewhere written into a line of a file or
/// a message: control characters (below 0x20, and DEL) become `replacement`.
std::string one_line(std::string_view s, char replacement = ' ');

/// The one-line error for a key of a deck or an input file: "FILE: key
/// 'KEY' has value 'VALUE': EXPECTED" ("deck" when there is no file).
[[noreturn]] void fail_key(const std::string &file, const std::string &key, const std::string &value,
                           const std::string &expected);
} // namespace demvv
