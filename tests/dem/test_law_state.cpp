// A contact law's own history (LawState) lives with the contact: it follows
// the entries through table rebuilds and snapshots, so a Burger's run saved
// mid-test continues its elements exactly.
#include "tests/dem/two_body.h"

#include "dem/bonds.h"
#include "dem/specimen.h"

#include <catch2/catch.hpp>

#include <omp.h>

#include <algorithm>
#include <map>
#include <random>
#include <string>

using namespace demtest;

namespace
{
/// A recognisable, non-rest Burger's state.
dem::LawState element(double scale)
{
  dem::BurgersHistory h;
  h.overlap = -1e-7 * scale;
  h.normal_force = -0.5 * scale;
  h.normal_kelvin = 2e-8 * scale;
  h.shear_kelvin = Vec3(1e-9, -3e-9, 5e-9) * scale;
  dem::LawState s;
  dem::BurgersHistory::store(h, s);
  return s;
}

/// A bonded FCC cylinder (about 300 balls) between platens, the top one
/// moving down; `law` is a registry keyword.
dem::Simulation compressed_cylinder(std::string_view law)
{
  const dem::BallSpec spec = ball(Vec3::Zero(), 0, 1.2e7, 1.2e6, 0.5);
  dem::Specimen s = dem::lattice_specimen(dem::Lattice::face_centred_cubic, 0.885e-3, 0.008, 0.008, spec,
                                          {1.2e7, 1.2e6, 0.3}, {}, false);
  const dem::WallIndex top = s.top;
  dem::Simulation sim(std::move(s.particles), std::move(s.walls), dem::make_contact_model(law, {}), {});
  sim.refresh_contacts();
  dem::BondSettings bonds;
  bonds.normal_strength = bonds.shear_strength = 0.05;
  dem::bond_touching_pairs(sim.contacts(), sim.particles(), bonds);
  sim.walls()[top].velocity = Vec3(0, 0, -0.5);
  return sim;
}

std::size_t non_rest_states(const dem::ContactTable &t)
{
  std::size_t n = 0;
  for (const dem::LawState &s : t.law_states())
    n += s == dem::LawState{} ? 0 : 1;
  return n;
}
} // namespace

TEST_CASE("a Burger's history maps to its LawState slot and back, all zero at rest", "[dem][law_state]")
{
  const dem::LawState s = element(1.0);
  const dem::BurgersHistory h = dem::BurgersHistory::load(s);
  dem::LawState back;
  dem::BurgersHistory::store(h, back);
  CHECK(back == s);
  const dem::BurgersHistory rest = dem::BurgersHistory::load(dem::LawState{});
  CHECK(rest.overlap == 0);
  CHECK(rest.normal_force == 0);
  CHECK(rest.normal_kelvin == 0);
  CHECK(rest.shear_kelvin == Vec3::Zero());
  CHECK(dem::find_law("burgers")->state_fields.size() == dem::BurgersHistory::state_fields.size());
  CHECK(dem::find_law("linear")->state_fields.empty());
}

