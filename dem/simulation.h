// Simulation: one DEM model and its time loop (thesis §3.3.2, Fig. 3.8).
//
// A step is a short pipeline:
//
//   compute_forces()   rebuild neighbours if a ball moved more than skin/2,
//                      one force pass: resolve ball-ball contacts (law +
//                      bonds + slip) and sum each ball's resultant with
//                      walls and gravity (ball_forces.h); log bond breaks,
//                      choose the time step;
//   integrate()        centred differences with local damping (eq. 3.7-3.9),
//                      energy increments, blow-up checks, walls move.
//
// Between the two phases positions, forces and walls are all at the same
// time t, which is when measurements are taken (see Simulation::step).
//
// Time step: a safety fraction of the critical step bound of stability.h,
// re-evaluated every step from the contacts that carry force at that step;
// or a fixed step, refused (NumericalFault) when it exceeds the bound unless
// the caller allows unstable steps.  When the step changes, the velocity
// update uses the mean of the old and new steps, which keeps the scheme
// second order.
//
// Determinism: each contact is resolved by the thread that owns its first
// ball, each ball sums its loads in a fixed order (ball_forces.h) and every
// reduction is order-free (max, min, logical or) or serial, so results are
// identical for any thread count.
#pragma once

#include "dem/contact_model.h"
#include "dem/energy.h"
#include "dem/walls.h"

