#include "verify/io/output.h"

#include "build_info.h"

#include <omp.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace verify
{
void make_directories(const std::string &path)
{
  std::error_code ec;
  std::filesystem::create_directories(path, ec);
  if (ec)
    throw std::runtime_error(path + ": cannot create the output directory: " + ec.message());
}

void write_atomically(const std::string &path, const std::string &content)
{
  const std::string tmp = path + ".tmp";
  std::FILE *f = std::fopen(tmp.c_str(), "wb");
  if (!f)
    throw std::runtime_error(tmp + ": cannot write: " + std::strerror(errno));
  const bool ok = std::fwrite(content.data(), 1, content.size(), f) == content.size() &&
                  std::fflush(f) == 0 && fsync(fileno(f)) == 0;
  std::fclose(f);
  if (!ok || std::rename(tmp.c_str(), path.c_str()) != 0)
    throw std::runtime_error(path + ": cannot write: " + std::strerror(errno));
}

std::string read_file(const std::string &path)
{
  std::ifstream in(path, std::ios::binary);
  if (!in)
    throw std::runtime_error(path + ": cannot read");
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string json_text(const nlohmann::json &doc, int indent)
{
  return doc.dump(indent, ' ', false, nlohmann::json::error_handler_t::replace);
}

CsvSeries::CsvSeries(const std::string &path, const std::string &comment,
                     const std::vector<std::string> &columns)
  : columns_(columns.size()), path_(path)
{
  file_ = std::fopen(path.c_str(), "wb");
  if (!file_)
    throw std::runtime_error(path + ": cannot write: " + std::strerror(errno));
  std::string head = "# " + comment + "\n";
  for (std::size_t k = 0; k < columns.size(); ++k)
    head += (k ? "," : "") + columns[k];
  head += "\n";
  std::fwrite(head.data(), 1, head.size(), file_);
  std::fflush(file_);
}

CsvSeries::CsvSeries(const std::string &path, std::size_t columns, std::uintmax_t keep)
  : columns_(columns), path_(path)
{
  std::error_code ec;
  std::filesystem::resize_file(path, keep, ec);
  if (ec)
    throw std::runtime_error(path + ": cannot continue the file of the checkpoint: " + ec.message());
  file_ = std::fopen(path.c_str(), "ab");
  if (!file_)
    throw std::runtime_error(path + ": cannot write: " + std::strerror(errno));
}

CsvSeries::~CsvSeries()
{
  if (file_)
    std::fclose(file_);
}

void CsvSeries::write(const std::vector<double> &row)
{
  if (row.size() != columns_)
    throw std::logic_error("demvv bug: " + path_ + ": row has " + std::to_string(row.size()) +
                           " values for " + std::to_string(columns_) + " columns");
  buffer_.clear();
  char cell[32];
  for (std::size_t k = 0; k < row.size(); ++k)
  {
    std::snprintf(cell, sizeof cell, "%s%.10g", k ? "," : "", row[k]);
    buffer_ += cell;
  }
  buffer_ += "\n";
  // One write(2) per row: a row is either wholly in the file or not at all.
  std::fflush(file_);
  if (::write(fileno(file_), buffer_.data(), buffer_.size()) != static_cast<ssize_t>(buffer_.size()))
    throw std::runtime_error(path_ + ": cannot append a row: " + std::strerror(errno));
}

Progress::Progress(std::string label, bool wanted, double done_at_start)
  : label_(std::move(label)), enabled_(wanted && isatty(fileno(stdout)) != 0 && isatty(fileno(stderr)) != 0),
    done_at_start_(done_at_start), start_(std::chrono::steady_clock::now()), last_(start_)
{
}

bool Progress::due() const
{
  return enabled_ && std::chrono::steady_clock::now() - last_ >= std::chrono::milliseconds(250);
}

double Progress::elapsed() const
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

void Progress::update(double fraction, const std::string &text)
{
  if (!enabled_)
    return;
  const auto now = std::chrono::steady_clock::now();
  if (now - last_ < std::chrono::milliseconds(250))
    return;
  last_ = now;
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const double done = fraction - done_at_start_;
  const double eta = done > 1e-6 ? elapsed * (1 - fraction) / done : 0;
  std::fprintf(stderr, "\r%s %5.1f%%  %s  elapsed %.0f s, left ~%.0f s   ", label_.c_str(),
               100 * fraction, text.c_str(), elapsed, eta);
  std::fflush(stderr);
}

void Progress::finish()
{
  if (enabled_)
  {
    std::fprintf(stderr, "\r%*s\r", 100, "");
    std::fflush(stderr);
  }
}

std::string fnv1a_hex(const std::string &text)
{
  std::uint64_t h = 1469598103934665603ULL;
  for (unsigned char c : text)
  {
    h ^= c;
    h *= 1099511628211ULL;
  }
  char out[17];
  std::snprintf(out, sizeof out, "%016llx", static_cast<unsigned long long>(h));
  return out;
}

nlohmann::json provenance(int threads, long long seed, const std::string &deck_text)
{
  char when[32];
  const std::time_t now = std::time(nullptr);
  std::strftime(when, sizeof when, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
  return {{"program", "demvv"},
          {"version", build_info::version},
          {"git_sha", build_info::git_sha},
          {"compiler", build_info::compiler},
          {"build_type", build_info::build_type},
          {"dem_flags", build_info::dem_flags},
          {"threads", threads},
          {"max_threads", omp_get_max_threads()},
          {"seed", seed},
          {"deck_fnv1a64", fnv1a_hex(deck_text)},
          {"started_utc", when},
          {"units", "SI (m, kg, s, N, Pa, J); compression positive"}};
}
} // namespace verify
