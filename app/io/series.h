// Series: a named-column table kept in memory and, optionally, streamed to
// a CSV file row by row (output.h).  Runs record into Series; checks read
// the same Series back, so what a check compares is what a user would plot.
#pragma once

#include "app/io/output.h"

#include <memory>
#include <string>
#include <vector>

namespace demvv
{
class Series
{
public:
  Series() = default;
  explicit Series(std::vector<std::string> columns) : columns_(std::move(columns)) {}

  /// Streams every later row to `path` as well (header and comment written now).
  void stream_to(const std::string &path, const std::string &comment);
  /// Continues streaming to a file written earlier, cut back to `keep`
  /// bytes; the rows of that file are restored with restore_rows().
  void resume_stream(const std::string &path, std::uintmax_t keep);
  /// Replaces the rows in memory (a checkpoint's exact values).
  void restore_rows(std::vector<std::vector<double>> rows) { rows_ = std::move(rows); }
  const std::vector<std::vector<double>> &all_rows() const { return rows_; }

  void add(std::vector<double> row);
  std::size_t rows() const { return rows_.size(); }
  const std::vector<std::string> &columns() const { return columns_; }
  const std::vector<double> &row(std::size_t r) const { return rows_[r]; }
  /// All values of a column (std::out_of_range if the column is absent).
  std::vector<double> column(const std::string &name) const;
  /// Rows whose `key` column equals `value` (e.g. one particle of a long table).
  Series where(const std::string &key, double value) const;

private:
  std::size_t index(const std::string &name) const;
  std::vector<std::string> columns_;
  std::vector<std::vector<double>> rows_;
  std::unique_ptr<CsvSeries> sink_;
};
} // namespace demvv