#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace dem
{
struct SimulationSettings
{
  Vec3 gravity = Vec3::Zero();      ///< m/s^2
  double local_damping = 0.7;       ///< -, PFC local damping coefficient alpha
  double time_step_safety = 0.8;    ///< -, fraction of the critical step bound
  double fixed_time_step = 0;       ///< s, > 0 fixes the step
  bool allow_unstable_step = false; ///< run a fixed step above the bound anyway
  double skin_fraction = 0.25;      ///< -, neighbour skin / largest radius (the widest, when adaptive)
  bool adaptive_skin = true;        ///< narrow the skin while balls move slowly (Simulation::skin_for_rebuild)
  /// Resolve the linear law's ordinary contacts eight at a time where the
  /// CPU has AVX-512 (contact_lanes.h).  Faster where most contacts are
  /// ordinary (an unbonded packing), slower where bonds break; the results
  /// differ from the one-by-one path in the last bits, so a run keeps one
  /// choice throughout (a scene without bonds turns it on).
  bool contacts_in_lanes = false;
};

struct BondBreak
{
  double time = 0; ///< s
  Index first = 0, second = 0;
  BreakMode mode = BreakMode::none;
  double normal_force = 0;   ///< N, trial normal force at the break
  double shear_force = 0;    ///< N, trial shear force magnitude at the break
  Vec3 point = Vec3::Zero(); ///< m, centre_line_point of the pair at the break
};

/// What the energy ledger (energy.h) of a stable run can show, each part a
/// multiple of the energy supplied S = initial + positive boundary and
/// gravity work.  None is a tolerance on accuracy: each is a margin of one
/// order of magnitude or more above what stable runs show (argued below,
/// measured on the recorded runs), and below what an unstable one reaches.
struct LedgerLimits
{
  /// Kinetic (its positive part) plus strain energy above this multiple of
  /// S.  Dissipation only removes energy, and a stable step holds the strain
  /// energy of an oscillating contact below E / (1 - (omega dt / 2)^2) for
  /// the scheme's invariant E (under 3 E at the default step safety, where
  /// omega dt <= 1.6): only an unstable integration creates ten times S.
  double runaway = 10;
  /// Local damping's cumulative dissipation below -this multiple of S.  Its
  /// booked work (force times mid-step velocity, exact for the kinetic
  /// energy) is non-negative unless a ball reverses within a step; runs of
  /// every recorded kind at the default step stay above -3e-2 S.  Damping
  /// that feeds the flip-flop mode (stability.h) gives back a fifth of S
  /// and more; so does a free oscillation stepped coarsely (omega dt of the
  /// damped mode above 1.3, e.g. an unloaded bonded pair at the default
  /// safety), which is stable but whose ledger no longer describes it.
  double negative_damping = 0.05;
  /// |residual| above this multiple of S, where the ledger is exact to
  /// second order: laws whose every dissipation it books
  /// (ContactModel::books_every_dissipation) and no local damping (whose
  /// force switches within steps: a first-order term, 7 % of S on a free
  /// damped pair at omega dt = 0.3).  Stable runs then close the balance to
  /// 5e-3 S; an unstable one misses by half of S.
  double residual = 0.25;
  /// Steps before the residual is held: the ledger starts with a term of
  /// the first half kick (O(F v dt), the work booked before any kinetic
  /// energy is measured), while S grows with the step count, so in the
  /// first steps the residual is of the order of S in any run (a third of
  /// S at step 2 of a pulled bond) and 5e-2 S at step 20 of a ramp.  A
  /// runaway within them is stopped by the runaway and motion checks.  Held
  /// from step 100 before, an undamped free pair meeting at the default
  /// step (rebound energy 143 % above the impact's) finished in 66 steps
  /// and passed; no run of the tests comes within the bound from step 20.
  long residual_from_step = 20;
};

/// A numerical fault: NaN, runaway motion, unstable fixed step.
class NumericalFault : public std::runtime_error
{
public:
  NumericalFault(long step, double time, Index particle, const std::string &what);
  long step;
  double time;
  Index particle; ///< -1 when no single ball is to blame
};

/// Energy bookkeeping of one ball (energy.h).
struct BallEnergy
{
  double boundary = 0, body = 0, damping = 0, kinetic = 0; ///< J
};

/// Everything beyond balls, walls and contacts that a run carries from step
/// to step; with them it makes a Snapshot from which a run continues
/// exactly as if it had never stopped.
struct SimulationClock
{
  double time = 0; ///< s
  long steps = 0;
  double last_time_step = 0; ///< s, the step that produced the current positions
  std::vector<BallEnergy> ball_energy;
  double initial_energy = 0; ///< J
  bool initial_recorded = false;
  double removed_wall_strain = 0, removed_wall_friction = 0; ///< J
  std::size_t broken_tension = 0, broken_shear = 0, broken_displacement = 0;
  RetiredContactEnergy retired;
};

/// The law state travels with the keyword of the law that wrote it: a run
/// continued with another law starts every contact's law state at rest
/// (slots of different laws mean different things).
struct Snapshot
{
  ParticleStore particles;
  std::vector<Wall> walls;
  std::vector<WallContact> wall_contacts; ///< increasing (wall, ball); only balls that touched a wall
  std::vector<ContactRecord> contacts;    ///< sorted by (first, second)
  std::string contact_law;                ///< keyword of the law of law_states (empty: none)
  std::vector<LawState> law_states;       ///< one per contact, or none (all at rest)
  SimulationClock clock;
};

class Simulation;

/// Memory a simulation of `particles` balls and `walls` walls needs [bytes],
/// estimated from the engine's own arrays: the ball arrays and per-ball
/// scratch, the wall histories (an index entry per wall and ball, and a
/// history per ball: a layer of balls on a floor has one each), the cell
/// list, and for each neighbour pair its candidate, contact entry, law
/// state, adjacency index and load record (the table is rebuilt in place:
/// no second copy).  A dense packing with the default skin has about 7
/// candidate pairs per ball; 8 are counted, and half again for vector
/// growth and the heap, so the estimate errs high: 4.4 kB per ball with
/// three walls, against 1.1-1.4 kB measured on the sc lattice bench (peak
/// resident memory, one rebuild, BENCHMARKS.md).  Doubles, so that absurd counts (1e13 balls) do not overflow: it
/// serves to refuse a run that cannot fit before allocating.
double estimated_memory_bytes(double particles, int walls);

/// Lower bound of the number of steps needed to simulate `duration` seconds
/// of `particles`: the largest step the simulation could choose is the fixed
/// step, or the safety fraction of the critical step of one contact with a
/// ball's own stiffness (contacts only make it smaller).  Infinite when the
/// step would be zero.
double least_steps(const ParticleStore &particles, const SimulationSettings &settings, double duration);

/// The ball whose lone contact sets that largest step (the largest own
/// stiffness over mass, NaN ignored); -1 for no balls.
Index stiffest_ball(const ParticleStore &particles);

/// What a protocol may do at a step's force time (see StepHooks).
struct ForceTimeAction
{
  bool measure_kinetic = false; ///< evaluate the kinetic energy at the force time (energy())
  bool stop = false;            ///< end here: the step is not integrated
};

/// The named points of a step where a protocol acts (a platen ramp, a
/// servo, a measurement), so that no driver splits the step by hand:
///
///   before_forces(sim)   walls are given their motion for this step;
///   compute_forces()     positions, forces and walls all at time t;
///   at_force_time(sim)   measure, or act on the forces (a servo reads the
///                        wall forces and sets the wall velocities);
///   integrate()          unless at_force_time asked to stop;
///   after_integration(sim)
class StepHooks
{
public:
  virtual ~StepHooks() = default;
  virtual void before_forces(Simulation & /*sim*/) {}
  virtual ForceTimeAction at_force_time(Simulation & /*sim*/) { return {}; }
  virtual void after_integration(Simulation & /*sim*/) {}
};

class Simulation
{
public:
  Simulation(ParticleStore particles, WallSet walls, std::unique_ptr<ContactModel> model, SimulationSettings settings);
  /// Continues a saved run (see Snapshot); the contacts' law states only
  /// when the snapshot's law is the model's.
  Simulation(Snapshot snapshot, std::unique_ptr<ContactModel> model, SimulationSettings settings);

  /// The state a run can be continued from, exactly.
  Snapshot snapshot() const;
  /// Continues from a saved state with this simulation's law and settings,
  /// exactly as if the run that saved it had never stopped.
  void restore(Snapshot snapshot);

  /// One full step.  Equivalent to compute_forces(); integrate(false).
  void step();
  /// One step with a protocol's hooks (StepHooks).  Returns false when a
  /// hook stopped the step at its force time (not integrated).
  bool step(StepHooks &hooks);
  void compute_forces();
  /// Advances by the step chosen in compute_forces().  With measure_kinetic
  /// the kinetic energy at the force time is evaluated (energy()).
  void integrate(bool measure_kinetic = false);

  double time() const { return time_; }
  long steps() const { return step_; }
  /// The step chosen by the last compute_forces() [s].
  double time_step() const { return dt_; }
  /// The critical step bound of the force-carrying contacts at the last
  /// compute_forces() [s]; infinite when no contact carries force.
  double critical_time_step() const { return dt_critical_; }
  /// Ball that sets the critical step bound (-1 if no contact carries force).
  Index critical_particle() const;

  ParticleStore &particles() { return particles_; }
  const ParticleStore &particles() const { return particles_; }
  WallSet &walls() { return walls_; }
  const WallSet &walls() const { return walls_; }
  ContactTable &contacts() { return contacts_; }
  const ContactTable &contacts() const { return contacts_; }
  const ContactModel &model() const { return *model_; }
  const NeighborList &neighbors() const { return neighbors_; }
  /// Whether the pass resolves the law's ordinary contacts eight at a time:
  /// the settings ask for it and the law and the build can.
  bool contacts_in_lanes() const { return settings_.contacts_in_lanes && model_->has_lanes(); }
  SimulationSettings &settings() { return settings_; }
  const SimulationSettings &settings() const { return settings_; }

  /// Forces the neighbour list and contact table to be rebuilt before the
  /// next force computation (after radii or positions were edited).
  void invalidate_neighbors() { rebuild_requested_ = true; }
  /// Rebuilds the neighbour list and contact table now (e.g. before bonding).
  void refresh_contacts();

  /// Energy terms at the last force time.  Kinetic energy is current only
  /// after integrate(true).
  EnergyLedger energy() const;

  /// Holds the energy ledger to what a stable integration can produce
  /// (LedgerLimits); a breach stops the run with a NumericalFault naming
  /// the ball most to blame.  Call it after integrate(true).
  void check_energy_ledger(const LedgerLimits &limits) const;

  /// Stops the run (NumericalFault naming the ball) when a contact overlaps
  /// by more than `fraction` of the smaller radius (of the ball's radius at
  /// a wall): the linear spring is then far outside its meaning (half a
  /// radius is also what a sample or particle file may start with at most),
  /// the mark of a load the stiffness cannot carry or of balls pressed
  /// through one another.
  void check_contact_overlaps(double fraction) const;

  /// Force exerted by the balls on wall w at the last force time [N].
  Vec3 wall_force(WallIndex w) const;

  /// Removes (or restores) wall w, e.g. the lateral wall before a uniaxial
  /// test (thesis §5.3.4).
  void set_wall_enabled(WallIndex w, bool enabled);

  /// Bond breaks since the last call (oldest first).
  std::vector<BondBreak> take_breaks();
  std::size_t bonds_broken(BreakMode mode) const;

private:
  /// What the ball loop of a step found: the first ball that moved more
  /// than half its radius or spun to a non-finite rate (n if none), and
  /// whether any moved far enough to need a neighbour rebuild.
  struct BallAdvance
  {
    Index first_bad;
    bool moved;
  };
  /// The kick and drift of every ball with its energy ledger (eq. 3.7-3.9).
  template <bool damped, bool weighted, bool kinetic>
  BallAdvance advance_balls();
  void record_breaks();
  void choose_time_step();
  /// The neighbour skin for the build about to be made [m].
  double skin_for_rebuild() const;
  [[noreturn]] void fail(Index particle, const std::string &what) const;
  /// Strain energy stored in and friction work done by the contacts of wall w [J].
  std::pair<double, double> wall_energy(WallIndex w) const;

  ParticleStore particles_;
  WallSet walls_;
  std::unique_ptr<ContactModel> model_;
  SimulationSettings settings_;
  NeighborList neighbors_;
  ContactTable contacts_;

  double time_ = 0;
  long step_ = 0;
  long built_at_step_ = 0; ///< the step of the last neighbour build
  double dt_ = 0, dt_prev_ = 0, dt_critical_ = infinity;
  bool rebuild_requested_ = true;
  bool forces_current_ = false;

  // Per-ball scratch, sized once: no allocation inside the step.
  std::vector<double> row_bound_;       ///< 1/s^2, stability row bound of the contacts
  double lone_bound_max_ = 0;           ///< 1/s^2, largest row bound of one contact with a ball's own stiffness
  std::vector<double> wall_power_;      ///< W, sum over walls of F_wall->ball . v_wall
  std::vector<WallIndex> active_walls_; ///< enabled walls, refreshed each step
  BalancedRanges ball_ranges_;          ///< the balls, one range per thread, of the pass and the integration

  std::vector<BallEnergy> ball_energy_;
  double initial_energy_ = 0;
  double removed_wall_strain_ = 0, removed_wall_friction_ = 0;
  bool initial_recorded_ = false;

  std::vector<BrokenBond> broken_; ///< bonds broken by the last force pass
  std::vector<BondBreak> breaks_;
  std::size_t broken_tension_ = 0, broken_shear_ = 0, broken_displacement_ = 0;
  std::size_t &broken_count(BreakMode mode);
};
} // namespace dem
