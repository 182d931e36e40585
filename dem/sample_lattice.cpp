#include "dem/sample_lattice.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace dem
{
bool parse_lattice(std::string_view name, Lattice &out)
{
  if (name == "sc")
    out = Lattice::simple_cubic;
  else if (name == "fcc")
    out = Lattice::face_centred_cubic;
  else
    return false;
  return true;
}

std::string_view lattice_name(Lattice l) { return l == Lattice::simple_cubic ? "sc" : "fcc"; }

double lattice_porosity(Lattice l)
{
  return l == Lattice::simple_cubic ? 1.0 - pi / 6.0 : 1.0 - pi / (3.0 * std::sqrt(2.0));
}

int lattice_coordination(Lattice l) { return l == Lattice::simple_cubic ? 6 : 12; }

std::vector<Vec3> lattice_box(Lattice l, double r, int nx, int ny, int nz)
{
  std::vector<Vec3> basis;
  double a;
  if (l == Lattice::simple_cubic)
  {
    a = 2 * r;
    basis = {Vec3(0, 0, 0)};
  }
  else
  {
    a = 2 * std::sqrt(2.0) * r;
    basis = {Vec3(0, 0, 0), Vec3(0.5, 0.5, 0), Vec3(0.5, 0, 0.5), Vec3(0, 0.5, 0.5)};
  }
  std::vector<Vec3> out;
  out.reserve(basis.size() * nx * ny * nz);
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        for (const Vec3 &b : basis)
          out.push_back(a * (Vec3(i, j, k) + b));
  return out;
}

namespace
{
/// Cube edge of the lattice of spheres of radius r.
double cube_edge(Lattice l, double r) { return l == Lattice::simple_cubic ? 2 * r : 2 * std::sqrt(2.0) * r; }

/// Cubes of edge a along a length, with one spare at each end.
double cubes_along(double length, double a) { return std::ceil(length / a) + 2; }
} // namespace

double lattice_cylinder_sites(Lattice l, double r, double diameter, double height)
{
  const double a = cube_edge(l, r);
  const double basis = l == Lattice::simple_cubic ? 1 : 4;
  return basis * cubes_along(diameter, a) * cubes_along(diameter, a) * cubes_along(height, a);
}

LatticeCylinder lattice_cylinder(Lattice l, double r, double diameter, double height)
{
  const double sites = lattice_cylinder_sites(l, r, diameter, height);
  if (!(sites <= double(std::numeric_limits<Index>::max())))
    throw std::length_error("a lattice cylinder of " + std::to_string(sites) + " sites (ball radius " +
                            std::to_string(r) + " m): more than a ball index counts");
  const double a = cube_edge(l, r);
  const int n_xy = static_cast<int>(cubes_along(diameter, a));
  const int n_z = static_cast<int>(cubes_along(height, a));
  const std::vector<Vec3> box = lattice_box(l, r, n_xy, n_xy, n_z);
  const Vec3 centre(0.5 * (n_xy - 1) * a, 0.5 * (n_xy - 1) * a, 0);
  const double tol = 1e-9 * r;

  LatticeCylinder out;
  out.radius = r;
  double z_min = std::numeric_limits<double>::max(), z_max = -z_min, rim = 0;
  for (const Vec3 &x : box)
  {
    const double rho = std::hypot(x.x() - centre.x(), x.y() - centre.y());
    if (rho + r > 0.5 * diameter + tol || x.z() - r < -tol || x.z() + r > height + tol)
      continue;
    out.centres.push_back(Vec3(x.x() - centre.x(), x.y() - centre.y(), x.z()));
    z_min = std::min(z_min, x.z());
    z_max = std::max(z_max, x.z());
    rim = std::max(rim, rho + r);
  }
  // Shift so the lowest balls rest on z = 0; the sample is as tall as its
  // balls reach and as wide as its rim balls.
  for (Vec3 &x : out.centres)
    x.z() += r - z_min;
  out.height = out.centres.empty() ? 0 : z_max - z_min + 2 * r;
  out.diameter = 2 * rim;
  return out;
}
} // namespace dem
