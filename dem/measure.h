// Measurements on a DEM sample (thesis §5.4).
//
//  - Measurement spheres (§5.4.1): porosity with overlap correction
//      n = 1 - V_ball / V_sphere,  V_ball = sum_p V(p in sphere) - V_overlap
//    (eq. 5.2-5.3), where V(p in sphere) is the exact sphere-sphere
//    intersection volume and V_overlap sums the lens volumes of touching
//    pairs whose contact point lies in the sphere; coordination number
//    C_n = sum n_c / N_b over balls whose centres lie in the sphere (eq. 5.4).
//  - Platens (§5.4.2): axial strain from the platen separation, nominal
//    stress = force on the platen / initial area.
//  - Radial gauges (§5.4.3): balls on the circumference within a central band
//    of thickness t * H; radial strain is their mean relative change of
//    distance from the axis.
//  - Unbalanced-force ratio: mean resultant on free balls / mean contact force.
//  - Average stress (Love-Weber): sigma = (1/V) sum_c F_c (x) l_c over the
//    force-carrying contacts, F_c the force on the second entity and l_c the
//    branch vector from the first to the second (for a wall contact, from
//    the contact point to the ball centre); compression positive.
//  - Fabric tensor: (1/N_c) sum_c n_c (x) n_c over ball-ball contacts; its
//    deviatoric part is zero for an isotropic packing.
//
// Sign convention: compression positive.  Axial strain
// (H0 - H)/H0 > 0 when shortening; radial strain -(r - r0)/r0, so a bulging
// sample has negative radial strain and Poisson's ratio is -eps_r / eps_a.
#pragma once

#include "dem/simulation.h"

#include <vector>

namespace dem
{
/// Volume of the intersection of two spheres of radii a, b at centre distance d [m^3].
double sphere_intersection_volume(double a, double b, double d);

struct MeasurementSphere
{
  Vec3 centre = Vec3::Zero(); ///< m
  double radius = 0;          ///< m
};

/// Porosity inside a measurement sphere, overlaps corrected (eq. 5.2-5.3).
double porosity(const ParticleStore &particles, const ContactTable &contacts, const MeasurementSphere &sphere);

/// Mean number of touching ball-ball contacts of the balls whose centres lie
/// in the sphere (eq. 5.4); 0 if none.
double coordination_number(const ParticleStore &particles, const ContactTable &contacts,
                           const MeasurementSphere &sphere);

/// 2 x touching contacts / balls, over the whole sample.
double coordination_number(const ParticleStore &particles, const ContactTable &contacts);

/// The magnitudes |F| of the touching ball-ball contacts' forces (normal and
/// shear together) [N]: mean and largest over `touching` contacts (0 when none).
struct ContactForceStatistics
{
  double mean = 0, largest = 0;
  std::size_t touching = 0;
};
ContactForceStatistics contact_force_statistics(const ContactTable &contacts);

/// Mean |resultant force| on free balls divided by the mean contact force
/// magnitude (0 when no contact carries force).
double unbalanced_force_ratio(const ParticleStore &particles, const ContactTable &contacts);

using Tensor3 = Eigen::Matrix3d;

/// Average stress tensor over a volume V [Pa], compression positive,
/// symmetrised; includes ball-wall contacts.
Tensor3 average_stress(const Simulation &sim, double volume);

/// Mean of the diagonal of average_stress [Pa].
double mean_stress(const Simulation &sim, double volume);

/// Fabric tensor of the ball-ball contacts that carry force (identity/3 if none).
Tensor3 fabric_tensor(const ParticleStore &particles, const ContactTable &contacts);

/// Contacts of each ball, ball-ball and ball-wall, that carry force.
std::vector<int> contacts_per_ball(const Simulation &sim);

/// Radial-strain gauges on the circumference of a cylindrical sample.
class RadialGauges
{
public:
  /// Selects the balls within one diameter of the outer radius whose
  /// centres lie in the central band |z - z_mid| <= thickness * height / 2
  /// (axis along z through axis_point).
  RadialGauges(const ParticleStore &particles, const Vec3 &axis_point, double z_mid, double height, double thickness);

  /// Mean -(r - r0)/r0 over the gauges (compression positive).
  double radial_strain(const ParticleStore &particles) const;
  std::size_t size() const { return members_.size(); }
  const std::vector<Index> &members() const { return members_; }

private:
  Vec3 axis_point_;
  std::vector<Index> members_;
  std::vector<double> initial_radius_;
};
} // namespace dem