TEST_CASE("table rebuilds carry each contact's law state, a new pair starts at rest", "[dem][law_state][contacts]")
{
  dem::ParticleStore p;
  for (int k = 0; k < 4; ++k)
    p.add(ball(Vec3(2e-3 * k, 0, 0), 1e-3, 1e6));
  dem::ContactTable t;
  t.rebuild({{0, 1}, {2, 3}}, p);
  REQUIRE(t.law_states().size() == 2);
  t.law_states()[0] = element(1.0);
  t.law_states()[1] = element(2.0);
  t[1].state.normal = Vec3::UnitX(); // touching: (2, 3) stays even when no longer a candidate

  // (1, 2) is new and lands between the two old entries; (2, 3) is kept for
  // its touching state although it is no candidate any more.
  t.rebuild({{0, 1}, {1, 2}}, p);
  REQUIRE(t.size() == 3);
  REQUIRE(t.law_states().size() == 3);
  CHECK(t.law_states()[t.find(0, 1) - &t[0]] == element(1.0));
  CHECK(t.law_states()[t.find(1, 2) - &t[0]] == dem::LawState{});
  CHECK(t.law_states()[t.find(2, 3) - &t[0]] == element(2.0));

  // A pair inserted by ensure starts at rest and shifts the others' slots with them.
  t.ensure(0, 2, p);
  REQUIRE(t.law_states().size() == 4);
  CHECK(t.law_states()[t.find(0, 2) - &t[0]] == dem::LawState{});
  CHECK(t.law_states()[t.find(2, 3) - &t[0]] == element(2.0));

  // A pair that left the table and comes back is a new contact: at rest.
  t.rebuild({{0, 1}}, p);
  CHECK(t.find(2, 3) != nullptr);
  t.find(2, 3)->state.normal.setZero();
  t.rebuild({{0, 1}}, p);
  CHECK(t.find(2, 3) == nullptr);
  t.rebuild({{0, 1}, {2, 3}}, p);
  CHECK(t.law_states()[t.find(2, 3) - &t[0]] == dem::LawState{});
  CHECK(t.law_states()[t.find(0, 1) - &t[0]] == element(1.0));

  // Assigned entries take their states, or rest when none are given.
  const std::vector<dem::ContactRecord> entries = t.records();
  t.assign(entries, {element(3.0), element(4.0)}, p, {});
  CHECK(t.law_states()[1] == element(4.0));
  t.assign(entries, {}, p, {});
  CHECK(t.law_states() == std::vector<dem::LawState>(2));
  CHECK_THROWS_AS(t.assign(entries, {element(1.0)}, p, {}), std::invalid_argument);
}

TEST_CASE("an in-place rebuild gives the table a plain merge into a new one gives", "[dem][law_state][contacts]")
{
  // The reference is the obvious merge: keep every old entry that is a
  // candidate, touching or bonded, add every new candidate at rest, retire
  // the rest in increasing order.  Random tables over 40 balls and random
  // candidate lists, so that new pairs land before, between and after the
  // kept ones; the result must be equal entry for entry and to the bit
  // (retired energies included), with the adjacency lists that go with it.
  dem::ParticleStore p;
  for (int k = 0; k < 40; ++k)
    p.add(ball(Vec3(2e-3 * k, 0, 0), 1e-3, 1e6 * (1 + k % 3)));
  std::mt19937 random(7);
  const auto random_pairs = [&](double share)
  {
    std::vector<dem::Pair> pairs;
    std::bernoulli_distribution take(share);
    for (dem::Index i = 0; i < 40; ++i)
      for (dem::Index j = i + 1; j < 40; ++j)
        if (take(random))
          pairs.emplace_back(i, j);
    return pairs;
  };
  std::uniform_real_distribution<double> unit(0, 1);
  for (int round = 0; round < 50; ++round)
  {
    dem::ContactTable t;
    t.rebuild(random_pairs(0.1 + 0.2 * (round % 3)), p);
    for (std::size_t c = 0; c < t.size(); ++c)
    {
      t[c].state.normal = unit(random) < 0.3 ? Vec3(Vec3::UnitX()) : Vec3(Vec3::Zero());
      t[c].bonded = unit(random) < 0.2;
      t[c].state.friction_work = unit(random);
      t[c].state.bond_energy = unit(random);
      t.law_states()[c] = element(unit(random));
    }
    const std::vector<dem::Pair> candidates = random_pairs(0.05 + 0.1 * (round % 4));

    std::map<dem::Pair, std::pair<dem::ContactRecord, dem::LawState>> expected;
    dem::RetiredContactEnergy retired;
    const std::vector<dem::ContactRecord> before = t.records();
    for (std::size_t c = 0; c < t.size(); ++c)
    {
      const dem::ContactRecord &k = before[c];
      const dem::Pair key{k.first, k.second};
      if (k.state.touching() || k.bonded || std::binary_search(candidates.begin(), candidates.end(), key))
        expected[key] = {k, t.law_states()[c]};
      else
      {
        retired.friction_work += k.state.friction_work;
        retired.bond_energy += k.state.bond_energy;
      }
    }
    for (const dem::Pair &pair : candidates)
      if (expected.count(pair) == 0)
      {
        dem::ContactRecord k;
        k.first = pair.first;
        k.second = pair.second;
        k.params = dem::ContactTable::pair_params(p, pair.first, pair.second);
        expected[pair] = {k, dem::LawState{}};
      }

    t.rebuild(candidates, p);
    REQUIRE(t.size() == expected.size());
    REQUIRE(t.law_states().size() == expected.size());
    std::size_t c = 0;
    for (const auto &[key, entry] : expected)
    {
      const dem::Contact &k = t[c];
      CHECK((k.first == key.first && k.second == key.second));
      const dem::ContactParams &pair = t.params(k), &expected_pair = entry.first.params;
      CHECK((pair.kn == expected_pair.kn && pair.ks == expected_pair.ks && pair.friction == expected_pair.friction));
      CHECK(k.state.touching() == entry.first.state.touching());
      CHECK(k.bonded == entry.first.bonded);
      CHECK(k.state.friction_work == entry.first.state.friction_work);
      CHECK(t.law_states()[c] == entry.second);
      ++c;
    }
    CHECK(t.retired().friction_work == retired.friction_work);
    CHECK(t.retired().bond_energy == retired.bond_energy);
    for (dem::Index b = 0; b < 40; ++b)
    {
      for (std::size_t k = t.first_begin(b); k < t.first_begin(b + 1); ++k)
        CHECK(t[k].first == b);
      std::vector<std::size_t> seconds;
      for (std::size_t k = 0; k < t.size(); ++k)
        if (t[k].second == b)
          seconds.push_back(k);
      const std::vector<std::size_t> listed(t.second_list().begin() + t.second_begin(b),
                                            t.second_list().begin() + t.second_begin(b + 1));
      CHECK(listed == seconds);
    }
  }
}

