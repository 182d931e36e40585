// Burger's contact checks (V14-V17): the law's
// Crank-Nicolson update against its closed forms (burgers_closed_form.h),
// two-ball pulls from cases/ exactly as `demvv run` does them, viscosity
// scaling (eq. 7.21) and its counter-example, and the displacement
// criterion of appendix A.
#include "verify/checks/checks_burgers.h"

#include "verify/checks/checks_support.h"

#include "dem/contact_model.h"
#include "dem/law_burgers.h"
#include "dem/rate_scaling.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace demvv
{
namespace
{
/// Thesis Table 7.1 / A.1: every constant 1 (MN/m, MN s/m).
dem::BurgersConstants table_7_1() { return {1e6, 1e6, 1e6, 1e6}; }

/// The normal element's constants of a run's Burger's law.
dem::BurgersConstants normal_constants(const dem::Simulation &sim)
{
  if (const auto *m = dynamic_cast<const dem::LawModel<dem::BurgersLaw> *>(&sim.model()))
    return m->law().constants().normal;
  throw std::runtime_error("the run does not use the burgers contact law");
}

/// One pulled pair: time, extension u = -overlap [m] and tensile force [N]
/// while the bond holds.
struct Pull
{
  std::vector<double> time, extension, tension;
  double speed = 0; ///< m/s, prescribed
  double dt = 0;    ///< s
  long steps = 0;
  dem::BurgersConstants law;        ///< as the run used them (after any scaling)
  double bond_strength = 0;         ///< N, normal strength at the end
  double break_time = std::nan(""); ///< s, first row with the bond broken
};

Pull pull(const CheckContext &ctx, const std::string &name, const std::vector<std::string> &overrides = {})
{
  const SceneResult r = run_case(ctx, name, overrides);
  Pull p;
  p.law = normal_constants(*r.sim);
  p.dt = r.series.column("time_step_s").back();
  p.steps = r.sim->steps();
  p.bond_strength = r.sim->contacts().size() ? r.sim->contacts()[0].bond.normal_strength : 0;
  const auto t = r.contacts.column("time_s"), overlap = r.contacts.column("overlap_m");
  const auto fn = r.contacts.column("normal_force_n"), bonded = r.contacts.column("bonded");
  for (std::size_t k = 0; k < t.size(); ++k)
  {
    if (bonded[k] != 1)
    {
      p.break_time = t[k];
      break;
    }
    p.time.push_back(t[k]);
    p.extension.push_back(-overlap[k]);
    p.tension.push_back(-fn[k]);
  }
  p.speed = p.time.size() > 1 ? (p.extension.back() - p.extension.front()) / (p.time.back() - p.time.front()) : 0;
  return p;
}

/// max |F(u) - closed form(u)| / (C_inf v) over a pull, the closed form for
/// `law` at speed `v` evaluated at t = u / v.
double curve_error(const Pull &p, const dem::BurgersConstants &law, double v)
{
  double e = 0;
  for (std::size_t k = 0; k < p.time.size(); ++k)
    e = std::max(e, std::abs(p.tension[k] - law.constant_velocity_force(p.extension[k] / v, v)));
  return e / (law.maxwell_viscosity * v);
}

/// The error a pull may carry against its closed form, relative to
/// C_inf v: the trapezoidal rule's on the fastest Burger's mode,
/// (lambda_2 dt)^2 / 12, plus one rounding of the force per step
/// (steps x 2.2e-16), which dominates where lambda_2 dt is small (Table
/// 7.1's own scale: lambda_2 dt ~ 3e-6, 780 000 steps).
double pull_tolerance(const Pull &p)
{
  const double x = p.law.lambda2() * p.dt;
  return x * x / 12 + static_cast<double>(p.steps) * std::numeric_limits<double>::epsilon();
}

/// The largest gap between two closed forms over a pull's extensions,
/// relative to C_inf v of the second: F_a(u / v_a) at v_a against F_b(u / v_b)
/// at v_b.
double closed_form_gap(const Pull &p, const dem::BurgersConstants &a, double v_a, const dem::BurgersConstants &b,
                       double v_b)
{
  double g = 0;
  for (double u : p.extension)
    g = std::max(g, std::abs(a.constant_velocity_force(u / v_a, v_a) - b.constant_velocity_force(u / v_b, v_b)));
  return g / (b.maxwell_viscosity * v_b);
}

/// Overrides of the v15 deck for a pull at thesis Table 7.1's own scale:
/// the balls file of `speed` ("1" or "100" m/s), run for 1 m of extension,
/// the viscosities as given (MN s/m in N s/m), 2000 rows.
std::vector<std::string> table_7_1_pull(const std::string &speed, const std::string &maxwell_viscosity,
                                        const std::string &kelvin_viscosity)
{
  const std::string duration = speed == "1" ? "1" : "0.01";
  std::vector<std::string> o = {speed == "1" ? "particles/file=balls_fast.csv" : "particles/file=balls_100.csv",
                                "run/duration=" + duration, "output/interval=" + num(std::stod(duration) / 2000)};
  for (const char *element : {"normal", "shear"})
  {
    o.push_back(std::string("contact law/") + element + " maxwell viscosity=" + maxwell_viscosity);
    o.push_back(std::string("contact law/") + element + " kelvin viscosity=" + kelvin_viscosity);
  }
  return o;
}
} // namespace

CheckOutcome check_burgers_update(const CheckContext & /*ctx*/)
{
  CheckOutcome out;
  const dem::BurgersContactConstants k{table_7_1(), table_7_1(), 0};
  const dem::BurgersLaw law(k);
  const dem::ContactParams none;
  // --- order of the CN update at constant velocity (eq. 7.18) -------------
  // The law alone, driven by a prescribed overlap history U = -v t (a pull).
  const double v = 1, horizon = 2;
  const auto pull_error = [&](double dt)
  {
    dem::BurgersHistory h;
    const long n = std::lround(horizon / dt);
    double f = 0;
    for (long s = 1; s <= n; ++s)
    {
      const double overlap = -v * dt * static_cast<double>(s);
      f = law.normal_force(none, overlap, h, dt);
      law.commit(h, overlap, f, dem::Vec3::Zero(), dem::Vec3::Zero(), dt);
    }
    return std::abs(-f - k.normal.constant_velocity_force(horizon, v)) / (k.normal.maxwell_viscosity * v);
  };
  ConvergenceTable table;
  table.title = "Crank-Nicolson update of a Burger's contact pulled at constant velocity, Table 7.1 constants";
  table.h_name = "dt [s]";
  table.error_name = "|f(2 s) - eq. 7.18| / (C_inf v)";
  table.expected_order = 2;
  for (double dt : {0.1, 0.05, 0.025, 0.0125, 0.00625})
    table.add(dt, pull_error(dt));
  out.tables.push_back(table);
  out.metrics.push_back(bound("|observed order - 2| over the finest two halvings", table.largest_order_deviation(2),
                              0.05, false, ToleranceClass::B,
                              "the trapezoidal rule is second order; with dt |lambda_2| <= 0.1 "
                              "the next term shifts the observed order by less than 0.05"));
  // --- stiff limit: K_k dt / (2 C_k) > 1 -----------------------------------
  // Load the element, then let it carry no force (as an unbonded contact
  // pulled apart does): the Kelvin displacement recovers, exactly as
  // u_k e^{-K_k t / C_k}, monotonically.  The scheme multiplies it by B/A
  // per step: for K_k dt / (2 C_k) > 1, B/A < 0 and u_k changes sign every
  // step while shrinking (A-stable, not L-stable).
  struct Recovery
  {
    int sign_changes = 0;
    double ratio = 0; ///< u_k after / before, last step
  };
  const auto recover = [&](double dt)
  {
    dem::BurgersHistory h;
    double overlap = 0;
    for (int s = 0; s < 3; ++s)
    {
      overlap -= 1e-6;
      law.commit(h, overlap, law.normal_force(none, overlap, h, dt), dem::Vec3::Zero(), dem::Vec3::Zero(), dt);
    }
    law.commit(h, overlap, 0.0, dem::Vec3::Zero(), dem::Vec3::Zero(), dt);
    Recovery r;
    for (int s = 0; s < 9; ++s)
    {
      const double before = h.normal_kelvin;
      law.commit(h, overlap, 0.0, dem::Vec3::Zero(), dem::Vec3::Zero(), dt);
      r.sign_changes += h.normal_kelvin * before < 0 ? 1 : 0;
      r.ratio = h.normal_kelvin / before;
    }
    return r;
  };
  const dem::BurgersConstants &kn = k.normal;
  for (const double dt : {6.0, 0.1})
  {
    const double kappa = kn.kelvin_stiffness * dt / (2 * kn.kelvin_viscosity);
    const Recovery r = recover(dt);
    const std::string label = "K_k dt / 2C_k = " + num(kappa) + ": ";
    out.metrics.push_back(relative_error(label + "Kelvin recovery factor per step vs (1 - k)/(1 + k)", r.ratio,
                                         (1 - kappa) / (1 + kappa), 1e-12, ToleranceClass::A,
                                         "eq. 3.26 with zero force is u_k <- (B/A) u_k"));
    if (kappa > 1)
      out.metrics.push_back(bound(label + "sign changes of u_k in 9 steps (exact: none)", r.sign_changes, 9, true,
                                  ToleranceClass::A,
                                  "documented stiff-limit behaviour: B/A < 0 flips the sign every step"));
    else
      out.metrics.push_back(bound(label + "sign changes of u_k in 9 steps", r.sign_changes, 0, false, ToleranceClass::A,
                                  "B/A > 0: monotone recovery, as exact"));
    out.notes.push_back(label + "recovery factor " + num(r.ratio) + " per step against the exact " +
                        num(std::exp(-2 * kappa)) + ".");
  }
  out.notes.push_back("Stiff limit: with K_k dt / (2 C_k) > 1 the Crank-Nicolson update stays bounded (A-stable) "
                      "but the Kelvin displacement oscillates step to step instead of relaxing (not L-stable). "
                      "DEM steps are far below this limit (here K_k dt / 2C_k ~ 1e-6 in the pulls).");
  return out;
}

CheckOutcome check_burgers_pull(const CheckContext &ctx)
{
  CheckOutcome out;
  const Pull p = pull(ctx, "v15_burgers_pull");
  out.metrics.push_back(bound("max |F - eq. 7.18| / (C_inf v) over the pull", curve_error(p, p.law, p.speed),
                              pull_tolerance(p), false, ToleranceClass::B,
                              "trapezoidal error of the fastest mode, (lambda_2 dt)^2 / 12, and a rounding per step"));
  out.metrics.push_back(relative_error("force at the end vs eq. 7.18", p.tension.back(),
                                       p.law.constant_velocity_force(p.time.back(), p.speed), 1e-6, ToleranceClass::B,
                                       "as above, at one time"));
  std::vector<double> closed;
  for (double u : p.extension)
    closed.push_back(p.law.constant_velocity_force(u / p.speed, p.speed));
  out.figures.push_back(
    make_figure("pull", "Burger's contact pulled at constant speed", "extension [mm]", "tensile force [N]",
                {curve("demvv", p.extension, p.tension), curve("eq. 7.18", p.extension, closed, CurveStyle::dashed)},
                "The contact force at every step beside the closed form at the same extension."));
  std::vector<double> residual;
  const double scale = p.law.maxwell_viscosity * p.speed, tolerance = pull_tolerance(p);
  for (std::size_t k = 0; k < closed.size(); ++k)
    residual.push_back((p.tension[k] - closed[k]) / scale);
  out.figures.push_back(make_figure("pull_residual", "Residual of the pull against eq. 7.18", "extension [mm]",
                                    "(F - F_7.18) / (C_inf v) [-]", {curve("residual", p.extension, residual)},
                                    "The metric is the largest |residual|; it passes inside the dashed band."));
  add_band(out.figures.back(), "tolerance", p.extension.front(), p.extension.back(), -tolerance, tolerance);
  for (Figure &f : out.figures)
    for (Curve &c : f.curves)
      c.x_scale = 1e3;
  out.notes.push_back("Pulled at " + num(p.speed) + " m/s for " + num(p.time.back()) + " s in " +
                      std::to_string(p.steps) + " steps; f(end) = " + num(p.tension.back()) +
                      " N, C_inf v = " + num(p.law.maxwell_viscosity * p.speed) + " N.");
  if (!ctx.quick)
  {
    // The thesis's own pull (Table 7.1: every constant 1 MN/m or MN s/m,
    // 1 m/s, 1 s), not its eq. 7.21 image at 1/100 of the time scale.
    const Pull thesis = pull(ctx, "v15_burgers_pull", table_7_1_pull("1", "1e6", "1e6"));
    out.metrics.push_back(
      bound("Table 7.1 scale (1 m/s, 1 s): max |F - eq. 7.18| / (C_inf v)",
            curve_error(thesis, thesis.law, thesis.speed), pull_tolerance(thesis), false, ToleranceClass::B,
            "trapezoidal error of the fastest mode, (lambda_2 dt)^2 / 12, and a rounding per step"));
    out.notes.push_back("Table 7.1 scale: " + std::to_string(thesis.steps) +
                        " steps, f(1 s) = " + num(thesis.tension.back()) + " N against eq. 7.18's " +
                        num(thesis.law.constant_velocity_force(thesis.time.back(), thesis.speed)) + " N.");
  }
  return out;
}

namespace
{
/// Eq. 7.21's claim on a viscosity-scaled pull: its force-displacement
/// curve is the closed form of `law` at speed `v`, to the run's own error.
Metric same_curve(const std::string &name, const Pull &run, const dem::BurgersConstants &law, double v)
{
  return bound(name, curve_error(run, law, v), pull_tolerance(run), false, ToleranceClass::B,
               "eq. 7.21 is exact; the run's own trapezoidal error, (lambda_2 dt)^2/12, and a rounding per step");
}

/// Figs. 7.8-7.10 at thesis Table 7.1's own scale (every constant 1 MN/m
/// or MN s/m, 1 m/s).  The thesis's slow pull (0.01 m/s for 100 s, 8e7
/// steps) is represented by its closed form, which V15 holds the engine to;
/// the engine runs every fast pull.
void table_7_1_scaling(const CheckContext &ctx, CheckOutcome &out)
{
  const dem::BurgersConstants unscaled = table_7_1();
  const double v = 1, slow = v / 100;
  // Fig. 7.9 / 7.10(a): both viscosities / 100 at 1 m/s against 1/100 of the velocity.
  const Pull both = pull(ctx, "v15_burgers_pull", table_7_1_pull("1", "1e4", "1e4"));
  out.metrics.push_back(same_curve("Table 7.1 scale, both viscosities / 100 at 1 m/s: max |F(u) - eq. 7.18 at "
                                   "0.01 m/s| / (C_inf v)",
                                   both, unscaled, slow));
  // Fig. 7.8: C_inf alone / 100 at 1 m/s against 1/100 of the velocity.
  const Pull c_inf = pull(ctx, "v15_burgers_pull", table_7_1_pull("1", "1e4", "1e6"));
  const double expected_gap = closed_form_gap(c_inf, c_inf.law, v, unscaled, slow);
  out.metrics.push_back(bound("Table 7.1 scale, C_inf alone / 100: max gap to the curve at 0.01 m/s / (C_inf v)",
                              curve_error(c_inf, unscaled, slow), 0.5 * expected_gap, true, ToleranceClass::B,
                              "Fig. 7.8's counter-example: the closed forms differ by " + num(expected_gap) +
                                " of C_inf v; at least half of that"));
  // Fig. 7.10(b): 100 m/s with both viscosities / 100 against the unscaled pull.
  const Pull fast = pull(ctx, "v15_burgers_pull", table_7_1_pull("100", "1e4", "1e4"));
  out.metrics.push_back(same_curve("Table 7.1 scale, 100 m/s with both viscosities / 100: max |F(u) - eq. 7.18 at "
                                   "1 m/s| / (C_inf v)",
                                   fast, unscaled, v));
  out.notes.push_back("Table 7.1 scale: " + std::to_string(both.steps) + " + " + std::to_string(c_inf.steps) + " + " +
                      std::to_string(fast.steps) + " steps; the unscaled slow pull would take " + num(100 / both.dt) +
                      " steps.");
}
} // namespace

CheckOutcome check_viscosity_scaling(const CheckContext &ctx)
{
  CheckOutcome out;
  const Pull slow = pull(ctx, "v15_burgers_pull");
  const std::vector<std::string> fast = {"particles/file=balls_fast.csv", "run/duration=3e-4"};
  std::vector<std::string> scaled = fast;
  scaled.insert(scaled.end(), {"rate/physical strain rate=1", "rate/run strain rate=100", "rate/dependence=bonds"});
  const Pull both = pull(ctx, "v15_burgers_pull", scaled);
  std::vector<std::string> only = fast;
  only.push_back("contact law/normal maxwell viscosity=100");
  const Pull c_inf = pull(ctx, "v15_burgers_pull", only);

  // Eq. 7.21: 100 v with both viscosities / 100 gives the unscaled curve.
  out.metrics.push_back(relative_error("run speed / represented speed", both.speed / slow.speed, 100, 1e-9,
                                       ToleranceClass::A, "the fast pull runs 100 times faster"));
  out.metrics.push_back(
    bound("both viscosities / 100 at 100 v: max |F(u) - unscaled eq. 7.18| / (C_inf v)",
          curve_error(both, slow.law, slow.speed), pull_tolerance(both), false, ToleranceClass::B,
          "eq. 7.21 is exact; the fast run's own trapezoidal error, (lambda_2 dt)^2/12, and a rounding per step"));
  // The thesis's counter-example (Fig. 7.8): C_inf alone scaled.
  const double expected_gap = closed_form_gap(c_inf, c_inf.law, c_inf.speed, slow.law, slow.speed);
  out.metrics.push_back(bound("C_inf alone / 100 at 100 v: max |F(u) - its own eq. 7.18| / (C_inf v)",
                              curve_error(c_inf, c_inf.law, c_inf.speed), pull_tolerance(c_inf), false,
                              ToleranceClass::B, "the engine follows the scaled law's own closed form"));
  out.metrics.push_back(bound("C_inf alone / 100: max gap to the unscaled curve / (C_inf v)",
                              curve_error(c_inf, slow.law, slow.speed), 0.5 * expected_gap, true, ToleranceClass::B,
                              "the counter-example must differ from the unscaled curve (closed forms differ by " +
                                num(expected_gap) + " of C_inf v); at least half of that"));
  std::vector<double> closed;
  for (double u : slow.extension)
    closed.push_back(slow.law.constant_velocity_force(u / slow.speed, slow.speed));
  out.figures.push_back(make_figure(
    "viscosity_scaling", "Viscosity scaling: one pull at its speed and at 100 times it", "extension [mm]",
    "tensile force [N]",
    {curve("demvv, unscaled", slow.extension, slow.tension),
     curve("demvv, both viscosities / 100 at 100 v", both.extension, both.tension),
     curve("demvv, C_inf alone / 100 at 100 v", c_inf.extension, c_inf.tension),
     curve("eq. 7.18, unscaled", slow.extension, closed, CurveStyle::dashed)},
    "Dividing both viscosities by the speed-up gives the unscaled force-extension curve (eq. 7.21); scaling the "
    "Maxwell viscosity C_inf alone, the thesis's counter-example (Fig. 7.8), does not."));
  for (Curve &c : out.figures.back().curves)
    c.x_scale = 1e3;
  // Rate-dependent bond strength at the physical rate, not the run's.
  const dem::RateLaw rate;
  out.metrics.push_back(relative_error("bond strength factor with scaling on vs eq. 7.23 at the physical rate",
                                       both.bond_strength / 1e9, rate.strength_factor(1, 283), 1e-12, ToleranceClass::A,
                                       "(1 / 0.1)^0.29 at 283 K, not (100 / 0.1)^0.29"));
  out.notes.push_back("Cost: unscaled " + std::to_string(slow.steps) + " steps, viscosity-scaled " +
                      std::to_string(both.steps) + " steps for the same force-displacement curve.");
  if (!ctx.quick)
    table_7_1_scaling(ctx, out);
  return out;
}

CheckOutcome check_displacement_criterion(const CheckContext &ctx)
{
  CheckOutcome out;
  const double delta_c = 0.015e-3;
  std::vector<std::string> speeds = {"1e-4", "1e-3", "1e-2"};
  if (!ctx.quick)
    speeds.insert(speeds.begin(), "1e-5");
  double previous_peak = std::nan("");
  Figure figure = make_figure(
    "displacement_criterion", "Displacement criterion: pulls at several speeds", "extension [mm]", "tensile force [N]",
    {},
    "Each bond breaks (its curve ends) at the same extension delta_c whatever the speed, at the force eq. 7.18 "
    "gives there: the faster pull carries more force to the same extension (thesis Fig. A.1).");
  for (const std::string &v : speeds)
  {
    const double speed = std::stod(v);
    const Pull p = pull(ctx, "v17_displacement_criterion",
                        {"particles/file=balls_" + v + ".csv", "run/duration=" + num(2 * delta_c / speed)});
    // One colour per speed: the pull and its closed form.
    const int colour = static_cast<int>(figure.curves.size() / 2) + 1;
    figure.curves.push_back(thinned(curve("demvv, v = " + v + " m/s", p.extension, p.tension)));
    figure.curves.back().colour = colour;
    std::vector<double> law;
    for (double u : p.extension)
      law.push_back(u <= delta_c ? p.law.constant_velocity_force(u / speed, speed) : 0.0);
    figure.curves.push_back(
      thinned(curve("eq. 7.18 to delta_c, v = " + v + " m/s", p.extension, law, CurveStyle::dashed)));
    figure.curves.back().colour = colour;
    const double u_break = speed * p.break_time;
    out.metrics.push_back(relative_error("v = " + v + " m/s: extension at the break vs delta_c", u_break, delta_c,
                                         speed * p.dt / delta_c, ToleranceClass::C,
                                         "the break is detected at the first step past delta_c (v dt)"));
    const double peak = *std::max_element(p.tension.begin(), p.tension.end());
    const double closed = p.law.constant_velocity_force(delta_c / speed, speed);
    out.metrics.push_back(relative_error("v = " + v + " m/s: peak force vs eq. 7.18 at u = delta_c", peak, closed,
                                         p.law.maxwell_stiffness * speed * p.dt / closed + 1e-6, ToleranceClass::C,
                                         "the last bonded step is within dt of delta_c / v, where the "
                                         "force rises at most K_0 v"));
    if (!std::isnan(previous_peak))
      out.metrics.push_back(bound("v = " + v + " m/s: peak force above that of the next slower pull [N]", peak,
                                  previous_peak, true, ToleranceClass::C,
                                  "thesis Fig. A.1: the peak force grows with the velocity"));
    previous_peak = peak;
    out.notes.push_back("v = " + v + " m/s: break at u = " + num(u_break) + " m, peak " + num(peak) + " N");
  }
  for (Curve &c : figure.curves)
    c.x_scale = 1e3;
  out.figures.push_back(std::move(figure));
  return out;
}
} // namespace demvv
