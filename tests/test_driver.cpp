// The DEM run driver and the deck kinds: every case deck parses, a paused
// or interrupted run resumes bit for bit, walls are lists, and the time
// step's resolution of contact periods is reported.
#include "verify/decks/deck.h"
#include "verify/io/output.h"
#include "verify/kinds/scene.h"
#include "verify/kinds/uniaxial.h"
#include "verify/run/dem_driver.h"

#include "dem/types.h"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>

namespace
{
namespace fs = std::filesystem;

verify::Deck small_uniaxial(const std::string &law)
{
  verify::Deck d = verify::Deck::defaults("uniaxial");
  d.set("sample/diameter", "0.008");
  d.set("sample/height", "0.008");
  d.set("bonds/normal strength", "20");
  d.set("bonds/shear strength", "20");
  d.set("bonds/strength cov", "0.25");
  d.set("contact law/law", law);
  d.set("loading/final strain", "0.004");
  d.set("output/strain interval", "0.0005");
  return d;
}

/// summary.json without what legitimately differs between two runs of the
/// same deck: wall time, speed, the run's own status line and provenance.
nlohmann::json physics_of(nlohmann::json s)
{
  for (const char *k : {"wall_seconds", "particle_steps_per_second", "status", "provenance"})
    s.erase(k);
  return s;
}

nlohmann::json read_json(const fs::path &p) { return nlohmann::json::parse(verify::read_file(p.string())); }
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
    const verify::Deck deck = verify::Deck::from_file(entry.path().string());
    const verify::DeckKind *kind = verify::find_deck_kind(deck.kind());
    REQUIRE(kind != nullptr);
    CHECK_NOTHROW(kind->parse(deck));
    ++decks;
  }
  CHECK(decks >= 30);
}

TEST_CASE("a paused run resumed from its checkpoint equals the run that never stopped", "[run][resume]")
{
  // The checkpoint holds the whole simulation state (balls, walls, contacts
  // with their law state, clock, energy ledger) and the driver's (series
  // with exact doubles, file lengths, cadence): continuing from it repeats
  // exactly the operations of the uninterrupted run, so every double must
  // be equal, not close.
  const std::string law = GENERATE("linear", "burgers");
  INFO("law " << law);
  const verify::Deck deck = small_uniaxial(law);
  const fs::path whole = fs::temp_directory_path() / ("demvv_resume_whole_" + law);
  const fs::path split = fs::temp_directory_path() / ("demvv_resume_split_" + law);
  fs::remove_all(whole);
  fs::remove_all(split);
  const auto reference = verify::run_uniaxial(deck, {whole.string(), 1, false});
  REQUIRE(reference.status.steps > 400);

  verify::RunOptions pause{split.string(), 1, false};
  pause.pause_after = reference.status.steps / 3;
  const auto first = verify::run_uniaxial(deck, pause);
  REQUIRE(first.status.paused);
  CHECK(fs::exists(verify::checkpoint_state_file(split.string())));
  CHECK(read_json(split / "summary.json")["status"]["state"] == "paused");
  CHECK_NOTHROW(verify::check_resumable(split.string(), deck));

  verify::RunOptions resume{split.string(), 2, false};
  resume.resume = true;
  const auto rest = verify::run_uniaxial(deck, resume);
  REQUIRE_FALSE(rest.status.fault);
  CHECK(rest.status.steps == reference.status.steps);
  REQUIRE(rest.series.rows() == reference.series.rows());
  for (std::size_t r = 0; r < reference.series.rows(); ++r)
    CHECK(rest.series.row(r) == reference.series.row(r));
  for (const char *file : {"series.csv", "bond_breaks.csv"})
  {
    INFO(file);
    CHECK(verify::read_file((split / file).string()) == verify::read_file((whole / file).string()));
  }
  CHECK(physics_of(read_json(split / "summary.json")) == physics_of(read_json(whole / "summary.json")));
  CHECK(read_json(split / "summary.json")["status"]["state"] == "completed");
}

