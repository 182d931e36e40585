// Sample files: a prepared specimen saved so that many tests can start from
// it and any run can continue exactly where it stopped.
//
// Format (JSON, SI units, compression positive; version 2):
//   format, format_version, units, title, seed, contact_law (the keyword of
//               the law the sample was run with, dem/law_registry.cpp)
//   cell        {diameter_m, height_m, bottom, top, lateral}  wall indices (-1: none)
//   preparation the preparation report (stages, measures; see PackingReport)
//   provenance  who wrote it (demvv version, git SHA, deck hash, ...)
//   clock       time_s, steps, last_time_step_s and the energy ledger
//   walls       [{name, shape, point_m, direction, radius_m, velocity_mps,
//                 radial_velocity_mps, kn_npm, ks_npm, friction, enabled}]
//   balls       {columns, rows}: x_m y_m z_m radius_m density_kgpm3 kn_npm
//               ks_npm friction vx_mps vy_mps vz_mps wx_radps wy_radps wz_radps
//               hold_velocity hold_spin boundary_work_j body_work_j
//               damping_work_j kinetic_energy_j
//   contacts    {columns, rows}: first second kn_npm ks_npm friction bonded
//               normal_strength_n shear_strength_n break_distance_m (the
//               displacement criterion's centre distance, null when off;
//               not in version 1) touching normal_force_n
//               overlap_m nx ny nz shear_x_n shear_y_n shear_z_n
//               friction_work_j bond_energy_j, then the contact law's own
//               state (LawState, dem/contact.h): one column per name in
//               the law's state_fields, prefixed "law_"; for Burger's laws
//               law_reference_overlap_m law_element_normal_force_n
//               law_normal_kelvin_m law_shear_kelvin_{x,y,z}_m; none for
//               the linear law
//   wall_contacts {columns, rows}: wall ball + the contact columns above from
//               touching to bond_energy_j, for every (wall, ball) pair with
//               history (walls always use the linear law: no law state)
// Numbers are written in their shortest exact form, so reading a file gives
// back the same doubles: a run continued from a file matches the run that
// never stopped, Burger's elements included.
//
// Version 1 files (no law columns) still load, every law state at rest.
// The law state belongs to the law that wrote it: a test run with another
// law than contact_law starts every contact's law state at rest (dem::
// Simulation does this when it continues a Snapshot of another law), while
// apply_test_properties keeps it, so a test with the sample's own law
// continues its elements where the preparation left them.
#pragma once

#include "dem/prep_packing.h"
#include "dem/simulation.h"

#include <nlohmann/json.hpp>

#include <string>

namespace demvv
{
struct SampleFile
{
  dem::Snapshot snapshot;
  dem::Specimen cell; ///< wall indices and size; its particles/walls are in the snapshot
  /// The law the sample was run with.  Empty: the snapshot's (linear if it
  /// names none); when both name one they must agree.  Reading sets both.
  std::string contact_law;
  long long seed = 0;
  nlohmann::json preparation; ///< the report, as written
  nlohmann::json provenance;
  std::string title;
};

/// Gives every ball of a loaded sample the properties of `ball` (density,
/// kn, ks, friction; positions and radii kept), every contact the pair
/// constants that follow, the platens `platen`, and restarts the clock at
/// zero (keeping the last time step) for a new test.  Contact histories and
/// law states are kept (see the header note on tests of another law); the
/// friction work and bond energy they booked are the preparation's and are
/// zeroed with the clock, so the test's energy ledger starts at zero.
void apply_test_properties(SampleFile &sample, const dem::BallSpec &ball, const dem::WallProps &platen);

/// Writes a sample file atomically; returns the text written.
std::string write_sample(const std::string &path, const SampleFile &sample);

/// Reads a sample file.  Every field is checked on load: its type, its
/// range (finite numbers; radii, densities and stiffnesses > 0; flags 0 or
/// 1), and every cross-reference (cell and wall-contact wall indices name
/// walls of the right shape, contacts name two balls, sorted, each pair
/// once).  Any problem is the one-line DeckError naming the file, the field
/// ("balls.rows[5].radius_m"), its value and what was expected.  A file that
/// names no platens (a checkpoint) loads; check_test_cell() refuses it for a
/// test.
SampleFile read_sample(const std::string &path);

/// read_sample on a sample file's text already read from `path`.
SampleFile parse_sample(const std::string &text, const std::string &path);

/// Refuses (one-line DeckError naming `path`) a sample a uniaxial test
/// cannot run on: no platens, a cell without size, platens that do not
/// face each other across a positive gap (the strain would never grow), a
/// ball centre outside the platens or farther from the lateral wall's axis
/// than its radius (than the cell's diameter when the wall is removed), or
/// two balls that overlap by more than half the smaller radius (balls piled
/// on one point).
void check_test_cell(const SampleFile &sample, const std::string &path);

/// The preparation report as JSON.
nlohmann::json report_json(const dem::PackingReport &report);
} // namespace demvv
