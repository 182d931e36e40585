// The deck kinds and the DEM run driver: every case deck parses, walls are
// lists, and the time step's resolution of contact periods is reported
// (resuming a run is tested in test_runs.cpp).
#include "app/decks/deck.h"
#include "app/io/output.h"
#include "app/kinds/deck_kinds.h"
#include "app/kinds/scene.h"
#include "app/kinds/uniaxial.h"
#include "app/run/dem_driver.h"

#include "dem/types.h"

#include "tests/test_folder.h"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>

namespace
{
namespace fs = std::filesystem;

} // namespace

TEST_CASE("every deck in cases/ parses into its kind's spec", "[decks]")
{
  // A renamed or removed key cannot silently break a thesis deck.
  std::size_t decks = 0;
  for (const auto &entry : fs::recursive_directory_iterator(DEMVV_CASES))
  {
    if (entry.path().extension() != ".prm")
      continue;
    INFO(entry.path().string());
    const demvv::Deck deck = demvv::Deck::from_file(demvv::deck_kinds(), entry.path().string());
    const demvv::DeckKind *kind = &deck.kind_row();
    REQUIRE(kind != nullptr);
    CHECK_NOTHROW(kind->parse(deck));
    ++decks;
  }
  CHECK(decks >= 30);
}

TEST_CASE("a box of six planes runs and its walls carry the weight of the balls at rest", "[run][walls]")
{
  // Static equilibrium: at rest the walls' forces on the balls balance
  // gravity, so the force of the balls on the floor is -N m g in z.  The
  // settled stack still creeps under damping; 0.1 % of the weight is far
  // above round-off and far below any missing or doubled wall.
  const demvv::Deck deck =
    demvv::Deck::from_file(demvv::deck_kinds(), std::string(DEMVV_CASES) + "/s01_box_six_planes/case.prm");
  const auto r = demvv::run_scene(deck, {"", 0, false});
  REQUIRE_FALSE(r.status.fault);
  REQUIRE(r.sim->walls().size() == 6);
  const std::vector<std::string> names = {"floor", "lid", "west", "east", "south", "north"};
  for (int w = 0; w < 6; ++w)
    CHECK(r.sim->walls()[w].name == names[static_cast<std::size_t>(w)]);
  const dem::ParticleStore &p = r.sim->particles();
  double weight = 0;
  for (dem::Index b = 0; b < p.size(); ++b)
    weight += p.mass[b] * 9.81;
  CHECK(r.series.column("floor_force_z_n").back() == Approx(-weight).epsilon(1e-3));
  CHECK(r.series.column("lid_force_z_n").back() == 0.0);
  double sum_z = 0;
  for (const std::string &n : names)
    sum_z += r.series.column(n + "_force_z_n").back();
  CHECK(sum_z == Approx(-weight).epsilon(1e-3));
}

TEST_CASE("a wall friction without wall shear stiffness is refused", "[decks][walls]")
{
  demvv::Deck deck =
    demvv::Deck::from_file(demvv::deck_kinds(), std::string(DEMVV_CASES) + "/s01_box_six_planes/case.prm");
  deck.set("walls/plane floor/friction", "0.5");
  CHECK_THROWS_WITH(demvv::parse_scene(deck),
                    Catch::Contains("walls/plane floor/friction") && Catch::Contains("shear stiffness"));
  deck.set("walls/plane floor/shear stiffness", "1e6");
  CHECK_NOTHROW(demvv::parse_scene(deck));
}

TEST_CASE("a scene reports how many steps resolve the shortest contact period", "[run]")
{
  // Two-ball impact at the default safety 0.8: N = pi dt_c / dt = pi / 0.8
  // steps per period (the bound is the automatic step's own reference), a
  // period error above 1 %, so a warning; at safety 0.1, N = 10 pi, none.
  demvv::Deck deck =
    demvv::Deck::from_file(demvv::deck_kinds(), std::string(DEMVV_CASES) + "/v01_linear_impact/case.prm");
  deck.set("motion/fixed time step", "0");
  const fs::path dir = demvv_tests::test_folder("contact_resolution");
  fs::remove_all(dir);
  demvv::run_scene(deck, {dir.string(), 0, false});
  nlohmann::json s = demvv_tests::read_json(dir / "summary.json");
  CHECK(s["critical_time_step_bound_s"].is_number());
  CHECK(s["contact_resolution"]["steps_per_shortest_contact_period"].get<double>() ==
        Approx(dem::pi / 0.8).epsilon(1e-9));
  CHECK(s["contact_resolution"].contains("warning"));
  deck.set("motion/time step safety", "0.1");
  fs::remove_all(dir);
  demvv::run_scene(deck, {dir.string(), 0, false});
  s = demvv_tests::read_json(dir / "summary.json");
  CHECK(s["contact_resolution"]["steps_per_shortest_contact_period"].get<double>() ==
        Approx(10 * dem::pi).epsilon(1e-9));
  CHECK_FALSE(s["contact_resolution"].contains("warning"));
  // Local damping shortens the step by sqrt(1 + alpha) for stability, not
  // the contact's period: the count grows by that factor.
  deck.set("motion/local damping", "0.7");
  fs::remove_all(dir);
  demvv::run_scene(deck, {dir.string(), 0, false});
  s = demvv_tests::read_json(dir / "summary.json");
  CHECK(s["contact_resolution"]["steps_per_shortest_contact_period"].get<double>() ==
        Approx(10 * dem::pi * std::sqrt(1.7)).epsilon(1e-9));
}

TEST_CASE("repeated deck sections: any number of instances, each named, in the order written", "[decks]")
{
  demvv::Deck deck =
    demvv::Deck::from_file(demvv::deck_kinds(), std::string(DEMVV_CASES) + "/s01_box_six_planes/case.prm");
  CHECK(deck.instances("walls", "plane") ==
        std::vector<std::string>{"plane floor", "plane lid", "plane west", "plane east", "plane south", "plane north"});
  deck.set("walls/plane 7/point", "0, 0, -0.001");
  CHECK(deck.instances("walls", "plane").back() == "plane 7");
  CHECK(deck.resolved().find("subsection plane 7") != std::string::npos);
  CHECK_THROWS_WITH(deck.set("walls/plane 7/colour", "red"), Catch::Contains("unknown key"));
  CHECK(demvv::Deck::defaults(demvv::deck_kinds(), "scene").documented().find("Repeatable section 'plane'") !=
        std::string::npos);
}

TEST_CASE("a uniaxial deck naming a sample file that does not exist is refused at parse time", "[decks]")
{
  demvv::Deck deck = demvv::Deck::from_file(demvv::deck_kinds(), std::string(DEMVV_CASES) + "/t61_damage/case.prm");
  deck.set("sample/file", "no_such_sample.json");
  CHECK_THROWS_WITH(demvv::parse_uniaxial(deck), Catch::Contains("sample/file") && Catch::Contains("no such file"));
}
