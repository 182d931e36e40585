#include "app/run/numerical_uncertainty.h"

#include "app/io/input.h"
#include "app/io/text.h"

#include "build_info.h"

#include <cmath>
#include <filesystem>
#include <limits>

namespace demvv
{
std::string time_step_study_dir() { return std::string(build_info::source_dir) + "/cases/s02_time_step_study"; }

namespace
{
nlohmann::json not_estimated(const std::string &why) { return {{"estimated", false}, {"why", why}}; }
} // namespace

nlohmann::json numerical_time_step_uncertainty(double balls, double safety, double local_damping,
                                               const std::string &study_dir)
{
  namespace fs = std::filesystem;
  std::error_code ec;
  std::string best;
  double best_balls = 0, best_distance = inf;
  for (const fs::directory_entry &e : fs::directory_iterator(study_dir, ec))
  {
    const std::string name = e.path().filename().string();
    if (name.rfind("results_", 0) != 0 || e.path().extension() != ".json")
      continue;
    const double n = std::atof(name.c_str() + 8);
    const double distance = std::abs(std::log(n / balls));
    if (n > 0 && distance < best_distance)
    {
      best = e.path().string();
      best_balls = n;
      best_distance = distance;
    }
  }
  if (best.empty())
    return not_estimated("no time-step study found in " + study_dir);
  if (best_distance > std::log(2.0))
    return not_estimated("no time-step study of a sample within a factor of two of " +
                         std::to_string(static_cast<long>(balls)) + " balls (the nearest has " +
                         std::to_string(static_cast<long>(best_balls)) + ")");
  try
  {
    const nlohmann::json study =
      parse_json_input(read_input(best, "time-step study", max_summary_bytes), best, "time-step study");
    const nlohmann::json &quantities = study.at("quantities");
    // Steps as fractions of the undamped bound (header note); the finest
    // studied level at or above the run's step.
    const double step_fraction = safety / std::sqrt(1 + local_damping);
    const double study_damping =
      study.value("safety_bound", "") == "damped" ? study.at("local_damping").get<double>() : 0.0;
    const auto level_fraction = [&](const nlohmann::json &l) {
      return l.at("safety").get<double>() / std::sqrt(1 + study_damping);
    };
    const nlohmann::json &peak_levels = quantities.at("peak_stress_pa").at("levels");
    std::size_t level = peak_levels.size();
    for (std::size_t i = 0; i < peak_levels.size(); ++i)
      if (level_fraction(peak_levels[i]) >= step_fraction * (1 - 1e-12))
        level = i;
    if (level == peak_levels.size())
      return not_estimated("the time step (safety " + format_number(safety) + " under local damping " +
                           format_number(local_damping) + ", " + format_number(step_fraction) +
                           " of the undamped bound) is coarser than every level of the study " + best);
    nlohmann::json block = {{"estimated", true},
                            {"study", fs::path(best).filename().string()},
                            {"study_balls", best_balls},
                            {"step_fraction_of_undamped_bound", step_fraction},
                            {"study_safety", peak_levels[level].at("safety")},
                            {"study_step_fraction_of_undamped_bound", level_fraction(peak_levels[level])},
                            {"study_seeds", study.at("seeds")},
                            {"study_build", study.at("provenance").at("sources_sha256")},
                            {"study_date", study.at("provenance").at("started_utc")},
                            {"meaning", "U_num: a 95 % bound on the time-step error at this safety, relative to the "
                                        "ensemble mean; u_num = U_num / 2 as a standard uncertainty (ASME V&V 20)"},
                            {"applies", "measured on the recipe of cases/t66_friction (thesis §6.2, 0.01 m/s, "
                                        "friction 0.5); other laws, rates or strengths carry it over as an "
                                        "estimate"}};
    for (const auto &[name, q] : quantities.items())
    {
      const nlohmann::json &l = q.at("levels").at(level);
      const nlohmann::json bound = l.at("u_num_bound_relative");
      block[name] = {{"u_num_bound_relative_95", bound},
                     {"u_num_relative", bound.is_number() ? nlohmann::json(bound.get<double>() / 2) : bound}};
    }
    return block;
  }
  catch (const nlohmann::json::exception &e)
  {
    return not_estimated(best + ": not a readable time-step study (" + e.what() + ")");
  }
  catch (const std::runtime_error &e)
  {
    return not_estimated(e.what());
  }
}
} // namespace demvv
