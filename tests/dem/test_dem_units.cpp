// Unit tests of engine pieces, each against an exact value.
#include "dem/balanced_ranges.h"
#include "tests/dem/two_body.h"

#include "dem/bonds.h"
#include "dem/contact_lanes.h"
#include "dem/contact_model.h"
#include "dem/contact_resolve.h"
#include "dem/law_linear.h"
#include "dem/measure.h"
#include "dem/neighbors.h"
#include "dem/protocol_uniaxial.h"
#include "dem/sample_lattice.h"
#include "dem/spatial_bands.h"
#include "dem/spatial_order.h"
#include "dem/stability.h"
#include "dem/walls.h"

#include <catch2/catch.hpp>
#include <gsl/gsl_cdf.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <optional>
#include <random>
#include <tuple>
#include <vector>

using namespace demtest;
using Catch::Matchers::WithinRel;

TEST_CASE("stiffnesses combine in series (thesis eq. 3.17-3.18)", "[dem][law]")
{
  CHECK(dem::in_series(2.0, 2.0) == 1.0);
  CHECK_THAT(dem::in_series(1.2e7, 3.0e7), WithinRel(1.2e7 * 3.0e7 / 4.2e7, 1e-15));
  CHECK(dem::in_series(1.2e7, 0.0) == 0.0); // a shear-free platen
}

TEST_CASE("sphere intersection volume: limits and the half-overlap lens", "[dem][measure]")
{
  const double r = 1.0, ball = 4.0 / 3.0 * dem::pi;
  CHECK(dem::sphere_intersection_volume(r, r, 2.0) == 0.0);
  CHECK_THAT(dem::sphere_intersection_volume(r, 3.0, 0.5), WithinRel(ball, 1e-15)); // ball inside
  // Two unit spheres at distance 1: two caps of height 1/2, pi h^2 (3r - h)/3 each.
  const double cap = dem::pi * 0.25 * (3.0 - 0.5) / 3.0;
  CHECK_THAT(dem::sphere_intersection_volume(r, r, 1.0), WithinRel(2 * cap, 1e-14));
}

TEST_CASE("shear force rotation keeps magnitude and follows the plane", "[dem][law]")
{
  const Vec3 n0 = Vec3(1, 0, 0), n1 = Vec3(std::cos(1e-3), std::sin(1e-3), 0);
  const Vec3 f(0, 2.0, 0.5); // in the plane normal to n0
  const Vec3 r = dem::rotate_with_contact_plane(f, n0, n1, 0.0);
  CHECK(std::abs(r.dot(n1)) < 1e-15);
  // |r| = |f| (1 + O(phi^4)), phi = 1e-3.
  CHECK_THAT(r.norm(), WithinRel(f.norm(), 1e-12));
  // A pure twist by t about n turns f by atan-accurate angle: third order.
  const Vec3 twisted = dem::rotate_with_contact_plane(f, n0, n0, 1e-3);
  const Vec3 exact = Eigen::AngleAxisd(1e-3, n0) * f;
  CHECK((twisted - exact).norm() < 1e-9 * f.norm());
}

namespace
{
/// The shear force a new linear contact (normal along z, overlap 1e-6 m,
/// kn 1e6 N/m: F_n = 1 N; ks dt = 0.1 N s/m) carries after one step whose
/// tangential velocity difference is u, at friction mu.
Vec3 one_step_shear(const Vec3 &u, double mu, double overlap = 1e-6)
{
  const dem::ContactParams params{1e6, 1e5, mu};
  const dem::ContactGeometry g{Vec3::UnitZ(), overlap, u, Vec3::Zero(), Vec3::Zero(), 1e-3, 1e-3};
  bool bonded = false;
  dem::ContactState state;
  dem::LinearLaw::History none;
  return dem::resolve_contact(dem::LinearLaw{}, params, bonded, dem::ContactBond{}, state, none, g, 1e-6).shear;
}
} // namespace

TEST_CASE("the Coulomb limit decides slip as |F_s| > mu F_n does, to the last bit at the cone's edge", "[dem][law]")
{
  // The resolver skips the square root when |F_s|^2 is below (mu F_n)^2 by
  // a relative 1e-12; every trial here is as close to the cone as the
  // offsets say (whole ulps around the margin and the edge), in 64
  // directions, and the result must be the rule's: the trial itself (the
  // shear at friction 1e300) inside the cone, scaled onto it outside.
  const double ulp = std::ldexp(1.0, -52);
  std::vector<double> offsets{-1e-6, -1e-11, -5e-13, 1e-13, 1e-9, 1e-6};
  for (int k = -6; k <= 6; ++k)
  {
    offsets.push_back(k * ulp);
    offsets.push_back(-1e-12 + k * ulp);
  }
  std::size_t inside = 0, outside = 0;
  for (const double overlap : {1e-6, 1e-166}) // F_n 1 N, and a limit whose square is subnormal
    for (int d = 0; d < 64; ++d)
    {
      const double a = 2 * dem::pi * d / 64;
      const double limit = 0.5 * (1e6 * overlap);
      for (const double offset : offsets)
      {
        const Vec3 u = (limit * (1 + offset) / 0.1) * Vec3(std::cos(a), std::sin(a), 0);
        const Vec3 trial = one_step_shear(u, 1e300, overlap);
        const double magnitude = trial.norm();
        const Vec3 expected = magnitude > limit ? Vec3(trial * (limit / magnitude)) : trial;
        const Vec3 got = one_step_shear(u, 0.5, overlap);
        CHECK(got.x() == expected.x());
        CHECK(got.y() == expected.y());
        CHECK(got.z() == expected.z());
        ++(magnitude > limit ? outside : inside);
      }
    }
  // Both sides of the edge were tried.
  CHECK(inside > 500);
  CHECK(outside > 500);
}

TEST_CASE("a contact without shear stiffness resolves as the general resolver does, to its closed form", "[dem][law]")
{
  // The walls' shortcut (frictionless platens) must give the force and the
  // state the general resolver gives the same contact: random geometries,
  // fresh and touching states, apart and overlapping, compared with ==
  // (equal values; a zero's sign may differ).  Its force is also the
  // closed form max(K^n U, 0) n, exactly.
  std::mt19937_64 random(20261205);
  std::uniform_real_distribution<double> unit(-1.0, 1.0), share(0.0, 1.0);
  const auto direction = [&]
  {
    Vec3 v(unit(random), unit(random), unit(random));
    return Vec3(v / v.norm());
  };
  int touching = 0;
  for (int trial = 0; trial < 4000; ++trial)
  {
    const dem::ContactParams params{std::pow(10.0, 5 + 3 * share(random)), 0.0, share(random)};
    dem::ContactGeometry g;
    g.normal = direction();
    g.overlap = 1e-4 * (share(random) - 0.2);
    g.velocity_difference = 0.1 * direction();
    g.spin_first = 10 * direction();
    g.spin_second = 10 * direction();
    g.arm_first = 1e-3 * (1 + share(random));
    g.arm_second = 1e-3 * (1 + share(random));
    dem::ContactState before;
    if (trial % 2 == 1)
    {
      before.normal = direction();
      before.normal_force = share(random);
      before.overlap = 1e-5 * share(random);
    }
    before.friction_work = trial % 3 == 0 ? share(random) : 0.0;
    dem::ContactState general = before, shortcut = before;
    bool bonded = false;
    dem::LinearLaw::History none;
    const dem::ResolvedContact a =
      dem::resolve_contact(dem::LinearLaw{}, params, bonded, dem::ContactBond{}, general, none, g, 1e-6);
    const dem::ResolvedContact b = dem::resolve_shear_free_contact(params, shortcut, g);
    INFO("trial " << trial << ", overlap " << g.overlap);
    REQUIRE(b.touching == a.touching);
    REQUIRE(b.broke == a.broke);
    REQUIRE(a.shear == Vec3::Zero());
    REQUIRE(b.shear == Vec3::Zero());
    REQUIRE(b.force == a.force);
    REQUIRE(b.force == std::max(params.kn * g.overlap, 0.0) * (b.touching ? g.normal : Vec3(Vec3::Zero())));
    REQUIRE(shortcut.shear_force == general.shear_force);
    REQUIRE(shortcut.normal == general.normal);
    REQUIRE(shortcut.normal_force == general.normal_force);
    REQUIRE(shortcut.overlap == general.overlap);
    REQUIRE(shortcut.friction_work == general.friction_work);
    REQUIRE(shortcut.bond_energy == general.bond_energy);
    touching += b.touching ? 1 : 0;
  }
  // Both branches were taken often.
  CHECK(touching > 2000);
  CHECK(touching < 3800);
}