TEST_CASE("entries share their pair constants, each distinct set once, through edits, saves and rebuilds",
          "[dem][contacts]")
{
  // Twelve balls of three stiffnesses: 66 pairs with six distinct sets of
  // constants (stiffnesses in series), the list the entries index.
  dem::ParticleStore p;
  for (int k = 0; k < 12; ++k)
    p.add(ball(Vec3(2e-3 * k, 0, 0), 1e-3, 1e6 * (1 + k % 3), 1e5, 0.5));
  std::vector<dem::Pair> all;
  for (dem::Index i = 0; i < 12; ++i)
    for (dem::Index j = i + 1; j < 12; ++j)
      all.emplace_back(i, j);
  const auto same = [](const dem::ContactParams &a, const dem::ContactParams &b)
  { return a.kn == b.kn && a.ks == b.ks && a.friction == b.friction; };
  dem::ContactTable t;
  t.rebuild(all, p);
  REQUIRE(t.size() == 66);
  CHECK(t.distinct_params().size() == 6);
  for (std::size_t c = 0; c < t.size(); ++c)
    CHECK(same(t.params(t[c]), dem::ContactTable::pair_params(p, t[c].first, t[c].second)));

  // An edit gives each entry its own constants and leaves the others'.
  for (std::size_t c = 0; c < t.size(); ++c)
  {
    dem::ContactParams edited = t.params(t[c]);
    edited.friction = 1 + 0.001 * double(c + 1); // none equal to the balls' 0.5
    t.set_params(t[c], edited);
  }
  CHECK(t.distinct_params().size() == 6 + 66);
  for (std::size_t c = 0; c < t.size(); ++c)
  {
    CHECK(t.params(t[c]).friction == 1 + 0.001 * double(c + 1));
    CHECK(t.params(t[c]).kn == dem::ContactTable::pair_params(p, t[c].first, t[c].second).kn);
  }

  // Saved and assigned, every entry has the same constants.
  const std::vector<dem::ContactRecord> saved = t.records();
  dem::ContactTable u;
  u.assign(saved, {}, p, {});
  REQUIRE(u.size() == saved.size());
  CHECK(u.distinct_params().size() == 66);
  for (std::size_t c = 0; c < u.size(); ++c)
    CHECK(same(u.params(u[c]), saved[c].params));

  // A rebuild that leaves one entry drops the sets no entry uses once they
  // outnumber the entries, and keeps that entry's constants.
  t.rebuild({{0, 1}}, p);
  REQUIRE(t.size() == 1);
  CHECK(t.distinct_params().size() == 1);
  CHECK(same(t.params(t[0]), saved[0].params));
}

