// ContactModel: the ball-ball contact law of a simulation, chosen by keyword
// from the registry (law_registry.cpp).
//
// The virtual call happens once per step; inside, LawModel<Law> runs the
// whole force pass (contacts resolved, each ball's resultant summed) with
// the law inlined.  Each contact writes only its own entries and each
// ball's sums keep one order (ball_forces.h), so results do not depend on
// the thread count.
//
// A model holds the law's parameters and per-step constants only.  Every
// contact's history, the law's own included (LawState), lives in the
// ContactTable, so it follows the entries through rebuilds and goes into
// snapshots and sample files with them.  A law with no state fields (the
// linear law) never touches the LawState array.
//
// Ball-wall contacts always use the linear law with the wall's own
// properties (walls.h): walls are steel platens, and the viscoelastic laws
// describe the bitumen between grains.
#pragma once

#include "dem/balanced_ranges.h"
#include "dem/ball_forces.h"
#include "dem/contact_lanes.h"
#include "dem/contact_resolve.h"
#include "dem/contacts.h"
#include "dem/law_burgers.h"
#include "dem/law_linear.h"
#include "dem/stability.h"

#include <omp.h>

#include <algorithm>
#include <memory>
#include <string_view>
#include <type_traits>
#include <vector>

namespace dem
{
/// Stability row terms of a ball-ball contact (stability.h) whose arms are
/// at most fi R_i and fj R_j.
DEM_HOT_INLINE StabilityTerms contact_stability_terms(const ParticleStore &p, Index i, Index j, double kn, double ks,
                                                      double fi, double fj)
{
  const double sbi = fi * p.sqrt_shear_mobility[i], sbj = fj * p.sqrt_shear_mobility[j];
  const double sqrt_ww = p.sqrt_inv_mass[i] * p.sqrt_inv_mass[j], sqrt_bb = sbi * sbj;
  return {stability_row_term(kn, ks, p.inv_mass[i], sbi * sbi, sqrt_ww, sqrt_bb),
          stability_row_term(kn, ks, p.inv_mass[j], sbj * sbj, sqrt_ww, sqrt_bb)};
}

class ContactModel
{
public:
  virtual ~ContactModel() = default;
  virtual std::string_view name() const = 0;

  /// The force pass of a step (ball_forces.h): resolves every entry of
  /// the table at the current positions (dt is the step that produced the
  /// displacement since the last pass) and sums each ball's resultant
  /// force, torque and stability row bound into `balls`.  Appends the bonds
  /// that broke, in increasing entry order, to `breaks`; returns the largest
  /// row bound [1/s^2].
  virtual double resolve_and_sum(ContactTable &table, const BallForces &balls, std::vector<BrokenBond> &breaks) = 0;

  /// Frees the force pass's per-contact scratch (the next pass makes it
  /// anew), so that a neighbour rebuild never holds it beside its own.
  virtual void release_scratch() = 0;

  /// Whether the law keeps history of its own in the table's LawState slots.
  virtual bool keeps_law_state() const = 0;
  /// Whether this build can resolve the law's ordinary contacts eight at a
  /// time (contact_lanes.h: the linear law, on a CPU with AVX-512).
  virtual bool has_lanes() const = 0;

  /// Whether the energy ledger books every dissipation of the law (energy.h):
  /// a law with history of its own (the Burger's dashpots) dissipates
  /// energy that no ledger term holds, so its residual is that dissipation.
  virtual bool books_every_dissipation() const = 0;

  /// Elastic energy stored in all ball-ball contacts [J].
  virtual double stored_energy(const ContactTable &table) const = 0;

  /// Tangent normal and shear stiffness of a contact with these pair
  /// constants [N/m] (kn, ks of the result; friction unused), as the
  /// stability bound sees them.
  virtual ContactParams tangent_stiffness(const ContactParams &pair) const = 0;