TEST_CASE("eight contacts at once resolve as the general resolver resolves each", "[dem][law][lanes]")
{
  // The linear law's blocks of eight (contact_lanes.h) must resolve exactly
  // the ordinary lanes (unbonded, touching at the last pass and still, and
  // sticking) and leave every other lane to the general resolver; where
  // they resolve, their state and loads must be resolve_contact's.  Both do
  // the same operations in the same order, so only the compiler's fusing
  // of multiplies and adds can differ: a few roundings, each at most an
  // ulp (2.2e-16) of a term no larger than the contact's force scale
  // |F_n| + |F_s|, which 1e-12 of that scale bounds with room to spare; a
  // wrong term or sign is off by far more (the shear increment alone is
  // 1e-4 to 1e-1 of the scale here).  The overlap R_i + R_j - |d| inherits
  // the distance's roundings, each at most an ulp of R_i + R_j: eight such
  // ulps bound it.  The lanes that are not ordinary are kept far from every
  // threshold: a last pass's shear at ten times the friction limit, a
  // sliding velocity that takes a sticking contact's shear force far out of
  // the cone in one step, separation at -0.2 to -1 of an overlap.  A lane's
  // result must not depend on the lanes beside it (a block holds whichever
  // candidates the pass met together, fewer at the end of a range): each
  // resolved lane is resolved again alone and must come out the same to
  // the bit.
  if (!dem::contact_lanes)
  {
    WARN("this build resolves every contact one by one (no AVX-512): nothing to compare");
    return;
  }
#if defined(__AVX512F__)
  std::mt19937_64 random(20261205);
  std::uniform_real_distribution<double> unit(-1.0, 1.0), share(0.0, 1.0);
  const auto direction = [&]
  {
    Vec3 v(unit(random), unit(random), unit(random));
    return Vec3(v / v.norm());
  };
  const std::vector<dem::ContactParams> constants{{6e6, 6e5, 0.5}, {2e7, 1e7, 0.3}, {1e5, 3e4, 0.9}};
  enum Kind
  {
    ordinary,
    slipping,
    pushed_out,
    fresh,
    apart,
    bonded
  };
  const double dt = 5e-7;
  int resolved_lanes = 0, other_lanes = 0;
  for (int block = 0; block < 400; ++block)
  {
    dem::ParticleStore p;
    std::vector<dem::Contact> entries(8);
    std::vector<Kind> kinds(8);
    const bool one_set = block % 2 == 0;
    for (int l = 0; l < 8; ++l)
    {
      // One kind per lane: mostly ordinary, so that whole blocks occur too.
      const double pick = share(random);
      const Kind kind = block % 5 == 0 ? ordinary
                        : pick < 0.55  ? ordinary
                        : pick < 0.65  ? slipping
                        : pick < 0.72  ? pushed_out
                        : pick < 0.8   ? fresh
                        : pick < 0.9   ? apart
                                       : bonded;
      kinds[static_cast<std::size_t>(l)] = kind;
      dem::BallSpec a, b;
      a.radius = 1e-3 * (0.8 + 0.4 * share(random));
      b.radius = 1e-3 * (0.8 + 0.4 * share(random));
      const Vec3 n = direction();
      const double overlap = (kind == apart ? -(0.2 + 0.8 * share(random)) : 0.1 + share(random)) * 1e-5;
      a.position = Vec3(unit(random), unit(random), unit(random)) * 0.01;
      b.position = a.position + (a.radius + b.radius - overlap) * n;
      a.velocity = 0.01 * direction();
      b.velocity = 0.01 * direction();
      if (kind == pushed_out) // sticks at the last pass, slides far out of the cone in this step
        b.velocity += 1e4 * direction().cross(n).normalized();
      a.spin = 5.0 * direction();
      b.spin = 5.0 * direction();
      dem::Contact &e = entries[static_cast<std::size_t>(l)];
      e.first = p.add(a);
      e.second = p.add(b);
      e.constants = one_set ? 0u : static_cast<dem::ConstantsIndex>(random() % constants.size());
      const dem::ContactParams &k = constants[e.constants];
      if (kind != fresh)
      {
        // Touching at the last pass: its normal a small turn from today's.
        e.state.normal = Vec3(n + 1e-3 * direction()).normalized();
        e.state.normal_force = k.kn * overlap;
        e.state.overlap = overlap;
      }
      const double limit = k.friction * k.kn * std::max(overlap, 1e-6);
      const Vec3 tangent = direction().cross(n).normalized();
      e.state.shear_force = (kind == slipping ? 10.0 : 0.1 * share(random)) * limit * tangent;
      e.state.friction_work = share(random) * 1e-9;
      e.bonded = kind == bonded;
      if (e.bonded)
        e.bond = dem::ContactBond{1e3, 1e3};
      e.stability = {share(random), share(random)};
    }
    dem::LaneResults lanes;
    const std::vector<dem::Contact> before = entries;
    const int count = block % 3 == 1 ? 1 + block % 8 : 8;
    // The pass queues its candidates as it meets them, so a block's lanes
    // are entries in any order, not always side by side.
    std::size_t queued[8] = {0, 1, 2, 3, 4, 5, 6, 7};
    if (block % 2 == 1)
      std::shuffle(std::begin(queued), std::end(queued), random);
    const __mmask8 resolved = dem::linear_block(p, constants.data(), entries.data(), queued, count, dt, lanes);
    for (int l = 0; l < 8; ++l)
    {
      const std::size_t c = queued[l];
      INFO("block " << block << ", lane " << l << ", kind " << kinds[c]);
      // The block writes no entry.
      REQUIRE(entries[c].state.shear_force == before[c].state.shear_force);
      REQUIRE(entries[c].state.normal == before[c].state.normal);
      const bool taken = (resolved >> l) & 1;
      REQUIRE(taken == (l < count && kinds[c] == ordinary));
      if (!taken)
      {
        ++other_lanes;
        continue;
      }
      ++resolved_lanes;
      dem::LaneResults alone;
      REQUIRE(dem::linear_block(p, constants.data(), entries.data(), &queued[l], 1, dt, alone) == 1);
      CHECK(alone.force_x[0] == lanes.force_x[l]);
      CHECK(alone.force_y[0] == lanes.force_y[l]);
      CHECK(alone.force_z[0] == lanes.force_z[l]);
      CHECK(alone.shear_x[0] == lanes.shear_x[l]);
      CHECK(alone.normal_z[0] == lanes.normal_z[l]);
      CHECK(alone.lever_y[0] == lanes.lever_y[l]);
      dem::Contact general = before[c];
      dem::LinearLaw::History none;
      const dem::ContactGeometry g = dem::sphere_sphere(p, general.first, general.second);
      const dem::ResolvedContact r = dem::resolve_contact(dem::LinearLaw{}, constants[general.constants],
                                                          general.bonded, general.bond, general.state, none, g, dt);
      REQUIRE(r.touching);
      dem::ContactState lane_state = before[c].state;
      lanes.commit(l, lane_state);
      const double scale = std::abs(general.state.normal_force) + general.state.shear_force.norm();
      const double tolerance = 1e-12 * scale;
      CHECK((lane_state.shear_force - general.state.shear_force).norm() <= tolerance);
      CHECK(std::abs(lane_state.normal_force - general.state.normal_force) <= tolerance);
      CHECK((lane_state.normal - general.state.normal).norm() <= 1e-15);
      const double overlap_tolerance =
        8 * std::numeric_limits<double>::epsilon() * (p.radius[general.first] + p.radius[general.second]);
      CHECK(std::abs(lane_state.overlap - general.state.overlap) <= overlap_tolerance);
      CHECK(lane_state.friction_work == general.state.friction_work);
      const Vec3 force(lanes.force_x[l], lanes.force_y[l], lanes.force_z[l]);
      const Vec3 lever(lanes.lever_x[l], lanes.lever_y[l], lanes.lever_z[l]);
      CHECK((force - r.force).norm() <= tolerance);
      CHECK((lever - dem::cross(g.normal, r.shear)).norm() <= tolerance);
      CHECK(lanes.overlap[l] == lane_state.overlap);
      CHECK(lanes.bound_first[l] == before[c].stability.first);
      CHECK(lanes.bound_second[l] == before[c].stability.second);
    }
  }
  // Both paths were taken often.
  CHECK(resolved_lanes > 1000);
  CHECK(other_lanes > 400);
#endif
}

