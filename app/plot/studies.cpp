#include "app/plot/studies.h"

#include <algorithm>
#include <cmath>

namespace demvv
{
void add_order_study(Figure &figure, const std::string &label, const std::vector<double> &h,
                     const std::vector<double> &error, double expected_order, const std::string &reference_label)
{
  std::vector<double> hs, es;
  for (std::size_t k = 0; k < h.size() && k < error.size(); ++k)
    if (h[k] > 0 && error[k] > 0 && std::isfinite(h[k]) && std::isfinite(error[k]))
    {
      hs.push_back(h[k]);
      es.push_back(error[k]);
    }
  figure.log_x = figure.log_y = true;
  int colour = 1;
  for (const Curve &c : figure.curves)
    colour += c.style == CurveStyle::markers_and_line ? 1 : 0;
  figure.curves.push_back(curve(label, hs, es, CurveStyle::markers_and_line));
  figure.curves.back().colour = colour;
  if (hs.empty() || !(expected_order > 0))
    return;
  const std::size_t finest = static_cast<std::size_t>(std::min_element(hs.begin(), hs.end()) - hs.begin());
  std::vector<double> reference;
  for (double x : hs)
    reference.push_back(es[finest] * std::pow(x / hs[finest], expected_order));
  char order[32];
  std::snprintf(order, sizeof order, "%.3g", expected_order);
  figure.curves.push_back(
    curve("order " + std::string(order) + " (" + reference_label + ")", hs, reference, CurveStyle::dashed));
  figure.curves.back().colour = colour;
}

double richardson_value(const GciLevels &l, double h)
{
  return l.extrapolated + (l.value.front() - l.extrapolated) * std::pow(h / l.h.front(), l.observed_order);
}

Figure gci_figure(const std::string &name, const std::string &quantity, const GciLevels &levels, double h_scale,
                  double value_scale, const std::string &h_label, const std::string &value_label)
{
  Figure f;
  f.name = name;
  f.title = "Grid convergence index: " + quantity;
  f.x_label = h_label;
  f.y_label = value_label;
  if (levels.h.empty() || levels.h.size() != levels.value.size())
    return f;
  const double f1 = levels.value.front();
  const double h_max = *std::max_element(levels.h.begin(), levels.h.end());
  std::vector<double> hs, richardson;
  for (int k = 0; k <= 40; ++k)
  {
    const double h = h_max * k / 40.0;
    hs.push_back(h);
    richardson.push_back(richardson_value(levels, h));
  }
  f.curves.push_back(curve("levels", levels.h, levels.value, CurveStyle::points));
  f.curves.push_back(curve("Richardson curve (observed order)", hs, richardson, CurveStyle::dashed));
  f.curves.push_back(curve("extrapolated value", {0.0}, {levels.extrapolated}, CurveStyle::points));
  const double band = levels.gci_fine * std::abs(f1);
  add_band(f, "fine value +- GCI_fine", 0.0, h_max, f1 - band, f1 + band, CurveStyle::line);
  for (Curve &c : f.curves)
  {
    c.x_scale = h_scale;
    c.y_scale = value_scale;
  }
  char text[160];
  std::snprintf(text, sizeof text, "Observed order %.3g; extrapolated %.6g; GCI on the finest level %.3g %%.",
                levels.observed_order, levels.extrapolated * value_scale, 100 * levels.gci_fine);
  f.caption = text;
  return f;
}

Figure parameter_study_figure(const StudyAxes &axes, const std::vector<StudySeries> &series)
{
  Figure f = make_figure(axes.name, axes.title, axes.x_label, axes.y_label, {});
  f.log_x = axes.log_x;
  f.x_margins = !axes.log_x; // a log axis already reaches whole decades
  int colour = 0;
  for (const StudySeries &s : series)
  {
    ++colour;
    std::vector<Curve> curves = {curve(s.title, s.x, s.mean, CurveStyle::markers_and_line),
                                 curve("", s.member_x, s.member_y, CurveStyle::points)};
    curves[1].point_type = 6;
    if (std::any_of(s.ci95.begin(), s.ci95.end(), [](double h) { return std::isfinite(h); }))
    {
      std::vector<double> half_width;
      for (double h : s.ci95)
        half_width.push_back(std::isfinite(h) ? h : 0.0);
      curves.push_back(curve("", s.x, s.mean, CurveStyle::points));
      curves.back().y_error = half_width;
    }
    for (Curve &c : curves)
    {
      c.colour = colour;
      c.x_scale = axes.x_scale;
      c.y_scale = axes.y_scale;
      f.curves.push_back(std::move(c));
    }
  }
  f.caption = "Lines join the means over seeds; bars: 95 % confidence half-width of the mean (Student t); open "
              "circles: every member.";
  return f;
}
} // namespace demvv
