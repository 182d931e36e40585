// Whole runs: determinism, thread-count independence, sign conventions,
// outputs that stay valid when a run stops on a numerical fault, and runs
// that pause and resume bit for bit.
#include "app/decks/deck.h"
#include "app/io/output.h"
#include "app/kinds/deck_kinds.h"
#include "app/kinds/scene.h"
#include "app/kinds/uniaxial.h"
#include "app/run/dem_driver.h"
#include "verify/checks/checks_support.h"

#include "tests/test_folder.h"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <array>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <omp.h>
#include <optional>
#include <sstream>
#include <thread>
#include <vector>

namespace
{
namespace fs = std::filesystem;

demvv::Deck small_uniaxial(const std::string &law = "linear")
{
  demvv::Deck d = demvv::Deck::defaults(demvv::deck_kinds(), "uniaxial");
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
  // Cost counters are not physics: the neighbour list's builds follow its
  // adaptive skin, which a resumed run starts afresh (dem/simulation.cpp).
  for (const char *k : {"wall_seconds", "particle_steps_per_second", "neighbour_rebuilds", "status", "provenance"})
    s.erase(k);
  return s;
}

} // namespace

TEST_CASE("same deck and seed give identical series whatever the thread count", "[run]")
{
  const demvv::Deck d = small_uniaxial();
  const auto a = demvv::run_uniaxial(d, {"", 1, false});
  const auto b = demvv::run_uniaxial(d, {"", 1, false});
  const auto c = demvv::run_uniaxial(d, {"", 2, false});
  REQUIRE(a.series.rows() > 3);
  REQUIRE(a.series.rows() == b.series.rows());
  REQUIRE(a.series.rows() == c.series.rows());
  for (std::size_t r = 0; r < a.series.rows(); ++r)
  {
    CHECK(a.series.row(r) == b.series.row(r));
    CHECK(a.series.row(r) == c.series.row(r)); // contacts and balls are summed in a fixed order
  }
  omp_set_num_threads(omp_get_num_procs());
}