TEST_CASE("a resume is refused for another deck or a directory without a checkpoint", "[run][resume]")
{
  const fs::path dir = fs::temp_directory_path() / "demvv_resume_refused";
  fs::remove_all(dir);
  const verify::Deck deck = small_uniaxial("linear");
  CHECK_THROWS_AS(verify::check_resumable(dir.string(), deck), verify::DeckError);
  verify::RunOptions pause{dir.string(), 1, false};
  pause.pause_after = 50;
  verify::run_uniaxial(deck, pause);
  verify::Deck other = small_uniaxial("linear");
  other.set("loading/final strain", "0.005");
  CHECK_THROWS_WITH(verify::check_resumable(dir.string(), other), Catch::Contains("another deck"));
}

TEST_CASE("a box of six planes runs and its walls carry the weight of the balls at rest", "[run][walls]")
{
  // Static equilibrium: at rest the walls' forces on the balls balance
  // gravity, so the force of the balls on the floor is -N m g in z.  The
  // settled stack still creeps under damping; 0.1 % of the weight is far
  // above round-off and far below any missing or doubled wall.
  const verify::Deck deck = verify::Deck::from_file(std::string(DEMVV_CASES) + "/s01_box_six_planes/case.prm");
  const auto r = verify::run_scene(deck, {"", 0, false});
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
  verify::Deck deck = verify::Deck::from_file(std::string(DEMVV_CASES) + "/s01_box_six_planes/case.prm");
  deck.set("walls/plane floor/friction", "0.5");
  CHECK_THROWS_WITH(verify::parse_scene(deck), Catch::Contains("walls/plane floor/friction") &&
                                                  Catch::Contains("shear stiffness"));
  deck.set("walls/plane floor/shear stiffness", "1e6");
  CHECK_NOTHROW(verify::parse_scene(deck));
}

TEST_CASE("a scene reports how many steps resolve the shortest contact period", "[run]")
{
  // Two-ball impact at the default safety 0.8: N = pi dt_c / dt = pi / 0.8
  // steps per period (the bound is the automatic step's own reference), a
  // period error above 1 %, so a warning; at safety 0.1, N = 10 pi, none.
  verify::Deck deck = verify::Deck::from_file(std::string(DEMVV_CASES) + "/v01_linear_impact/case.prm");
  deck.set("motion/fixed time step", "0");
  const fs::path dir = fs::temp_directory_path() / "demvv_contact_resolution";
  fs::remove_all(dir);
  verify::run_scene(deck, {dir.string(), 0, false});
  nlohmann::json s = read_json(dir / "summary.json");
  CHECK(s["critical_time_step_bound_s"].is_number());
  CHECK(s["contact_resolution"]["steps_per_shortest_contact_period"].get<double>() ==
        Approx(dem::pi / 0.8).epsilon(1e-9));
  CHECK(s["contact_resolution"].contains("warning"));
  deck.set("motion/time step safety", "0.1");
  fs::remove_all(dir);
  verify::run_scene(deck, {dir.string(), 0, false});
  s = read_json(dir / "summary.json");
  CHECK(s["contact_resolution"]["steps_per_shortest_contact_period"].get<double>() ==
        Approx(10 * dem::pi).epsilon(1e-9));
  CHECK_FALSE(s["contact_resolution"].contains("warning"));
}

TEST_CASE("repeated deck sections: any number of instances, each named, in the order written", "[decks]")
{
  verify::Deck deck = verify::Deck::from_file(std::string(DEMVV_CASES) + "/s01_box_six_planes/case.prm");
  CHECK(deck.instances("walls", "plane") ==
        std::vector<std::string>{"plane floor", "plane lid", "plane west", "plane east", "plane south", "plane north"});
  deck.set("walls/plane 7/point", "0, 0, -0.001");
  CHECK(deck.instances("walls", "plane").back() == "plane 7");
  CHECK(deck.resolved().find("subsection plane 7") != std::string::npos);
  CHECK_THROWS_WITH(deck.set("walls/plane 7/colour", "red"), Catch::Contains("unknown key"));
  CHECK(verify::Deck::defaults("scene").documented().find("Repeatable section 'plane'") != std::string::npos);
}
