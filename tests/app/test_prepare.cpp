// Sample preparation (thesis ch. 5): a small sample meets its own targets,
// a saved sample continues exactly, the servo reaches its stress, and
// impossible requests are refused.
#include "app/decks/csv_input.h"
#include "app/decks/deck.h"
#include "app/io/output.h"
#include "app/io/sample_file.h"
#include "app/kinds/deck_kinds.h"
#include "app/kinds/prepare.h"
#include "app/kinds/uniaxial.h"
#include "verify/checks/checks_support.h"

#include "dem/measure.h"
#include "dem/prep_packing.h"
#include "dem/servo.h"
#include "dem/specimen.h"

#include "tests/test_folder.h"

#include <catch2/catch.hpp>

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <sstream>
#include <vector>

namespace
{
namespace fs = std::filesystem;

/// A finished sample cache entry of a deck whose resolved text is `deck`,
/// in `cache`, made by the build whose sources hash is `sources` (this
/// build's own when empty), its sample last used `days_ago`; its folder.
fs::path fake_cache_entry(const fs::path &cache, const std::string &deck, const std::string &sources, int days_ago)
{
  nlohmann::json build = demvv::build_identity();
  if (!sources.empty())
    build["sources_sha256"] = sources;
  const fs::path entry = cache / ("p-" + demvv::sample_cache_hash(deck, build));
  fs::create_directories(entry);
  // What differs between runs of one build must not split it.
  static int runs = 0;
  ++runs;
  nlohmann::json provenance = build;
  provenance["seed"] = runs;
  provenance["threads"] = runs;
  provenance["started_utc"] = "2026-11-01T00:00:" + std::to_string(10 + runs) + "Z";
  std::ofstream(entry / "summary.json") << nlohmann::json{{"kind", "prepare"}, {"provenance", provenance}}.dump();
  std::ofstream(entry / "deck.prm") << deck;
  std::ofstream(entry / "sample.json") << "{}";
  fs::last_write_time(entry / "sample.json", fs::file_time_type::clock::now() - std::chrono::hours(24 * days_ago));
  return entry;
}

/// A small prepare deck (200 balls, seed 5) written as small.prm into the
/// emptied folder `dir`; its path.
std::string small_prepare_deck_file(const fs::path &dir)
{
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string deck = (dir / "small.prm").string();
  std::ofstream(deck) << "set kind = prepare\nsubsection sample\n  set particles = 200\n  set seed = 5\nend\n";
  return deck;
}

demvv::Deck small_prepare_deck()
{
  demvv::Deck d = demvv::Deck::defaults(demvv::deck_kinds(), "prepare");
  d.set("sample/particles", "200");
  d.set("sample/seed", "5");
  return d;
}
} // namespace