TEST_CASE("a Burger's run snapshotted mid-test continues bit for bit", "[dem][law_state][snapshot]")
{
  // Exact equality is expected: the continued run starts from the same
  // doubles for everything a step reads (balls, walls, contact and law
  // states, the last time step, the clock) and performs the same operations
  // in the same order.  Its neighbour list is rebuilt at once, so its table
  // may list other untouching candidates, but those add exact zeros to the
  // per-ball sums; the touching contacts are gathered in the same pair
  // order.  Only the law state was missing before it moved into the table.
  for (const char *law : {"burgers", "modified_burgers"})
  {
    INFO(law);
    dem::Simulation a = compressed_cylinder(law);
    for (int k = 0; k < 300; ++k)
      a.step();
    const dem::Snapshot snap = a.snapshot();
    CHECK(snap.contact_law == law);
    REQUIRE(snap.law_states.size() == snap.contacts.size());
    REQUIRE(non_rest_states(a.contacts()) > 50); // the elements are loaded: the test has teeth
    dem::Simulation b(snap, dem::make_contact_model(law, {}), {});
    // The ball-wall histories come back too, whichever order a compiler
    // evaluates the constructor's arguments in.
    REQUIRE_FALSE(snap.wall_contacts.empty());
    CHECK(b.snapshot().wall_contacts.size() == snap.wall_contacts.size());
    // The same snapshot with the elements at rest, as before law state was saved.
    dem::Snapshot rested = snap;
    rested.law_states.clear();
    dem::Simulation c(rested, dem::make_contact_model(law, {}), {});
    for (int k = 0; k < 300; ++k)
    {
      a.step();
      b.step();
      c.step();
    }
    CHECK(a.bonds_broken(dem::BreakMode::tension) + a.bonds_broken(dem::BreakMode::shear) > 0);
    bool all_equal = true, rest_differs = false;
    for (dem::Index p = 0; p < a.particles().size(); ++p)
    {
      all_equal = all_equal && a.particles().position[p] == b.particles().position[p] &&
                  a.particles().velocity[p] == b.particles().velocity[p] &&
                  a.particles().spin[p] == b.particles().spin[p] && a.particles().force[p] == b.particles().force[p];
      rest_differs = rest_differs || a.particles().position[p] != c.particles().position[p];
    }
    CHECK(all_equal);
    CHECK(rest_differs);
    for (const dem::Contact &k : a.contacts().entries())
    {
      const dem::Contact *other = b.contacts().find(k.first, k.second);
      if (!k.state.touching())
        continue;
      REQUIRE(other != nullptr);
      CHECK(other->state.normal_force == k.state.normal_force);
      CHECK(other->state.shear_force == k.state.shear_force);
      CHECK(b.contacts().law_states()[other - &b.contacts()[0]] == a.contacts().law_states()[&k - &a.contacts()[0]]);
    }
    CHECK(a.time() == b.time());
    CHECK(a.bonds_broken(dem::BreakMode::tension) == b.bonds_broken(dem::BreakMode::tension));
    CHECK(a.bonds_broken(dem::BreakMode::shear) == b.bonds_broken(dem::BreakMode::shear));
    CHECK(a.energy().residual() == b.energy().residual());
  }
}