TEST_CASE("a ball is clear of a cylinder exactly when its clearance is at least its radius", "[dem][walls]")
{
  // clear_of answers balls far inside without the square root; near the
  // wall, and for a ball nearly as wide as the cylinder, the clearance
  // decides.  Centres at whole ulps around R - r, in 64 directions.
  dem::WallSet walls;
  dem::Wall c;
  c.shape = dem::WallShape::cylinder;
  c.point = Vec3(0.001, -0.002, 0.5);
  c.direction = Vec3(0.1, 0.2, 1.0);
  c.radius = 0.0165;
  const dem::WallIndex w = walls.add(c);
  const Vec3 axis = walls[w].direction, across = axis.unitOrthogonal(), third = axis.cross(across);
  const double ulp = std::ldexp(1.0, -52);
  std::size_t clear = 0, touching = 0;
  for (const double r : {0.885e-3, 0.0165 * (1 - 1e-7)})
    for (int d = 0; d < 64; ++d)
    {
      const double a = 2 * dem::pi * d / 64;
      for (const double offset : {-1e-3, -3e-9, -2e-9, -1e-9, -1e-12, 0.0, 1e-12, 1e-9})
        for (int k = -4; k <= 4; ++k)
        {
          const double rho = (c.radius - r) * (1 + offset + k * ulp);
          const Vec3 x = c.point + 0.01 * axis + rho * (std::cos(a) * across + std::sin(a) * third);
          const bool exact = walls.clearance(w, x) >= r;
          CHECK(walls.clear_of(w, x, r) == exact);
          ++(exact ? clear : touching);
        }
    }
  CHECK(clear > 1000);
  CHECK(touching > 500);
}

TEST_CASE("linear law closed forms are consistent", "[dem][law]")
{
  const double k = 6e6, m = 3.8e-6;
  CHECK_THAT(dem::LinearLaw::collision_time(k, m) * dem::LinearLaw::natural_frequency(k, m), WithinRel(dem::pi, 1e-15));
  CHECK_THAT(dem::LinearLaw::peak_force(k, m, 0.1), WithinRel(0.1 * std::sqrt(m * k), 1e-15));
  CHECK(dem::LinearLaw::reduced_mass(2.0, 2.0) == 1.0);
}

TEST_CASE("contact history survives neighbour rebuilds, bonded pairs stay listed", "[dem][contacts]")
{
  auto sim = two_balls(1e-3, 2e-3, 1e6, 1e5, 0.5);
  sim.refresh_contacts();
  dem::bond_pair(sim.contacts(), sim.particles(), 0, 1, 10.0, 10.0);
  sim.contacts().find(0, 1)->state.shear_force = Vec3(0, 0.25, 0);
  sim.contacts().find(0, 1)->state.normal = Vec3::UnitX(); // touching
  // Pull the balls far apart (beyond any skin) and rebuild: the bonded pair
  // must still be in the table with its history.
  sim.particles().position[1].x() = 5e-3;
  sim.invalidate_neighbors();
  sim.refresh_contacts();
  const dem::Contact *c = sim.contacts().find(0, 1);
  REQUIRE(c != nullptr);
  CHECK(c->bonded);
  CHECK(c->state.shear_force.y() == 0.25);
  // An unbonded, separated pair is dropped at the next rebuild.
  sim.contacts().find(0, 1)->bonded = false;
  sim.contacts().find(0, 1)->state.normal.setZero(); // not touching
  sim.invalidate_neighbors();
  sim.refresh_contacts();
  CHECK(sim.contacts().find(0, 1) == nullptr);
}

TEST_CASE("an adaptive skin narrows at rest, widens in a fall, and changes no ball's motion", "[dem][neighbors]")
{
  // A loose grid of balls falls onto a floor, starting at rest: the skin
  // starts at its narrowest (no motion yet), widens as the balls speed up
  // and rebuilds come often, and new contacts form all the time.  Any pair
  // the narrow lists missed would change the motion, so the two runs must
  // agree to the last bit in every ball, with the linear law's ordinary
  // contacts resolved one by one or eight at a time (which of them a block
  // holds depends on the table's other entries, so on the skin).
  const auto run = [](bool adaptive, bool in_lanes)
  {
    dem::ParticleStore p;
    for (int i = 0; i < 8; ++i)
      for (int j = 0; j < 8; ++j)
        for (int k = 0; k < 6; ++k)
        {
          const double jitter = 0.3e-3 * std::sin(1.7 * i + 2.3 * j + 3.1 * k);
          p.add(ball(Vec3(2.5e-3 * i + jitter, 2.5e-3 * j - jitter, 1.5e-3 + 2.5e-3 * k), 1e-3, 1e6, 1e5, 0.5));
        }
    dem::WallSet walls;
    walls.add(floor_wall(1e6, 1e5, 0.5));
    dem::SimulationSettings settings = undamped();
    settings.local_damping = 0.3;
    settings.gravity = Vec3(0, 0, -50);
    settings.adaptive_skin = adaptive;
    settings.contacts_in_lanes = in_lanes;
    dem::Simulation sim = make_sim(std::move(p), std::move(walls), settings);
    double narrowest = dem::infinity, widest = 0;
    for (int step = 0; step < 4000; ++step)
    {
      sim.step();
      narrowest = std::min(narrowest, sim.neighbors().skin());
      widest = std::max(widest, sim.neighbors().skin());
    }
    return std::make_tuple(std::move(sim), narrowest, widest);
  };
  for (const bool in_lanes : {false, true})
  {
    INFO((in_lanes ? "contacts in lanes" : "contacts one by one"));
    const auto [fixed, fixed_narrowest, fixed_widest] = run(false, in_lanes);
    const auto [adaptive, narrowest, widest] = run(true, in_lanes);
    const double largest_skin = 0.25 * 1e-3;
    CHECK(fixed_narrowest == largest_skin);
    CHECK(narrowest == 0.01 * largest_skin / 0.25); // 1 % of the radius, at rest
    CHECK(widest > 10 * narrowest);                 // it widened in the fall
    CHECK(widest <= largest_skin);
    CHECK(adaptive.neighbors().rebuilds() > fixed.neighbors().rebuilds());
    REQUIRE(fixed.contacts().size() > 100); // the balls landed and touch
    bool same = true;
    for (dem::Index b = 0; b < fixed.particles().size(); ++b)
      same = same && fixed.particles().position[b] == adaptive.particles().position[b] &&
             fixed.particles().velocity[b] == adaptive.particles().velocity[b] &&
             fixed.particles().spin[b] == adaptive.particles().spin[b];
    CHECK(same);
  }
}

