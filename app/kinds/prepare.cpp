#include "app/kinds/prepare.h"

#include "app/decks/deck_sections.h"
#include "app/io/input.h"
#include "app/io/output.h"
#include "app/io/paraview.h"
#include "app/io/section.h"
#include "app/kinds/deck_kinds.h"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <iostream>
#include <limits>
#include <map>
#include <optional>

namespace demvv
{
namespace
{

/// Deck key of each PackingSettings field a PackingError can name.
std::string key_of(const std::string &setting)
{
  if (setting == "target solid fraction")
    return "sample/target solid fraction";
  if (setting == "radius")
    return "sample/ball radius";
  if (setting == "diameter")
    return "sample/diameter";
  if (setting == "aspect ratio")
    return "sample/aspect ratio";
  return "sample/particles";
}

dem::PackingSettings read_settings(const Deck &d)
{
  dem::PackingSettings s;
  s.particles = d.integer("sample/particles");
  s.radius = d.real("sample/ball radius");
  s.diameter = d.real("sample/diameter");
  s.height = d.real("sample/height");
  s.aspect = d.real("sample/aspect ratio");
  s.target_solid_fraction = d.real("sample/target solid fraction");
  s.seed = static_cast<std::uint64_t>(d.integer("sample/seed"));
  s.ball = parse_ball_properties(d);
  s.walls = {d.real("walls/normal stiffness"), d.real("walls/shear stiffness"), 0};
  s.growth_stages = static_cast<int>(d.integer("preparation/growth stages"));
  s.growth_cycles = d.integer("preparation/growth cycles");
  s.servo_stress = d.real("preparation/servo stress");
  s.stress_target = d.real("preparation/stress target");
  s.equilibrium_ratio = d.real("preparation/equilibrium ratio");
  s.max_cycles = d.integer("preparation/max cycles");
  s.min_contacts = static_cast<int>(d.integer("preparation/min contacts"));
  s.max_expansion = d.real("preparation/max expansion");
  s.local_damping = d.real("preparation/local damping");
  s.bonds = parse_bond_settings(d);
  s.bond = d.text("bonds/install") == "touching";
  if (s.particles == 0 && (s.diameter <= 0 || s.height <= 0))
    d.fail("sample/particles", "expected a number of balls, or a cell diameter and height (both > 0)");
  return s;
}
} // namespace

void declare_prepare(DeckSchema &s)
{
  s.text("title", "", "One line saying what this sample is for (copied to the sample file).");
  s.enter("sample");
  s.integer("particles", 6000, 0, 100000000,
            "Number of balls, at least 50; 0 takes the cell diameter and height and eq. 5.1 "
            "(N = 3 V (1 - n) / (4 pi R^3)).");
  s.real("ball radius", 0.885e-3, 0, inf, "m", "Final radius of every ball (thesis: 1.77 mm diameter sand).",
         Interval::open_below);
  s.real("diameter", 0, 0, inf, "m", "Cell diameter, used when particles = 0.");
  s.real("height", 0, 0, inf, "m", "Cell height, used when particles = 0.");
  s.real("aspect ratio", 1, 0, inf, "-", "Cell height / diameter when the number of balls is given (thesis: H = D).",
         Interval::open_below);
  s.real("target solid fraction", 0.64, 0, 1, "-",
         "Solid fraction 1 - n that sizes the cell (eq. 5.1); at most 0.7405 (densest packing of equal spheres).  "
         "Above random close packing (about 0.64) the grown balls are jammed and the servo stage relaxes them; "
         "below it frictionless balls never jam in a fixed cell and the servo must compact them (slowly).",
         Interval::open_below);
  s.integer("seed", 1, 0, std::numeric_limits<int>::max(), "Seed of the random placement.");
  s.leave();
  declare_ball_properties(s);
  s.enter("walls");
  s.real("normal stiffness", 1.2e7, 0, inf, "N/m", "Normal stiffness of the cell walls (in series with the ball's).",
         Interval::open_below);
  s.real("shear stiffness", 0, 0, inf, "N/m",
         "Shear stiffness of the cell walls (they are frictionless during preparation, thesis §5.3.2).");
  s.leave();
  s.enter("preparation");
  s.integer("growth stages", 40, 1, 10000, "Stages in which the balls grow from half to full radius.");
  s.integer("growth cycles", 100, 0, 100000000,
            "Relaxation cycles after each growth stage (velocities are zeroed before each increment).");
  s.real("servo stress", 1e5, 0, inf, "Pa",
         "Confining stress the three walls are servo-controlled to before the radius reduction (thesis §6.1: "
         "0.1 MPa); 0 skips the servo stage.");
  s.real("stress target", 1e3, 0, inf, "Pa", "Mean stress the radius reduction must reach (thesis §5.3.2: 1 kPa).",
         Interval::open_below);
  s.real("equilibrium ratio", 1e-3, 0, 1, "-",
         "Unbalanced-force ratio below which a stage counts as in equilibrium (the servo and growth stages use "
         "ten times it).",
         Interval::open_below);
  s.integer("max cycles", 200000, 100, 2000000000, "Cycle budget of each equilibrium stage.");
  s.integer("min contacts", 4, 0, 12, "Contacts (walls count) every ball should have before bonding (thesis §5.3.3).");
  s.real("max expansion", 0.01, 0, 0.1, "-",
         "Largest relative growth of a ball with too few contacts (thesis: typically less than 1 %).");
  s.real("local damping", 0.7, 0, 1, "-", "Local damping during preparation (1 would cancel every force).",
         Interval::open_above);
  s.leave();
  declare_bonds(s, {"touching", "none"}, false);
  s.enter("output");
  s.flag("paraview", true, "Write a ParaView view of the prepared sample to paraview/.");
  s.flag("paraview stages", false,
         "Also write a ParaView frame at the end of every preparation stage (the balls placed at half radius, "
         "Fig. 5.2; grown, Fig. 5.3; after the servo, each radius reduction and the release) to paraview/stages/; "
         "summary.json lists them.");
  s.leave();
}

dem::PackingSettings parse_prepare(const Deck &deck)
{
  const dem::PackingSettings settings = read_settings(deck);
  try
  {
    // Refuse an impossible packing, or one that cannot fit in memory, before any file is written.
    const dem::CellSize cell = dem::cell_size(settings);
    const std::string key = key_of(settings.particles > 0 ? "particles" : "radius");
    check_memory(dem::estimated_memory_bytes(double(cell.particles), 3),
                 format_number(double(cell.particles)) + " balls", deck.path(), key, deck.text(key),
                 "expected fewer balls (a larger ball radius or a smaller cell)");
  }
  catch (const dem::PackingError &e)
  {
    deck.fail(key_of(e.setting), std::string(e.what()));
  }
  return settings;
}

PrepareSpec parse_prepare_spec(const Deck &deck)
{
  return {deck,
          parse_prepare(deck),
          deck.text("title"),
          deck.integer("sample/seed"),
          deck.real("preparation/stress target"),
          deck.flag("output/paraview"),
          deck.flag("output/paraview stages")};
}

PrepareResult run_prepare(const Deck &deck, const RunOptions &options)
{
  return run_prepare(parse_prepare_spec(deck), options);
}

PrepareResult run_prepare(const PrepareSpec &spec, const RunOptions &options)
{
  const int threads = apply_threads(options);
  const DeckRecord &deck = spec.deck;
  const dem::PackingSettings &settings = spec.settings;

  std::unique_ptr<RunDirectory> dir;
  if (!options.out_dir.empty())
    dir = std::make_unique<RunDirectory>(options.out_dir, deck, threads, spec.seed);
  std::vector<std::string> log;
  const auto say = [&](const std::string &line)
  {
    log.push_back(line);
    if (options.progress)
      std::cerr << "prepare " << deck.name << ": " << line << "\n";
  };

  // With output/paraview stages, a frame at the end of each stage (Figs
  // 5.2, 5.3, 5.5): paraview/stages/, the collection's timestep the stage's
  // number.
  // And always its vertical section (app/io/section.h) to
  // preparation_sections.csv, the stage's number in the first column: the
  // figures of the first, second and last stage draw it.
  std::unique_ptr<ParaviewWriter> stage_frames;
  std::unique_ptr<CsvSeries> sections;
  if (dir && spec.paraview_stages)
    stage_frames = std::make_unique<ParaviewWriter>(dir->path("paraview/stages"));
  if (dir)
  {
    std::vector<std::string> columns = section_columns();
    columns.insert(columns.begin(), "stage");
    sections = std::make_unique<CsvSeries>(dir->path("preparation_sections.csv"),
                                           "demvv prepare '" + deck.name + "': SI units; at the end of each stage (" +
                                             "its name in summary.json, preparation_stages), " + section_note(),
                                           columns);
  }
  nlohmann::json stages = nlohmann::json::array();
  const auto at_stage = [&](const dem::Simulation &sim, const std::string &name)
  {
    if (!sections)
      return;
    const double stage = double(stages.size());
    for (const SectionCircle &c : vertical_section(sim.particles()))
      sections->write({stage, c.x, c.z, c.radius});
    if (stage_frames)
      stage_frames->write_frame(sim, stage);
    stages.push_back({{"frame", stages.size()}, {"stage", name}, {"time_s", sim.time()}});
  };

  PrepareResult result;
  const auto start = std::chrono::steady_clock::now();
  dem::PreparedSample prepared;
  const StopSignals signals;
  try
  {
    prepared = dem::prepare_sample(
      settings, say, [&] { return signals.received() != 0; }, at_stage);
  }
  catch (const dem::NumericalFault &f)
  {
    record_fault(result.status, f);
  }
  catch (const dem::PreparationStopped &e)
  {
    result.status.interrupted_by = signals.received();
    result.status.message = std::string(e.what()) + "; a preparation has no checkpoint: run it again";
  }
  result.status.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  nlohmann::json summary = {{"kind", "prepare"}, {"title", spec.title}, {"log", log}};
  if (sections)
    summary["preparation_stages"] = stages;
  if (stage_frames)
    summary["paraview_stages"] = {{"folder", "paraview/stages"},
                                  {"frames", stages},
                                  {"note", "one frame at the end of each preparation stage; the collection's "
                                           "timestep is the frame's number, not a time"}};
  if (result.status.fault || result.status.interrupted_by)
  {
    summary["status"] = result.status.to_json();
    if (dir)
      dir->write_summary(summary);
    return result;
  }
  result.status.steps = prepared.sim->steps();
  SampleFile &sample = result.sample;
  sample.snapshot = prepared.sim->snapshot();
  sample.cell = std::move(prepared.cell);
  sample.contact_law = std::string(prepared.sim->model().name());
  sample.seed = spec.seed;
  sample.title = spec.title;
  sample.preparation = report_json(prepared.report);
  sample.provenance = provenance(threads, sample.seed, deck.resolved);
  summary["status"] = result.status.to_json();
  summary["preparation"] = sample.preparation;
  summary["stress_target_pa"] = spec.stress_target_pa;
  summary["sample_file"] = "sample.json";
  if (dir)
  {
    write_sample(dir->path("sample.json"), sample);
    if (spec.paraview)
      ParaviewWriter(dir->path("paraview")).write_frame(*prepared.sim, prepared.sim->time());
    dir->write_summary(summary);
  }
  return result;
}

std::string sample_cache_dir(const std::string &deck_path)
{
  const char *cache = std::getenv("DEMVV_CACHE");
  if (cache && *cache)
  {
    std::error_code ec;
    if (std::filesystem::exists(cache, ec) && !std::filesystem::is_directory(cache, ec))
      throw DeckError("DEMVV_CACHE='" + escaped(cache) +
                      "': not a directory: expected a folder for prepared samples (or DEMVV_CACHE unset: samples/ "
                      "beside the prepare deck)");
    return cache;
  }
  const auto slash = deck_path.find_last_of('/');
  return (slash == std::string::npos ? std::string(".") : deck_path.substr(0, slash)) + "/samples";
}

std::string sample_cache_hash(const std::string &resolved_deck, const nlohmann::json &build)
{
  return fnv1a_hex(resolved_deck + "\nbuild " + build.dump()).substr(0, 12);
}

namespace
{
/// The cache folder of a prepare deck with overrides.
std::string cache_entry(const Deck &deck, const std::string &path)
{
  if (deck.kind() != "prepare")
    throw DeckError(path + ": a deck of kind '" + deck.kind() + "': expected a prepare deck or a sample file");
  // Keyed by the resolved deck and the build, so that neither another deck
  // nor a changed procedure (or its arithmetic) is served a stale sample.
  return sample_cache_dir(path) + "/" + deck.name() + "-" + sample_cache_hash(deck.resolved(), build_identity());
}

/// The whole text of a small file (read_input), or nullopt when it cannot
/// be read or is larger than `max_bytes`.
std::optional<std::string> small_file_text(const std::filesystem::path &file, std::uintmax_t max_bytes)
{
  try
  {
    return read_input(file.string(), "file", max_bytes);
  }
  catch (const DeckError &)
  {
    return std::nullopt;
  }
}

/// The build that made the sample cache entry `entry`, and when the entry
/// was last used; nullopt unless the folder is provably one cache_entry()
/// made: a finished prepare run (a summary of kind "prepare" with a
/// provenance) whose name ends in the hash of its deck.prm and that build.
struct CacheEntryUse
{
  nlohmann::json build;
  std::filesystem::file_time_type used;
};
std::optional<CacheEntryUse> cache_entry_use(const std::filesystem::path &entry)
{
  namespace fs = std::filesystem;
  constexpr std::uintmax_t most = 1 << 22; // bytes: a summary or resolved deck is a few kB
  const std::string name = entry.filename().string();
  const auto dash = name.rfind('-');
  const std::optional<std::string> summary_text = small_file_text(entry / "summary.json", most);
  const std::optional<std::string> deck_text = small_file_text(entry / "deck.prm", most);
  if (dash == std::string::npos || !summary_text || !deck_text)
    return std::nullopt;
  const nlohmann::json summary = nlohmann::json::parse(*summary_text, nullptr, false);
  if (!summary.is_object() || !summary.contains("kind") || summary["kind"] != "prepare" ||
      !summary.contains("provenance") || !summary["provenance"].is_object())
    return std::nullopt;
  const nlohmann::json &provenance = summary["provenance"];
  const nlohmann::json identity = build_identity(); // named: items() does not keep a temporary alive
  CacheEntryUse use;
  use.build = nlohmann::json::object();
  for (const auto &[key, value] : identity.items())
    use.build[key] = provenance.contains(key) ? provenance[key] : nlohmann::json();
  if (name.substr(dash + 1) != sample_cache_hash(*deck_text, use.build))
    return std::nullopt;
  // The sample's time, renewed on each use; a preparation that failed has
  // only its summary.
  std::error_code ec;
  use.used = fs::last_write_time(entry / "sample.json", ec);
  if (ec)
    use.used = fs::last_write_time(entry / "summary.json", ec);
  if (ec)
    return std::nullopt;
  return use;
}
} // namespace

void prune_sample_cache(const std::string &dir, std::size_t keep, std::chrono::hours grace)
{
  namespace fs = std::filesystem;
  struct Entry
  {
    fs::path path;
    std::string build;
    fs::file_time_type used;
  };
  std::vector<Entry> entries;
  std::map<std::string, fs::file_time_type> last_use; // by build
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec))
  {
    std::error_code not_a_folder;
    if (!it->is_directory(not_a_folder))
      continue;
    const std::optional<CacheEntryUse> use = cache_entry_use(it->path());
    if (!use)
      continue;
    std::string build = use->build.dump();
    const auto [at, added] = last_use.emplace(build, use->used);
    if (!added)
      at->second = std::max(at->second, use->used);
    entries.push_back({it->path(), std::move(build), use->used});
  }
  std::vector<std::pair<fs::file_time_type, std::string>> builds;
  for (const auto &[build, used] : last_use)
    builds.emplace_back(used, build);
  std::sort(builds.begin(), builds.end(), std::greater<>());
  std::vector<std::string> kept = {build_identity().dump()};
  for (std::size_t k = 0; k < builds.size() && k < keep; ++k)
    kept.push_back(builds[k].second);
  const fs::file_time_type since = fs::file_time_type::clock::now() - grace;
  for (const Entry &e : entries)
    if (e.used < since && std::find(kept.begin(), kept.end(), e.build) == kept.end())
      fs::remove_all(e.path, ec);
}

