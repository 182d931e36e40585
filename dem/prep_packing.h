// Numerical sample preparation (thesis ch. 5).
//
// The thesis's procedure, stage by stage, each reported with its figures:
//
//   1. cell: platens and a cylinder of diameter D and height H = aspect D;
//      N from eq. 5.1, N = 3 V (1 - n) / (4 pi R^3), for a target porosity,
//      or N given and the cell sized to hold it at that porosity;
//   2. generate: balls at half their final radius placed at random without
//      overlap (seeded), then grown to the final radius in small steps, each
//      followed by relaxation;
//   3. equilibrate with frictionless balls and walls; where a confining
//      stress is asked for (the 0.1 MPa compaction stage of §6.1) the three
//      walls are servo-controlled to it (eq. 3.12-3.16);
//   4. while the network is loaded (at the servo stress), grow balls with
//      fewer than four contacts (walls count; a contact is a pair within the
//      bond touch tolerance) in steps of 0.1 %, re-settling in between, by
//      at most a fraction (default 1 %) of their radius;
//   5. reduce all radii slightly and re-equilibrate until the isotropic
//      (mean) stress is below the target (default 1 kPa, §5.3.2): the
//      radius scale is found by secant steps on the stress;
//   6. bond every contact (friction restored), remove the lateral wall and
//      settle; the locked-in forces are reported against the mean contact
//      force before bonding (§5.3.4).
//
// Equilibrium means an unbalanced-force ratio below a tolerance; each stage
// has a cycle budget and says whether it was met.  Measures: solid fraction
// of the whole cell, porosity and coordination in two measurement spheres
// (§5.4.1), mean coordination, the least number of contacts of a ball, the
// fabric tensor's deviatoric part, the mean stress (Love-Weber, over the
// cell volume).
#pragma once

#include "dem/bonds.h"
#include "dem/simulation.h"
#include "dem/spatial_bands.h"
#include "dem/specimen.h"

