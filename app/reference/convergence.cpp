#include "app/reference/convergence.h"

#include <algorithm>
#include <cmath>

namespace demvv
{
void ConvergenceTable::add(double h, double error)
{
  ConvergenceRow r{h, error, 0};
  if (!rows.empty() && rows.back().error > 0 && error > 0 && rows.back().h != h)
    r.order = std::log(rows.back().error / error) / std::log(rows.back().h / h);
  rows.push_back(r);
}

double ConvergenceTable::last_order() const { return rows.size() < 2 ? 0.0 : rows.back().order; }

double ConvergenceTable::largest_order_deviation(double expected) const
{
  if (rows.size() < 3)
    return std::nan("");
  const std::size_t n = rows.size();
  return std::max(std::abs(rows[n - 1].order - expected), std::abs(rows[n - 2].order - expected));
}
} // namespace demvv