std::string cached_sample_file_name(const std::string &path, const std::vector<std::string> &overrides)
{
  return cache_entry(Deck::from_file(dem_deck_kinds(), path, overrides), path) + "/sample.json";
}

std::string cached_sample_file(const std::string &path, const std::vector<std::string> &overrides, bool progress)
{
  const Deck deck = Deck::from_file(dem_deck_kinds(), path, overrides);
  const std::string dir = cache_entry(deck, path);
  const std::string file = dir + "/sample.json";
  if (std::filesystem::exists(file))
  {
    // The time of its last use, which pruning reads; a cache this process
    // may not write is still served.
    std::error_code ignored;
    std::filesystem::last_write_time(file, std::filesystem::file_time_type::clock::now(), ignored);
    return file;
  }
  // On the caller's thread count (at most the cores), and the caller's count
  // set again after, so that the run it prepares for goes on with the count
  // it was given.
  const int caller = omp_get_max_threads();
  const PrepareResult r = run_prepare(deck, {dir, caller, progress});
  omp_set_num_threads(caller);
  if (r.status.fault)
    throw std::runtime_error(path + ": sample preparation stopped: " + r.status.diagnostic());
  if (r.status.interrupted_by)
    throw Interrupted(path + ": " + signal_name(r.status.interrupted_by) + " while preparing the sample in " + dir +
                        " (a preparation has no checkpoint: the next run prepares it again)",
                      r.status.interrupted_by);
  try
  {
    prune_sample_cache(sample_cache_dir(path), cached_builds, cache_grace);
  }
  catch (const std::exception &)
  {
    // Housekeeping only: a cache that could not be pruned serves as before.
  }
  return file;
}

SampleFile load_or_prepare_sample(const std::string &path, bool progress)
{
  const bool is_deck = path.size() > 4 && path.compare(path.size() - 4, 4, ".prm") == 0;
  const std::string file = is_deck ? cached_sample_file(path, {}, progress) : path;
  SampleFile sample = read_sample(file);
  check_test_cell(sample, file);
  return sample;
}
} // namespace demvv