#include <cstdint>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace dem
{
struct PackingSettings
{
  long particles = 0;                  ///< N; 0: from eq. 5.1 with the cell diameter and height
  double radius = 0.885e-3;            ///< m, final radius
  double diameter = 0;                 ///< m, cell diameter when particles == 0
  double height = 0;                   ///< m, cell height when particles == 0
  double aspect = 1.0;                 ///< H / D when particles > 0
  double target_solid_fraction = 0.64; ///< 1 - n of eq. 5.1 (the servo stage sets the final density)
  BallSpec ball;                       ///< density, kn, ks, friction of every ball
  WallProps walls;                     ///< kn, ks of the cell walls (frictionless during preparation)
  std::uint64_t seed = 1;
  int growth_stages = 40;          ///< radius growth from R/2 to R
  long growth_cycles = 100;        ///< relaxation cycles per growth stage
  double servo_stress = 1e5;       ///< Pa, 0: no servo stage (thesis §6.1: 0.1 MPa)
  double stress_target = 1e3;      ///< Pa, mean stress after radius reduction
  double equilibrium_ratio = 1e-3; ///< unbalanced-force ratio that counts as equilibrium
  long max_cycles = 200000;        ///< cycle budget of each equilibrium stage
  int min_contacts = 4;            ///< contacts every ball should have before bonding
  double max_expansion = 0.01;     ///< largest growth of a ball with too few contacts
  BondSettings bonds;
  bool bond = true; ///< install bonds (stage 6)
  double local_damping = 0.7;
};

/// One stage's figures, for the log and the sample file.
struct StageReport
{
  std::string name;
  long cycles = 0;
  bool converged = false;
  double mean_stress = 0; ///< Pa
  double unbalanced_ratio = 0;
  double solid_fraction = 0; ///< balls / cell volume
  double coordination = 0;   ///< ball-ball, 2 Nc / N
};

/// One step of the radius reduction (thesis Fig. 5.5): the radii's relative
/// change from the packed sample and the mean stress once settled there.
struct RadiusReductionStep
{
  double radius_change = 0; ///< relative, negative: reduced
  double mean_stress = 0;   ///< Pa
};

struct PackingReport
{
  long particles = 0;
  double cell_diameter = 0, cell_height = 0; ///< m, final cell
  std::vector<StageReport> stages;
  double radius_change = 0;                          ///< relative change of the radii in stage 4 (negative: reduced)
  std::vector<RadiusReductionStep> radius_reduction; ///< stage 4 step by step, from no change
  double solid_fraction_cost = 0;                    ///< solid fraction lost by stage 4
  double stress_before_bonding = 0;                  ///< Pa, mean stress after stages 4-5
  long rattlers_before = 0;                          ///< balls below min_contacts before the expansion stage
  long rattlers_after = 0;                           ///< ... at bonding (0 if the target was met)
  double coordination_before_bonding = 0;            ///< ball-ball, force-carrying
  double largest_expansion = 0;                      ///< relative growth given to a ball in stage 5
  double solid_fraction = 0;                         ///< final, whole cell
  double sphere_porosity[2] = {0, 0};
  double sphere_coordination[2] = {0, 0};
  double coordination = 0;         ///< final, ball-ball
  int fewest_contacts = 0;         ///< final, ball-ball and ball-wall, before the lateral wall goes
  double fabric_deviator_norm = 0; ///< |F - I/3| (Frobenius) of the final fabric tensor
  double fabric_eigenvalues[3] = {0, 0, 0};
  BondReport bonds;
  double mean_contact_force_before = 0; ///< N, before bonding
  BandMeans force_bands;                ///< compressive normal forces by band before bonding (thesis Fig. 5.6)
  double locked_in_mean_force = 0;      ///< N, mean |F| after settling without the lateral wall
  double locked_in_max_force = 0;       ///< N
  double wall_seconds = 0;
};

/// Bad preparation input (impossible packing, cell too small): names what.
class PackingError : public std::runtime_error
{
public:
  PackingError(std::string setting, std::string what) : std::runtime_error(std::move(what)), setting(std::move(setting))
  {
  }
  std::string setting; ///< which setting is at fault
};

/// A preparation ended early because its caller asked it to stop (a signal).
class PreparationStopped : public std::runtime_error
{
public:
  using std::runtime_error::runtime_error;
};

struct PreparedSample
{
  std::unique_ptr<Simulation> sim; ///< lateral wall removed, bonded, settled
  Specimen cell;                   ///< wall indices and final size (its balls are in sim)
  PackingReport report;
};

/// What a preparation shows as it goes: the stage's name and the
/// simulation as that stage left it (the balls placed at R/2, Fig. 5.2;
/// grown, Fig. 5.3; after the servo, each radius reduction and the
/// release).
using StageView = std::function<void(const Simulation &, const std::string &)>;

/// Runs the whole procedure.  `log` receives one line per stage;
/// `stop_requested`, when given, is asked every 128 steps whether to stop
/// (then PreparationStopped is thrown); `at_stage`, when given, sees each
/// stage's end.
PreparedSample prepare_sample(const PackingSettings &settings, const std::function<void(const std::string &)> &log = {},
                              const std::function<bool()> &stop_requested = {}, const StageView &at_stage = {});

/// The cell geometry of eq. 5.1 for the settings: (N, D, H); throws
/// PackingError for an impossible request.
/// The fewest balls a preparation packs: below this every ball touches or
/// neighbours a wall (a 50-ball cell is about 3.7 ball diameters across), so
/// coordination, solid fraction and the measurement spheres describe the
/// wall layer, not a packing.  One ball prepared for 2.2 million steps and
/// exited 0 with coordination 0.
constexpr long min_packing_balls = 50;

struct CellSize
{
  long particles;
  double diameter, height;
};
CellSize cell_size(const PackingSettings &settings);
} // namespace dem