TEST_CASE("near-wall marks: a ball within its radius plus the reach of a wall, until a wall moves a quarter reach",
          "[dem][neighbors][walls]")
{
  const double r = 1e-3, reach = 1e-4;
  dem::WallSet walls;
  walls.add(floor_wall(1e6));
  dem::Wall drum;
  drum.shape = dem::WallShape::cylinder;
  drum.radius = 10e-3;
  walls.add(drum);
  // Ball 0 is 0.9 reach from touching the floor, ball 1 1.1 reach; ball 2
  // 0.9 reach from the drum, ball 3 1.1 reach (and far above the floor).
  const std::vector<Vec3> centres = {Vec3(0, 0, r + 0.9 * reach), Vec3(1e-3, 0, r + 1.1 * reach),
                                     Vec3(10e-3 - r - 0.9 * reach, 0, 5e-3), Vec3(0, 10e-3 - r - 1.1 * reach, 5e-3)};
  const std::vector<double> radii(4, r);
  CHECK(walls.near_stale()); // never marked
  walls.mark_near(centres, radii, reach);
  CHECK(walls.near_marks() == 1);
  CHECK(walls.near_walls(0) == 1);
  CHECK(walls.near_walls(1) == 0);
  CHECK(walls.near_walls(2) == 2);
  CHECK(walls.near_walls(3) == 0);
  CHECK_FALSE(walls.near_stale());
  // A quarter reach in all: the floor's point and the drum's radius.
  walls[0].point = Vec3(0.1 * reach, 0, 0.1 * reach);
  walls[1].radius -= 0.1 * reach;
  CHECK_FALSE(walls.near_stale());
  walls[1].radius -= 0.2 * reach;
  CHECK(walls.near_stale());
  walls[1].radius = drum.radius;
  walls[0].point = Vec3::Zero();
  CHECK_FALSE(walls.near_stale());
  walls[0].direction = Vec3(0, 1e-12, 1).normalized(); // turned
  CHECK(walls.near_stale());
  walls[0].direction = Vec3::UnitZ();
  walls.add(floor_wall(1e6));
  CHECK(walls.near_stale()); // a wall added
}

TEST_CASE("near-wall marks change no ball's motion against moving walls", "[dem][neighbors][walls]")
{
  // Balls at rest in a drum that shrinks, a floor, and a lid coming down
  // fast: with the narrowest skin (balls at rest) the walls outrun the
  // marks every few steps and are marked anew from the neighbour list's
  // centres.  A ball that a stale mark left out of a wall's reach would
  // pass through it, so the run must agree to the last bit with one whose
  // reach takes in every wall from every ball.
  const auto run = [](double skin_fraction, bool adaptive)
  {
    dem::ParticleStore p;
    for (int i = 0; i < 5; ++i)
      for (int j = 0; j < 5; ++j)
        for (int k = 0; k < 4; ++k)
        {
          const double jitter = 0.05e-3 * std::sin(1.7 * i + 2.3 * j + 3.1 * k);
          p.add(
            ball(Vec3(2.3e-3 * (i - 2) + jitter, 2.3e-3 * (j - 2) - jitter, 1.1e-3 + 2.3e-3 * k), 1e-3, 1e6, 1e5, 0.5));
        }
    dem::WallSet walls;
    walls.add(floor_wall(1e6, 1e5, 0.5));
    dem::Wall lid = floor_wall(1e6, 1e5, 0.5);
    lid.name = "lid";
    lid.point = Vec3(0, 0, 9.5e-3);
    lid.direction = -Vec3::UnitZ();
    lid.velocity = Vec3(0, 0, -0.08);
    walls.add(lid);
    dem::Wall drum;
    drum.name = "drum";
    drum.shape = dem::WallShape::cylinder;
    drum.radius = 7.7e-3;
    drum.radial_velocity = -0.03;
    drum.props = {1e6, 1e5, 0.5};
    walls.add(drum);
    dem::SimulationSettings settings = undamped();
    settings.local_damping = 0.3;
    settings.skin_fraction = skin_fraction;
    settings.adaptive_skin = adaptive;
    dem::Simulation sim = make_sim(std::move(p), std::move(walls), settings);
    for (int step = 0; step < 3000; ++step)
      sim.step();
    return sim;
  };
  const dem::Simulation marked = run(0.25, true);
  const dem::Simulation every = run(100, false); // every wall within reach of every ball
  INFO("marks " << marked.walls().near_marks() << ", rebuilds " << marked.neighbors().rebuilds() << ", wall contacts "
                << marked.walls().contacts().size() << ", time " << marked.time());
  REQUIRE(marked.walls().near_marks() > marked.neighbors().rebuilds() + 100); // walls outran the marks
  REQUIRE(marked.walls().contacts().size() > 20);                             // the walls reached the balls
  bool same = true;
  for (dem::Index b = 0; b < marked.particles().size(); ++b)
    same = same && marked.particles().position[b] == every.particles().position[b] &&
           marked.particles().velocity[b] == every.particles().velocity[b] &&
           marked.particles().spin[b] == every.particles().spin[b];
  CHECK(same);
}

TEST_CASE("a contact that slid hands its friction work to the retired total at the step it parts", "[dem][contacts]")
{
  // Not when a rebuild drops it: rebuild steps follow the skin (and a
  // resume), and the ledger's sums must be grouped alike in every run.
  // Two balls 1 um into each other, one sliding across at 1 m/s: the
  // contact slips at once (mu kn U = 0.1 N, ks v dt about 2 N), pushes them
  // apart, and parts within a few steps, well within the skin.
  auto sim = two_balls(1e-3, 2e-3 - 1e-6, 1e6, 1e6, 0.1);
  sim.particles().velocity[1] = Vec3(0, 1, 0);
  sim.step();
  double slid = 0, ledger = 0;
  for (int k = 0; k < 1000 && sim.contacts().find(0, 1)->state.touching(); ++k)
  {
    slid = sim.contacts().find(0, 1)->state.friction_work;
    ledger = sim.energy().friction;
    sim.step();
  }
  const dem::Contact *c = sim.contacts().find(0, 1);
  REQUIRE(c != nullptr); // parted, still listed: no rebuild dropped it
  REQUIRE_FALSE(c->state.touching());
  REQUIRE(slid > 0);
  CHECK(sim.neighbors().rebuilds() == 1);
  CHECK(c->state.friction_work == 0);
  CHECK(sim.contacts().retired().friction_work == slid);
  CHECK(sim.energy().friction == ledger);
}

TEST_CASE("the neighbour grid takes balls at huge coordinates without casting them out of range", "[dem][neighbors]")
{
  // Under UBSan (float-cast-overflow, the sanitizer build of CI) a cell
  // index cast from 1e300 / h is an error; the pairs must still be the
  // brute-force ones.
  const auto pairs_of = [](const std::vector<Vec3> &centres)
  {
    dem::ParticleStore p;
    for (const Vec3 &x : centres)
    {
      dem::BallSpec b;
      b.position = x;
      b.radius = 1e-3;
      p.add(b);
    }
    dem::NeighborList list(1e-4);
    list.rebuild(p);
    CHECK(list.pairs() == dem::brute_force_pairs(p, 1e-4));
    return list.pairs().size();
  };
  CHECK(pairs_of({Vec3(0, 0, 0), Vec3(1.5e-3, 0, 0), Vec3(1e300, 0, 0), Vec3(1e300, 1.5e-3, 0)}) == 2);
  CHECK(pairs_of({Vec3(-1e308, 0, 0), Vec3(1e308, 0, 0), Vec3(0, 0, 0), Vec3(0, 0, 1.5e-3)}) == 1);
  CHECK(pairs_of({Vec3(0, 0, 0), Vec3(0, 1e-300, 0), Vec3(0, 0, 1e300)}) == 1);
}