TEST_CASE("a scene's balls in any file order run alike, to the last bit, on any thread count", "[run][order]")
{
  // 343 balls on a jittered lattice in a box of six planes, pressed by the
  // lid: once in lattice order, once shuffled.  The run numbers the balls
  // along a Morton curve (dem/spatial_order.h), a canonical order, so every
  // row is the same bit for bit; tracked balls and pairs are named by file
  // row in the deck and in the outputs, the pair's shear force on the
  // ball of the larger row in both.
  const fs::path dir = demvv_tests::test_folder("test_ball_order");
  fs::remove_all(dir);
  fs::create_directories(dir);
  const double r = 0.5e-3, gap = 1.02 * 2 * r;
  std::vector<std::array<double, 3>> balls;
  std::uint64_t state = 12345;
  const auto jitter = [&state]()
  {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return (static_cast<double>(state >> 11) / 9007199254740992.0 - 0.5) * 0.02e-3;
  };
  for (int i = 0; i < 7; ++i)
    for (int j = 0; j < 7; ++j)
      for (int k = 0; k < 7; ++k)
        balls.push_back({{(i + 0.5) * gap + jitter(), (j + 0.5) * gap + jitter(), (k + 0.5) * gap + jitter()}});
  std::vector<std::size_t> shuffled(balls.size());
  for (std::size_t k = 0; k < shuffled.size(); ++k)
    shuffled[k] = (k * 97) % balls.size(); // 97 and 343 are coprime: a permutation
  // Lattice rows of two neighbours (same i, j; k and k + 1) that the
  // shuffle lists in the other order (rows 290 and 191).
  const std::size_t a = 4, b = 5;
  std::size_t row_a = 0, row_b = 0;
  for (std::size_t k = 0; k < shuffled.size(); ++k)
  {
    row_a = shuffled[k] == a ? k : row_a;
    row_b = shuffled[k] == b ? k : row_b;
  }
  const double side = 7 * gap;
  const auto write_scene =
    [&](const std::string &name, const std::vector<std::size_t> &rows, std::size_t ta, std::size_t tb)
  {
    std::ofstream csv(dir / (name + ".csv"));
    csv << "x_m,y_m,z_m,radius_m\n";
    csv.precision(17);
    for (std::size_t k : rows)
      csv << balls[k][0] << "," << balls[k][1] << "," << balls[k][2] << "," << r << "\n";
    std::ofstream prm(dir / (name + ".prm"));
    prm.precision(17);
    prm << "set kind = scene\nsubsection particles\n  set file = " << name << ".csv\nend\n"
        << "subsection balls\n  set friction = 0.5\nend\nsubsection walls\n";
    const char *names[6] = {"floor", "lid", "west", "east", "south", "north"};
    for (int w = 0; w < 6; ++w)
    {
      const int axis = 2 - w / 2; // floor and lid normal to z
      const bool high = w % 2 == 1;
      std::array<double, 3> point{}, normal{};
      point[axis] = high ? side : 0;
      normal[axis] = high ? -1 : 1;
      prm << "  subsection plane " << names[w] << "\n    set point = " << point[0] << ", " << point[1] << ", "
          << point[2] << "\n    set normal = " << normal[0] << ", " << normal[1] << ", " << normal[2] << "\n";
      if (w == 1)
        prm << "    set velocity = 0, 0, -0.5\n";
      prm << "  end\n";
    }
    prm << "end\nsubsection motion\n  set local damping = 0.7\nend\n"
        << "subsection run\n  set duration = 4e-4\nend\nsubsection output\n  set interval = 2e-5\n"
        << "  set track particles = " << ta << "\n  set track pairs = " << ta << "-" << tb << "\nend\n";
    csv.close();
    prm.close();
    return demvv::Deck::from_file(demvv::deck_kinds(), (dir / (name + ".prm")).string());
  };
  std::vector<std::size_t> lattice(balls.size());
  for (std::size_t k = 0; k < lattice.size(); ++k)
    lattice[k] = k;
  const auto in_order = demvv::run_scene(write_scene("lattice", lattice, a, b), {"", 1, false});
  const auto one = demvv::run_scene(write_scene("shuffled", shuffled, row_a, row_b), {"", 1, false});
  const auto two = demvv::run_scene(write_scene("shuffled", shuffled, row_a, row_b), {"", 2, false});
  omp_set_num_threads(omp_get_num_procs());
  REQUIRE(in_order.series.rows() > 10);
  REQUIRE(in_order.series.rows() == one.series.rows());
  REQUIRE(in_order.series.rows() == two.series.rows());
  CHECK(in_order.series.column("contacts").back() > 500); // the lid pressed the balls together
  // Without bonds the scene asks for the linear law's ordinary contacts
  // eight at a time, which the engine does where its build can
  // (docs/running.md), and the order still holds.
  CHECK(one.sim->settings().contacts_in_lanes);
  CHECK(one.sim->contacts_in_lanes() == one.sim->model().has_lanes());
  for (std::size_t k = 0; k < in_order.series.rows(); ++k)
  {
    CHECK(in_order.series.row(k) == one.series.row(k));
    CHECK(one.series.row(k) == two.series.row(k));
  }
  REQUIRE(in_order.particles.rows() == one.particles.rows());
  REQUIRE(in_order.contacts.rows() == one.contacts.rows());
  for (std::size_t k = 0; k < in_order.particles.rows(); ++k)
  {
    std::vector<double> x = in_order.particles.row(k), y = one.particles.row(k);
    CHECK(x[1] == double(a));
    CHECK(y[1] == double(row_a));
    x[1] = y[1] = 0;
    CHECK(x == y);
  }
  // The pair is (a, b) by lattice rows and (row_a, row_b) shuffled; with
  // the smaller row first both times the force is on the same ball only
  // when the two orders agree on which row is smaller.
  const double flip = (row_a < row_b) == (a < b) ? 1.0 : -1.0;
  REQUIRE(flip == -1.0); // the pair's order swaps: the shear force's sign must follow
  bool touched = false;
  for (std::size_t k = 0; k < in_order.contacts.rows(); ++k)
  {
    const std::vector<double> x = in_order.contacts.row(k), y = one.contacts.row(k);
    CHECK(y[1] == double(std::min(row_a, row_b)));
    CHECK(y[2] == double(std::max(row_a, row_b)));
    for (std::size_t c = 3; c < x.size(); ++c)
      CHECK(y[c] == (c >= 6 && c <= 8 ? flip * x[c] : x[c]));
    touched = touched || x.back() == 1.0;
  }
  CHECK(touched);
}

