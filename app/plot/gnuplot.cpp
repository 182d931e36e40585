#include "app/plot/gnuplot.h"
#include "app/io/text.h"

#include "app/io/output.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

namespace demvv
{
Curve curve(std::string title, std::vector<double> x, std::vector<double> y, CurveStyle style)
{
  Curve c;
  c.title = std::move(title);
  c.x = std::move(x);
  c.y = std::move(y);
  c.style = style;
  return c;
}

Curve thinned(Curve c, std::size_t at_most)
{
  const std::size_t n = c.x.size();
  if (at_most < 2 || n <= at_most)
    return c;
  const std::size_t every = (n - 1 + at_most - 2) / (at_most - 1);
  std::vector<std::size_t> kept;
  for (std::size_t k = 0; k < n; k += every)
    kept.push_back(k);
  if (kept.back() != n - 1)
    kept.push_back(n - 1);
  const auto pick = [&kept](std::vector<double> &v)
  {
    if (v.empty())
      return;
    std::vector<double> picked;
    for (std::size_t k : kept)
      picked.push_back(v[k]);
    v = std::move(picked);
  };
  pick(c.x);
  pick(c.y);
  pick(c.y_error);
  return c;
}

void add_band(Figure &f, std::string title, double x0, double x1, double low, double high, CurveStyle style)
{
  const int colour = static_cast<int>(f.curves.size()) + 1;
  f.curves.push_back(curve(std::move(title), {x0, x1}, {high, high}, style));
  f.curves.push_back(curve("", {x0, x1}, {low, low}, style));
  f.curves[f.curves.size() - 2].colour = f.curves.back().colour = colour;
}

Curve column_curve(std::string title, std::string file, std::string x_column, std::string y_column, double x_scale,
                   double y_scale, CurveStyle style)
{
  Curve c;
  c.title = std::move(title);
  c.file = std::move(file);
  c.x_column = std::move(x_column);
  c.y_column = std::move(y_column);
  c.x_scale = x_scale;
  c.y_scale = y_scale;
  c.style = style;
  return c;
}

Figure make_figure(std::string name, std::string title, std::string x_label, std::string y_label,
                   std::vector<Curve> curves, std::string caption)
{
  Figure f;
  f.name = std::move(name);
  f.title = std::move(title);
  f.x_label = std::move(x_label);
  f.y_label = std::move(y_label);
  f.curves = std::move(curves);
  f.caption = std::move(caption);
  return f;
}

namespace
{
/// A gnuplot single-quoted string ('' stands for one quote inside): inside
/// single quotes gnuplot substitutes neither `backquoted` commands nor
/// @macros, and control characters are gone (one_line: a newline would
/// start a command of its own).
std::string quoted(const std::string &s)
{
  std::string out = "'";
  for (char c : one_line(s))
    out += c == '\'' ? std::string("''") : std::string(1, c);
  return out + "'";
}

/// Text for a comment line: gnuplot reads a comment's line too (a trailing
/// backslash continues it, backquotes are substituted before the `#`), so
/// only letters, digits and plain punctuation stay.
std::string comment_text(const std::string &s)
{
  std::string out = one_line(s);
  for (char &c : out)
    if (c == '`' || c == '\\' || c == '@' || c == '$')
      c = '_';
  return out;
}

/// 17 significant digits: a double read back bit for bit.
std::string number(double v) { return format_number(v, 17); }

/// gnuplot's `using` item for column `c` (a number or a name) times `scale`.
std::string using_item(const std::string &c, double scale)
{
  const bool numbered = c.find_first_not_of("0123456789") == std::string::npos;
  if (scale == 1 && numbered)
    return c;
  return "(" + (numbered ? "$" + c : "column(" + quoted(c) + ")") + (scale == 1 ? "" : "*" + number(scale)) + ")";
}

std::string style_clause(CurveStyle s, int colour, int point_type)
{
  const std::string lc = " lc " + std::to_string(colour);
  const std::string pt = " pt " + std::to_string(point_type);
  switch (s)
  {
  case CurveStyle::line:
    return "with lines lw 2" + lc;
  case CurveStyle::dashed:
    return "with lines lw 2 dt 2" + lc;
  case CurveStyle::points:
    return "with points" + pt + " ps 0.9" + lc;
  case CurveStyle::markers_and_line:
    return "with linespoints lw 2" + pt + " ps 0.9" + lc;
  case CurveStyle::circles:
    return "with circles" + lc + " fs transparent solid 0.3";
  }
  return "with lines";
}

bool in_memory(const Curve &c) { return c.file.empty(); }

/// Whether a curve is drawn: a file's columns, or points held in memory.
bool drawn(const Curve &c) { return !in_memory(c) || !c.x.empty(); }

bool plottable(const Figure &f) { return std::any_of(f.curves.begin(), f.curves.end(), drawn); }

/// The last non-empty line of gnuplot's messages, as the reason it failed.
std::string last_line(const std::string &text)
{
  std::istringstream in(text);
  std::string line, last;
  while (std::getline(in, line))
    if (line.find_first_not_of(" \t\r^") != std::string::npos)
      last = line;
  return last;
}

/// Whether an SVG file is whole: gnuplot ends it with its closing tag, and
/// one cut by a full disk or a file-size limit (gnuplot says nothing and
/// exits 0) lacks it.
bool whole_svg(const std::string &path)
{
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  const std::streamoff size = in ? static_cast<std::streamoff>(in.tellg()) : 0;
  if (size <= 0)
    return false;
  const std::streamoff tail = std::min<std::streamoff>(size, 64);
  std::string end(static_cast<std::size_t>(tail), '\0');
  in.seekg(size - tail);
  in.read(end.data(), tail);
  return end.find("</svg>") != std::string::npos;
}

/// Runs `gnuplot NAME.gp` inside `dir`; the empty string on success, else
/// why not.  The figure drawn before is kept until the new one is whole; a
/// picture cut short (a full disk, a file-size limit) is an OutputError,
/// the picture before it restored.
std::string run_gnuplot(const std::string &dir, const std::string &name)
{
  const std::string svg = dir + "/" + name + ".svg", log = dir + "/" + name + ".log";
  const std::string previous = svg + ".previous";
  const std::string script = name + ".gp", log_name = name + ".log";
  std::remove(previous.c_str());
  const bool kept = std::rename(svg.c_str(), previous.c_str()) == 0;
  std::remove(log.c_str()); // a link named so is removed, never followed (the child creates it exclusively)
  // Only async-signal-safe calls between fork and exec: the strings are made before.
  const pid_t pid = fork();
  if (pid < 0)
    return std::string("cannot start gnuplot: ") + std::strerror(errno);
  if (pid == 0)
  {
    if (chdir(dir.c_str()) != 0)
      _exit(126);
    const int in = open("/dev/null", O_RDONLY);
    const int out = open(log_name.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW, 0644);
    if (in < 0 || out < 0)
      _exit(126);
    dup2(in, 0);
    dup2(out, 1);
    dup2(out, 2);
    execlp("gnuplot", "gnuplot", script.c_str(), static_cast<char *>(nullptr));
    _exit(127);
  }
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR)
    ;
  struct stat st
  {
  };
  const std::string messages = stat(log.c_str(), &st) == 0 ? read_file(log) : std::string();
  const bool written = stat(svg.c_str(), &st) == 0 && st.st_size > 0;
  const bool finished = WIFEXITED(status) && WEXITSTATUS(status) == 0;
  if (finished && written && whole_svg(svg))
  {
    std::remove(log.c_str());
    std::remove(previous.c_str());
    return {};
  }
  std::remove(svg.c_str());
  if (kept)
    std::rename(previous.c_str(), svg.c_str());
  if (finished && written)
    throw OutputError(svg + ": cannot write: the picture was cut short (the disk is full, or a file-size limit)" +
                      std::string(kept ? "; the picture drawn before is kept" : ""));
  const std::string why = last_line(messages);
  return "gnuplot could not draw it" + (why.empty() ? std::string() : ": " + why) + " (messages in " + log + ")";
}

std::size_t characters(const std::string &utf8)
{
  return static_cast<std::size_t>(
    std::count_if(utf8.begin(), utf8.end(), [](char c) { return (static_cast<unsigned char>(c) & 0xC0) != 0x80; }));
}

// The key's layout below the frame.  gnuplot lets a key below run past the
// picture's edges when its columns do not fit; demvv chooses the columns
// itself from gnuplot's own width of an entry (8.4 px a character at 12 px
// and 60 px of sample and gaps, measured from its key boxes for titles of
// 10, 40 and 80 characters) and grows the picture by the rows, so that a
// key of six titles neither leaves the picture nor squeezes the frame.
// gnuplot centres the key on the frame, not on the picture, and the y
// axis's labels move the frame up to 50 px right, so about 640 px are free:
// a title of more than 69 characters does not fit in one column, and the
// figure lint of the tests finds it.
constexpr int picture_width = 760;
constexpr int frame_height = 420; ///< the picture's height without a key below
constexpr int key_row_height = 18;

struct KeyLayout
{
  int columns = 1, rows = 0;
};

KeyLayout key_layout(const Figure &f)
{
  std::size_t entries = 0, widest = 0;
  for (const Curve &c : f.curves)
    if (!c.title.empty() && drawn(c))
    {
      ++entries;
      widest = std::max(widest, characters(c.title));
    }
  if (entries == 0 || f.key != KeyPlace::below)
    return {1, 0};
  const double entry_width = 8.4 * static_cast<double>(widest) + 60;
  const int fit = std::max(1, static_cast<int>((picture_width - 120) / entry_width));
  const int columns = std::min(fit, static_cast<int>(entries));
  return {columns, static_cast<int>((entries + columns - 1) / columns)};
}

int picture_height(const KeyLayout &k) { return frame_height + (k.rows > 0 ? key_row_height * (k.rows + 1) : 40); }

std::string key_clause(const Figure &f, const KeyLayout &k)
{
  switch (f.key)
  {
  case KeyPlace::none:
    return "set key off";
  case KeyPlace::right:
    return "set key outside right top box opaque";
  case KeyPlace::below:
    break;
  }
  // gnuplot sets the x axis's label on the key's top edge; a bottom margin
  // of the key's rows and four lines more lifts the frame and its label
  // clear of the box.
  return "set key below box opaque maxcols " + std::to_string(k.columns) + "\nset bmargin " +
         std::to_string(k.rows + 4);
}
} // namespace