  /// Recomputes every contact's compressive stability terms (after the
  /// table or the balls' masses changed).
  void update_stability_terms(const ParticleStore &p, ContactTable &table) const
  {
    for (Contact &c : table.entries())
    {
      const ContactParams k = tangent_stiffness(table.params(c));
      c.stability = contact_stability_terms(p, c.first, c.second, k.kn, k.ks, 1.0, 1.0);
    }
  }
};

/// Geometry of the ball-ball contact (i, j) at the current positions.
DEM_HOT_INLINE ContactGeometry sphere_sphere(const ParticleStore &p, Index i, Index j)
{
  ContactGeometry g;
  const Vec3 d = p.position[j] - p.position[i];
  const double dist = d.norm();
  g.normal = dist > 0 ? Vec3(d * (1.0 / dist)) : Vec3::UnitX();
  g.overlap = p.radius[i] + p.radius[j] - dist;
  g.arm_first = p.radius[i] - 0.5 * g.overlap;
  g.arm_second = p.radius[j] - 0.5 * g.overlap;
  g.velocity_difference = p.velocity[j] - p.velocity[i];
  g.spin_first = p.spin[i];
  g.spin_second = p.spin[j];
  return g;
}

template <class Law>
class LawModel final : public ContactModel
{
public:
  explicit LawModel(Law law) : law_(std::move(law)) {}

  std::string_view name() const override { return Law::keyword; }
  const Law &law() const { return law_; }