TEST_CASE("a scene's bond breaks and ParaView ids name balls by their row in the particle file", "[run][order]")
{
  // A bonded pair pulled apart, a third ball far off; listed as (far, a, b),
  // (a, far, b) and (b, far, a): the break is between rows 1 and 2, then 0
  // and 2 twice.
  const fs::path dir = demvv_tests::test_folder("test_break_rows");
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string far = "0.02,0,0,0.001,0", a = "0,0,0,0.001,-5", b = "0.002,0,0,0.001,5";
  const auto breaks_of = [&](const std::string &name, const std::vector<std::string> &rows)
  {
    {
      std::ofstream csv(dir / (name + ".csv"));
      csv << "x_m,y_m,z_m,radius_m,vx_mps\n";
      for (const std::string &r : rows)
        csv << r << "\n";
      std::ofstream prm(dir / (name + ".prm"));
      prm << "set kind = scene\nsubsection particles\n  set file = " << name << ".csv\nend\n"
          << "subsection bonds\n  set install = touching\n  set normal strength = 1\n"
          << "  set shear strength = 1\nend\nsubsection motion\n  set local damping = 0\nend\n"
          << "subsection run\n  set duration = 2e-4\nend\nsubsection output\n  set paraview = true\n"
          << "  set paraview interval = 1e-4\nend\n";
    }
    const fs::path out = dir / (name + "_run");
    demvv::run_scene(demvv::Deck::from_file(demvv::deck_kinds(), (dir / (name + ".prm")).string()),
                     {out.string(), 1, false});
    std::ifstream log(out / "bond_breaks.csv");
    std::vector<std::string> lines;
    for (std::string line; std::getline(log, line);)
      if (!line.empty() && line[0] != '#')
        lines.push_back(line.substr(line.find(',') + 1));
    const std::string frame = demvv::read_file((out / "paraview" / "particles_00000.vtp").string());
    // A bonded scene resolves its contacts one by one (docs/running.md).
    CHECK(nlohmann::json::parse(demvv::read_file((out / "summary.json").string()))["contacts_in_lanes"] == false);
    return std::make_pair(lines, frame);
  };
  const auto [first, first_frame] = breaks_of("far_first", {far, a, b});
  const auto [middle, middle_frame] = breaks_of("far_middle", {a, far, b});
  const auto [reversed, reversed_frame] = breaks_of("reversed", {b, far, a});
  REQUIRE(first.size() == 2); // the header and one break
  REQUIRE(middle.size() == 2);
  // Pair and mode, then where it broke: the point on the line of centres,
  // for two equal balls pulled apart symmetrically their midpoint (1 mm, 0, 0).
  const auto pair_and_mode = [](const std::string &row)
  {
    std::size_t end = 0;
    for (int field = 0; field < 3; ++field)
      end = row.find(',', end) + 1;
    return row.substr(0, end - 1);
  };
  CHECK(pair_and_mode(first[1]) == "1,2,1");
  CHECK(pair_and_mode(middle[1]) == "0,2,1");
  REQUIRE(reversed.size() == 2);
  CHECK(pair_and_mode(reversed[1]) == "0,2,1"); // the run's pair (a, b) is rows (2, 0): written smaller first
  for (const std::string &row : {first[1], middle[1], reversed[1]})
  {
    std::istringstream fields(row);
    std::vector<double> v;
    for (std::string f; std::getline(fields, f, ',');)
      v.push_back(std::stod(f));
    REQUIRE(v.size() == 6);
    CHECK(v[3] == Approx(1e-3).margin(1e-12));
    CHECK(v[4] == Approx(0).margin(1e-12));
    CHECK(v[5] == Approx(0).margin(1e-12));
  }
  // The frames list the balls in the run's order, the same for both files
  // (a, b, then the far ball, along the curve); their ids are the rows of
  // each file.
  const auto ids = [](const std::string &frame)
  {
    const auto at = frame.find("Name=\"id\"");
    const auto open = frame.find('>', at) + 1;
    std::istringstream values(frame.substr(open, frame.find('<', open) - open));
    std::vector<double> out;
    for (double v; values >> v;)
      out.push_back(v);
    return out;
  };
  CHECK(ids(first_frame) == std::vector<double>{1, 2, 0});
  CHECK(ids(middle_frame) == std::vector<double>{0, 2, 1});
}