TEST_CASE("a 200-ball preparation meets its own targets and feeds a uniaxial test", "[prepare]")
{
  const demvv::Deck deck = small_prepare_deck();
  const auto result = demvv::run_prepare(deck, {"", 0, false});
  REQUIRE_FALSE(result.status.fault);
  const nlohmann::json &r = result.sample.preparation;
  INFO(r.dump(1));
  // Stage 5 target: mean stress below 1 kPa (and the network not lost).
  CHECK(r["mean_stress_before_bonding_pa"].get<double>() <= 1e3);
  CHECK(r["mean_stress_before_bonding_pa"].get<double>() > 0);
  // Stage 4 target: no ball grew by more than the allowed 1 %.
  CHECK(r["largest_expansion"].get<double>() <= 0.01 + 1e-12);
  // Stage 6: bonds on the contacts, lateral wall gone.
  CHECK(r["bonds"]["installed"].get<long>() > 0);
  const dem::Snapshot &snap = result.sample.snapshot;
  CHECK_FALSE(snap.walls[result.sample.cell.lateral].enabled);
  // Isotropy: for n contact normals drawn isotropically the deviator of the
  // fabric tensor has E|D|^2 = (2/3)/n; three standard deviations of that
  // sampling noise are allowed (walls add a little real anisotropy).
  std::size_t contacts = 0;
  for (const dem::ContactRecord &c : snap.contacts)
    contacts += c.state.touching() ? 1 : 0;
  REQUIRE(contacts > 100);
  CHECK(r["fabric_deviator_norm"].get<double>() < 3 * std::sqrt(2.0 / (3.0 * contacts)));

  // The sample file is what a uniaxial deck loads.  A preparation with
  // friction leaves the work its contacts did in their histories: one such
  // contact is written here, work the test's ledger must not count.
  demvv::SampleFile sample = result.sample;
  const auto slid = std::find_if(sample.snapshot.contacts.begin(), sample.snapshot.contacts.end(),
                                 [](const dem::ContactRecord &c) { return c.state.touching(); });
  REQUIRE(slid != sample.snapshot.contacts.end());
  slid->state.friction_work = 1e-6;
  slid->state.bond_energy = 2e-6;
  const std::string file = demvv_tests::test_file("test_prepare", "small_sample.json");
  demvv::write_sample(file, sample);
  demvv::Deck test = demvv::Deck::defaults(demvv::deck_kinds(), "uniaxial");
  test.set("sample/source", "file");
  test.set("sample/file", file);
  test.set("loading/final strain", "0.002");
  test.set("output/strain interval", "0.0005");
  const auto run = demvv::run_uniaxial(test, {"", 0, false});
  REQUIRE_FALSE(run.status.fault);
  CHECK(run.series.column("axial_stress_pa").back() > 0);
  CHECK(run.summary["sample"]["particles"].get<long>() == 200);
  // ...but the test's ledger starts at zero, as its clock does.
  CHECK(run.series.column("time_s").front() == 0);
  CHECK(run.series.column("friction_dissipated_j").front() == 0);
  CHECK(run.series.column("bond_energy_released_j").front() == 0);
}

TEST_CASE("a saved run continues exactly as if it had never stopped", "[prepare][sample]")
{
  // A small bonded FCC cylinder under compression: steps, saved, read back.
  dem::BallSpec ball = demvv::ball(dem::Vec3::Zero(), 0, 1.2e7, 1.2e6, 0.5);
  dem::Specimen s = dem::lattice_specimen(dem::Lattice::face_centred_cubic, 0.885e-3, 0.008, 0.008, ball,
                                          {1.2e7, 1.2e6, 0.3}, {}, false);
  const dem::WallIndex top = s.top;
  dem::Simulation a(std::move(s.particles), std::move(s.walls), dem::make_contact_model("linear", {}), {});
  a.refresh_contacts();
  dem::BondSettings bonds;
  bonds.normal_strength = bonds.shear_strength = 5;
  dem::bond_touching_pairs(a.contacts(), a.particles(), bonds);
  a.walls()[top].velocity = dem::Vec3(0, 0, -0.05);
  for (int k = 0; k < 400; ++k)
    a.step();

  demvv::SampleFile file;
  file.snapshot = a.snapshot();
  file.cell.bottom = 0;
  file.cell.top = top;
  const std::string path = demvv_tests::test_file("test_prepare", "continue.json");
  demvv::write_sample(path, file);
  dem::Simulation b(demvv::read_sample(path).snapshot, dem::make_contact_model("linear", {}), {});
  for (int k = 0; k < 400; ++k)
  {
    a.step();
    b.step();
  }
  REQUIRE(a.particles().size() == b.particles().size());
  for (dem::Index p = 0; p < a.particles().size(); ++p)
  {
    INFO("ball " << p);
    CHECK(a.particles().position[p] == b.particles().position[p]);
    CHECK(a.particles().velocity[p] == b.particles().velocity[p]);
  }
  CHECK(a.time() == b.time());
  CHECK(a.bonds_broken(dem::BreakMode::tension) + a.bonds_broken(dem::BreakMode::shear) ==
        b.bonds_broken(dem::BreakMode::tension) + b.bonds_broken(dem::BreakMode::shear));
  CHECK(a.energy().residual() == b.energy().residual());
}

