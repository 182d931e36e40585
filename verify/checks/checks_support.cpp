#include "verify/checks/checks_support.h"

#include <cmath>
#include <stdexcept>
#include <sstream>

namespace verify
{
Deck load_case(const CheckContext &ctx, const std::string &name, const std::vector<std::string> &overrides)
{
  return Deck::from_file(ctx.cases_dir + "/" + name + "/case.prm", overrides);
}

SceneResult run_case(const CheckContext &ctx, const std::string &name, const std::vector<std::string> &overrides)
{
  return completed(name, run_scene(load_case(ctx, name, overrides), RunOptions{"", 0, false}));
}

SceneResult completed(const std::string &name, SceneResult r)
{
  if (r.status.fault)
    throw std::runtime_error(name + ": " + r.status.diagnostic());
  if (r.series.rows() == 0)
    throw std::runtime_error(name + ": the run produced no output rows");
  return r;
}

double first_crossing(const std::vector<double> &time, const std::vector<double> &values, double level)
{
  for (std::size_t k = 1; k < values.size(); ++k)
    if (values[k - 1] < level && values[k] >= level)
      return time[k - 1] + (level - values[k - 1]) / (values[k] - values[k - 1]) * (time[k] - time[k - 1]);
  return std::nan("");
}


std::string num(double v)
{
  std::ostringstream o;
  o.precision(6);
  o << v;
  return o.str();
}
} // namespace verify
