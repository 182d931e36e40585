#include "app/io/output.h"
#include "app/io/text.h"

#include "build_info.h"
#include "sources_sha256.h" // here alone: it changes with every edit of the sources

#include <fcntl.h>
#include <omp.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace demvv
{
void make_directories(const std::string &path)
{
  std::error_code ec;
  std::filesystem::create_directories(path, ec);
  if (ec)
    throw std::runtime_error(path + ": cannot create the output directory: " + ec.message());
}

namespace
{
/// Writes all of `data` to a file descriptor (write(2) may take part of it);
/// the errno of the failing call, 0 on success; `written` counts the bytes
/// the file took.
int write_all(int fd, const char *data, std::size_t size, std::size_t &written)
{
  written = 0;
  while (written < size)
  {
    const ssize_t n = ::write(fd, data + written, size - written);
    if (n < 0 && errno == EINTR)
      continue;
    if (n <= 0)
      return n < 0 ? errno : ENOSPC;
    written += static_cast<std::size_t>(n);
  }
  return 0;
}

int write_all(int fd, const char *data, std::size_t size)
{
  std::size_t written = 0;
  return write_all(fd, data, size, written);
}

[[noreturn]] void output_failed(const std::string &path, const std::string &what, int error)
{
  throw OutputError(path + ": " + what + ": " + std::strerror(error));
}
} // namespace

namespace
{
/// What stands at `path` now, links not followed: 0 when nothing does.
mode_t kind_at(const std::string &path)
{
  struct stat st
  {
  };
  return ::lstat(path.c_str(), &st) == 0 ? st.st_mode & S_IFMT : 0;
}

/// A temporary file beside `path`, created exclusively (mkstemp: O_EXCL,
/// so never through a link or over another file); its name in `tmp`.
int temporary_beside(const std::string &path, std::string &tmp)
{
  std::string name = path + ".XXXXXX.tmp";
  const int fd = ::mkstemps(name.data(), 4);
  if (fd >= 0)
  {
    ::fchmod(fd, 0644);
    tmp = name;
  }
  return fd;
}
} // namespace

void write_atomically(const std::string &path, const std::string &content)
{
  const mode_t kind = kind_at(path);
  if (kind == S_IFLNK)
    throw OutputError(path + ": is a symbolic link: demvv replaces only regular files it can see (a link could "
                             "point anywhere): expected a regular file or a new name");
  if (kind != 0 && kind != S_IFREG)
    throw OutputError(path + ": is not a regular file (a directory, device, pipe or socket): expected a regular "
                             "file or a new name");
  std::string tmp;
  const int fd = temporary_beside(path, tmp);
  if (fd < 0)
  {
    // The temporary beside it could not be made: name the file the user
    // asked for, and its folder when that is what is missing.
    const int error = errno;
    const std::string folder = std::filesystem::path(path).parent_path().string();
    output_failed(path + (error == ENOENT && !folder.empty() ? " (no folder '" + folder + "')" : std::string()),
                  "cannot write", error);
  }
  int error = write_all(fd, content.data(), content.size());
  if (!error && fsync(fd) != 0)
    error = errno;
  ::close(fd);
  if (!error && std::rename(tmp.c_str(), path.c_str()) != 0)
    error = errno;
  if (error)
  {
    ::unlink(tmp.c_str());
    output_failed(path, "cannot write", error);
  }
}

void remove_regular_file(const std::string &path)
{
  if (kind_at(path) == S_IFREG)
    ::unlink(path.c_str());
}

namespace
{
/// A pipe opened for writing once a process reads it.  A pipe nobody reads
/// would block the open forever: its reader gets 5 s to open it (as a shell
/// starts `cat pipe &` just before), then the write is refused.
int open_read_pipe(const std::string &path)
{
  for (int tries = 0; tries < 100; ++tries)
  {
    const int fd = ::open(path.c_str(), O_WRONLY | O_NONBLOCK | O_NOFOLLOW | O_CLOEXEC);
    if (fd >= 0)
    {
      ::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) & ~O_NONBLOCK);
      return fd;
    }
    if (errno != ENXIO)
      return -1;
    ::usleep(50000);
  }
  output_failed(path + " (a pipe no process opened for reading within 5 s)", "cannot write", ENXIO);
}
} // namespace

