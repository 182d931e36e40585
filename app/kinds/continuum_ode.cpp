#include "app/kinds/continuum_ode.h"

#include "app/reference/continuum_reference.h"

#include "continuum/burgers_ode.h"
#include "continuum/numerical_failure.h"

#include <chrono>
#include <cmath>
#include <limits>

namespace demvv
{
namespace
{
}

void declare_burgers_ode(DeckSchema &s)
{
  s.text("title", "", "One line saying what this run is for (copied to summary.json).");
  s.enter("chain");
  s.choice("scale", "contact", {"contact", "material point"},
           "What the chain is: a contact (stiffnesses N/m, viscosities N s/m, displacement m, force N) or a "
           "material point in one dimension (moduli Pa, viscosities Pa s, strain, stress Pa; compression "
           "positive).");
  s.real("maxwell spring", 1e6, 0, inf, "N/m or Pa", "Maxwell spring K0 (thesis Table 7.1: 1 MN/m).",
         Interval::open_below);
  s.real("maxwell dashpot", 1e6, 0, inf, "N s/m or Pa s", "Maxwell dashpot C_inf (Table 7.1: 1 MN s/m).",
         Interval::open_below);
  s.real("kelvin spring", 1e6, 0, inf, "N/m or Pa", "Kelvin spring K1 (Table 7.1: 1 MN/m).", Interval::open_below);
  s.real("kelvin dashpot", 1e6, 0, inf, "N s/m or Pa s", "Kelvin dashpot C1 (Table 7.1: 1 MN s/m).",
         Interval::open_below);
  s.leave();
  s.enter("loading");
  s.choice("control", "displacement", {"displacement", "force"},
           "What is prescribed: the displacement (strain) history, or the force (stress) history.");
  s.choice("history", "constant rate", {"constant rate", "ramp and hold", "cyclic", "step"},
           "Shape of the prescribed history from rest: x = rate t; x = rate min(t, ramp time); "
           "x = amplitude sin(2 pi frequency t); x = level for t > 0.  Under force control only 'step' "
           "(creep, eq. 2.15) has a closed form and is accepted.");
  s.real("rate", 1, -inf, inf, "m/s or 1/s",
         "Displacement (strain) rate of 'constant rate' and 'ramp and hold' "
         "(Table 7.1: 1 m/s).");
  s.real("ramp time", 1, 0, inf, "s", "End of the ramp of 'ramp and hold'.", Interval::open_below);
  s.real("amplitude", 0.1, -inf, inf, "m or -", "Displacement (strain) amplitude of 'cyclic'.");
  s.real("frequency", 1, 0, inf, "Hz", "Frequency of 'cyclic'.", Interval::open_below);
  s.real("level", 1e6, -inf, inf, "N, Pa, m or -",
         "Level of 'step': a force (stress) under force control, a displacement (strain) otherwise.");
  s.real("duration", 5, 0, inf, "s", "Simulated time.", Interval::open_below);
  s.leave();
  s.enter("solver");
  s.real("relative tolerance", 1e-8, 0, 1e-2, "-", "CVODE relative tolerance rtol.", Interval::open_below);
  s.real("absolute tolerance", 0, 0, inf, "m or -",
         "CVODE absolute tolerance of the displacements (the force's is K0 times it); 0 selects 1e-3 rtol times "
         "the largest displacement of the history.");
  s.integer("max steps", 1000000, 1, std::numeric_limits<int>::max(), "Largest number of CVODE steps.");
  s.leave();
  s.enter("output");
  s.real("interval", 0.01, 0, inf, "s", "Time between output rows.", Interval::open_below);
  s.leave();
}

namespace
{
using continuum::Control;
using continuum::History;

History read_history(const Deck &deck)
{
  const std::string shape = deck.text("loading/history");
  if (shape == "ramp and hold")
    return History::ramp_and_hold(deck.real("loading/rate"), deck.real("loading/ramp time"));
  if (shape == "cyclic")
    return History::cyclic(deck.real("loading/amplitude"), deck.real("loading/frequency"));
  if (shape == "step")
    return History::step(deck.real("loading/level"));
  return History::constant_rate(deck.real("loading/rate"));
}

/// Column names with unit suffixes for a contact or a material point.
struct Units
{
  std::string displacement, force, closed_form, kelvin, dashpot;
};

Units units(bool contact, Control control)
{
  Units u = contact ? Units{"displacement_m", "force_n", "", "kelvin_displacement_m", "maxwell_dashpot_displacement_m"}
                    : Units{"strain", "stress_pa", "", "kelvin_strain", "maxwell_viscous_strain"};
  if (control == Control::displacement)
    u.closed_form = contact ? "force_closed_form_n" : "stress_closed_form_pa";
  else
    u.closed_form = contact ? "displacement_closed_form_m" : "strain_closed_form";
  return u;
}
} // namespace

BurgersOdeSpec parse_burgers_ode(const Deck &deck)
{
  BurgersOdeSpec spec;
  spec.deck = DeckRecord(deck);
  spec.title = deck.text("title");
  spec.chain = {deck.real("chain/maxwell spring"), deck.real("chain/maxwell dashpot"), deck.real("chain/kelvin spring"),
                deck.real("chain/kelvin dashpot")};
  spec.contact = deck.text("chain/scale") == "contact";
  spec.control_name = deck.text("loading/control");
  spec.history_name = deck.text("loading/history");
  spec.control = spec.control_name == "force" ? Control::force : Control::displacement;
  spec.history = read_history(deck);
  if (!has_closed_form(spec.control, spec.history))
    deck.fail("loading/history", "expected 'step' under force control (creep, eq. 2.15, is the closed form "
                                 "demvv checks a prescribed force against)");
  spec.duration = deck.real("loading/duration");
  spec.interval = deck.real("output/interval");
  if (spec.interval > spec.duration || spec.duration / spec.interval > 1e7)
    deck.fail("output/interval",
              "expected an interval between duration / 1e7 and the duration (" + std::to_string(spec.duration) + " s)");
  spec.tolerances.relative = deck.real("solver/relative tolerance");
  spec.tolerances.absolute = deck.real("solver/absolute tolerance");
  spec.tolerances.max_steps = deck.integer("solver/max steps");
  return spec;
}

OdeResult run_burgers_ode(const Deck &deck, const RunOptions &options)
{
  return run_burgers_ode(parse_burgers_ode(deck), options);
}

OdeResult run_burgers_ode(const BurgersOdeSpec &spec, const RunOptions &options)
{
  const int threads = apply_threads(options);
  const continuum::BurgersChain &chain = spec.chain;
  const Control control = spec.control;
  const History &history = spec.history;
  const double duration = spec.duration, interval = spec.interval;
  const bool contact = spec.contact;
  const Units u = units(contact, control);

  std::vector<double> times;
  const auto rows = static_cast<long>(std::floor(duration / interval + 1e-9));
  for (long k = 0; k <= rows; ++k)
    times.push_back(k * interval);
  if (times.back() < duration)
    times.push_back(duration);

  OdeResult result;
  result.series = Series({"time_s", u.displacement, u.force, u.closed_form, u.kelvin, u.dashpot});
  std::unique_ptr<RunDirectory> dir;
  if (!options.out_dir.empty())
  {
    dir = std::make_unique<RunDirectory>(options.out_dir, spec.deck, threads, 0);
    result.series.stream_to(dir->path("series.csv"), "demvv burgers_ode '" + spec.deck.name +
                                                       "': SUNDIALS CVODE (BDF) solution and " +
                                                       closed_form_name(control, history) + "; SI units" +
                                                       (contact ? "" : "; compression positive"));
  }

  const continuum::OdeTolerances &tolerances = spec.tolerances;
  continuum::OdeStatistics statistics;
  const auto start = std::chrono::steady_clock::now();
  double largest_error = 0, largest_reference = 0;
  try
  {
    const continuum::BurgersOde ode(chain, control, history);
    ode.solve(
      times, tolerances,
      [&](const continuum::OdeState &s)
      {
        const double reference = closed_form(chain, control, history, s.time);
        const double computed = control == Control::displacement ? s.force : s.displacement;
        largest_error = std::max(largest_error, std::abs(computed - reference));
        largest_reference = std::max(largest_reference, std::abs(reference));
        result.series.add({s.time, s.displacement, s.force, reference, s.kelvin, s.dashpot});
      },
      &statistics);
    result.status.time = duration;
  }
  catch (const continuum::NumericalFailure &f)
  {
    record_failure(result.status, f);
  }
  result.status.steps = statistics.steps;
  result.status.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  result.relative_error = largest_reference > 0 ? largest_error / largest_reference : std::nan("");

  const std::string stiffness = contact ? "n_per_m" : "pa", viscosity = contact ? "n_s_per_m" : "pa_s";
  result.summary = {
    {"kind", "burgers_ode"},
    {"title", spec.title},
    {"status", result.status.to_json()},
    {"scale", contact ? "contact" : "material point"},
    {"chain",
     {{"maxwell_spring_" + stiffness, chain.maxwell_spring},
      {"maxwell_dashpot_" + viscosity, chain.maxwell_dashpot},
      {"kelvin_spring_" + stiffness, chain.kelvin_spring},
      {"kelvin_dashpot_" + viscosity, chain.kelvin_dashpot}}},
    {"loading", {{"control", spec.control_name}, {"history", spec.history_name}, {"duration_s", duration}}},
    {"solver",
     {{"method", "SUNDIALS CVODE, BDF, Newton with exact dense Jacobian"},
      {"relative_tolerance", tolerances.relative},
      {"absolute_tolerance_displacement", statistics.absolute_tolerance},
      {"steps", statistics.steps},
      {"rhs_evaluations", statistics.rhs_evaluations},
      {"jacobian_evaluations", statistics.jacobian_evaluations},
      {"error_test_failures", statistics.error_test_failures},
      {"restarts_at_kinks", statistics.restarts}}},
    {"closed_form", closed_form_name(control, history)},
    {"max_abs_error", largest_error},
    {"max_relative_error",
     std::isfinite(result.relative_error) ? nlohmann::json(result.relative_error) : nlohmann::json(nullptr)},
    {"relative_error_over_rtol", std::isfinite(result.relative_error)
                                   ? nlohmann::json(result.relative_error / tolerances.relative)
                                   : nlohmann::json(nullptr)},
    {"wall_seconds", result.status.wall_seconds}};
  if (dir)
    dir->write_summary(result.summary);
  return result;
}
} // namespace demvv