TEST_CASE("servo-controlled walls bring a packing to the target stress", "[prepare][servo]")
{
  dem::BallSpec ball = demvv::ball(dem::Vec3::Zero(), 0, 1.2e7, 1.2e6, 0);
  dem::Specimen cell = dem::lattice_specimen(dem::Lattice::face_centred_cubic, 0.885e-3, 0.008, 0.008, ball,
                                             {1.2e7, 0, 0}, {1.2e7, 0, 0}, true);
  dem::Specimen view;
  view.bottom = cell.bottom;
  view.top = cell.top;
  view.lateral = cell.lateral;
  dem::Simulation sim(std::move(cell.particles), std::move(cell.walls), dem::make_contact_model("linear", {}), {});
  dem::ServoSettings servo;
  servo.target_stress = 1e5;
  dem::CellStress stress;
  for (int k = 0; k < 20000; ++k)
  {
    sim.compute_forces();
    stress = dem::servo_cell(sim, view, servo);
    sim.integrate();
  }
  sim.compute_forces();
  stress = dem::cell_stress(sim, view);
  // The servo's own convergence criterion in preparation is 1 % of the target.
  INFO("bottom " << stress.bottom << " top " << stress.top << " lateral " << stress.lateral);
  CHECK(stress.largest_error(1e5) < 0.01 * 1e5);
}

TEST_CASE("impossible packings and cells are refused with one line naming the key", "[prepare][deck]")
{
  const auto error_of = [](demvv::Deck d)
  {
    try
    {
      demvv::run_prepare(d, {"", 0, false});
    }
    catch (const demvv::DeckError &e)
    {
      return std::string(e.what());
    }
    return std::string();
  };
  demvv::Deck dense = small_prepare_deck();
  dense.set("sample/target solid fraction", "0.8");
  const std::string m1 = error_of(std::move(dense));
  CHECK(m1.find("sample/target solid fraction") != std::string::npos);
  CHECK(m1.find("0.7405") != std::string::npos);
  demvv::Deck tiny = small_prepare_deck();
  tiny.set("sample/particles", "0");
  tiny.set("sample/diameter", "0.001");
  tiny.set("sample/height", "0.01");
  const std::string m2 = error_of(std::move(tiny));
  CHECK(m2.find("too small for one ball") != std::string::npos);
  CHECK(m2.find('\n') == std::string::npos);
}

TEST_CASE("preparing a cached sample leaves the caller's thread count as it was and prunes the cache",
          "[prepare][threads][cache]")
{
  // Neither a cache elsewhere nor a count fixed by the environment may hide
  // what is tested (ctest runs each test case in a process of its own).
  unsetenv("DEMVV_CACHE");
  unsetenv("OMP_NUM_THREADS");
  const fs::path dir = demvv_tests::test_file("test_prepare", "cached");
  const std::string deck = small_prepare_deck_file(dir);
  // A count idle_cores(), which a preparation left to itself would take,
  // can never return: more threads than cores.
  const int before = omp_get_max_threads();
  const int asked = omp_get_num_procs() + 1;
  omp_set_num_threads(asked);
  // Samples of four other builds, none used for a week: the preparation
  // keeps the two used last beside its own (cached_builds = 3).
  std::vector<fs::path> others;
  for (int k = 1; k <= 4; ++k)
    others.push_back(fake_cache_entry(dir / "samples", "deck", std::to_string(k), 7 + k));
  const std::string prepared = demvv::cached_sample_file(deck, {}, false);
  CHECK(omp_get_max_threads() == asked);
  omp_set_num_threads(before);
  CHECK(fs::exists(prepared));
  CHECK(demvv::cached_sample_file(deck, {}, false) == prepared); // served from the cache the second time
  CHECK(fs::exists(others[0]));
  CHECK(fs::exists(others[1]));
  CHECK_FALSE(fs::exists(others[2]));
  CHECK_FALSE(fs::exists(others[3]));
}