TEST_CASE("a snapshot of another law's state continues with every law state at rest", "[dem][law_state][snapshot]")
{
  dem::Simulation a = compressed_cylinder("burgers");
  for (int k = 0; k < 100; ++k)
    a.step();
  REQUIRE(non_rest_states(a.contacts()) > 0);
  const dem::Simulation b(a.snapshot(), dem::make_contact_model("modified_burgers", {}), {});
  CHECK(b.contacts().size() == a.contacts().size());
  CHECK(non_rest_states(b.contacts()) == 0);
}

TEST_CASE("the force pass gives the same balls and break log on one to three threads", "[dem][threads]")
{
  // Contacts are resolved by the thread that owns their first ball and
  // every ball sums its loads in one fixed order (dem/ball_forces.h), so the
  // thread count must change nothing, bonds breaking included, nor a count
  // that changes from step to step (as a run's thread governor may change
  // it: app/run/run.h); run(0) cycles through one to three threads.
  // The linear law runs a second time with its ordinary contacts resolved
  // eight at a time (where the build has them): the contacts of broken
  // bonds become ordinary ones as the cylinder fails.
  const int threads_before = omp_get_max_threads();
  const std::pair<const char *, bool> variants[] = {
    {"linear", false}, {"linear", true}, {"burgers", false}, {"modified_burgers", false}};
  for (const auto &[law, in_lanes] : variants)
  {
    INFO(law << (in_lanes ? ", contacts in lanes" : ""));
    const auto run = [&, law = law, in_lanes = in_lanes](int threads)
    {
      omp_set_num_threads(threads);
      dem::Simulation sim = compressed_cylinder(law);
      sim.settings().contacts_in_lanes = in_lanes;
      std::vector<dem::BondBreak> breaks;
      for (int k = 0; k < 400; ++k)
      {
        if (threads == 0)
          omp_set_num_threads(1 + k % 3);
        sim.step();
        for (const dem::BondBreak &b : sim.take_breaks())
          breaks.push_back(b);
      }
      return std::make_pair(std::move(sim), std::move(breaks));
    };
    const auto [one, one_breaks] = run(1);
    REQUIRE(one_breaks.size() > 10); // bonds break: the break log's order is tested too
    for (int threads : {2, 3, 0})
    {
      INFO(threads << " threads (0: one to three in turn)");
      const auto [many, many_breaks] = run(threads);
      bool same_balls = true;
      for (dem::Index p = 0; p < one.particles().size(); ++p)
        same_balls = same_balls && one.particles().position[p] == many.particles().position[p] &&
                     one.particles().velocity[p] == many.particles().velocity[p] &&
                     one.particles().spin[p] == many.particles().spin[p] &&
                     one.particles().force[p] == many.particles().force[p] &&
                     one.particles().torque[p] == many.particles().torque[p];
      CHECK(same_balls);
      REQUIRE(many_breaks.size() == one_breaks.size());
      for (std::size_t k = 0; k < one_breaks.size(); ++k)
      {
        CHECK(many_breaks[k].first == one_breaks[k].first);
        CHECK(many_breaks[k].second == one_breaks[k].second);
        CHECK(many_breaks[k].mode == one_breaks[k].mode);
        CHECK(many_breaks[k].normal_force == one_breaks[k].normal_force);
      }
      CHECK(many.time() == one.time());
      CHECK(many.energy().residual() == one.energy().residual());
    }
  }
  omp_set_num_threads(threads_before);
}