  // The pass is one parallel region of two loops.  The first resolves
  // every contact (each by one thread, each writing only its own entries)
  // and leaves its loads on both balls in a 72-byte record; after the
  // barrier, the second sums each ball's records, first the contacts where
  // it is first, then those where it is second (via the table's second
  // list), then its walls (ball_forces.h).  The sums keep that order, so
  // results do not depend on the thread count.  Each loop's items are cut
  // into one contiguous range per thread, the cuts moved from pass to pass
  // towards equal times (balanced_ranges.h): the entries' here, the balls'
  // by the step, whose integration advances the same ranges (BallForces).
  // Breaks and energies to retire are collected per range, so that ranges
  // in order are entries in order.
  //
  // Each loop reads at one scattered index that the hardware prefetcher
  // cannot follow: the second ball's motion (the entries run in first-ball
  // order) and the records of the second list.  Where the second ball or
  // the contact belongs to the other thread, the line comes from the other
  // core: 400-550 ns there and back on a virtual machine whose two cores sit
  // on different chiplets (bench/core_round_trip.cpp), 150-200 ns on one.
  // Both loops ask for those lines some items ahead; on the identical-work
  // scene this made two threads about a tenth faster where the cores were
  // far apart and one thread no slower (BENCHMARKS.md, "Cores far apart").
  //
  // The linear law resolves its ordinary entries eight at a time where the
  // CPU has the instructions and the run asks for it (contact_lanes.h,
  // SimulationSettings::contacts_in_lanes); which entries the blocks
  // resolve depends on each entry alone, so the ranges may cut anywhere.
  double resolve_and_sum(ContactTable &table, const BallForces &balls, std::vector<BrokenBond> &breaks) override
  {
    const ParticleStore &p = balls.particles;
    Contact *const contacts = table.entries().data();
    const ContactParams *const constants = table.distinct_params().data();
    LawState *const states = table.law_states().data();
    const std::vector<EntryIndex> &second_list = table.second_list();
    loads_.resize(table.size());
    PairLoad *const loads = loads_.data();
    const double dt = balls.dt;
    law_.prepare(dt);
    const int ranges = omp_get_max_threads();
    contact_ranges_.prepare(table.size(), ranges);
    balls.ranges.prepare(static_cast<std::size_t>(p.size()), ranges);
    events_.resize(static_cast<std::size_t>(ranges));
    double largest = 0;
#pragma omp parallel reduction(max : largest)
    {
      const int team = omp_get_num_threads();
      for (int r = omp_get_thread_num(); r < ranges; r += team)
      {
        PassEvents &events = events_[static_cast<std::size_t>(r)];
        events.broken.clear();
        events.released.clear();
        const double start = omp_get_wtime();
        const std::size_t first_entry = contact_ranges_.begin(r), last_entry = contact_ranges_.end(r);
        if (lanes_built && balls.in_lanes)
          resolve_in_lanes(p, contacts, constants, first_entry, last_entry, dt, loads, events);
        else
          for (std::size_t c = first_entry; c < last_entry; ++c)
          {
            if (c + entries_ahead < last_entry)
              prefetch_motion(p, contacts[c + entries_ahead].second);
            loads[c] = resolve_pair(p, contacts[c], constants[contacts[c].constants], states, c, dt, events);
          }
        contact_ranges_.record(r, omp_get_wtime() - start);
      }
#pragma omp barrier
      for (int r = omp_get_thread_num(); r < ranges; r += team)
      {
        const double start = omp_get_wtime();
        const auto last_ball = static_cast<Index>(balls.ranges.end(r));
        for (auto b = static_cast<Index>(balls.ranges.begin(r)); b < last_ball; ++b)
        {
          double f[3], t[3] = {0, 0, 0};
          balls.weight(b, f);
          double bound = 0;
          const std::size_t end = table.first_begin(b + 1);
          for (std::size_t c = table.first_begin(b); c < end; ++c)
          {
            const PairLoad &load = loads[c];
            const double arm = p.radius[b] - 0.5 * load.overlap;
            for (int d = 0; d < 3; ++d)
            {
              f[d] -= load.force[d];
              t[d] -= arm * load.lever[d];
            }
            bound += load.bound_first;
          }
          const std::size_t last = table.second_begin(b + 1);
          for (std::size_t k = table.second_begin(b); k < last; ++k)
          {
            if (k + records_ahead < second_list.size())
              prefetch_record(loads[second_list[k + records_ahead]]);
            const PairLoad &load = loads[second_list[k]];
            const double arm = p.radius[b] - 0.5 * load.overlap;
            for (int d = 0; d < 3; ++d)
            {
              f[d] += load.force[d];
              t[d] -= arm * load.lever[d];
            }
            bound += load.bound_second;
          }
          largest = std::max(largest, balls.finish(b, f, t, bound));
        }
        balls.ranges.record(r, omp_get_wtime() - start);
      }
    }
    contact_ranges_.rebalance();
    // Each range's entries ascend, and the ranges too: this is entry order
    // on any thread count.
    for (const PassEvents &events : events_)
    {
      breaks.insert(breaks.end(), events.broken.begin(), events.broken.end());
      for (std::size_t c : events.released)
        table.retire_energies(c);
    }
    std::sort(breaks.begin(), breaks.end(),
              [](const BrokenBond &a, const BrokenBond &b) { return a.contact < b.contact; });
    return largest;
  }

  void release_scratch() override { std::vector<PairLoad>().swap(loads_); }

  bool keeps_law_state() const override { return stateful; }
  bool has_lanes() const override { return lanes_built; }

  bool books_every_dissipation() const override { return !stateful; }

  double stored_energy(const ContactTable &table) const override
  {
    double e = 0;
    for (std::size_t c = 0; c < table.size(); ++c)
    {
      const ContactState &s = table[c].state;
      if (s.touching())
        e +=
          law_.stored_energy(table.params(table[c]), s.normal_force, s.shear_force, history_of(table.law_states(), c));
    }
    return e;
  }

  ContactParams tangent_stiffness(const ContactParams &pair) const override
  {
    return {law_.normal_stiffness(pair), law_.shear_stiffness(pair), 0};
  }

private:
  /// What a contact gives its two balls at this step: the force F on the
  /// second [N] (the first gets -F), the torques' lever n x F_s [N], the
  /// overlap U [m] that gives each ball its arm R - U/2 (T = -arm lever,
  /// the arm computed as the geometry computes it, so to the bit), and the
  /// stability row terms [1/s^2]; all zero when the contact carries none.
  struct PairLoad
  {
    double force[3];
    double lever[3];
    double overlap;
    double bound_first, bound_second;
  };

