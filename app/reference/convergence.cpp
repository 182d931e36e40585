#include "app/reference/convergence.h"

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
} // namespace demvv
