// A figure as data: what to draw, not how.
//
// A Figure is a titled pair of axes (a right axis when a curve asks for
// one) holding curves.  A curve takes its points either from memory (a
// check's measured history and its closed form) or from two columns of a
// CSV file a run wrote (series.csv), so that a run's figure script reads
// the run's own data and a user can edit and rerun it.  Values are plotted
// as x * x_scale, y * y_scale: the files keep SI units, a figure may show
// strain in % or stress in MPa and says so in its axis label.
//
// gnuplot.h turns a Figure into a gnuplot script and an SVG picture.
#pragma once

#include <limits>
#include <string>
#include <vector>

namespace demvv
{
enum class CurveStyle
{
  line,   ///< a solid line: a measured history
  dashed, ///< a dashed line: a reference (closed form, law, continuum)
  points, ///< markers only: discrete measurements (levels of a study)
  markers_and_line,
  circles, ///< a circle of each point's radius about it (a ball's section)
};

struct Curve
{
  std::string title;
  CurveStyle style = CurveStyle::line;
  bool right_axis = false; ///< plotted against the right-hand y axis
  int colour = 0;          ///< gnuplot's line colour index; 0: the curve's place in the figure
  int point_type = 7;      ///< gnuplot's marker (7 a filled circle, 5 a filled square)

  /// Points in memory (written beside the script)...
  std::vector<double> x, y;
  /// ...with, when given, a half-width for each y (drawn as error bars,
  /// e.g. a 95 % confidence interval)...
  std::vector<double> y_error;
  /// ...or, drawn as CurveStyle::circles, a radius for each point (in x's
  /// units, scaled by x_scale)...
  std::vector<double> radius;
  /// ...or two columns of a CSV file, its path relative to the figure's folder.
  std::string file, x_column, y_column;

  double x_scale = 1, y_scale = 1;
};

/// A curve of points held in memory.
Curve curve(std::string title, std::vector<double> x, std::vector<double> y, CurveStyle style = CurveStyle::line);
/// A smooth curve held in memory with at most `at_most` of its points:
/// every k-th point and the last (a picture resolves about a thousand
/// points across; a slow pull may have a hundred thousand rows).  Not for
/// curves with sharp events between rows (a pulse's peak): thin those by
/// hand, keeping the event.
Curve thinned(Curve c, std::size_t at_most = 1000);
/// A curve read from two columns of a CSV file.
Curve column_curve(std::string title, std::string file, std::string x_column, std::string y_column, double x_scale = 1,
                   double y_scale = 1, CurveStyle style = CurveStyle::line);

/// Where a figure's key goes: never over the data.  Below the frame, in as
/// many columns as the picture's width holds (the picture grows by its
/// rows, so the frame keeps its size); right of the frame (a narrow figure
/// of few entries); or no key (a picture whose curves need no names).
enum class KeyPlace
{
  below,
  right,
  none,
};

struct Figure
{
  std::string name; ///< file stem: NAME.gp, NAME.svg (letters, digits, '_' and '-')
  std::string title;
  std::string x_label, y_label, y2_label; ///< with units
  bool log_x = false, log_y = false;
  bool equal_axes = false; ///< one unit as long on both axes (a mesh, a sample)
  bool x_margins = false;  ///< 5 % of the x range free at either end (markers at the ends drawn whole)
  /// The y axis's ends, in the plotted units (NaN: gnuplot's autoscale).
  double y_low = std::numeric_limits<double>::quiet_NaN(), y_high = std::numeric_limits<double>::quiet_NaN();
  KeyPlace key = KeyPlace::below;
  std::vector<Curve> curves;
  std::string caption; ///< one or two sentences under the picture in a report
};

/// A figure of curves on linear axes.
Figure make_figure(std::string name, std::string title, std::string x_label, std::string y_label,
                   std::vector<Curve> curves, std::string caption = "");

/// Adds a band to `f`: two horizontal lines from x0 to x1 at `low` and
/// `high` (a tolerance, a +- envelope), one title in the key, one colour
/// (the place of the first line in the figure).
void add_band(Figure &f, std::string title, double x0, double x1, double low, double high,
              CurveStyle style = CurveStyle::dashed);
} // namespace demvv