std::string gnuplot_script(const Figure &f)
{
  const KeyLayout key = key_layout(f);
  std::ostringstream o;
  o << "# demvv figure " << f.name << ": " << comment_text(f.title) << "\n"
    << "# Redraw with: gnuplot " << f.name << ".gp (in this folder; it writes " << f.name << ".svg)\n"
    << "reset\n"
    << "set terminal svg size " << picture_width << "," << picture_height(key)
    << " noenhanced font 'Sans,12' background rgb 'white'\n"
    << "set encoding utf8\n"
    << "set output " << quoted(f.name + ".svg") << "\n"
    << "set datafile separator ','\n"
    << "set title " << quoted(f.title) << "\n"
    << "set xlabel " << quoted(f.x_label) << "\n"
    << "set ylabel " << quoted(f.y_label) << "\n"
    << "set grid\n"
    << key_clause(f, key) << "\n";
  bool right = false;
  for (const Curve &c : f.curves)
    right = right || c.right_axis;
  if (right)
    o << "set y2label " << quoted(f.y2_label) << "\nset y2tics\nset ytics nomirror\n";
  if (f.log_x)
    o << "set logscale x\n";
  if (f.log_y)
    o << "set logscale y\n";
  if (f.log_x || f.log_y)
    o << "set format " << (f.log_x ? "x" : "") << (f.log_y ? "y" : "") << " '%g'\n";
  if (f.x_margins)
    o << "set offsets graph 0.05, graph 0.05, 0, 0\n";
  else if (std::all_of(f.curves.begin(), f.curves.end(),
                       [](const Curve &c) { return c.style == CurveStyle::line || c.style == CurveStyle::dashed; }))
    o << "set autoscale xfix\n"; // histories end where their data end, not at the next tick
  if (f.equal_axes)
    o << "set size ratio -1\n";
  if (std::isfinite(f.y_low) || std::isfinite(f.y_high))
    o << "set yrange [" << (std::isfinite(f.y_low) ? number(f.y_low) : "*") << ":"
      << (std::isfinite(f.y_high) ? number(f.y_high) : "*") << "]\n";
  o << "plot ";
  int block = 0, colour = 0;
  bool first = true;
  for (const Curve &c : f.curves)
  {
    ++colour;
    if (!drawn(c))
      continue;
    o << (first ? "" : ", \\\n     ");
    first = false;
    const bool bars = in_memory(c) && !c.y_error.empty();
    const bool circles = in_memory(c) && c.style == CurveStyle::circles;
    if (in_memory(c))
      o << quoted(f.name + ".csv") << " index " << block++ << " using " << using_item("1", c.x_scale) << ":"
        << using_item("2", c.y_scale) << (bars ? ":" + using_item("3", c.y_scale) : "")
        << (circles ? ":" + using_item("3", c.x_scale) : "");
    else
      o << quoted(c.file) << " using " << using_item(c.x_column, c.x_scale) << ":" << using_item(c.y_column, c.y_scale);
    const int lc = c.colour ? c.colour : colour;
    o << (c.right_axis ? " axes x1y2 " : " ")
      << (bars ? "with yerrorbars pt " + std::to_string(c.point_type) + " ps 0.9 lc " + std::to_string(lc)
               : style_clause(c.style, lc, c.point_type))
      << " title " << quoted(c.title);
  }
  o << "\n";
  return o.str();
}

