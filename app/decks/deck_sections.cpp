#include "app/decks/deck_sections.h"

#include "dem/rate_scaling.h"

#include <algorithm>
#include <limits>
#include <map>

namespace demvv
{
namespace
{
}

namespace
{
/// Every law's deck constants, each key once (laws may share keys), in the
/// order of the registry, with the laws that use it.
std::vector<std::pair<dem::LawConstant, std::string>> all_law_constants()
{
  std::vector<std::pair<dem::LawConstant, std::string>> all;
  for (const dem::LawEntry &law : dem::law_registry())
    for (const dem::LawConstant &c : law.deck_constants)
    {
      const auto same = std::find_if(all.begin(), all.end(), [&](const auto &a) { return a.first.key == c.key; });
      if (same == all.end())
        all.push_back({c, std::string(law.keyword)});
      else
        same->second += ", " + std::string(law.keyword);
    }
  return all;
}
} // namespace

void declare_contact_law(DeckSchema &s)
{
  std::vector<std::string> names;
  std::string help = "Ball-ball contact law, a keyword of the law registry:";
  for (const auto &e : dem::law_registry())
  {
    names.emplace_back(e.keyword);
    help += " '" + std::string(e.keyword) + "': " + std::string(e.summary) + ".";
  }
  s.enter("contact law");
  s.choice("law", names.front(), names, help);
  for (const auto &[c, laws] : all_law_constants())
    s.real(std::string(c.key), c.default_value, 0, inf, std::string(c.unit),
           std::string(c.help) + " Used by: " + laws + ".", Interval::open_below);
  s.leave();
}

LawSpec LawSpec::parse(const Deck &d)
{
  LawSpec law;
  law.keyword = d.text("contact law/law");
  // Only the chosen law's constants: the others are not read (a sweep over
  // one of them would vary nothing).
  for (const dem::LawConstant &c : dem::find_law(law.keyword)->deck_constants)
    law.constants.values[std::string(c.key)] = d.real("contact law/" + std::string(c.key));
  return law;
}

std::unique_ptr<dem::ContactModel> LawSpec::make(const RateScaling &rate) const
{
  return dem::make_contact_model(keyword, scaled_constants(rate));
}

dem::LawParameters LawSpec::scaled_constants(const RateScaling &rate) const
{
  dem::LawParameters p = constants;
  for (const auto &[c, laws] : all_law_constants())
  {
    const auto it = p.values.find(c.key);
    if (it != p.values.end())
      it->second *= c.scaling == dem::RateScaled::stiffness ? rate.stiffness_factor : rate.viscosity_factor;
  }
  return p;
}

void declare_rate(DeckSchema &s)
{
  s.enter("rate");
  s.real("temperature", 283, 0, inf, "K",
         "Test temperature T of the temperature-compensated strain rate (thesis eq. 4.3; reference 283 K).",
         Interval::open_below);
  s.real("physical strain rate", 0, 0, inf, "1/s",
         "Strain rate of the test the run represents; 0: the run's own rate.  Both Burger's viscosities are "
         "multiplied by rate_T / run rate, rate_T the temperature-compensated physical rate (viscosity scaling, "
         "thesis §7.3 and §7.5.3, eq. 7.21 with eq. 4.3; at 283 K rate_T is the physical rate), and "
         "rate-dependent properties use the physical rate at the temperature.");
  s.real("run strain rate", 0, 0, inf, "1/s",
         "Strain rate actually simulated, for decks without a loading rate of their own (scenes); uniaxial "
         "decks take it from their loading.");
  s.choice("dependence", "none", {"none", "bonds", "bonds and stiffness"},
           "What scales with (rate_T / 0.1 1/s)^0.29 at the physical rate (thesis eq. 7.23, n = 0.29, "
           "k = 13.4e3 K, T_0 = 283 K): nothing, the bond strengths, or the bond strengths and every contact "
           "stiffness (ball kn, ks and the Burger's springs).");
  s.leave();
}

void RateScaling::scale_ball_stiffness(dem::ParticleStore &p) const
{
  for (dem::Index b = 0; b < p.size(); ++b)
  {
    p.kn[b] *= stiffness_factor;
    p.ks[b] *= stiffness_factor;
  }
}

nlohmann::json RateScaling::to_json() const
{
  return {{"temperature_k", temperature},
          {"physical_strain_rate_per_s", physical_rate},
          {"temperature_compensated_rate_per_s", compensated_rate},
          {"run_strain_rate_per_s", run_rate},
          {"viscosity_factor", viscosity_factor},
          {"bond_strength_factor", strength_factor},
          {"stiffness_factor", stiffness_factor}};
}

RateSpec RateSpec::parse(const Deck &d)
{
  RateSpec r;
  r.deck = d.path();
  r.temperature = d.real("rate/temperature");
  r.physical_rate = d.real("rate/physical strain rate");
  r.run_rate = d.real("rate/run strain rate");
  r.dependence = d.text("rate/dependence");
  return r;
}

RateScaling RateSpec::scaling(double loading_rate) const
{
  RateScaling r;
  r.temperature = temperature;
  r.run_rate = loading_rate > 0 ? loading_rate : run_rate;
  r.physical_rate = physical_rate;
  if (r.physical_rate > 0 && !(r.run_rate > 0))
    fail_key(deck, "rate/run strain rate", format_number(run_rate),
             "expected the simulated strain rate (> 0) when a physical strain rate is given");
  if (r.physical_rate == 0)
    r.physical_rate = r.run_rate;
  // Temperature acts through the temperature-compensated rate (eq. 4.3): a
  // test at T stands for one at rate_T at T_0, so the viscosities are
  // scaled to rate_T (thesis §7.5.3).  At T_0 the factor is exactly 1.
  r.compensated_rate = dem::RateLaw{}.compensated_rate(r.physical_rate, r.temperature);
  if (r.physical_rate > 0)
    r.viscosity_factor = dem::viscosity_scale(r.compensated_rate, r.run_rate);
  if (dependence != "none")
  {
    if (!(r.physical_rate > 0))
      fail_key(deck, "rate/dependence", dependence,
               "expected a strain rate (rate/physical strain rate or the loading) for it");
    r.strength_factor = dem::RateLaw{}.strength_factor(r.physical_rate, r.temperature);
    if (dependence == "bonds and stiffness")
      r.stiffness_factor = r.strength_factor;
  }
  return r;
}

void declare_motion(DeckSchema &s, const std::string &default_gravity, double default_damping)
{
  s.enter("motion");
  s.vector3("gravity", default_gravity, "m/s^2", "Gravitational acceleration.");
  s.real("local damping", default_damping, 0, 1, "-",
         "PFC local non-viscous damping coefficient alpha (0 = undamped; 0.7 is PFC's default; 1 would cancel "
         "every force).",
         Interval::open_above);
  s.real("time step safety", 0.8, 0, 1, "-",
         "Fraction of the critical time step bound used by the automatic step; the bound is "
         "2 / sqrt((1 + local damping) x the largest stiffness-to-mass bound), local damping "
         "stiffening the fastest mode.",
         Interval::open_below);
  s.real("fixed time step", 0, 0, inf, "s", "Fixed time step; 0 selects the automatic step.");
  s.choice("unstable fixed step", "stop", {"stop", "run"},
           "What to do when a fixed step exceeds the critical step bound: stop with exit code 3, "
           "or run anyway (to demonstrate instability).");
  s.real("neighbour skin", 0.25, 0, inf, "-",
         "Verlet skin of the neighbour list as a fraction of the largest radius (the widest one, when adaptive).",
         Interval::open_below);
  s.choice("neighbour skin mode", "adaptive", {"adaptive", "fixed"},
           "adaptive: at each neighbour rebuild the skin is narrowed, down to 1 % of the largest radius, while the "
           "balls move slowly (fewer candidate pairs to test each step); fixed: always the neighbour skin. Results "
           "do not depend on the skin, only the speed does.");
  s.leave();
}

dem::SimulationSettings parse_motion(const Deck &d)
{
  dem::SimulationSettings m;
  m.gravity = parse_vec3(d, "motion/gravity");
  m.local_damping = d.real("motion/local damping");
  m.time_step_safety = d.real("motion/time step safety");
  m.fixed_time_step = d.real("motion/fixed time step");
  m.allow_unstable_step = d.text("motion/unstable fixed step") == "run";
  m.skin_fraction = d.real("motion/neighbour skin");
  m.adaptive_skin = d.text("motion/neighbour skin mode") == "adaptive";
  return m;
}

void declare_bonds(DeckSchema &s, const std::vector<std::string> &modes, bool test)
{
  s.enter("bonds");
  const std::map<std::string, std::string> meaning = {{"none", "no bonds"},
                                                      {"touching", "every touching pair"},
                                                      {"sample", "the bonds the sample file carries"},
                                                      {"list", "the pairs of the list file"}};
  std::string help = "Which pairs get PFC contact bonds at the start:";
  for (const std::string &m : modes)
    help += " '" + m + "': " + meaning.at(m) + ";";
  help.back() = '.';
  s.choice("install", modes.front(), modes, help);
  if (std::find(modes.begin(), modes.end(), "list") != modes.end())
    s.file("list file", "",
           "CSV of bonded pairs for install = list: columns first,second (ball indices from 0) and "
           "optionally normal_strength_n, shear_strength_n [N] (no other columns).");
  s.real("normal strength", 31.3, 0, inf, "N",
         "Mean tensile strength phi_n of a bond, a force (thesis eq. 6.1: phi = 4 sigma R^2).", Interval::open_below);
  s.real("shear strength", 31.3, 0, inf, "N", "Mean shear strength phi_s of a bond, a force.", Interval::open_below);
  s.real("strength cov", 0, 0, 10, "-",
         "Coefficient of variation of both strengths (Gaussian; thesis §6.5 uses 0, 0.25, 0.5).");
  s.real("strength floor", 0.01, 0, 1, "-", "Draws below this fraction of the mean are raised to it and counted.",
         Interval::open_below);
  s.real("removed fraction", 0, 0, 1, "-",
         "Fraction of installed bonds removed at random to leave frictional contacts (thesis §7.4).");
  s.real("touch tolerance", 1e-6, 0, 1, "-",
         "Largest gap, relative to the smaller radius, at which a pair counts as touching.");
  s.integer("seed", 1, 0, std::numeric_limits<int>::max(), "Seed of the strength and removal draws.");
  if (test)
    s.real("break displacement", 0, 0, inf, "m",
           "Displacement criterion delta_c (thesis appendix A: 0.015e-3 m): a bond also breaks when the centre "
           "distance has grown by more than this since the run started (bonds are formed then); 0: off.");
  s.leave();
}

BondSpec BondSpec::parse(const Deck &d, bool test)
{
  BondSpec b;
  b.install = d.text("bonds/install");
  if (b.install == "list")
  {
    if (d.text("bonds/list file").empty())
      d.fail("bonds/list file", "expected a CSV file of bonded pairs when install = list");
    b.list_file = d.file("bonds/list file");
  }
  b.settings = parse_bond_settings(d);
  if (test)
    b.break_displacement = d.real("bonds/break displacement");
  return b;
}

void BondSpec::finish(dem::ContactTable &table, const dem::ParticleStore &p, const RateScaling &rate) const
{
  dem::scale_bond_strengths(table, rate.strength_factor);
  if (break_displacement > 0)
    dem::set_break_displacement(table, p, break_displacement);
}

dem::BondSettings parse_bond_settings(const Deck &d)
{
  dem::BondSettings b;
  b.normal_strength = d.real("bonds/normal strength");
  b.shear_strength = d.real("bonds/shear strength");
  b.cov = d.real("bonds/strength cov");
  b.floor_fraction = d.real("bonds/strength floor");
  b.removed_fraction = d.real("bonds/removed fraction");
  b.touch_tolerance = d.real("bonds/touch tolerance");
  b.seed = static_cast<std::uint64_t>(d.integer("bonds/seed"));
  return b;
}

void declare_ball_properties(DeckSchema &s)
{
  s.enter("balls");
  s.real("density", 2650, 0, inf, "kg/m^3", "Density of every ball (sand: 2650).", Interval::open_below);
  s.real("normal stiffness", 1.2e7, 0, inf, "N/m",
         "Normal stiffness kn of every ball; a pair has kn_A kn_B / (kn_A + kn_B) (eq. 3.17).", Interval::open_below);
  s.real("shear stiffness", 1.2e6, 0, inf, "N/m",
         "Shear stiffness ks of every ball; a pair has ks in series (eq. 3.18).");
  s.real("friction", 0.5, 0, inf, "-", "Friction coefficient of every ball; a pair uses the smaller.");
  s.leave();
}

dem::BallSpec parse_ball_properties(const Deck &d)
{
  dem::BallSpec b;
  b.density = d.real("balls/density");
  b.kn = d.real("balls/normal stiffness");
  b.ks = d.real("balls/shear stiffness");
  b.friction = d.real("balls/friction");
  return b;
}

dem::BallSpec scaled(dem::BallSpec ball, const RateScaling &rate)
{
  ball.kn *= rate.stiffness_factor;
  ball.ks *= rate.stiffness_factor;
  return ball;
}

void declare_wall_properties(DeckSchema &s, double kn, double ks, double friction)
{
  s.real("normal stiffness", kn, 0, inf, "N/m", "Normal stiffness of the wall (in series with the ball's).",
         Interval::open_below);
  s.real("shear stiffness", ks, 0, inf, "N/m", "Shear stiffness of the wall (in series with the ball's).");
  s.real("friction", friction, 0, inf, "-", "Friction coefficient of the wall (a pair uses the smaller).");
}

dem::WallProps parse_wall_properties(const Deck &d, const std::string &section)
{
  const dem::WallProps w{d.real(section + "/normal stiffness"), d.real(section + "/shear stiffness"),
                         d.real(section + "/friction")};
  if (w.friction > 0 && w.ks == 0)
    d.fail(section + "/friction", "a wall with shear stiffness 0 carries no shear force, so its friction does "
                                  "nothing: expected friction 0, or a shear stiffness > 0 N/m");
  return w;
}

dem::Vec3 parse_vec3(const Deck &d, const std::string &key, bool nonzero)
{
  const auto v = d.vector3(key);
  const dem::Vec3 out(v[0], v[1], v[2]);
  if (nonzero && out.norm() == 0)
    d.fail(key, "expected a non-zero vector");
  return out;
}
} // namespace demvv
