#include "app/decks/csv_input.h"

#include "app/decks/deck.h"
#include "app/io/input.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <set>
#include <sstream>

namespace demvv
{
namespace
{
std::string trim(const std::string &s)
{
  const auto b = s.find_first_not_of(" \t\r");
  if (b == std::string::npos)
    return {};
  return s.substr(b, s.find_last_not_of(" \t\r") - b + 1);
}

std::vector<std::string> cells(const std::string &line)
{
  std::vector<std::string> out;
  std::string cell;
  std::istringstream in(line);
  while (std::getline(in, cell, ','))
    out.push_back(trim(cell));
  return out;
}
} // namespace

CsvTable CsvTable::read(const std::string &path, Values values)
{
  CsvTable t;
  t.path_ = path;
  std::istringstream in(read_input(path, "CSV file", max_table_bytes));
  std::string raw;
  int line = 0;
  while (std::getline(in, raw))
  {
    ++line;
    const std::string s = trim(raw);
    if (s.empty() || s[0] == '#')
      continue;
    const auto c = cells(s);
    if (t.header_.empty())
    {
      std::set<std::string> seen; // a set: a header of a million columns is refused in a second, not hours
      for (std::size_t k = 0; k < c.size(); ++k)
        if (!seen.insert(c[k]).second)
          throw DeckError(path + ":" + std::to_string(line) + ": column '" + escaped(c[k]) +
                          "' is named twice in the header: expected each column once (one of the two would be "
                          "ignored)");
      t.header_ = c;
      continue;
    }
    if (c.size() != t.header_.size())
      throw DeckError(path + ":" + std::to_string(line) + ": " + std::to_string(c.size()) + " values for " +
                      std::to_string(t.header_.size()) + " columns");
    std::vector<double> row;
    for (std::size_t k = 0; k < c.size(); ++k)
    {
      char *end = nullptr;
      const double v = std::strtod(c[k].c_str(), &end);
      // The whole cell is the number: a NUL inside it ends the C string early.
      const bool number = !c[k].empty() && end == c[k].c_str() + c[k].size();
      if (!number || (values == Values::finite && !std::isfinite(v)))
        throw DeckError(path + ":" + std::to_string(line) + ": column '" + t.header_[k] + "' has value '" +
                        escaped(c[k]) + "': expected a " + (number ? "finite number" : "number"));
      row.push_back(v);
    }
    t.rows_.push_back(std::move(row));
    t.lines_.push_back(line);
  }
  if (t.header_.empty())
    throw DeckError(path + ": the file is empty: expected a header line and at least one row");
  return t;
}

void CsvTable::allow_only(const std::vector<std::string> &known, const std::string &what) const
{
  for (const std::string &column : header_)
    if (std::find(known.begin(), known.end(), column) == known.end())
    {
      std::string list;
      for (const std::string &k : known)
        list += (list.empty() ? "" : ",") + k;
      throw DeckError(path_ + ": column '" + escaped(column) + "' is not a column of " + what +
                      ": expected columns among " + list + " (a misspelt column would be ignored)");
    }
}

int CsvTable::index(const std::string &column) const
{
  for (std::size_t k = 0; k < header_.size(); ++k)
    if (header_[k] == column)
      return static_cast<int>(k);
  return -1;
}

double CsvTable::get(std::size_t r, const std::string &column, double fallback) const
{
  const int k = index(column);
  return k < 0 ? fallback : rows_[r][k];
}

double CsvTable::get(std::size_t r, const std::string &column) const
{
  const int k = index(column);
  if (k < 0)
    throw DeckError(path_ + ": column '" + column + "' is missing from the header");
  return rows_[r][k];
}

void CsvTable::fail(std::size_t r, const std::string &column, const std::string &expected) const
{
  std::ostringstream v;
  v << get(r, column, 0.0);
  throw DeckError(path_ + ":" + std::to_string(lines_[r]) + ": column '" + column + "' has value '" + v.str() +
                  "': " + expected);
}
} // namespace demvv