  /// What a range of the pass collects: bonds broken, and the
  /// entries that stopped carrying force with energy booked (friction work,
  /// a bond's released energy), to be moved to the retired totals.
  struct PassEvents
  {
    std::vector<BrokenBond> broken;
    std::vector<std::size_t> released;
    LaneResults lanes; ///< the range's blocks' results (kept off the stack)
  };

  /// How far ahead the pass asks for the lines of the second ball's motion
  /// (entries) and of the second list's records: about one cross-core round
  /// trip of work at 20-30 ns an entry (the scene's pass on one thread).
  static constexpr std::size_t entries_ahead = 16, records_ahead = 8;

  /// The lines of a ball's position, velocity and spin.
  static DEM_HOT_INLINE void prefetch_motion(const ParticleStore &p, Index ball)
  {
    __builtin_prefetch(&p.position[ball]);
    __builtin_prefetch(&p.velocity[ball]);
    __builtin_prefetch(&p.spin[ball]);
  }

  /// Both lines a 72-byte record may span.
  static DEM_HOT_INLINE void prefetch_record(const PairLoad &load)
  {
    __builtin_prefetch(&load);
    __builtin_prefetch(reinterpret_cast<const char *>(&load) + 64);
  }

  /// Resolves entries [begin, end): the ordinary candidates (unbonded,
  /// touching at the last pass) eight at a time (contact_lanes.h), as they
  /// gather, every other entry at once, one by one; a candidate that the
  /// block does not resolve goes to the general resolver after it.
  DEM_HOT_INLINE void resolve_in_lanes(const ParticleStore &p, Contact *contacts, const ContactParams *constants,
                                       std::size_t begin, std::size_t end, double dt, PairLoad *loads,
                                       PassEvents &events)
  {
#if defined(__AVX512F__)
    if constexpr (lanes_built) // the linear law's: no other law is ever resolved here
    {
      LaneResults &lane = events.lanes;
      std::size_t queued[8];
      int count = 0;
      bool deferred_general = false;
      const auto resolve_queued = [&]
      {
        const __mmask8 resolved = linear_block(p, constants, contacts, queued, count, dt, lane);
        for (int l = 0; l < count; ++l)
        {
          const std::size_t c = queued[l];
          if ((resolved >> l) & 1)
          {
            lane.commit(l, contacts[c].state);
            loads[c] = {{lane.force_x[l], lane.force_y[l], lane.force_z[l]},
                        {lane.lever_x[l], lane.lever_y[l], lane.lever_z[l]},
                        lane.overlap[l],
                        lane.bound_first[l],
                        lane.bound_second[l]};
          }
          else
          {
            loads[c] = resolve_pair(p, contacts[c], constants[contacts[c].constants], nullptr, c, dt, events);
            deferred_general = true;
          }
        }
        count = 0;
      };
      for (std::size_t c = begin; c < end; ++c)
      {
        if (c + entries_ahead < end)
          prefetch_motion(p, contacts[c + entries_ahead].second);
        const Contact &k = contacts[c];
        if (lane_candidate(k))
        {
          queued[count++] = c;
          if (count == 8)
            resolve_queued();
        }
        else
          loads[c] = resolve_pair(p, contacts[c], constants[k.constants], nullptr, c, dt, events);
      }
      if (count > 0)
        resolve_queued();
      // A deferred candidate's energies may have been released after a later
      // entry's: the ledger retires them in entry order.
      if (deferred_general)
        std::sort(events.released.begin(), events.released.end());
      return;
    }
#endif
    (void)p, (void)contacts, (void)constants, (void)begin, (void)end, (void)dt, (void)loads, (void)events;
  }

