// Sample files (app/io/sample_file.h): version 2 carries every contact's
// law state exactly; version 1 files still load, law state at rest.
#include "app/decks/deck.h"
#include "app/io/sample_file.h"
#include "verify/checks/checks_support.h"

#include "dem/bonds.h"
#include "dem/specimen.h"

#include "tests/test_folder.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>

namespace
{
namespace fs = std::filesystem;

/// A bonded FCC cylinder under compression with a Burger's law, stepped a while.
dem::Simulation loaded_burgers_cylinder(dem::WallIndex &top)
{
  const dem::BallSpec spec = demvv::ball(dem::Vec3::Zero(), 0, 1.2e7, 1.2e6, 0.5);
  dem::Specimen s = dem::lattice_specimen(dem::Lattice::face_centred_cubic, 0.885e-3, 0.006, 0.006, spec,
                                          {1.2e7, 1.2e6, 0.3}, {}, false);
  top = s.top;
  dem::Simulation sim(std::move(s.particles), std::move(s.walls), dem::make_contact_model("burgers", {}), {});
  sim.refresh_contacts();
  dem::BondSettings bonds;
  bonds.normal_strength = bonds.shear_strength = 1;
  dem::bond_touching_pairs(sim.contacts(), sim.particles(), bonds);
  sim.walls()[top].velocity = dem::Vec3(0, 0, -0.5);
  for (int k = 0; k < 200; ++k)
    sim.step();
  return sim;
}
} // namespace

TEST_CASE("a version 2 sample file carries Burger's element state exactly", "[sample]")
{
  dem::WallIndex top = 0;
  dem::Simulation a = loaded_burgers_cylinder(top);
  demvv::SampleFile file;
  file.snapshot = a.snapshot();
  file.cell.bottom = 0;
  file.cell.top = top;
  const std::string path = demvv_tests::test_file("test_sample_file", "burgers.json");
  demvv::write_sample(path, file);

  const demvv::SampleFile back = demvv::read_sample(path);
  CHECK(back.contact_law == "burgers");
  CHECK(back.snapshot.contact_law == "burgers");
  const auto &saved = file.snapshot.law_states;
  REQUIRE(back.snapshot.law_states.size() == saved.size());
  std::size_t loaded = 0, equal = 0;
  for (std::size_t c = 0; c < saved.size(); ++c)
  {
    loaded += saved[c] == dem::LawState{} ? 0 : 1;
    equal += back.snapshot.law_states[c] == saved[c] ? 1 : 0;
  }
  CHECK(loaded > 10); // elements loaded away from rest: the round trip has something to carry
  CHECK(equal == saved.size());

  // The file's columns name the law's state fields.
  std::ifstream in(path);
  const nlohmann::json doc = nlohmann::json::parse(in);
  CHECK(doc["format_version"] == 2);
  const auto columns = doc["contacts"]["columns"].get<std::vector<std::string>>();
  CHECK(columns.back() == "law_shear_kelvin_z_m");

  // And the run continues from the file as if it had never stopped.
  dem::Simulation b(back.snapshot, dem::make_contact_model("burgers", {}), {});
  for (int k = 0; k < 100; ++k)
  {
    a.step();
    b.step();
  }
  bool same = true;
  for (dem::Index p = 0; p < a.particles().size(); ++p)
    same = same && a.particles().position[p] == b.particles().position[p] &&
           a.particles().velocity[p] == b.particles().velocity[p];
  CHECK(same);
}

TEST_CASE("a version 1 sample file still loads, its law state at rest", "[sample]")
{
  const demvv::SampleFile v1 = demvv::read_sample(DEMVV_TEST_DATA "/sample_v1.json");
  CHECK(v1.contact_law == "linear");
  CHECK(v1.snapshot.particles.size() == 30);
  CHECK(v1.snapshot.contacts.size() == 73);
  CHECK(v1.snapshot.law_states.empty());
  // Continued with a Burger's law, every contact starts with its element at rest.
  dem::Simulation sim(v1.snapshot, dem::make_contact_model("burgers", {}), {});
  for (const dem::LawState &s : sim.contacts().law_states())
    CHECK(s == dem::LawState{});
  sim.step();
  CHECK(sim.steps() == v1.snapshot.clock.steps + 1);
}

TEST_CASE("a sample file of an unknown contact law is refused, naming it", "[sample]")
{
  std::ifstream in(DEMVV_TEST_DATA "/sample_v1.json");
  nlohmann::json doc = nlohmann::json::parse(in);
  doc["format_version"] = 2;
  doc["contact_law"] = "no_such_law";
  const std::string path = demvv_tests::test_file("test_sample_file", "unknown_law.json");
  std::ofstream(path) << doc.dump();
  CHECK_THROWS_WITH(demvv::read_sample(path), Catch::Contains("no_such_law"));
}

TEST_CASE("a touching contact needs its unit normal, one that carries no force keeps none", "[sample]")
{
  std::ifstream in(DEMVV_TEST_DATA "/sample_v1.json");
  const nlohmann::json original = nlohmann::json::parse(in);
  const nlohmann::json &columns = original["contacts"]["columns"];
  const auto column = [&](const char *name)
  { return static_cast<std::size_t>(std::find(columns.begin(), columns.end(), name) - columns.begin()); };
  const std::size_t touching = column("touching"), nx = column("nx"), ny = column("ny"), nz = column("nz");
  const nlohmann::json &rows = original["contacts"]["rows"];
  const auto touching_row =
    std::find_if(rows.begin(), rows.end(), [&](const nlohmann::json &row) { return row[touching] == 1; });
  REQUIRE(touching_row != rows.end());
  const std::size_t r = static_cast<std::size_t>(touching_row - rows.begin());

  // A touching contact without a normal is refused with the one-line error.
  nlohmann::json doc = original;
  for (std::size_t k : {nx, ny, nz})
    doc["contacts"]["rows"][r][k] = 0.0;
  const std::string broken = demvv_tests::test_file("test_sample_file", "touching_without_normal.json");
  std::ofstream(broken) << doc.dump();
  CHECK_THROWS_WITH(demvv::read_sample(broken),
                    Catch::Contains("contacts.rows[" + std::to_string(r) + "].nx") && Catch::Contains("unit normal"));

  // A contact that is not touching loads with a zero normal, whatever the
  // file says (earlier builds kept the last normal of a bond broken apart).
  doc = original;
  doc["contacts"]["rows"][r][touching] = 0;
  const std::string apart = demvv_tests::test_file("test_sample_file", "apart_with_normal.json");
  std::ofstream(apart) << doc.dump();
  const demvv::SampleFile loaded = demvv::read_sample(apart);
  CHECK_FALSE(loaded.snapshot.contacts[r].state.touching());
  CHECK(loaded.snapshot.contacts[r].state.normal == dem::Vec3::Zero());
}