TEST_CASE("uniaxial compression gives positive axial stress and strain and negative radial strain", "[run]")
{
  const auto r = demvv::run_uniaxial(small_uniaxial(), {"", 0, false});
  REQUIRE_FALSE(r.status.fault);
  CHECK(r.series.column("axial_strain").back() >= 0.004);
  CHECK(r.series.column("axial_stress_pa").back() > 0);
  CHECK(r.series.column("axial_stress_top_pa").back() > 0);
  CHECK(r.series.column("axial_stress_bottom_pa").back() > 0);
  CHECK(r.series.column("radial_strain").back() < 0); // the sample bulges
  CHECK(r.summary["initial_modulus_pa"].get<double>() > 0);
  const double nu = r.summary["poisson_ratio"].get<double>();
  CHECK(nu > 0);
  CHECK(nu < 0.5);
}

TEST_CASE("a run directory holds the resolved deck and provenance and a complete series", "[run]")
{
  const fs::path dir = demvv_tests::test_folder("test_run");
  fs::remove_all(dir);
  const demvv::Deck deck = small_uniaxial();
  demvv::run_uniaxial(deck, {dir.string(), 0, false});
  for (const char *f : {"deck.prm", "summary.json", "series.csv", "bond_breaks.csv"})
    CHECK(fs::exists(dir / f));
  const auto summary = nlohmann::json::parse(demvv::read_file((dir / "summary.json").string()));
  CHECK(summary["status"]["state"] == "completed");
  for (const char *k :
       {"version", "git_sha", "sources_sha256", "compiler", "dem_macros_sha256", "threads", "seed", "deck_fnv1a64"})
    CHECK(summary["provenance"].contains(k));
  CHECK(summary["sample"]["description"].get<std::string>().find("verification stand-in") != std::string::npos);
  // The resolved deck reads back as the deck that was run.
  CHECK(demvv::Deck::from_file(demvv::deck_kinds(), (dir / "deck.prm").string()).resolved() == deck.resolved());
  std::ifstream series(dir / "series.csv");
  std::string comment, header;
  std::getline(series, comment);
  std::getline(series, header);
  CHECK(comment.find("compression positive") != std::string::npos);
  CHECK(header.find("axial_stress_pa") != std::string::npos);
}

