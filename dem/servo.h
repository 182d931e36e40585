// Servo-controlled walls (thesis §3.3.4, eq. 3.12-3.16).
//
// Each step, a servo wall moves at
//   u' = G (sigma_measured - sigma_target),   G = alpha A / (k_n N_c dt),
// where A is the wall's area, N_c its number of contacts, k_n their mean
// normal stiffness and alpha < 1 a relaxation factor: the stress change one
// step can cause is at most alpha times the error.  Two safeguards keep the
// loop stable against the packing's delayed response: N_c is never taken
// below the number of balls that cover the wall, A / (2R)^2, and the error
// is limited to the target stress, so a wall moves at most by the overlap
// that carries the target per step (also when it touches nothing).
//
// Stresses are measured on the cylindrical cell of a Specimen: the platens
// carry force / (pi r^2), the lateral wall radial force / (2 pi r H); all
// compression positive.  Moving a plane "back" means along -normal; moving
// the cylinder back means expanding it.
#pragma once

#include "dem/specimen.h"

namespace dem
{
class Simulation;

struct ServoSettings
{
  double target_stress = 0;        ///< Pa, compression positive
  double relaxation = 0.5;         ///< alpha of eq. 3.15, in (0, 1)
  double max_step_fraction = 0.01; ///< largest wall move per step, fraction of the smallest ball radius
  /// Integral action of a platen servo that tracks a moving target (creep):
  /// each step adds this fraction of the proportional speed to a held
  /// speed, which removes the lag a proportional servo keeps behind a
  /// target that needs a steady platen speed.  0: proportional only (the
  /// preparation servo).  With alpha = 0.5 and 0.05 the loop's discrete
  /// eigenvalues are real and inside the unit circle.
  double integral = 0;
};

/// Stress on each wall of the cylindrical cell [Pa], compression positive.
struct CellStress
{
  double bottom = 0, top = 0, lateral = 0;
  double mean() const { return (bottom + top + 2 * lateral) / 4.0; }
  double largest_error(double target) const;
};

/// Measures the wall stresses of a specimen's cell (its lateral wall must exist).
CellStress cell_stress(const Simulation &sim, const Specimen &cell);

/// Sets the velocities of the platens and the lateral wall for the coming
/// step so that each approaches the target stress (eq. 3.12-3.16); returns
/// the stresses measured.
CellStress servo_cell(Simulation &sim, const Specimen &cell, const ServoSettings &settings);

/// Speed at which a platen moves towards the balls (along its direction) so
/// that its nominal stress `measured` approaches `target` (eq. 3.12-3.16,
/// with the safeguards above) [m/s]; area is the nominal platen area.
double servo_platen_speed(const Simulation &sim, WallIndex platen, double area, double measured, double target,
                          const ServoSettings &settings);

/// Stops every wall of the cell.
void stop_walls(Simulation &sim, const Specimen &cell);
} // namespace dem