  /// Resolves contact c (entry k, pair constants `pair`) at this step and
  /// returns its loads.
  DEM_HOT_INLINE PairLoad resolve_pair(const ParticleStore &p, Contact &k, const ContactParams &pair, LawState *states,
                                       std::size_t c, double dt, PassEvents &events)
  {
    const Index i = k.first, j = k.second;
    if (!k.bonded && !k.state.touching())
    {
      // Fast exit for candidates that are not touching.
      const double reach = p.radius[i] + p.radius[j];
      if ((p.position[j] - p.position[i]).squaredNorm() >= reach * reach)
        return {};
    }
    const ContactGeometry g = sphere_sphere(p, i, j);
    typename Law::History history{};
    if constexpr (stateful)
      history = Law::load(states[c]);
    const ResolvedContact r = resolve_contact(law_, pair, k.bonded, k.bond, k.state, history, g, dt);
    if constexpr (stateful)
      Law::store(history, states[c]);
    if (r.broke != BreakMode::none)
      events.broken.push_back({c, r.broke, r.trial});
    if (!r.touching)
    {
      // Its energies leave the entry now, at a step the motion decides, not
      // when a neighbour rebuild (whose steps follow the skin, or a resume)
      // drops it: the ledger's sums are then grouped alike in every run.
      if (k.state.friction_work != 0 || k.state.bond_energy != 0)
        events.released.push_back(c);
      return {};
    }
    const Vec3 lever = cross(g.normal, r.shear);
    // In compression the arms are at most the radii and the precomputed
    // terms hold; a bonded pair in tension has longer arms.
    const StabilityTerms terms = g.overlap < 0 ? tension_terms(p, k, pair) : k.stability;
    return {
      {r.force.x(), r.force.y(), r.force.z()}, {lever.x(), lever.y(), lever.z()}, g.overlap, terms.first, terms.second};
  }

  /// Stability row terms of a touching contact in tension (arms longer
  /// than the radii), from its state at this step.
  StabilityTerms tension_terms(const ParticleStore &p, const Contact &k, const ContactParams &pair) const
  {
    const Index i = k.first, j = k.second;
    const double overlap = k.state.overlap;
    return contact_stability_terms(p, i, j, law_.normal_stiffness(pair), law_.shear_stiffness(pair),
                                   arm_factor(p.radius[i] - 0.5 * overlap, p.inv_radius[i]),
                                   arm_factor(p.radius[j] - 0.5 * overlap, p.inv_radius[j]));
  }

  static constexpr bool stateful = !Law::state_fields.empty();
  /// Whether this law's entries can be resolved in blocks of eight.
  static constexpr bool lanes_built = contact_lanes && std::is_same_v<Law, LinearLaw>;

  /// The law history of entry c (a law without one has no slots to read).
  static typename Law::History history_of(const std::vector<LawState> &states, std::size_t c)
  {
    if constexpr (stateful)
      return Law::load(states[c]);
    else
      return {};
  }
  static_assert(Law::state_fields.size() <= LawState::capacity, "a law's history must fit a LawState slot");

  Law law_;
  std::vector<PairLoad> loads_;    ///< per entry, rewritten by every pass
  std::vector<PassEvents> events_; ///< per range, reused from step to step
  BalancedRanges contact_ranges_;  ///< the entries, one range per thread
};

/// The registry: one row per law keyword (law_registry.cpp).
struct LawEntry
{
  std::string_view keyword;
  std::unique_ptr<ContactModel> (*make)(const LawParameters &);
  std::string_view summary;
  std::vector<std::string_view> state_fields; ///< names (with units) of the law's LawState values, in order
  std::vector<LawConstant> deck_constants;    ///< what a deck sets for this law
};

const std::vector<LawEntry> &law_registry();
/// The registry row of a keyword, or nullptr if the keyword is unknown.
const LawEntry *find_law(std::string_view keyword);
/// The model for a keyword, or nullptr if the keyword is unknown.
std::unique_ptr<ContactModel> make_contact_model(std::string_view keyword, const LawParameters &p);
} // namespace dem
