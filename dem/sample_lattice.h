// Regular lattice samples: the verification stand-in for a prepared packing.
//
// Simple cubic (spacing 2R, coordination 6, porosity 1 - pi/6) and face-
// centred cubic (cube edge 2 sqrt(2) R, coordination 12, porosity
// 1 - pi/(3 sqrt 2)) arrays of touching spheres.  They have closed-form
// porosity and coordination (check V11), which makes them
// legitimate verification samples; they are not the dense random packing of
// thesis chapter 5, and every run on one says so.
#pragma once

#include "dem/types.h"

#include <string_view>
#include <vector>

namespace dem
{
enum class Lattice
{
  simple_cubic,
  face_centred_cubic,
};

/// "sc" or "fcc"; false if the name is neither.
bool parse_lattice(std::string_view name, Lattice &out);
std::string_view lattice_name(Lattice l);
double lattice_porosity(Lattice l);
int lattice_coordination(Lattice l);

/// Centres of a lattice of touching spheres of radius r filling the box
/// [0, nx*a) x [0, ny*a) x [0, nz*a), a the cube edge.
std::vector<Vec3> lattice_box(Lattice l, double r, int nx, int ny, int nz);

/// A cylinder of lattice spheres, axis z, bottom of the lowest balls at z = 0.
struct LatticeCylinder
{
  std::vector<Vec3> centres;
  double radius = 0;   ///< m, ball radius
  double diameter = 0; ///< m, outer diameter of the sample (rim balls touch it)
  double height = 0;   ///< m, bottom to top of the sample (balls touch both ends)
};

/// Balls of the lattice whose whole sphere fits in a cylinder of the given
/// diameter and height.  std::length_error when its box has more sites than
/// a ball index counts (lattice_cylinder_sites).
LatticeCylinder lattice_cylinder(Lattice l, double ball_radius, double diameter, double height);

/// Sites of the box lattice_cylinder() lays out and keeps the cylinder's
/// balls from (about 4/pi times as many as it keeps, more for thin
/// samples), as a double so that a tiny radius cannot overflow: callers
/// check it against memory before building the cylinder.
double lattice_cylinder_sites(Lattice l, double ball_radius, double diameter, double height);
} // namespace dem