TEST_CASE("the cell search finds the brute-force pairs and the first deep overlap", "[dem][neighbors]")
{
  // A random cloud of unequal balls, dense enough for deep overlaps: the
  // candidate list equals the O(N^2) oracle, and the first pair found
  // overlapping by more than a fraction of the smaller radius is the first
  // such pair of the oracle's order, or none when the oracle finds none.
  dem::ParticleStore p;
  std::uint64_t state = 12345;
  const auto uniform = [&state]()
  {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return double(state >> 11) * 0x1.0p-53;
  };
  for (int k = 0; k < 400; ++k)
  {
    dem::BallSpec b;
    b.position = Vec3(uniform(), uniform(), uniform()) * 0.02;
    b.radius = 5e-4 + 1e-3 * uniform();
    p.add(b);
  }
  dem::NeighborList list(2e-4);
  list.rebuild(p);
  CHECK(list.pairs() == dem::brute_force_pairs(p, 2e-4));
  for (const double fraction : {0.2, 0.5, 0.9, 2.0})
  {
    std::optional<dem::Pair> expected;
    for (const dem::Pair &pair : dem::brute_force_pairs(p, 0))
    {
      const auto [i, j] = pair;
      const double overlap = p.radius[i] + p.radius[j] - (p.position[j] - p.position[i]).norm();
      if (overlap > fraction * std::min(p.radius[i], p.radius[j]))
      {
        expected = pair;
        break;
      }
    }
    const std::optional<dem::DeepOverlap> found = dem::first_deep_overlap(p, fraction);
    CHECK(found.has_value() == expected.has_value());
    if (found && expected)
    {
      // The cell order visits i ascending; for one i, its partners in cell order.
      CHECK(found->pair.first == expected->first);
      const auto [i, j] = found->pair;
      CHECK(p.radius[i] + p.radius[j] - (p.position[j] - p.position[i]).norm() >
            fraction * std::min(p.radius[i], p.radius[j]));
    }
  }
  // 200 000 balls on one point: the full candidate list would hold 2e10
  // pairs (a hang, then memory); the search stops at the first pair.
  dem::ParticleStore pile;
  pile.reserve(200000);
  for (int k = 0; k < 200000; ++k)
  {
    dem::BallSpec b;
    b.radius = 1e-3;
    pile.add(b);
  }
  const std::optional<dem::DeepOverlap> piled = dem::first_deep_overlap(pile, 0.5);
  CHECK((piled && piled->pair == dem::Pair(0, 1)));
}

TEST_CASE("the Morton order is a permutation, canonical whatever the input order, and keeps neighbours near",
          "[dem][order]")
{
  // 4096 balls of two radii on a jittered 16^3 grid, listed in a scrambled
  // order (consecutive rows far apart, as a file in generation order).
  dem::ParticleStore grid;
  std::uint64_t state = 7;
  const auto jitter = [&state]()
  {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return (static_cast<double>(state >> 11) / 9007199254740992.0 - 0.5) * 0.2e-3;
  };
  for (int i = 0; i < 16; ++i)
    for (int j = 0; j < 16; ++j)
      for (int k = 0; k < 16; ++k)
      {
        dem::BallSpec b;
        b.position = Vec3(i + jitter(), j + jitter(), k + jitter()) * 2.2e-3;
        b.radius = (i + j + k) % 2 ? 1e-3 : 0.8e-3;
        b.kn = 1e6;
        grid.add(b);
      }
  const dem::Index n = grid.size();
  std::vector<dem::Index> scramble(static_cast<std::size_t>(n));
  for (dem::Index k = 0; k < n; ++k)
    scramble[k] = static_cast<dem::Index>((static_cast<std::int64_t>(k) * 1237) % n); // 1237 is prime: a permutation
  const dem::ParticleStore listed = dem::renumbered(grid, scramble);
  const auto mean_step = [](const dem::ParticleStore &p)
  {
    double sum = 0;
    for (dem::Index k = 1; k < p.size(); ++k)
      sum += (p.position[k] - p.position[k - 1]).norm();
    return sum / (p.size() - 1);
  };

  const std::vector<dem::Index> order = dem::morton_order(listed);
  std::vector<dem::Index> sorted = order;
  std::sort(sorted.begin(), sorted.end());
  std::vector<dem::Index> identity(static_cast<std::size_t>(n));
  std::iota(identity.begin(), identity.end(), dem::Index{0});
  REQUIRE(sorted == identity);
  const std::vector<dem::Index> inverse = dem::inverse_permutation(order);
  for (dem::Index k = 0; k < n; ++k)
    REQUIRE(inverse[order[k]] == k);

  // Canonical: the grid in its own order and scrambled give the same balls
  // in the same places, every array moved with its ball.
  const dem::ParticleStore a = dem::renumbered(grid, dem::morton_order(grid)), b = dem::renumbered(listed, order);
  CHECK(a.position == b.position);
  CHECK(a.radius == b.radius);
  CHECK(a.mass == b.mass);
  CHECK(a.inv_inertia == b.inv_inertia);
  // Near in memory is near in space: on the curve consecutive balls are
  // about one spacing (2.2 mm) apart, against a third of the block
  // (about 12 mm) in the scrambled list.
  CHECK(mean_step(listed) > 10e-3);
  CHECK(mean_step(b) < 4e-3);
}

TEST_CASE("six bands of equal volume and their analysis of variance", "[dem][measure]")
{
  dem::CylinderBands bands;
  bands.base = dem::Vec3(1, 2, 3);
  bands.height = 0.03;
  bands.radius = 0.01;
  // Thirds of the height, the core inside R / sqrt(2) (equal areas); a
  // point beyond the cylinder counts in the nearest band.
  const double core = 0.01 / std::sqrt(2.0);
  CHECK(bands.band(bands.base + dem::Vec3(0.99 * core, 0, 0.001)) == 0);
  CHECK(bands.band(bands.base + dem::Vec3(0, 1.01 * core, 0.001)) == 1);
  CHECK(bands.band(bands.base + dem::Vec3(0, 0, 0.0101)) == 2);
  CHECK(bands.band(bands.base + dem::Vec3(0.0102, 0, 0.029)) == 5);
  CHECK(bands.band(bands.base + dem::Vec3(0, 0, -0.001)) == 0);
  CHECK(bands.band(bands.base + dem::Vec3(0, 0, 0.031)) == 4);

  // Two bands by hand: {1, 2, 3} and {4, 5, 6}: means 2 and 5, between-band
  // sum of squares 13.5 on 1 degree of freedom, within 4 on 4: F = 13.5,
  // and with two groups F(1, n) is t(n) squared.
  std::vector<dem::Vec3> points;
  std::vector<double> values;
  for (int i = 0; i < 6; ++i)
  {
    points.push_back(bands.base + dem::Vec3(i < 3 ? 0.0 : 0.009, 0, 0.001));
    values.push_back(i + 1);
  }
  const dem::BandMeans two = dem::band_means(bands, points, values);
  CHECK(two.contacts[0] == 3);
  CHECK(two.contacts[1] == 3);
  CHECK(two.mean[0] == 2);
  CHECK(two.mean[1] == 5);
  CHECK(std::isnan(two.mean[2]));
  CHECK(two.overall_mean == 3.5);
  CHECK_THAT(two.f_statistic, Catch::Matchers::WithinRel(13.5, 1e-14));
  CHECK_THAT(two.p_value, Catch::Matchers::WithinRel(2 * gsl_cdf_tdist_Q(std::sqrt(13.5), 4), 1e-10));
  CHECK_THAT(two.half_width[0], Catch::Matchers::WithinRel(1.96 * 1 / std::sqrt(3.0), 1e-14));

  // A quantity that does not depend on where it is: the bands agree (p far
  // from 0); one that grows with the height by 20 %: they do not.
  std::vector<double> flat, graded;
  points.clear();
  std::uint64_t state = 12345;
  const auto uniform = [&state]
  {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return double(state >> 11) / double(1ULL << 53);
  };
  for (int i = 0; i < 6000; ++i)
  {
    const double r = 0.01 * std::sqrt(uniform()), a = 2 * dem::pi * uniform(), z = 0.03 * uniform();
    points.push_back(bands.base + dem::Vec3(r * std::cos(a), r * std::sin(a), z));
    const double noise = -std::log(1 - uniform()); // exponential, as contact forces roughly are
    flat.push_back(noise);
    graded.push_back(noise * (1 + 0.2 * z / 0.03));
  }
  const dem::BandMeans even = dem::band_means(bands, points, flat);
  CHECK(even.p_value > 0.01);
  for (int b = 0; b < dem::CylinderBands::count; ++b)
    CHECK(std::abs(even.mean[b] - even.overall_mean) < 2 * even.half_width[b]);
  const dem::BandMeans rising = dem::band_means(bands, points, graded);
  CHECK(rising.p_value < 1e-6);
  CHECK(rising.mean[4] > rising.mean[0] + rising.half_width[4] + rising.half_width[0]);
}

