// Convergence tables: the levels of a study (time step or mesh size), the
// error of each against its exact solution, and the observed order
// p = log(e_{k-1} / e_k) / log(h_{k-1} / h_k) between neighbouring levels.
// Written by the runs that are convergence studies (mms) beside their
// results and read by the checks that hold them to an expected order.
#pragma once

#include <string>
#include <vector>

namespace demvv
{
/// One level of a convergence study.
struct ConvergenceRow
{
  double h = 0; ///< step or mesh size
  double error = 0;
  double order = 0; ///< observed order against the previous level (0 for the first)
};

struct ConvergenceTable
{
  std::string title;
  std::string h_name;     ///< e.g. "dt [s]"
  std::string error_name; ///< e.g. "max |u - u_exact| [m]"
  double expected_order = 0;
  /// What expected_order is, and so what the figure's dashed line claims:
  /// the theoretical order (the default); an order fitted to these same
  /// points (no theory gives one, so the line is labelled fitted); the
  /// slowest decay the check accepts (a bound, not a prediction); or none:
  /// the scheme reproduces the quantity exactly, its errors are round-off
  /// and are drawn against roundoff_bound, the bound the check holds them to.
  enum class Reference
  {
    theory,
    fitted,
    least,
    roundoff
  };
  Reference reference = Reference::theory;
  double roundoff_bound = 0;
  std::vector<ConvergenceRow> rows;

  /// Appends a level and computes its observed order from the previous one.
  void add(double h, double error);
  /// Observed order of the last level (0 if fewer than two levels).
  double last_order() const;
  /// The largest |observed - expected| order over the finest two halvings
  /// (the last three levels): what tolerance class B holds; NaN with fewer
  /// than three levels.
  double largest_order_deviation(double expected) const;
};
} // namespace demvv