void write_figure_files(const Figure &f, const std::string &dir)
{
  std::ostringstream data;
  bool any = false;
  for (const Curve &c : f.curves)
  {
    if (!in_memory(c) || c.x.empty())
      continue;
    data << (any ? "\n\n" : "") << "# " << one_line(c.title) << "\n";
    any = true;
    for (std::size_t k = 0; k < c.x.size() && k < c.y.size(); ++k)
      data << number(c.x[k]) << "," << number(c.y[k])
           << (c.y_error.empty() ? "" : "," + number(k < c.y_error.size() ? c.y_error[k] : 0.0))
           << (c.style == CurveStyle::circles ? "," + number(k < c.radius.size() ? c.radius[k] : 0.0) : "") << "\n";
  }
  if (any)
    write_atomically(dir + "/" + f.name + ".csv", data.str());
  write_atomically(dir + "/" + f.name + ".gp", gnuplot_script(f));
}

std::string undrawn(const std::vector<DrawnFigure> &figures)
{
  std::string text;
  for (const DrawnFigure &f : figures)
    if (!f.drawn())
      text += (text.empty() ? "" : "; ") + f.name + ": " + f.problem;
  return text;
}

bool gnuplot_available()
{
  const char *path = std::getenv("PATH");
  std::istringstream dirs(path ? path : "/usr/bin:/bin");
  std::string d;
  while (std::getline(dirs, d, ':'))
    if (!d.empty() && access((d + "/gnuplot").c_str(), X_OK) == 0)
      return true;
  return false;
}

