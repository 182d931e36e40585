#include "dem/sample_lattice.h"

#include <algorithm>
#include <cmath>

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

std::string_view lattice_name(Lattice l)
{
  return l == Lattice::simple_cubic ? "sc" : "fcc";
}

double lattice_porosity(Lattice l)
{
  return l == Lattice::simple_cubic ? 1.0 - pi / 6.0 : 1.0 - pi / (3.0 * std::sqrt(2.0));
}

int lattice_coordination(Lattice l)
{
  return l == Lattice::simple_cubic ? 6 : 12;
}

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

LatticeCylinder lattice_cylinder(Lattice l, double r, double diameter, double height)
{
  const double a = l == Lattice::simple_cubic ? 2 * r : 2 * std::sqrt(2.0) * r;
  const int n_xy = static_cast<int>(std::ceil(diameter / a)) + 2;
  const int n_z = static_cast<int>(std::ceil(height / a)) + 2;
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
