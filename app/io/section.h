// A vertical section of a sample, for a picture that needs no ParaView.
//
// The plane y = 0 holds the axis of demvv's cylinder cells (the z axis,
// through x = y = 0); a ball of radius R whose centre lies a distance |y|
// from it cuts the plane in a circle of radius sqrt(R^2 - |y|^2) about
// (x, z).  Drawn as circles, the cut shows the packing as the thesis's
// Figs. 5.2-5.3 show it in 3-D (the balls placed at half radius, grown),
// and, with the bonds that broke near the plane marked on it, where a
// sample cracked (Figs. 7.7, A.3).  Units: m.
#pragma once

#include "dem/particles.h"

#include <string>
#include <vector>

namespace demvv
{
struct SectionCircle
{
  double x = 0;      ///< m, the ball's centre across the plane
  double z = 0;      ///< m, the ball's centre along the axis
  double radius = 0; ///< m, of the circle the ball leaves on the plane
};

/// The balls the plane y = 0 cuts, in ball order.
std::vector<SectionCircle> vertical_section(const dem::ParticleStore &balls);

/// The columns of a section's CSV rows (x_m, z_m, section_radius_m), and
/// the sentence that says what they are, for the file's header.
const std::vector<std::string> &section_columns();
std::string section_note();
} // namespace demvv