TEST_CASE("band counts against a uniform share: chi-square, Poisson intervals, contact directions", "[dem][measure]")
{
  using Bands = std::array<double, dem::CylinderBands::count>;
  // By hand: weights 1:1:2:2:0:0, 30 events seen as 10, 0, 10, 10, 0, 0.
  // Expected 5, 5, 10, 10 (and 0, 0, left out): X^2 = 25/5 + 25/5 = 10 on
  // 3 degrees of freedom.
  const dem::BandCounts c = dem::band_counts(Bands{10, 0, 10, 10, 0, 0}, Bands{1, 1, 2, 2, 0, 0});
  CHECK(c.expected == Bands{5, 5, 10, 10, 0, 0});
  CHECK_THAT(c.chi_square, Catch::Matchers::WithinRel(10.0, 1e-14));
  CHECK(c.degrees_of_freedom == 3);
  CHECK_THAT(c.p_value, Catch::Matchers::WithinRel(gsl_cdf_chisq_Q(10.0, 3), 1e-14));
  CHECK(std::isnan(c.ratio_low[4]));
  // Exact Poisson 95 % bounds (Garwood; tabulated: 0 seen, [0, 3.689];
  // 10 seen, [4.795, 18.39]), over the expectation.
  CHECK(c.ratio_low[1] == 0);
  CHECK_THAT(c.ratio_high[1] * 5, Catch::Matchers::WithinAbs(3.689, 1e-3));
  CHECK_THAT(c.ratio_low[2] * 10, Catch::Matchers::WithinAbs(4.795, 1e-3));
  CHECK_THAT(c.ratio_high[2] * 10, Catch::Matchers::WithinAbs(18.39, 1e-2));
  // Counts in proportion to the weights: X^2 = 0, p = 1.
  const dem::BandCounts even = dem::band_counts(Bands{3, 3, 6, 6, 9, 9}, Bands{1, 1, 2, 2, 3, 3});
  CHECK(even.chi_square == 0);
  CHECK(even.p_value == 1);

  // Directions: a pair pressed together along z and a bonded pair pulled
  // apart along x; (n . z)^2 is 1 for the first, 0 for the second.
  dem::ParticleStore p;
  for (const dem::Vec3 &at :
       {dem::Vec3(0, 0, 0), dem::Vec3(0, 0, 1.9e-3), dem::Vec3(1, 0, 0), dem::Vec3(1.002001, 0, 0)})
    p.add(dem::small_systems::ball(at, 1e-3, 1e6, 1e5, 0.5));
  auto sim = demtest::make_sim(std::move(p));
  sim.refresh_contacts();
  dem::bond_pair(sim.contacts(), sim.particles(), 2, 3, 1e6, 1e6);
  sim.compute_forces();
  const dem::ContactDirections d = dem::contact_directions(sim, dem::Vec3::UnitZ());
  CHECK(d.compressive.contacts == 1);
  CHECK_THAT(d.compressive.mean, Catch::Matchers::WithinAbs(1.0, 1e-15));
  CHECK(d.tensile.contacts == 1);
  CHECK_THAT(d.tensile.mean, Catch::Matchers::WithinAbs(0.0, 1e-15));
}

TEST_CASE("a test stops when its platens close on no sample or a contact overlaps beyond half a radius",
          "[dem][protocol]")
{
  // One ball on the bottom platen, the top platen 3r above: the ball is
  // sent sideways out of the cell, so the top platen closes on nothing.
  // Below one ball radius of gap no sample is left between the platens:
  // the test stops there (a creep load beyond the strength ends the same
  // way, the balls squeezed out) instead of measuring strains past 100 %.
  const double r = 1e-3, kn = 1e6;
  const auto cell = [&](const Vec3 &velocity)
  {
    dem::WallSet walls;
    walls.add(floor_wall(kn));
    dem::Wall top = floor_wall(kn);
    top.name = "top";
    top.point = Vec3(0, 0, 3 * r);
    top.direction = -Vec3::UnitZ();
    walls.add(top);
    dem::ParticleStore p;
    dem::BallSpec b = ball(Vec3(0, 0, r), r, kn);
    b.velocity = velocity;
    p.add(b);
    return make_sim(std::move(p), std::move(walls));
  };
  dem::UniaxialSettings settings;
  settings.platen_speed = 10; // m/s: the gap closes in 3e-4 s
  settings.final_strain = 0.99;
  auto escaped = cell(Vec3(20, 0, 0));
  dem::UniaxialCompression test(escaped, 0, 1, dem::pi * r * r, settings);
  std::string message;
  try
  {
    while (escaped.step(test))
      ;
  }
  catch (const dem::NumericalFault &f)
  {
    message = f.what();
  }
  CHECK(message.find("the sample collapsed") != std::string::npos);
  // It stopped at the first step whose gap was below r (the platen moves
  // 10 m/s * dt, a few hundredths of r, per step).
  const double gap = escaped.walls()[1].point.z();
  CHECK(gap < r);
  CHECK(gap > 0.9 * r);

  // The ball kept in the cell: the platen squeezes it, and the overlap
  // check names it once the overlap passes half its radius.
  auto squeezed = cell(Vec3::Zero());
  dem::UniaxialCompression press(squeezed, 0, 1, dem::pi * r * r, settings);
  double deepest = 0;
  message.clear();
  try
  {
    while (squeezed.step(press))
    {
      squeezed.check_contact_overlaps(0.5);
      deepest = std::max(deepest, squeezed.walls().state(0, 0).overlap);
    }
  }
  catch (const dem::NumericalFault &f)
  {
    message = f.what();
    CHECK(f.particle == 0);
  }
  CHECK(message.find("contact overlap beyond the law's meaning") != std::string::npos);
  CHECK(deepest <= 0.5 * r); // the last overlap checked and passed
  CHECK(deepest > 0.45 * r); // ... and it stopped at the first one beyond
}

TEST_CASE("a bond break is logged with the trial forces that broke it", "[dem][bonds]")
{
  // Two touching balls bonded with phi_n = 0.1 N, pulled apart at 2 v: the
  // normal force K^n U falls by K^n 2 v dt per step at most (the spring slows them), so the trial force at
  // the break lies within one such decrement beyond -phi_n; no shear motion.
  const double kn = 1e6, phi = 0.1, v = 0.1, dt = 1e-7;
  auto sim = two_balls(1e-3, 2e-3, kn);
  sim.settings().fixed_time_step = dt;
  sim.refresh_contacts();
  dem::bond_pair(sim.contacts(), sim.particles(), 0, 1, phi, 10.0);
  sim.particles().velocity[0] = Vec3(-v, 0, 0);
  sim.particles().velocity[1] = Vec3(v, 0, 0);
  std::vector<dem::BondBreak> breaks;
  for (int k = 0; k < 100000 && breaks.empty(); ++k)
  {
    sim.step();
    breaks = sim.take_breaks();
  }
  REQUIRE(breaks.size() == 1);
  CHECK(breaks[0].mode == dem::BreakMode::tension);
  CHECK(breaks[0].normal_force <= -phi);
  const double pair_kn = dem::in_series(kn, kn);
  CHECK(breaks[0].normal_force > -phi - pair_kn * 2 * v * dt * (1 + 1e-9));
  CHECK(breaks[0].shear_force == 0);
  CHECK(sim.contacts().find(0, 1)->state.normal_force == 0); // the applied force after the break
}