void write_named_output(const std::string &path, const std::string &content)
{
  if (path == "-")
  {
    std::fwrite(content.data(), 1, content.size(), stdout);
    if (std::fflush(stdout) != 0)
      output_failed("standard output", "cannot write", errno);
    return;
  }
  const mode_t kind = kind_at(path);
  if (kind == S_IFCHR || kind == S_IFIFO)
  {
    // A device or a pipe the user named (/dev/null, /dev/stdout, a FIFO):
    // written through, never replaced.
    const int fd = kind == S_IFIFO ? open_read_pipe(path) : ::open(path.c_str(), O_WRONLY | O_NOFOLLOW | O_CLOEXEC);
    if (fd < 0)
      output_failed(path, "cannot write", errno);
    const int error = write_all(fd, content.data(), content.size());
    ::close(fd);
    if (error)
      output_failed(path, "cannot write", error);
    return;
  }
  write_atomically(path, content);
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

namespace
{
/// A series file opened for writing without following a link (a run
/// directory may be shared: a link planted in it must not lead elsewhere).
std::FILE *open_series(const std::string &path, int flags)
{
  const int fd = ::open(path.c_str(), O_WRONLY | O_NOFOLLOW | O_CLOEXEC | flags, 0644);
  if (fd < 0)
    output_failed(path, "cannot write", errno);
  std::FILE *f = ::fdopen(fd, "ab");
  if (!f)
  {
    const int error = errno;
    ::close(fd);
    output_failed(path, "cannot write", error);
  }
  return f;
}
} // namespace

CsvSeries::CsvSeries(const std::string &path, const std::string &comment, const std::vector<std::string> &columns)
  : columns_(columns.size()), path_(path)
{
  file_ = open_series(path, O_CREAT | O_TRUNC);
  // The comment is one line whatever it quotes (a deck's file name may hold
  // a newline): control characters become spaces.
  std::string head = "# " + one_line(comment) + "\n";
  for (std::size_t k = 0; k < columns.size(); ++k)
    head += (k ? "," : "") + columns[k];
  head += "\n";
  if (const int error = write_all(fileno(file_), head.data(), head.size()))
    output_failed(path, "cannot write the header", error);
}

void sync_file(const std::string &path)
{
  const int fd = ::open(path.c_str(), O_RDONLY | O_NOFOLLOW | O_CLOEXEC);
  if (fd < 0)
    return;
  const int failed = ::fsync(fd);
  const int error = errno;
  ::close(fd);
  if (failed != 0)
    output_failed(path, "cannot flush to disk", error);
}

CsvSeries::CsvSeries(const std::string &path, std::size_t columns, std::uintmax_t keep) : columns_(columns), path_(path)
{
  const std::string expected = "expected the run's own file (or the run from its start, --replace)";
  std::error_code ec;
  const std::filesystem::file_status st = std::filesystem::symlink_status(path, ec);
  if (!ec && std::filesystem::exists(st) && !std::filesystem::is_regular_file(st))
    throw std::runtime_error(path + ": a link or a special file, not the series the run wrote: " + expected);
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec || size < keep)
    throw std::runtime_error(
      path + ": " + (ec ? "missing" : std::to_string(size) + " bytes") + ", shorter than the " + std::to_string(keep) +
      " bytes its checkpoint recorded: the file was cut or replaced since the run paused: " + expected);
  // The kept part must be whole rows after the two header lines: the
  // checkpoint's size ends a line, and the header ends before it.
  std::ifstream in(path, std::ios::binary);
  std::string line;
  std::uintmax_t header = 0;
  int header_lines = 0;
  while (header_lines < 2 && std::getline(in, line) && !in.eof())
  {
    header += line.size() + 1;
    ++header_lines;
  }
  char last = '\0';
  if (keep > 0)
  {
    in.clear();
    in.seekg(static_cast<std::streamoff>(keep - 1));
    in.get(last);
  }
  if (header_lines < 2 || header > keep || last != '\n')
    throw std::runtime_error(
      path + ": the checkpoint's size " + std::to_string(keep) +
      " does not end a row after the header: the checkpoint or the file was edited: " + expected);
  std::filesystem::resize_file(path, keep, ec);
  if (ec)
    throw std::runtime_error(path + ": cannot continue the file of the checkpoint: " + ec.message());
  file_ = open_series(path, O_APPEND);
}