TEST_CASE("the sample cache keeps this build's samples, those of the builds used last and those used lately",
          "[prepare][cache]")
{
  const fs::path cache = demvv_tests::test_file("test_prepare", "cache_pruning");
  fs::remove_all(cache);
  fs::create_directories(cache);
  const auto old = fs::file_time_type::clock::now() - std::chrono::hours(24 * 60);
  const std::chrono::hours week(24 * 7);
  const fs::path v = fake_cache_entry(cache, "deck c", "v", 2);      // used within the week
  const fs::path v_old = fake_cache_entry(cache, "deck a", "v", 30); // its build too, but not this entry
  const fs::path x1 = fake_cache_entry(cache, "deck a", "x", 10);    // build x: used 8 days ago, by its newer entry
  const fs::path x2 = fake_cache_entry(cache, "deck b", "x", 8);
  const fs::path z = fake_cache_entry(cache, "deck a", "z", 9);
  const fs::path y = fake_cache_entry(cache, "deck a", "y", 11);
  const fs::path w1 = fake_cache_entry(cache, "deck a", "w", 13); // the build used longest ago
  const fs::path w2 = fake_cache_entry(cache, "deck b", "w", 14);
  const fs::path failed = fake_cache_entry(cache, "deck d", "w", 15); // a preparation that stopped: no sample
  fs::remove(failed / "sample.json");
  fs::last_write_time(failed / "summary.json", old);
  const fs::path ours = fake_cache_entry(cache, "deck a", "", 30);

  // Never to be removed: an entry still being prepared (its summary says
  // only "running"), folders whose name is not the hash of their deck and
  // build, a run of another kind.
  // Each is an old entry of build w but for what the comment names.
  const auto rewrite_summary = [&](const fs::path &entry, const auto &change)
  {
    std::ifstream in(entry / "summary.json");
    nlohmann::json summary = nlohmann::json::parse(in);
    in.close();
    change(summary);
    std::ofstream(entry / "summary.json") << summary.dump();
    fs::last_write_time(entry / "summary.json", old);
  };
  const fs::path running = fake_cache_entry(cache, "deck e", "w", 20); // as RunDirectory starts it
  fs::remove(running / "sample.json");
  rewrite_summary(running,
                  [](nlohmann::json &s)
                  {
                    s.erase("kind");
                    s["status"] = {{"state", "running"}};
                  });
  fs::rename(fake_cache_entry(cache, "deck f", "w", 20), cache / "notes");
  fs::rename(fake_cache_entry(cache, "deck g", "w", 20), cache / "p-0123456789ab");
  const fs::path other_kind = fake_cache_entry(cache, "deck h", "w", 20);
  rewrite_summary(other_kind, [](nlohmann::json &s) { s["kind"] = "uniaxial"; });
  const auto others_stay = [&]
  {
    for (const fs::path &p : {running, cache / "notes", cache / "p-0123456789ab", other_kind})
      CHECK(fs::exists(p));
  };

  demvv::prune_sample_cache(cache.string(), 4, week); // v, x, z, y and ours
  for (const fs::path &p : {v, v_old, x1, x2, z, y, ours})
    CHECK(fs::exists(p));
  for (const fs::path &p : {w1, w2, failed})
    CHECK_FALSE(fs::exists(p));
  others_stay();

  demvv::prune_sample_cache(cache.string(), 2, week); // v and x (8 days ago, not 10), and ours
  for (const fs::path &p : {v, x1, x2, ours})
    CHECK(fs::exists(p));
  CHECK_FALSE(fs::exists(z));
  CHECK_FALSE(fs::exists(y));

  demvv::prune_sample_cache(cache.string(), 0, week); // ours, and the entry of v used within the week
  CHECK(fs::exists(ours));
  CHECK(fs::exists(v));
  CHECK_FALSE(fs::exists(v_old));
  CHECK_FALSE(fs::exists(x1));
  CHECK_FALSE(fs::exists(x2));
  others_stay();
  // A folder that is not there is no error.
  demvv::prune_sample_cache((cache / "absent").string(), 0, week);
}