TEST_CASE("a numerical fault stops the run with a diagnostic and keeps valid outputs", "[run]")
{
  // The deck fixes a step five times the stability limit and allows it:
  // the run blows up, is stopped by the runaway guard, and the rows written
  // before stay whole.
  const fs::path dir = demvv_tests::test_folder("test_fault");
  fs::remove_all(dir);
  demvv::Deck d = demvv::Deck::from_file(demvv::deck_kinds(), std::string(DEMVV_TEST_DATA) + "/unstable.prm");
  const auto r = demvv::run_scene(d, {dir.string(), 0, false});
  REQUIRE(r.status.fault);
  CHECK(r.status.particle >= 0);
  CHECK(r.status.step > 0);
  const auto summary = nlohmann::json::parse(demvv::read_file((dir / "summary.json").string()));
  CHECK(summary["status"]["state"] == "numerical fault");
  CHECK(summary["status"]["fault"]["step"].get<long>() == r.status.step);
  std::ifstream series(dir / "series.csv");
  std::string line;
  std::size_t rows = 0, columns = 0;
  while (std::getline(series, line))
  {
    if (line.empty() || line[0] == '#')
      continue;
    const std::size_t commas = static_cast<std::size_t>(std::count(line.begin(), line.end(), ','));
    if (columns == 0)
      columns = commas;
    CHECK(commas == columns); // every row whole
    ++rows;
  }
  CHECK(rows > 2);
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
  const demvv::Deck deck = small_uniaxial(law);
  const fs::path whole = demvv_tests::test_folder("resume_whole_" + law);
  const fs::path split = demvv_tests::test_folder("resume_split_" + law);
  fs::remove_all(whole);
  fs::remove_all(split);
  const auto reference = demvv::run_uniaxial(deck, {whole.string(), 1, false});
  REQUIRE(reference.status.steps > 400);

  demvv::RunOptions pause{split.string(), 1, false};
  pause.pause_after = reference.status.steps / 3;
  const auto first = demvv::run_uniaxial(deck, pause);
  REQUIRE(first.status.paused);
  CHECK(fs::exists(demvv::checkpoint_state_file(split.string())));
  CHECK(demvv_tests::read_json(split / "summary.json")["status"]["state"] == "paused");
  CHECK_NOTHROW(demvv::check_resumable(split.string(), deck));

  demvv::RunOptions resume{split.string(), 2, false};
  resume.resume = true;
  const auto rest = demvv::run_uniaxial(deck, resume);
  REQUIRE_FALSE(rest.status.fault);
  CHECK(rest.status.steps == reference.status.steps);
  REQUIRE(rest.series.rows() == reference.series.rows());
  for (std::size_t r = 0; r < reference.series.rows(); ++r)
    CHECK(rest.series.row(r) == reference.series.row(r));
  for (const char *file : {"series.csv", "bond_breaks.csv"})
  {
    INFO(file);
    CHECK(demvv::read_file((split / file).string()) == demvv::read_file((whole / file).string()));
  }
  CHECK(physics_of(demvv_tests::read_json(split / "summary.json")) ==
        physics_of(demvv_tests::read_json(whole / "summary.json")));
  CHECK(demvv_tests::read_json(split / "summary.json")["status"]["state"] == "completed");
}

TEST_CASE("a resume is refused for another deck or a directory without a checkpoint", "[run][resume]")
{
  const fs::path dir = demvv_tests::test_folder("resume_refused");
  fs::remove_all(dir);
  const demvv::Deck deck = small_uniaxial("linear");
  CHECK_THROWS_AS(demvv::check_resumable(dir.string(), deck), demvv::DeckError);
  demvv::RunOptions pause{dir.string(), 1, false};
  pause.pause_after = 50;
  demvv::run_uniaxial(deck, pause);
  demvv::Deck other = small_uniaxial("linear");
  other.set("loading/final strain", "0.005");
  CHECK_THROWS_WITH(demvv::check_resumable(dir.string(), other), Catch::Contains("another deck"));
}

TEST_CASE("the default thread count leaves out a core another task is running on", "[run][threads]")
{
  const int cores = omp_get_num_procs();
  if (cores < 2)
    return; // one core: one thread whatever the load
  std::atomic<bool> stop{false};
  std::thread busy(
    [&]
    {
      while (!stop.load(std::memory_order_relaxed))
        ;
    });
  int seen = cores;
  for (int k = 0; k < 50 && seen == cores; ++k) // until the scheduler has started it
  {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
    seen = demvv::idle_cores();
  }
  stop = true;
  busy.join();
  CHECK(seen >= 1);
  CHECK(seen <= cores - 1);
}

