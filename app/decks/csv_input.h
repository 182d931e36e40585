// Reading numeric CSV tables named by decks (particle lists, bond lists).
//
// The first non-comment line is the header; every later non-empty line must
// have one finite number per column (nan and inf are refused: no column of
// any table a deck names means them); a header names each column once.
// Lines starting with '#' are comments.  Any problem is a DeckError naming
// the file, the line and the column.  The file must be a regular file of at
// most max_table_bytes (app/io/input.h).
// A run's own outputs, read back to draw its figures, may hold nan where a
// value is undefined (the order of accuracy of a study's first level).
#pragma once

#include <string>
#include <vector>

namespace demvv
{
class CsvTable
{
public:
  /// What a value may be: a finite number (tables decks name), or any
  /// number, nan and inf included (a run's own outputs).
  enum class Values
  {
    finite,
    any_number
  };
  static CsvTable read(const std::string &path, Values values = Values::finite);

  const std::string &path() const { return path_; }
  std::size_t rows() const { return rows_.size(); }
  bool has(const std::string &column) const { return index(column) >= 0; }
  const std::vector<std::string> &header() const { return header_; }
  /// Refuses (DeckError naming the file and the column) a header column
  /// not in `known`: a table whose reader would ignore a column (a misspelt
  /// density_kgpm3) must not run as if the column held nothing.
  void allow_only(const std::vector<std::string> &known, const std::string &what) const;
  /// Value of a column in row r; `fallback` if the column is absent.
  double get(std::size_t r, const std::string &column, double fallback) const;
  /// Value of a required column (DeckError if the table lacks it).
  double get(std::size_t r, const std::string &column) const;
  /// Line of the file row r came from (for messages).
  int line(std::size_t r) const { return lines_[r]; }
  /// Throws a DeckError about row r.
  [[noreturn]] void fail(std::size_t r, const std::string &column, const std::string &expected) const;

private:
  int index(const std::string &column) const;
  std::string path_;
  std::vector<std::string> header_;
  std::vector<std::vector<double>> rows_;
  std::vector<int> lines_;
};
} // namespace demvv