std::string figure_name(const std::string &text)
{
  static const std::string allowed = "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-";
  std::string name = text.substr(0, 100);
  for (char &c : name)
    if (allowed.find(c) == std::string::npos)
      c = '_';
  return name.empty() ? "figure" : name;
}

std::vector<DrawnFigure> draw_figures(const std::vector<Figure> &figures, const std::string &dir)
{
  struct stat st
  {
  };
  if (::lstat(dir.c_str(), &st) == 0 && !S_ISDIR(st.st_mode))
    throw OutputError(dir + ": is not a directory (a symbolic link or a file): demvv draws figures only into a "
                            "directory of its own: expected a plots directory or none (remove it)");
  make_directories(dir);
  const bool have_gnuplot = gnuplot_available();
  std::vector<DrawnFigure> out;
  for (const Figure &named : figures)
  {
    Figure f = named; // its name from a fixed alphabet: it becomes file names and script text
    f.name = figure_name(named.name);
    write_figure_files(f, dir);
    DrawnFigure d;
    d.name = f.name;
    if (!plottable(f))
      d.problem = "no data to draw";
    else if (!have_gnuplot)
      d.problem =
        "gnuplot is not installed (Debian: apt-get install gnuplot-nox); the script " + f.name + ".gp is written";
    else
      d.problem = run_gnuplot(dir, f.name);
    if (d.drawn())
      d.svg = dir + "/" + f.name + ".svg";
    else
      remove_regular_file(dir + "/" + f.name + ".svg"); // an earlier drawing's, not of these data
    out.push_back(std::move(d));
  }
  return out;
}
} // namespace demvv