TEST_CASE("a count with a ceiling (--threads, a sweep's share) is governed up to it, an exact count is kept",
          "[run][threads]")
{
  demvv::RunOptions exact{"", 2};
  CHECK_FALSE(demvv::threads_are_ours(exact));
  demvv::RunOptions share{"", 2};
  share.most_threads = 1;
  CHECK(demvv::threads_are_ours(share));
  CHECK(demvv::thread_ceiling(share) == 1);
  CHECK(demvv::thread_ceiling(exact) == omp_get_num_procs());
  // A ceiling beyond the machine is its cores (--threads 1024 runs on them).
  share.most_threads = omp_get_num_procs() + 1000;
  CHECK(demvv::thread_ceiling(share) == omp_get_num_procs());
  // demvv verify --threads N: each run of a check may use N threads, never more.
  const demvv::RunOptions check = demvv::run_options(demvv::CheckContext{"", true, 3, {}});
  CHECK(check.threads == 3);
  CHECK(check.most_threads == 3);
}

TEST_CASE("the thread governor keeps an exact count as it is and clamps a governed one to its ceiling",
          "[run][threads]")
{
  const int before = omp_get_max_threads();
  const int cores = omp_get_num_procs();
  omp_set_num_threads(cores + 2);
  const demvv::ThreadGovernor exact(cores + 2, cores, false);
  CHECK(exact.threads() == cores + 2);
  CHECK(omp_get_max_threads() == cores + 2);
  CHECK(exact.to_json()["at_end"] == cores + 2);
  CHECK_FALSE(exact.to_json().contains("most"));
  const demvv::ThreadGovernor governed(cores + 2, cores, true);
  CHECK(governed.threads() == cores);
  CHECK(omp_get_max_threads() == cores); // the clamped count is the one that runs
  CHECK(governed.to_json()["most"] == cores);
  omp_set_num_threads(before);
}