TEST_CASE("Gaussian bond strengths are seeded and truncated and counted, removal is exact", "[dem][bonds]")
{
  dem::ParticleStore p;
  for (const Vec3 &x : dem::lattice_box(dem::Lattice::simple_cubic, 1e-3, 6, 6, 6))
    p.add(ball(x, 1e-3, 1e6));
  auto make = [&]
  {
    auto sim = make_sim(p);
    sim.refresh_contacts();
    return sim;
  };
  dem::BondSettings s;
  s.normal_strength = s.shear_strength = 10;
  s.cov = 0.5;
  s.seed = 42;
  auto a = make(), b = make();
  const auto ra = dem::bond_touching_pairs(a.contacts(), a.particles(), s);
  const auto rb = dem::bond_touching_pairs(b.contacts(), b.particles(), s);
  CHECK(ra.bonded == 3 * 6 * 6 * 5); // SC lattice 6^3: 3 x 6 x 6 x 5 touching pairs
  CHECK(ra.truncated_draws == rb.truncated_draws);
  CHECK(ra.truncated_draws > 0); // at CoV 0.5, P(z < -1.98) ~ 2.4 % of 1080 draws fall below 1 % of the mean
  for (std::size_t k = 0; k < a.contacts().size(); ++k)
    CHECK(a.contacts()[k].bond.normal_strength == b.contacts()[k].bond.normal_strength);
  double lowest = 1e300;
  for (const auto &c : a.contacts().entries())
    lowest = std::min(lowest, c.bond.normal_strength);
  CHECK(lowest == Approx(0.1)); // the floor, 1 % of the mean

  s.removed_fraction = 0.2;
  auto c = make();
  const auto rc = dem::bond_touching_pairs(c.contacts(), c.particles(), s);
  CHECK(rc.removed == static_cast<std::size_t>(std::llround(0.2 * 540)));
  CHECK(rc.bonded + rc.removed == 540);
}

TEST_CASE("a ball resting on a wall gets a finite step that is exactly the limit", "[dem][stability]")
{
  dem::WallSet walls;
  walls.add(floor_wall(1e6, 1e5));
  dem::ParticleStore p;
  p.add(ball(Vec3(0, 0, 1e-3 - 1e-8), 1e-3, 1e6, 1e5));
  auto sim = make_sim(std::move(p), std::move(walls));
  sim.compute_forces();
  // One ball on a wall with ks > 0: exact omega_max^2 = max(K_n/m, K_s(1/m + R^2/I)).
  REQUIRE(std::isfinite(sim.critical_time_step()));
  CHECK_THAT(sim.critical_time_step(), WithinRel(dem::exact_stability_limit(sim), 1e-12));
}

TEST_CASE("centred differences run a linear oscillator at (2/dt) asin(omega dt/2)", "[dem][stability]")
{
  // Two bonded balls pulled apart oscillate about touching with omega^2 =
  // K / m* = kn / m (K = kn / 2 in series, m* = m / 2), tension and
  // compression alike.  At a fixed step dt = theta / omega the measured
  // period, from the upward zero crossings of the gap over 50 periods
  // (linear interpolation), must match the closed form the summaries quote:
  // frequency high by (2/theta) asin(theta/2) - 1 (4.7 % at theta = 1, 1.1 %
  // at 0.5).  Interpolating a sampled sine near its zero is accurate to
  // O(theta^3) dt per crossing; over 50 periods that is below 1e-4 of the
  // period, so 1e-3 separates the closed form from either no error or the
  // leading-order estimate theta^2 / 24 (4.2 % at theta = 1).
  for (const double theta : {1.0, 0.5})
  {
    CAPTURE(theta);
    const double kn = 1e6, r = 1e-3, v = 1e-3;
    auto sim = two_balls(r, 2 * r, kn);
    sim.refresh_contacts();
    dem::bond_pair(sim.contacts(), sim.particles(), 0, 1, 1e12, 1e12);
    const double omega = std::sqrt(kn / sim.particles().mass[0]);
    const double dt = theta / omega;
    sim.settings().fixed_time_step = dt;
    sim.particles().velocity[0] = Vec3(-v, 0, 0);
    sim.particles().velocity[1] = Vec3(v, 0, 0);
    std::vector<double> crossings;
    double previous_gap = 0, previous_time = 0;
    while (crossings.size() < 52)
    {
      sim.step();
      const double gap = (sim.particles().position[1] - sim.particles().position[0]).norm() - 2 * r;
      if (previous_gap <= 0 && gap > 0 && sim.time() > dt)
        crossings.push_back(previous_time + dt * (-previous_gap) / (gap - previous_gap));
      previous_gap = gap;
      previous_time = sim.time();
    }
    const double period = (crossings.back() - crossings[1]) / double(crossings.size() - 2);
    const double measured_error = (2 * dem::pi / omega) / period - 1;
    const double steps_per_period = 2 * dem::pi / theta;
    CHECK(measured_error == Approx(dem::centred_difference_frequency_error(steps_per_period)).epsilon(1e-3));
    CHECK(std::abs(measured_error - theta * theta / 24) > 1e-3 * measured_error);
  }
}

TEST_CASE("local damping lowers the stability limit to 2 / sqrt((1 + alpha) omega^2)", "[dem][stability]")
{
  // Two bonded balls oscillate freely with omega^2 = kn / m (see above).
  // Under local damping alpha the flip-flop mode is an exact solution of the
  // scheme with the stiffness (1 + alpha) kn (stability.h), so it grows once
  // omega dt > 2 / sqrt(1 + alpha) = 1.534 at alpha = 0.7, although the
  // undamped scheme is stable up to 2; the engine's bound is the damped one.
  // Measured over 400 steps at three steps:
  //   1.0 (0.65 of the damped limit): the motion dies out (under 1e-3 of
  //     the start over the last 100 steps) and the damping's booked work
  //     never goes negative;
  //   1.227 (the default safety 0.8 of it): the motion dies out too, but
  //     the work booked over steps that reverse the velocity comes out
  //     negative (-0.6 of the energy supplied): the ledger check stops
  //     such a run, whose ledger no longer describes it;
  //   1.59 (4 % above it): the mode grows more than a hundredfold, or
  //     faults as runaway motion.
  const double alpha = 0.7, limit = 2 / std::sqrt(1 + alpha);
  struct Case
  {
    double theta;
    bool dies_out, ledger_sound;
  };
  for (const Case &c : {Case{1.0, true, true}, Case{0.8 * limit, true, false}, Case{1.59, false, false}})
  {
    CAPTURE(c.theta);
    const double kn = 1e6, r = 1e-3, v = 1e-3;
    auto sim = two_balls(r, 2 * r, kn);
    sim.settings().local_damping = alpha;
    sim.refresh_contacts();
    dem::bond_pair(sim.contacts(), sim.particles(), 0, 1, 1e12, 1e12);
    const double omega = std::sqrt(kn / sim.particles().mass[0]);
    sim.settings().fixed_time_step = c.theta / omega;
    sim.settings().allow_unstable_step = true;
    sim.particles().velocity[0] = Vec3(-v, 0, 0);
    sim.particles().velocity[1] = Vec3(v, 0, 0);
    sim.compute_forces();
    CHECK_THAT(sim.critical_time_step() * omega, WithinRel(limit, 1e-12));
    const double start = v / omega;
    double late = 0, least_damping = 0;
    std::string ledger_fault;
    try
    {
      for (int k = 0; k < 400; ++k)
      {
        sim.compute_forces();
        sim.integrate(true);
        least_damping = std::min(least_damping, sim.energy().damping);
        try
        {
          sim.check_energy_ledger(dem::LedgerLimits{});
        }
        catch (const dem::NumericalFault &f)
        {
          ledger_fault = ledger_fault.empty() ? f.what() : ledger_fault;
        }
        if (k >= 300)
          late = std::max(late, std::abs((sim.particles().position[1] - sim.particles().position[0]).norm() - 2 * r));
      }
    }
    catch (const dem::NumericalFault &f)
    {
      CHECK(std::string(f.what()).find("runaway motion") != std::string::npos);
      late = dem::infinity;
    }
    CHECK((late < 1e-3 * start) == c.dies_out);
    CHECK((late > 100 * start) == !c.dies_out);
    CHECK((least_damping >= 0) == c.ledger_sound);
    CHECK((ledger_fault.find("local damping gave energy") != std::string::npos) == !c.ledger_sound);
  }
}

