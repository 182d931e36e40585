#include "app/run/input_uncertainty.h"

#include "app/decks/deck.h"
#include "app/io/input.h"
#include "app/io/text.h"

#include <cmath>
#include <cstdlib>
#include <vector>

namespace demvv
{
namespace
{
/// Whether two deck values are the same: as numbers to round-off when both
/// are numbers (a resolved deck may print a fitted value differently), else
/// as text.
bool same_value(const std::string &a, const std::string &b)
{
  char *end_a = nullptr, *end_b = nullptr;
  const double x = std::strtod(a.c_str(), &end_a), y = std::strtod(b.c_str(), &end_b);
  if (end_a != a.c_str() && *end_a == '\0' && end_b != b.c_str() && *end_b == '\0')
    return std::abs(x - y) <= 1e-9 * std::max(std::abs(x), std::abs(y));
  return trimmed(a) == trimmed(b);
}
} // namespace

double calibrated_input_uncertainty(const nlohmann::json &calibration, const std::string &quantity, std::string *why)
{
  const auto none = [&](const std::string &reason)
  {
    if (why)
      *why = reason;
    return nan;
  };
  const nlohmann::json &parameters = calibration.at("parameters");
  const nlohmann::json *target = nullptr;
  for (const nlohmann::json &t : calibration.at("targets"))
    if (t.value("quantity", "") == quantity)
      target = &t;
  if (target == nullptr)
    return none("not a target of the calibration: its sensitivity to the fitted parameters was not measured");
  const nlohmann::json &slopes = target->at("slope_per_ln_parameter");
  const double mean = json_number(*target, "fitted_mean");
  if (!slopes.is_array() || slopes.size() != parameters.size())
    return none("the record gives no slope of " + quantity + " for each fitted parameter");
  std::vector<double> g(parameters.size()), r(parameters.size());
  for (std::size_t j = 0; j < parameters.size(); ++j)
  {
    g[j] = (slopes[j].is_number() ? slopes[j].get<double>() : nan) / mean;
    r[j] = json_number(parameters[j], "relative_standard_error");
    if (!std::isfinite(g[j]) || !std::isfinite(r[j]))
      return none("the record gives no finite slope of " + quantity + " or standard error of parameter '" +
                  parameters[j].value("name", "") + "'");
  }
  const nlohmann::json correlation = calibration.value("correlation", nlohmann::json::array());
  double variance = 0;
  for (std::size_t j = 0; j < g.size(); ++j)
    for (std::size_t k = 0; k < g.size(); ++k)
    {
      double rho = j == k ? 1.0 : nan;
      if (j != k && correlation.is_array() && correlation.size() == g.size() && correlation[j].is_array() &&
          correlation[j].size() == g.size() && correlation[j][k].is_number())
        rho = correlation[j][k].get<double>();
      if (!std::isfinite(rho))
        return none("the record gives no correlation between its fitted parameters");
      variance += g[j] * g[k] * rho * r[j] * r[k];
    }
  return std::sqrt(std::max(variance, 0.0));
}

nlohmann::json input_uncertainty_block(const Deck &deck)
{
  const std::string key = calibration_record_key;
  if (!deck_declares(deck, key) || deck.text(key).empty())
    return {{"estimated", false},
            {"why", "the deck names no calibration record (calibration/record): none of its inputs was fitted by "
                    "demvv calibrate"}};
  const std::string path = deck.input_file(key);
  const nlohmann::json record =
    parse_json_input(read_input(path, "calibration record", max_summary_bytes), path, "calibration record");
  const auto refuse = [&](const std::string &what)
  { deck.fail(key, what + ": expected the calibration.json of a converged demvv calibrate run"); };
  // A record damaged or edited by hand (a field of another type) is the
  // deck's error, as a missing one is.
  nlohmann::json block;
  try
  {
    if (!record.is_object() || !record.contains("parameters") || !record["parameters"].is_array() ||
        !record.contains("targets") || !record["targets"].is_array())
      refuse("it holds no fitted parameters and targets");
    if (record.value("status", "") != "converged")
      refuse("its calibration did not converge (status '" +
             (record.contains("status") && record["status"].is_string() ? record["status"].get<std::string>() : "") +
             "')");
    nlohmann::json parameters = nlohmann::json::array();
    for (const nlohmann::json &p : record["parameters"])
    {
      if (!p.is_object() || !p.contains("keys") || !p["keys"].is_array() || !p.contains("deck_value") ||
          !p["deck_value"].is_string())
        refuse("a parameter has no keys or fitted value");
      const std::string fitted = p["deck_value"].get<std::string>();
      for (const nlohmann::json &k : p["keys"])
      {
        const std::string entry = k.is_string() ? k.get<std::string>() : "";
        if (!deck_declares(deck, entry))
          refuse("its fitted entry '" + entry + "' is not an entry of this deck");
        if (!same_value(deck.text(entry), fitted))
          deck.fail(entry, "the calibration " + path + " fitted " + fitted +
                             " here: expected the fitted value (a deck whose fitted entries changed is no longer the "
                             "calibrated one; empty calibration/record to run it without u_input)");
      }
      parameters.push_back({{"name", p.value("name", "")},
                            {"keys", p["keys"]},
                            {"value", fitted},
                            {"relative_standard_error", p.value("relative_standard_error", nlohmann::json())}});
    }
    block = {{"estimated", true},
             {"record", path},
             {"parameters", parameters},
             {"meaning",
              "u_input: the fitted parameters' standard errors (seeds and the target's own uncertainty) through "
              "the model's sensitivity to them, u_input / |q| = sqrt(sum_jk g_j g_k rho_jk r_j r_k), g_j = "
              "d ln q / d ln parameter_j from the calibration's last Jacobian (ASME V&V 20)"},
             {"applies", "the sensitivity measured at the calibration condition, carried to this run's condition as an "
                         "estimate"}};
    for (const char *quantity : calibrated_quantities)
    {
      std::string why;
      const double u = calibrated_input_uncertainty(record, quantity, &why);
      block[quantity] = std::isfinite(u) ? nlohmann::json{{"u_input_relative", u}}
                                         : nlohmann::json{{"u_input_relative", nullptr}, {"why", why}};
    }
  }
  catch (const nlohmann::json::exception &)
  {
    refuse("it cannot be read as a calibration's record (damaged or edited)");
  }
  return block;
}
} // namespace demvv