TEST_CASE("the thread governor gives up a thread a busy machine holds back and keeps both on an idle one",
          "[run][threads]")
{
  // A simulated machine of two cores: each step advances a simulated clock
  // by the step's time at the governor's thread count.  Idle, two threads
  // take 0.5 ms a step and one 1 ms; beside a busy process (from `busy_at`
  // on) two take 3 ms, since they wait for the core the other process holds.
  // Its runnable tasks are the run's threads and the busy process.
  const int threads_before = omp_get_max_threads();
  struct Machine
  {
    double clock = 0, busy_at = 1e9, fewer_seconds = 0;
    double load_period = 0, load_phase = 0;  // s: a load busy at the start of every period (none at 0)
    double load_share = 0.5;                 // the share of each period the load is busy
    double one_busy = 1e-3, two_busy = 3e-3; // s, a step on one and on two threads while the load runs
    int cores = 2;
    bool busy() const
    {
      if (load_period > 0)
        return std::fmod(clock + load_phase, load_period) < load_share * load_period;
      return clock >= busy_at;
    }
    const demvv::ThreadGovernor *governor = nullptr;
    demvv::ThreadGovernor::Probes probes()
    {
      return {[this] { return clock; },
              [this]() -> std::optional<int> { return cores - governor->threads() - (busy() ? 1 : 0); }};
    }
  };
  const auto governed = [](Machine &m, int start, int most)
  {
    auto g = std::make_unique<demvv::ThreadGovernor>(start, most, true, m.probes());
    m.governor = g.get();
    return g;
  };
  const auto run = [](Machine &m, demvv::ThreadGovernor &g, double until)
  {
    while (m.clock < until)
    {
      const bool busy = m.busy();
      const double step = g.threads() == 1 ? (busy ? m.one_busy : 1e-3) : (busy ? m.two_busy : 0.5e-3);
      if (g.threads() == 1)
        m.fewer_seconds += step;
      m.clock += step;
      g.after_step();
    }
  };
  SECTION("idle: two threads stay, with no trial in a short run and one every 32 s in a long one")
  {
    Machine m;
    const auto g = governed(m, 2, 2);
    run(m, *g, 10);
    CHECK(g->threads() == 2);
    CHECK(m.fewer_seconds == 0); // no competitor seen: no trial (each cost 0.1 s at half speed)
    CHECK(g->trials() == 0);
    run(m, *g, 600);
    CHECK(g->threads() == 2);
    CHECK(g->changes() == 0);
    // Trials of 0.2 s only every 32 s, for a competitor the probe cannot
    // see: 18 in 600 s, 3.6 s.
    CHECK(m.fewer_seconds > 0);
    CHECK(m.fewer_seconds < 0.01 * 600);
  }
  SECTION("busy from the start: one thread after the first trial (at 2 s), and kept")
  {
    Machine m;
    m.busy_at = 0;
    const auto g = governed(m, 2, 2);
    run(m, *g, 3);
    CHECK(g->threads() == 1);
    run(m, *g, 120);
    CHECK(g->threads() == 1);
    CHECK(g->changes() == 1);
  }
  SECTION("a load that arrives mid-run is met within a trial's recheck and windows")
  {
    Machine m;
    m.busy_at = 300;
    const auto g = governed(m, 2, 2);
    run(m, *g, 300);
    CHECK(g->threads() == 2);
    // Seen within 0.25 s; then a window, the trial's and the confirming one
    // (its steps fitted to 0.2 s at the idle pace, 1.2 s at the busy one).
    run(m, *g, 302);
    CHECK(g->threads() == 1);
    CHECK(g->changes() == 1);
  }
  SECTION("a run that started on one core because another was busy takes the second when it is free")
  {
    Machine m;
    const auto g = governed(m, 1, 2);
    run(m, *g, 1); // the first trial of one more thread comes after 0.5 s
    CHECK(g->threads() == 2);
    CHECK(g->changes() == 1);
    run(m, *g, 60);
    CHECK(g->threads() == 2);
  }
  SECTION("a run that started on one core beside a load that comes and goes takes the second, whatever its phase")
  {
    // A core busy 50 ms of every 100 (the identical-work benchmark's half
    // load), with the steps' times that make two threads 1.4 times one on
    // average, as on that benchmark (BENCHMARKS.md): in the load's busy
    // half one thread takes 1.2 ms a step and two 1.76 ms.  The governor's
    // windows (0.2 s) span whole periods of the load, so a single look at
    // the machine at each window's end sees the same phase every time: in
    // half of these phases a run never saw the free core and kept one
    // thread.  The looks spread over the window see both halves.
    for (int phase = 0; phase < 10; ++phase)
    {
      Machine m;
      m.load_period = 0.1;
      m.one_busy = 1.2e-3;
      m.two_busy = 1.76e-3;
      m.load_phase = 0.01 * phase;
      const auto g = governed(m, 1, 2);
      run(m, *g, 4);
      INFO("the load's phase " << m.load_phase << " s, trials " << g->trials());
      CHECK(g->threads() == 2);
    }
  }
  SECTION("a process that only passes by (5 ms of every 100) starts no trial on two threads, whatever its phase")
  {
    // One look at each window's end would land in the passing process's
    // 5 ms at one phase in twenty, and there at every window; the looks
    // see it in one of twenty, under the quarter a reason needs.
    for (int phase = 0; phase < 20; ++phase)
    {
      Machine m;
      m.load_period = 0.1;
      m.load_share = 0.05;
      m.load_phase = 0.005 * phase;
      m.two_busy = 0.5e-3;
      const auto g = governed(m, 2, 2);
      run(m, *g, 10);
      INFO("the passing process's phase " << m.load_phase << " s");
      CHECK(g->trials() == 0);
      CHECK(g->threads() == 2);
    }
  }
  SECTION("a run that started below its ceiling tries one more thread first")
  {
    Machine m;
    m.cores = 3;
    omp_set_num_threads(3);
    const auto g = governed(m, 2, 3);
    while (m.clock < 0.9 && g->threads() == 2)
    {
      m.clock += 1e-3;
      g->after_step();
    }
    CHECK(g->threads() == 3); // the trial, within 0.9 s
  }
  SECTION("a run that started on one core beside a busy process keeps it, trying two only every 32 s")
  {
    Machine m;
    m.busy_at = 0;
    const auto g = governed(m, 1, 2);
    run(m, *g, 120);
    CHECK(g->threads() == 1);
    CHECK(g->changes() == 0);
    // No free core seen, so a trial only every 32 s: three in 120 s.  A
    // trial is the 0.2 s window's steps (200 at 1 ms), taken at 3 ms: 0.6
    // s if it ran them all, but it ends once past 0.18 s (90 % of the 0.2
    // s its steps took on one thread: it can no longer win), at 61 steps,
    // 0.183 s.  (Before the probe: a trial at 0.5 s, then after 4, 8, 16,
    // 32, 32 s, six.)
    CHECK(m.fewer_seconds > 120 - 3 * 0.19);
    CHECK(m.fewer_seconds < 120 - 0.3);
    CHECK(g->trials() == 3);
    CHECK(g->to_json()["trials"] == 3);
  }
  SECTION("without a probe of the machine the trials keep their spacing")
  {
    Machine m;
    m.busy_at = 0;
    demvv::ThreadGovernor::Probes blind = m.probes();
    blind.spare_cores = [] { return std::optional<int>(); };
    demvv::ThreadGovernor g(1, 2, true, blind);
    m.governor = &g;
    run(m, g, 120);
    CHECK(g.threads() == 1);
    // The six trials of two threads: 0.5 s, then after 4, 8, 16, 32, 32 s.
    CHECK(g.trials() == 6);
    CHECK(m.fewer_seconds < 120 - 5 * 0.17);
    CHECK(m.fewer_seconds > 120 - 8 * 0.19);
  }
  SECTION("a count the user fixed is never changed")
  {
    Machine m;
    m.busy_at = 0;
    demvv::ThreadGovernor g(2, 2, false, m.probes());
    m.governor = &g;
    run(m, g, 60);
    CHECK(g.threads() == 2);
    CHECK(g.changes() == 0);
  }
  omp_set_num_threads(threads_before);
}