TEST_CASE("the energy check stops a step the contacts cannot follow and passes one they can", "[dem][stability]")
{
  // Two bonded balls oscillate about touching with omega^2 = kn / m.  The
  // scheme conserves its invariant E (kinetic at the force time + strain)
  // at any step, but the strain part peaks at E / (1 - theta^2 / 4),
  // theta = omega dt: 1.33 E at theta = 1, 2.3 E at 1.5, 20 E at 1.95
  // (stable, 2.5 % under the limit theta = 2) and without bound above 2.
  // The check (factor 10 on the energy supplied, here E) passes the first
  // two and stops the others within a few periods.
  for (const auto &[theta, stops] : {std::pair{1.0, false}, {1.5, false}, {1.95, true}, {2.1, true}})
  {
    CAPTURE(theta);
    const double kn = 1e6, r = 1e-3, v = 1e-3;
    auto sim = two_balls(r, 2 * r, kn);
    sim.refresh_contacts();
    dem::bond_pair(sim.contacts(), sim.particles(), 0, 1, 1e12, 1e12);
    sim.settings().fixed_time_step = theta / std::sqrt(kn / sim.particles().mass[0]);
    sim.settings().allow_unstable_step = true;
    sim.particles().velocity[0] = Vec3(-v, 0, 0);
    sim.particles().velocity[1] = Vec3(v, 0, 0);
    bool stopped = false;
    try
    {
      for (int k = 0; k < 500; ++k)
      {
        sim.compute_forces();
        sim.integrate(true);
        sim.check_energy_ledger(dem::LedgerLimits{});
      }
    }
    catch (const dem::NumericalFault &f)
    {
      stopped = true;
      CHECK(std::string(f.what()).find("runaway energy") != std::string::npos);
      CHECK(f.particle >= 0);
    }
    CHECK(stopped == stops);
  }
}

TEST_CASE("an elastic impact rebounds with its energy only when the step resolves the contact", "[dem][stability]")
{
  // A free pair of equal balls meets head on with no damping: the closed
  // form is a rebound with all its kinetic energy (restitution 1).  Where
  // the first touch falls within a step decides the error of the discrete
  // impact: the balls travel a whole step into the overlap before a force
  // acts.  Over twenty phases of that touch the largest error is measured
  // at the safeties the run's contact-resolution warning quotes (16 and 31
  // steps per period): under 3 % and 1 %; at the default 0.8 (3.9 steps)
  // it passes 100 % for some phase.  The bounds are the warning's claims,
  // each about 15 % above the largest error measured (2.6 %, 0.88 %).
  const double kn = 1e6, r = 1e-3, v = 0.01;
  const auto largest_rebound_error = [&](double safety)
  {
    double largest = 0;
    for (int phase = 0; phase < 20; ++phase)
    {
      auto sim = two_balls(r, 2 * r, kn);
      sim.settings().time_step_safety = safety;
      const double step = safety * 2 / std::sqrt(kn / sim.particles().mass[0]);
      sim.particles().position[1].x() += 2 * v * step * phase / 20.0;
      sim.particles().velocity[0] = Vec3(v, 0, 0);
      sim.particles().velocity[1] = Vec3(-v, 0, 0);
      const double before = sim.particles().mass[0] * v * v;
      while (sim.time() < 4 * dem::pi * std::sqrt(sim.particles().mass[0] / kn))
        sim.step();
      const auto &w = sim.particles().velocity;
      const double after = 0.5 * sim.particles().mass[0] * (w[0].squaredNorm() + w[1].squaredNorm());
      REQUIRE((sim.particles().position[1] - sim.particles().position[0]).norm() > 2 * r);
      largest = std::max(largest, std::abs(after / before - 1));
    }
    return largest;
  };
  CHECK(largest_rebound_error(0.2) < 0.03);
  CHECK(largest_rebound_error(0.1) < 0.01);
  CHECK(largest_rebound_error(0.8) > 1.0);
}

TEST_CASE("least_steps bounds the steps of a run from below", "[dem][stability]")
{
  // Two balls meet and part: the automatic step shrinks while they touch,
  // so the run takes more steps than the bound of one lone contact per ball.
  auto sim = two_balls(1e-3, 2.1e-3, 1e6);
  sim.particles().velocity[0] = Vec3(0.05, 0, 0);
  const double duration = 5e-3;
  const double least = dem::least_steps(sim.particles(), sim.settings(), duration);
  while (sim.time() < duration)
    sim.step();
  CHECK(least > 100);
  CHECK(double(sim.steps()) >= least);
  CHECK(double(sim.steps()) < 2 * least);
  // A fixed step gives the count exactly.
  sim.settings().fixed_time_step = 1e-6;
  CHECK_THAT(dem::least_steps(sim.particles(), sim.settings(), duration), WithinRel(5000.0, 1e-12));
}

namespace
{
/// Runs `passes` passes of a loop whose item i costs cost(i) seconds on
/// balanced ranges, checking after each that the ranges cover the items in
/// order; returns each range's time in the last pass.
template <class Cost>
std::vector<double> balance(dem::BalancedRanges &ranges, std::size_t items, int count, int passes, Cost cost)
{
  std::vector<double> seconds;
  for (int pass = 0; pass < passes; ++pass)
  {
    ranges.prepare(items, count);
    REQUIRE(ranges.ranges() == count);
    REQUIRE(ranges.begin(0) == 0);
    REQUIRE(ranges.end(count - 1) == items);
    seconds.assign(static_cast<std::size_t>(count), 0.0);
    for (int r = 0; r < count; ++r)
    {
      REQUIRE(ranges.begin(r) <= ranges.end(r));
      if (r > 0)
        REQUIRE(ranges.begin(r) == ranges.end(r - 1));
      for (std::size_t i = ranges.begin(r); i < ranges.end(r); ++i)
        seconds[static_cast<std::size_t>(r)] += cost(i);
      ranges.record(r, seconds[static_cast<std::size_t>(r)]);
    }
    ranges.rebalance();
  }
  return seconds;
}
} // namespace

TEST_CASE("balanced ranges cover a loop in order and move their cuts to equal times", "[dem][threads]")
{
  // Items 0-299 cost three times the rest: 1600 units in all, split equally
  // at 800/3 = 266.7 items.  Each pass moves the cut half way to where the
  // measured costs put it (rounded to an item), so after 40 passes it is
  // within an item.
  dem::BalancedRanges two;
  const auto step_cost = [](std::size_t i) { return i < 300 ? 3.0 : 1.0; };
  balance(two, 1000, 2, 40, step_cost);
  CHECK(std::abs(double(two.end(0)) - 800.0 / 3.0) <= 1.0);

  // A cost that grows along the loop (item i costs i + 1) on three ranges:
  // the times come out equal to within a few items' cost (about 1 %).
  dem::BalancedRanges three;
  const std::vector<double> t = balance(three, 3000, 3, 60, [](std::size_t i) { return double(i + 1); });
  const double total = t[0] + t[1] + t[2];
  for (double s : t)
    CHECK(std::abs(s - total / 3) <= 0.01 * total / 3);

  // A new item count keeps the cuts' fractions; a new range count starts
  // from equal shares; equal times leave the cuts where they are.
  two.prepare(2000, 2);
  CHECK(std::abs(double(two.end(0)) - 1600.0 / 3.0) <= 2.0);
  dem::BalancedRanges even;
  balance(even, 999, 3, 5, [](std::size_t) { return 1.0; });
  even.prepare(999, 3);
  CHECK(even.end(0) == 333);
  CHECK(even.end(1) == 666);
  even.prepare(999, 2);
  CHECK(even.end(0) == 499);
}
