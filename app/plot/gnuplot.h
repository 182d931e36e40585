// Figures drawn by gnuplot (Debian gnuplot-nox), as SVG.
//
// Every figure becomes a script NAME.gp in its folder (and NAME.csv with
// the points of in-memory curves); gnuplot run in that folder writes
// NAME.svg.  The script and its data stay, so a user can restyle a figure
// and redraw it with `gnuplot NAME.gp` without demvv.  A figure gnuplot
// could not draw (gnuplot missing, no data) is reported, never fatal: the
// numbers in the run directory are the result, the pictures a view of them.
#pragma once

#include "app/plot/figure.h"

#include <string>
#include <vector>

namespace demvv
{
struct DrawnFigure
{
  std::string name;
  std::string svg;     ///< path of NAME.svg (empty when not drawn)
  std::string problem; ///< why it was not drawn
  bool drawn() const { return problem.empty(); }
};

/// The gnuplot script of a figure (it writes NAME.svg in its own folder).
std::string gnuplot_script(const Figure &figure);
/// Writes NAME.gp and, when a curve holds points, NAME.csv into `dir`.
void write_figure_files(const Figure &figure, const std::string &dir);
/// `text` as a figure's name: letters, digits, '_' and '-' (anything else
/// becomes '_'), at most 100 characters; the name is the stem of the
/// figure's files and appears in its script, so a name made from a run
/// directory's contents (a summary key) can neither leave the folder nor
/// inject a script line.
std::string figure_name(const std::string &text);
/// Writes the files of each figure and runs gnuplot on them, one process a
/// figure, into `dir` (made when absent; refused when it is a symbolic link
/// or no directory).  Every name goes through figure_name(); every text
/// written into a script is one line, single-quoted (no substitution).
std::vector<DrawnFigure> draw_figures(const std::vector<Figure> &figures, const std::string &dir);
/// "NAME: PROBLEM; ..." of the figures that were not drawn ("" when all were).
std::string undrawn(const std::vector<DrawnFigure> &figures);
/// True when the gnuplot executable is on the PATH.
bool gnuplot_available();
} // namespace demvv