TEST_CASE("a series on a full disk says so with the system's reason", "[run][output]")
{
  // /dev/full takes no byte: every write fails with ENOSPC.
  try
  {
    demvv::CsvSeries full("/dev/full", "a comment", {"time_s", "x_m"});
    FAIL("the header was written to /dev/full");
  }
  catch (const demvv::OutputError &e)
  {
    CHECK(std::string(e.what()).find("/dev/full") != std::string::npos);
    CHECK(std::string(e.what()).find(std::strerror(ENOSPC)) != std::string::npos);
  }
}

TEST_CASE("a record names this build only when every part of the build's identity agrees", "[run][provenance]")
{
  nlohmann::json p = demvv::provenance(1, 1, "deck");
  CHECK(demvv::made_by_this_build(p));
  CHECK(demvv::made_by_this_build(demvv::build_identity()));
  const nlohmann::json identity = demvv::build_identity();
  CHECK(identity.size() == 5);
  for (const auto &item : identity.items())
  {
    nlohmann::json other = p;
    other[item.key()] = "another";
    CHECK_FALSE(demvv::made_by_this_build(other));
    other.erase(item.key());
    CHECK_FALSE(demvv::made_by_this_build(other));
  }
  CHECK_FALSE(demvv::made_by_this_build(nlohmann::json()));
  CHECK_FALSE(demvv::made_by_this_build(nlohmann::json::array()));
}

TEST_CASE("a check's sweep runs each member on at most verify's --threads", "[run][threads]")
{
  // One: a ceiling no default (the cores of this machine) equals where there
  // are two cores or more.
  const demvv::CheckContext ctx{"", true, 1, {}};
  demvv::SweepPlan plan;
  plan.base_deck = std::string(DEMVV_TEST_DATA) + "/small_lattice.prm";
  plan.keys = {"loading/final strain"};
  plan.points = {{"0.0005"}};
  plan.seeds = 1;
  const demvv::ScratchDirectory scratch;
  const int before = omp_get_max_threads();
  const demvv::SweepOutcome outcome = demvv::run_sweep_in(ctx, scratch, plan);
  omp_set_num_threads(before);
  REQUIRE(outcome.rows.size() == 1);
  REQUIRE(outcome.rows[0].status == "completed");
  const nlohmann::json threads =
    demvv_tests::read_json(fs::path(outcome.rows[0].directory) / "summary.json")["status"]["threads"];
  CHECK(threads["governed"] == true);
  CHECK(threads["most"] == 1);
}
