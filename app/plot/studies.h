// Figures of studies: convergence orders and grid convergence indices.
//
//  - add_order_study: the errors of a refinement study as markers joined by
//    a line, and beside them the theoretical order as a dashed line of slope
//    p through the finest level, e_ref(h) = e_finest (h / h_finest)^p: on
//    log-log axes the observed slope can be read against it.
//  - gci_figure: the three levels of a Roache GCI study (value against cell
//    size), the Richardson curve through them, f(h) = f_ext + (f_1 - f_ext)
//    (h / h_1)^p with the observed order p, the extrapolated value f_ext and
//    the band f_1 (1 +- GCI_fine) in which the exact value lies with the
//    GCI's factor of safety.
//  - parameter_study_figure: a parameter study over random seeds (a sweep):
//    per series the seed-ensemble mean at each value, joined by a line, its
//    95 % confidence half-width as error bars, and every member's own value
//    as an open marker, so the scatter the mean hides stays visible.
#pragma once

#include "app/plot/figure.h"

#include <string>
#include <vector>

namespace demvv
{
/// Adds one study (levels in any order) to a log-log figure; the dashed
/// line is labelled "order p (reference_label)".
void add_order_study(Figure &figure, const std::string &label, const std::vector<double> &h,
                     const std::vector<double> &error, double expected_order,
                     const std::string &reference_label = "theory");

struct GciLevels
{
  std::vector<double> h;     ///< cell sizes, fine to coarse [m]
  std::vector<double> value; ///< the quantity on each level, fine to coarse
  double extrapolated = 0;
  double observed_order = 0;
  double gci_fine = 0; ///< relative
};

/// The Richardson curve at cell size h: f_ext + (f_1 - f_ext) (h / h_1)^p.
double richardson_value(const GciLevels &levels, double h);

/// `h_scale`, `value_scale`: display units (e.g. 1e3 for mm, 1e-6 for MPa).
Figure gci_figure(const std::string &name, const std::string &quantity, const GciLevels &levels, double h_scale,
                  double value_scale, const std::string &h_label, const std::string &value_label);

/// One series of a parameter study: the mean over seeds and its 95 %
/// half-width at each value (NaN half-widths: fewer than two seeds, no
/// bars), and every completed member's value.
struct StudySeries
{
  std::string title;
  std::vector<double> x, mean, ci95;
  std::vector<double> member_x, member_y;
};

struct StudyAxes
{
  std::string name, title, x_label, y_label;
  double x_scale = 1, y_scale = 1; ///< display units, as Curve's
  bool log_x = false;
};

Figure parameter_study_figure(const StudyAxes &axes, const std::vector<StudySeries> &series);
} // namespace demvv