TEST_CASE("a pass with the contacts in lanes gives the one-by-one pass's loads, row bounds and break log",
          "[dem][lanes]")
{
  // The same table at the same positions, resolved once each way.  The
  // blocks resolve the ordinary contacts (contact_lanes.h) and leave the
  // rest, slips and breaks included, to the one-by-one resolver, so:
  //   - friction work, bonds, break log and stability row bounds are equal
  //     to the bit (a block leaves the stored terms that the resolver uses
  //     in compression, and the sums keep one order);
  //   - a contact's forces may differ by the blocks' own bound (their test
  //     argues 1e-12 of the force scale |F_n| + |F_s|) plus K^n times the
  //     overlap's roundings: U = R_i + R_j - |d| is a difference of numbers
  //     the size of R_i + R_j, so eight ulps of that; at the small
  //     overlaps of a barely loaded contact this term is the larger;
  //   - a ball sums at most a dozen contacts, so sixteen times the table's
  //     largest contact bound bounds a resultant, and that times the
  //     largest radius a torque.
  // The cylinder is compared at each of its first thirty steps, as it
  // fails: its bonds break, and their contacts become candidates for the
  // blocks, which stick, slip or part.
  dem::Simulation sim = compressed_cylinder("linear");
  if (!sim.model().has_lanes())
  {
    WARN("this build resolves every contact one by one (no AVX-512): nothing to compare");
    return;
  }
  const auto pass = [&](bool in_lanes)
  {
    struct Result
    {
      dem::ParticleStore particles;
      dem::ContactTable table;
      std::vector<double> row_bound;
      std::vector<dem::BrokenBond> breaks;
    } r{sim.particles(), sim.contacts(), {}, {}};
    dem::WallSet walls;
    const std::vector<dem::WallIndex> no_walls;
    std::vector<double> wall_power(r.particles.size());
    r.row_bound.resize(r.particles.size());
    dem::BalancedRanges ranges;
    const dem::BallForces balls{r.particles, walls,      no_walls, Vec3::Zero(), sim.time_step(),
                                r.row_bound, wall_power, ranges,   in_lanes};
    const std::unique_ptr<dem::ContactModel> model = dem::make_contact_model("linear", {});
    model->resolve_and_sum(r.table, balls, r.breaks);
    return r;
  };
  double widest = 0;
  for (dem::Index p = 0; p < sim.particles().size(); ++p)
    widest = std::max(widest, sim.particles().radius[p]);
  std::size_t candidates = 0, worked = 0, breaks = 0;
  for (int step = 0; step < 30; ++step)
  {
    INFO("step " << step);
    const auto one_by_one = pass(false), in_lanes = pass(true);
    double largest = 0;
    for (std::size_t c = 0; c < one_by_one.table.size(); ++c)
    {
      const dem::Contact &a = one_by_one.table[c], &b = in_lanes.table[c];
      const double reach = sim.particles().radius[a.first] + sim.particles().radius[a.second];
      const double tolerance = 1e-12 * (std::abs(a.state.normal_force) + a.state.shear_force.norm()) +
                               one_by_one.table.params(a).kn * 8 * std::numeric_limits<double>::epsilon() * reach;
      largest = std::max(largest, tolerance);
      INFO("contact " << c);
      REQUIRE(a.bonded == b.bonded);
      CHECK(std::abs(a.state.normal_force - b.state.normal_force) <= tolerance);
      CHECK((a.state.shear_force - b.state.shear_force).norm() <= tolerance);
      CHECK(a.state.friction_work == b.state.friction_work);
      candidates += dem::lane_candidate(sim.contacts()[c]) ? 1 : 0;
      // Its friction work changed: it slipped, or parted and released it.
      worked += a.state.friction_work != sim.contacts()[c].state.friction_work ? 1 : 0;
    }
    bool same_balls = true;
    for (dem::Index p = 0; p < sim.particles().size(); ++p)
      same_balls = same_balls && (one_by_one.particles.force[p] - in_lanes.particles.force[p]).norm() <= 16 * largest &&
                   (one_by_one.particles.torque[p] - in_lanes.particles.torque[p]).norm() <= 16 * largest * widest &&
                   one_by_one.row_bound[p] == in_lanes.row_bound[p];
    CHECK(same_balls);
    REQUIRE(one_by_one.breaks.size() == in_lanes.breaks.size());
    for (std::size_t k = 0; k < one_by_one.breaks.size(); ++k)
    {
      CHECK(one_by_one.breaks[k].contact == in_lanes.breaks[k].contact);
      CHECK(one_by_one.breaks[k].mode == in_lanes.breaks[k].mode);
    }
    breaks += one_by_one.breaks.size();
    sim.step();
  }
  // The table held what the pass must handle.
  CHECK(candidates > 1000);
  CHECK(worked > 100);
  CHECK(breaks > 150);
}