TEST_CASE("a sample served from the cache is marked as used", "[prepare][cache]")
{
  unsetenv("DEMVV_CACHE");
  const fs::path dir = demvv_tests::test_file("test_prepare", "cache_use");
  const std::string deck = small_prepare_deck_file(dir);
  // A stand-in for a prepared sample: a hit never reads it.
  const fs::path file = demvv::cached_sample_file_name(deck, {});
  fs::create_directories(file.parent_path());
  std::ofstream(file) << "{}";
  const auto long_ago = fs::file_time_type::clock::now() - std::chrono::hours(48);
  fs::last_write_time(file, long_ago);
  CHECK(demvv::cached_sample_file(deck, {}, false) == file.string());
  CHECK(fs::last_write_time(file) > long_ago + std::chrono::hours(47));
}

TEST_CASE("a preparation draws a ParaView frame at the end of each stage, the first of balls at half radius",
          "[prepare]")
{
  // Fig. 5.2 is the packing as placed, every ball at R/2; Fig. 5.3 the same
  // balls grown to R.  The frames are what a reader opens to see them.
  demvv::Deck deck = small_prepare_deck();
  deck.set("output/paraview stages", "true");
  const fs::path dir = demvv_tests::test_folder("prepare_stages");
  fs::remove_all(dir);
  const auto result = demvv::run_prepare(deck, {dir.string(), 0, false});
  REQUIRE_FALSE(result.status.fault);
  std::ifstream summary_file(dir / "summary.json");
  const nlohmann::json summary = nlohmann::json::parse(summary_file);
  const nlohmann::json &frames = summary.at("paraview_stages").at("frames");
  // placed, grown, the servo, the radius reductions, the release at least
  REQUIRE(frames.size() >= 5);
  CHECK(frames.front().at("stage").get<std::string>().rfind("placed", 0) == 0);
  CHECK(frames.back().at("stage").get<std::string>().rfind("release", 0) == 0);
  for (std::size_t k = 0; k < frames.size(); ++k)
  {
    char name[40]; // "particles_", up to 20 digits, ".vtp"
    std::snprintf(name, sizeof name, "particles_%05zu.vtp", k);
    CHECK(fs::exists(dir / "paraview" / "stages" / name));
  }
  // Frame 0's radii: all R/2 (the deck's default radius).
  std::ifstream first(dir / "paraview" / "stages" / "particles_00000.vtp");
  const std::string text((std::istreambuf_iterator<char>(first)), std::istreambuf_iterator<char>());
  const std::string tag = "Name=\"radius\" NumberOfComponents=\"1\" format=\"ascii\">";
  const std::size_t at = text.find(tag);
  REQUIRE(at != std::string::npos);
  std::istringstream values(text.substr(at + tag.size(), text.find("</DataArray>", at) - at - tag.size()));
  const double half = 0.5 * deck.real("sample/ball radius");
  int balls = 0;
  for (double r; values >> r; ++balls)
    CHECK(r == Approx(half).epsilon(1e-9));
  CHECK(balls == 200);

  // The section of every stage, in stage order: at stage 0 every circle
  // at most R/2 (the balls as placed), at the last at most the largest
  // grown radius.
  const nlohmann::json &stages = summary.at("preparation_stages");
  REQUIRE(stages.size() == frames.size());
  const demvv::CsvTable cut =
    demvv::CsvTable::read((dir / "preparation_sections.csv").string(), demvv::CsvTable::Values::any_number);
  std::set<double> seen;
  double previous = 0, largest_last = 0;
  for (std::size_t row = 0; row < cut.rows(); ++row)
  {
    const double stage = cut.get(row, "stage"), radius = cut.get(row, "section_radius_m");
    CHECK(stage >= previous);
    previous = stage;
    seen.insert(stage);
    CHECK(radius > 0);
    if (stage == 0)
      CHECK(radius <= half * (1 + 1e-12));
    if (stage == double(stages.size() - 1))
      largest_last = std::max(largest_last, radius);
  }
  CHECK(seen.size() == stages.size());
  CHECK(largest_last > half);
  CHECK(largest_last <= 1.02 * deck.real("sample/ball radius")); // a few 0.1 % expansions
}