CsvSeries::~CsvSeries()
{
  if (file_)
    std::fclose(file_);
}

void CsvSeries::write(const std::vector<double> &row)
{
  if (row.size() != columns_)
    throw std::logic_error("demvv bug: " + path_ + ": row has " + std::to_string(row.size()) + " values for " +
                           std::to_string(columns_) + " columns");
  buffer_.clear();
  for (std::size_t k = 0; k < row.size(); ++k)
  {
    if (k)
      buffer_ += ',';
    buffer_ += format_number(row[k], 10);
  }
  buffer_ += "\n";
  // A row is either wholly in the file or not at all: a part the disk took
  // is cut off again.
  const int fd = fileno(file_);
  std::size_t written = 0;
  if (const int error = write_all(fd, buffer_.data(), buffer_.size(), written))
  {
    const off_t end = ::lseek(fd, 0, SEEK_END) - static_cast<off_t>(written);
    if (::ftruncate(fd, end) != 0)
      output_failed(path_,
                    "cannot append a row (" + std::string(std::strerror(error)) +
                      ") nor cut the part written; its last row is incomplete",
                    errno);
    output_failed(path_, "cannot append a row (the file ends at the previous row)", error);
  }
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
  std::fprintf(stderr, "\r%s %5.1f%%  %s  elapsed %.0f s, left ~%.0f s   ", label_.c_str(), 100 * fraction,
               text.c_str(), elapsed, eta);
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
  std::uint64_t h = 14695981039346656037ULL; // the standard 64-bit offset basis
  for (unsigned char c : text)
  {
    h ^= c;
    h *= 1099511628211ULL;
  }
  char out[17];
  std::snprintf(out, sizeof out, "%016llx", static_cast<unsigned long long>(h));
  return out;
}

namespace
{
/// This machine's name and processor model (the first "model name" of
/// /proc/cpuinfo): builds use -march=native, so the machine is part of how a
/// result was made.
std::pair<std::string, std::string> machine()
{
  char host[256] = {0};
  if (gethostname(host, sizeof host - 1) != 0)
    host[0] = 0;
  std::string cpu;
  std::ifstream in("/proc/cpuinfo");
  for (std::string line; cpu.empty() && std::getline(in, line);)
    if (line.rfind("model name", 0) == 0 && line.find(':') != std::string::npos)
      cpu = line.substr(line.find(':') + 2);
  return {host, cpu};
}
} // namespace

nlohmann::json provenance(int threads, long long seed, const std::string &deck_text)
{
  static const std::pair<std::string, std::string> where = machine();
  char when[32];
  const std::time_t now = std::time(nullptr);
  std::strftime(when, sizeof when, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
  nlohmann::json p = {{"program", "demvv"},
                      {"version", build_info::version},
                      {"git_sha", build_info::git_sha},
                      {"threads", threads},
                      {"max_threads", omp_get_max_threads()},
                      {"seed", seed},
                      {"deck_fnv1a64", fnv1a_hex(deck_text)},
                      {"started_utc", when},
                      {"host", where.first},
                      {"cpu_model", where.second},
                      {"units", "SI (m, kg, s, N, Pa, J); compression positive"}};
  p.update(build_identity());
  return p;
}

nlohmann::json build_identity()
{
  return {{"sources_sha256", build_info::sources_sha256},
          {"compiler", build_info::compiler},
          {"build_type", build_info::build_type},
          {"dem_flags", build_info::dem_flags},
          {"dem_macros_sha256", build_info::dem_macros_sha256}};
}

bool made_by_this_build(const nlohmann::json &record)
{
  if (!record.is_object())
    return false;
  const nlohmann::json identity = build_identity(); // named: items() does not keep a temporary alive
  for (const auto &[key, value] : identity.items())
    if (!record.contains(key) || record.at(key) != value)
      return false;
  return true;
}
} // namespace demvv
