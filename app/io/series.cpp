#include "app/io/series.h"

#include <stdexcept>

namespace demvv
{
void Series::stream_to(const std::string &path, const std::string &comment)
{
  sink_ = std::make_unique<CsvSeries>(path, comment, columns_);
}

void Series::resume_stream(const std::string &path, std::uintmax_t keep)
{
  sink_ = std::make_unique<CsvSeries>(path, columns_.size(), keep);
}

void Series::add(std::vector<double> row)
{
  if (sink_)
    sink_->write(row);
  rows_.push_back(std::move(row));
}

std::size_t Series::index(const std::string &name) const
{
  for (std::size_t k = 0; k < columns_.size(); ++k)
    if (columns_[k] == name)
      return k;
  throw std::out_of_range("series has no column '" + name + "'");
}

std::vector<double> Series::column(const std::string &name) const
{
  const std::size_t k = index(name);
  std::vector<double> out;
  out.reserve(rows_.size());
  for (const auto &r : rows_)
    out.push_back(r[k]);
  return out;
}

Series Series::where(const std::string &key, double value) const
{
  const std::size_t k = index(key);
  Series out(columns_);
  for (const auto &r : rows_)
    if (r[k] == value)
      out.rows_.push_back(r);
  return out;
}
} // namespace demvv
