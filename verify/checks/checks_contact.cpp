// Contact-level code verification (V01, V02, V03, V05): each
// check runs a case deck from cases/ exactly as `demvv run` would and
// compares its series with the closed form of the law (law_linear.h).
#include "verify/checks/checks_contact.h"

#include "verify/checks/checks_support.h"

#include "app/run/analysis.h"
#include "dem/law_linear.h"

#include <algorithm>
#include <cmath>

namespace demvv
{
namespace
{
double first_row_value(const Series &s, const std::string &column) { return s.column(column).front(); }

/// The steps of an impact: the first and last times with a positive force and
/// the largest force.
struct Pulse
{
  double first = std::nan(""), last = std::nan(""), peak_force = 0;
};

Pulse pulse(const std::vector<double> &t, const std::vector<double> &force)
{
  Pulse p;
  for (std::size_t k = 0; k < t.size(); ++k)
    if (force[k] > 0)
    {
      p.first = std::isnan(p.first) ? t[k] : p.first;
      p.last = t[k];
      p.peak_force = std::max(p.peak_force, force[k]);
    }
  return p;
}

/// The measured force of an impact beside the closed-form half sine
/// F_max sin(omega (t - t_0)), t_0 putting its centre on the measured pulse's,
/// and under it their difference (the two curves coincide to the eye).
std::vector<Figure> impact_figures(const std::string &label, const std::vector<double> &t,
                                   const std::vector<double> &force, const Pulse &measured, double dt, double kn,
                                   double reduced_mass, double v_in)
{
  const double tc = dem::LinearLaw::collision_time(kn, reduced_mass);
  const double omega = dem::LinearLaw::natural_frequency(kn, reduced_mass);
  const double f_max = dem::LinearLaw::peak_force(kn, reduced_mass, v_in);
  const double t0 = 0.5 * (measured.first + measured.last + dt) - 0.5 * tc;
  std::vector<double> closed;
  for (double time : t)
    closed.push_back(time > t0 && time < t0 + tc ? f_max * std::sin(omega * (time - t0)) : 0.0);
  std::string name = label;
  for (char &c : name)
    c = c == '-' ? '_' : c;
  std::vector<double> difference;
  for (std::size_t k = 0; k < t.size(); ++k)
    difference.push_back(force[k] - closed[k]);
  Figure residual = make_figure(name + "_residual", label + " impact: demvv minus the closed form", "time [s]",
                                "force difference [N]", {curve("demvv - closed form", t, difference)},
                                "Inside the pulse the difference is the scheme's amplitude and phase error, "
                                "O((omega dt)^2) of F_max; at its two edges, where the force switches on and off "
                                "within a step, it is bounded by one step's worth of the sine's slope (F_max omega "
                                "dt, the dashed band).");
  add_band(residual, "+- F_max omega dt (one step's slope)", t.front(), t.back(), -f_max * omega * dt,
           f_max * omega * dt);
  return {make_figure(name, label + " impact: normal force", "time [s]", "normal force [N]",
                      {curve("demvv", t, force), curve("closed form (half sine)", t, closed, CurveStyle::dashed)},
                      "The closed form is placed with its centre on the measured pulse's centre; their difference "
                      "is the next figure."),
          residual};
}

/// Duration, peak force and restitution of one impact (item 1).
void impact_metrics(CheckOutcome &out, const std::string &label, const std::vector<double> &t,
                    const std::vector<double> &force, double dt, double kn, double reduced_mass, double v_in,
                    double v_out)
{
  const Pulse measured = pulse(t, force);
  const double omega_dt = dem::LinearLaw::natural_frequency(kn, reduced_mass) * dt;
  const double tc = dem::LinearLaw::collision_time(kn, reduced_mass);
  // Onset and end each fall inside one step: the force is positive on the
  // steps in (t_on, t_off), so (last - first + dt) is within one step of t_c.
  out.metrics.push_back(relative_error(label + ": contact duration, relative error",
                                       measured.last - measured.first + dt, tc, dt / tc, ToleranceClass::C,
                                       "onset and end each resolved to one step (dt / t_c)"));
  // The centred-difference solution of a linear spring has amplitude and
  // phase errors O((omega dt)^2) (both below (omega dt)^2 / 2), and
  // sampling the sine at steps misses its top by at most (omega dt)^2 / 8.
  out.metrics.push_back(relative_error(label + ": peak normal force, relative error", measured.peak_force,
                                       dem::LinearLaw::peak_force(kn, reduced_mass, v_in), omega_dt * omega_dt,
                                       ToleranceClass::B, "(omega dt)^2 bounds the amplitude and sampling errors"));
  // Energy is conserved up to the spring energy left when the force
  // switches off inside a step: at most 1/2 K (v dt)^2 against 1/2 m* v^2.
  out.metrics.push_back(relative_error(label + ": coefficient of restitution, relative error", v_out / v_in,
                                       dem::LinearLaw::restitution(), omega_dt * omega_dt, ToleranceClass::B,
                                       "spring energy at the switch-off step, (omega dt)^2"));
  for (Figure &f : impact_figures(label, t, force, measured, dt, kn, reduced_mass, v_in))
    out.figures.push_back(std::move(f));
}
} // namespace

CheckOutcome check_linear_impact(const CheckContext &ctx)
{
  CheckOutcome out;
  {
    const SceneResult r = run_case(ctx, "v01_linear_impact");
    const dem::ParticleStore &p = r.sim->particles();
    const double kn = dem::ContactTable::pair_params(p, 0, 1).kn;
    const double m_red = dem::LinearLaw::reduced_mass(p.mass[0], p.mass[1]);
    const Series b0 = r.particles.where("particle", 0), b1 = r.particles.where("particle", 1);
    const double v_in = first_row_value(b0, "vx_mps") - first_row_value(b1, "vx_mps");
    const double v_out = b1.column("vx_mps").back() - b0.column("vx_mps").back();
    const double dt = r.series.column("time_step_s").back();
    impact_metrics(out, "ball-ball", r.contacts.column("time_s"), r.contacts.column("normal_force_n"), dt, kn, m_red,
                   v_in, v_out);
  }
  {
    const SceneResult r = run_case(ctx, "v01_linear_impact_wall");
    const dem::ParticleStore &p = r.sim->particles();
    const double kn = dem::in_series(p.kn[0], r.sim->walls()[0].props.kn);
    const std::vector<double> vz = r.particles.column("vz_mps");
    std::vector<double> force = r.series.column("plane1_force_z_n");
    for (double &f : force)
      f = -f; // the wall pushes the ball up: compression on the ball
    const double dt = r.series.column("time_step_s").back();
    impact_metrics(out, "ball-wall", r.series.column("time_s"), force, dt, kn, p.mass[0], -vz.front(), vz.back());
  }
  return out;
}

CheckOutcome check_bond_failure(const CheckContext &ctx)
{
  CheckOutcome out;
  // --- tension ---------------------------------------------------------
  {
    const Deck deck = load_case(ctx, "v02_bond_tension");
    const SceneResult r = completed(deck.name(), run_scene(deck, run_options(ctx)));
    const double K = dem::ContactTable::pair_params(r.sim->particles(), 0, 1).kn;
    const double phi = deck.real("bonds/normal strength");
    const double v = 1e-3; // m/s, the prescribed separation speed of the case
    const auto t = r.contacts.column("time_s"), fn = r.contacts.column("normal_force_n");
    const auto bonded = r.contacts.column("bonded");
    const double dt = r.series.column("time_step_s").back();
    double law_error = 0, after = 0, u_break = std::nan("");
    std::vector<double> extension, tension, closed;
    for (std::size_t k = 0; k < t.size(); ++k)
    {
      const double u = v * t[k]; // imposed extension, independent of the engine's geometry
      if (bonded[k] == 1)
        law_error = std::max(law_error, std::abs(fn[k] + K * u) / phi);
      else
      {
        if (std::isnan(u_break))
          u_break = u;
        after = std::max(after, std::abs(fn[k]));
      }
      extension.push_back(u);
      tension.push_back(-fn[k]);
      closed.push_back(u < phi / K ? K * u : 0.0);
    }
    out.figures.push_back(
      make_figure("bond_tension", "Contact bond pulled apart: tensile force against extension", "extension u [m]",
                  "tensile force -F_n [N]",
                  {curve("demvv", extension, tension),
                   curve("closed form: K_n u up to phi_n, then 0", extension, closed, CurveStyle::dashed)},
                  "The bond carries K_n u until the force reaches its normal strength phi_n, then both forces are zero "
                  "(thesis §3.4.2); the break falls within one step's extension (v dt) of phi_n / K_n."));
    // Positions carry round-off of ~1e-16 x 2R; K times that is ~1e-12 N.
    out.metrics.push_back(bound("tension: max |F_n + K_n u| / phi_n before the break", law_error, 1e-9, false,
                                ToleranceClass::A, "secant law, round-off in positions only"));
    out.metrics.push_back(relative_error("tension: extension at break vs phi_n / K_n", u_break, phi / K,
                                         v * dt / (phi / K), ToleranceClass::C,
                                         "the break is detected at a step (v dt)"));
    out.metrics.push_back(bound("tension: largest |F_n| after the break [N]", after, 0.0, false, ToleranceClass::A,
                                "rule of thesis §3.4.2: both forces are set to zero"));
  }
  // --- shear under a compressive preload ---------------------------------
  {
    const Deck deck = load_case(ctx, "v02_bond_shear");
    const SceneResult r = completed(deck.name(), run_scene(deck, run_options(ctx)));
    const auto params = dem::ContactTable::pair_params(r.sim->particles(), 0, 1);
    const double phi = deck.real("bonds/shear strength");
    const double v = 1e-3;
    const double d = 2 * r.sim->particles().radius[0];
    const auto t = r.contacts.column("time_s"), fs = r.contacts.column("shear_force_n");
    const auto fn = r.contacts.column("normal_force_n"), bonded = r.contacts.column("bonded");
    const double dt = r.series.column("time_step_s").back();
    double law_error = 0, slip_error = 0, u_break = std::nan("");
    std::vector<double> displacement, shear, closed;
    for (std::size_t k = 0; k < t.size(); ++k)
    {
      const double u = v * t[k];
      if (bonded[k] == 1)
        law_error = std::max(law_error, std::abs(fs[k] - params.ks * u) / phi);
      else
      {
        if (std::isnan(u_break))
          u_break = u;
        slip_error = std::max(slip_error, std::abs(fs[k] - params.friction * fn[k]) / (params.friction * fn[k]));
      }
      displacement.push_back(u);
      shear.push_back(fs[k]);
      closed.push_back(u < phi / params.ks ? params.ks * u : params.friction * fn[k]);
    }
    out.figures.push_back(make_figure(
      "bond_shear", "Contact bond sheared under a compressive preload: shear force against displacement",
      "shear displacement u_s [m]", "shear force F_s [N]",
      {curve("demvv", displacement, shear),
       curve("closed form: K_s u_s up to phi_s, then mu F_n", displacement, closed, CurveStyle::dashed)},
      "The bond carries K_s u_s until the shear force reaches its shear strength phi_s; once it has broken the "
      "contact slides, its shear force held at the Coulomb limit mu F_n of the preload."));
    // The driven ball moves on a straight line, so the contact normal turns
    // by u/d and the shear force lags the straight-line displacement by a
    // relative (u/d)^2 / 2 (< 1e-6 here); 1e-5 allows for it.
    const double turn = (phi / params.ks) / d;
    out.metrics.push_back(bound("shear: max |F_s - K_s u_s| / phi_s before the break", law_error,
                                std::max(1e-5, turn * turn), false, ToleranceClass::A,
                                "exact up to the geometric turn of the normal, (u/d)^2 / 2"));
    out.metrics.push_back(relative_error("shear: displacement at break vs phi_s / K_s", u_break, phi / params.ks,
                                         v * dt / (phi / params.ks), ToleranceClass::C,
                                         "the break is detected at a step (v dt)"));
    out.metrics.push_back(bound("shear: max | |F_s| / (mu F_n) - 1 | after the break", slip_error, 1e-12, false,
                                ToleranceClass::A, "slip rescales the shear force to mu F_n exactly"));
  }
  // --- compression ----------------------------------------------------------
  {
    const Deck deck = load_case(ctx, "v02_bond_compression");
    const SceneResult r = completed(deck.name(), run_scene(deck, run_options(ctx)));
    const double phi = deck.real("bonds/normal strength");
    const double broken = r.sim->bonds_broken(dem::BreakMode::tension) + r.sim->bonds_broken(dem::BreakMode::shear);
    out.metrics.push_back(bound("compression: largest compressive force / phi_n",
                                max_abs(r.contacts.column("normal_force_n")) / phi, 10, true, ToleranceClass::B,
                                "the pair is pushed well beyond the tensile strength"));
    out.metrics.push_back(bound("compression: bonds broken", broken, 0, false, ToleranceClass::A,
                                "thesis §3.4.2: only tension can break a bond in the normal direction"));
  }
  return out;
}

CheckOutcome check_coulomb_slip(const CheckContext &ctx)
{
  CheckOutcome out;
  {
    const SceneResult r = run_case(ctx, "v03_slip");
    const auto params = dem::ContactTable::pair_params(r.sim->particles(), 0, 1);
    const double v = 1e-3;
    const double d = 2 * r.sim->particles().radius[0];
    const auto t = r.contacts.column("time_s"), fs = r.contacts.column("shear_force_n");
    const auto fn = r.contacts.column("normal_force_n");
    const double dt = r.series.column("time_step_s").back();
    double stick_error = 0, slip_error = 0, onset = std::nan(""), onset_expected = std::nan("");
    std::vector<double> displacement, closed;
    for (std::size_t k = 0; k < t.size(); ++k)
    {
      const double limit = params.friction * fn[k];
      displacement.push_back(v * t[k]);
      closed.push_back(std::min(params.ks * v * t[k], limit));
      if (fs[k] < limit * (1 - 1e-12))
        stick_error = std::max(stick_error, std::abs(fs[k] - params.ks * v * t[k]) / limit);
      else
      {
        if (std::isnan(onset))
        {
          // The ball slides on a straight line, so F_n falls slightly as it
          // goes: the onset is where K_s u_s reaches mu F_n at that moment.
          onset = v * t[k];
          onset_expected = limit / params.ks;
        }
        slip_error = std::max(slip_error, std::abs(fs[k] / limit - 1));
      }
    }
    out.figures.push_back(make_figure(
      "coulomb_slip", "Coulomb slip: shear force against displacement", "shear displacement u_s [m]",
      "shear force F_s [N]",
      {curve("demvv", displacement, fs),
       curve("closed form: min(K_s u_s, mu F_n)", displacement, closed, CurveStyle::dashed)},
      "The contact sticks, carrying K_s u_s, until the shear force reaches the Coulomb limit mu F_n, then slides "
      "with its shear force held at that limit; mu F_n falls slightly as the ball slides along a straight line."));
    const double turn = onset_expected / d;
    out.metrics.push_back(bound("slip: max |F_s - K_s u_s| / (mu F_n) while sticking", stick_error,
                                std::max(1e-5, turn * turn), false, ToleranceClass::A,
                                "exact up to the geometric turn of the normal, (u/d)^2 / 2"));
    out.metrics.push_back(relative_error("slip: displacement at slip onset vs mu F_n / K_s", onset, onset_expected,
                                         v * dt / onset_expected, ToleranceClass::C,
                                         "onset resolved to one step (v dt)"));
    out.metrics.push_back(bound("slip: max | |F_s| / (mu F_n) - 1 | while slipping", slip_error, 1e-12, false,
                                ToleranceClass::A, "the trial force is rescaled to the Coulomb limit exactly"));
  }
  const double g = 9.81, mu = 0.5;
  {
    // Sticks: tan(10 deg) < mu, and even the undamped overshoot (2 m g sin)
    // stays below mu m g cos, so the ball oscillates elastically:
    // x(t) = (m g sin / K_s)(1 - cos(omega t)), largest 2 m g sin / K_s.
    const SceneResult r = run_case(ctx, "v03_incline_stick");
    const double theta = 10 * dem::pi / 180;
    const dem::ParticleStore &p = r.sim->particles();
    const double ks = dem::in_series(p.ks[0], r.sim->walls()[0].props.ks);
    const double dt = r.series.column("time_step_s").back();
    const double omega_dt = std::sqrt(ks / p.mass[0]) * dt;
    const double largest = max_abs(r.particles.column("x_m"));
    out.metrics.push_back(relative_error("incline 10 deg: largest down-slope displacement vs 2 m g sin / K_s", largest,
                                         2 * p.mass[0] * g * std::sin(theta) / ks, omega_dt * omega_dt,
                                         ToleranceClass::B, "centred-difference amplitude error, (omega dt)^2"));
    out.metrics.push_back(bound("incline 10 deg: friction work [J]", r.series.column("friction_dissipated_j").back(),
                                0.0, false, ToleranceClass::A, "the ball must never slip"));
  }
  {
    // Slides: tan(35 deg) > mu; once slipping, friction is mu N, constant,
    // so the acceleration is g (sin - mu cos) exactly.
    const SceneResult r = run_case(ctx, "v03_incline_slide");
    const double theta = 35 * dem::pi / 180;
    const auto t = r.particles.column("time_s"), vx = r.particles.column("vx_mps");
    const LineFit fit = fit_line(t, vx, 0.5 * t.back(), t.back());
    // The velocity column is v(t - dt/2) while t is the force time; the
    // slope is unaffected.  The normal spring starts at its equilibrium
    // overlap written to 17 digits, so N is constant to ~1e-12.
    out.metrics.push_back(relative_error("incline 35 deg: sliding acceleration vs g (sin - mu cos)", fit.slope,
                                         g * (std::sin(theta) - mu * std::cos(theta)), 1e-9, ToleranceClass::A,
                                         "constant force, the scheme is exact up to round-off"));
  }
  return out;
}

CheckOutcome check_free_flight(const CheckContext &ctx)
{
  CheckOutcome out;
  const SceneResult r = run_case(ctx, "v05_projectile");
  const auto t = r.particles.column("time_s");
  const auto x = r.particles.column("x_m"), z = r.particles.column("z_m");
  const double vx0 = 1, vz0 = 2, g = 9.81;
  double err = 0;
  std::vector<double> x_closed, z_closed;
  for (std::size_t k = 0; k < t.size(); ++k)
  {
    x_closed.push_back(vx0 * t[k]);
    z_closed.push_back(vz0 * t[k] - 0.5 * g * t[k] * t[k]);
    err = std::max(err, std::hypot(x[k] - x_closed.back(), z[k] - z_closed.back()));
  }
  out.figures.push_back(make_figure(
    "projectile", "Free flight: the ball's path", "x [m]", "z [m]",
    {curve("demvv", x, z),
     curve("closed form: x = v_x t, z = v_z t - g t^2 / 2", x_closed, z_closed, CurveStyle::dashed)},
    "Under gravity alone the path is a parabola, which the integrator follows to round-off (the metric gives "
    "the largest distance from it)."));
  const double steps = static_cast<double>(r.sim->steps());
  const double travel = std::hypot(vx0, vz0) * t.back();
  // Each step rounds x and v once: the error grows like n eps |x| for n
  // steps (n = 4e4, eps = 1.1e-16: ~5e-12 relative); 100 n eps allows it.
  out.metrics.push_back(bound("projectile: max |x - (x0 + v0 t + g t^2 / 2)| / travel", err / travel,
                              100 * steps * 1.1e-16, false, ToleranceClass::A,
                              "exact for a constant force; n steps of round-off"));
  return out;
}
} // namespace demvv
