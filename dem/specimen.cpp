#include "specimen.h"

#include <sstream>

namespace dem
{
Specimen lattice_specimen(Lattice lattice, double radius, double diameter, double height,
                          const BallSpec &ball, const WallProps &platen, const WallProps &lateral,
                          bool with_lateral)
{
  const LatticeCylinder cyl = lattice_cylinder(lattice, radius, diameter, height);
  Specimen s;
  s.diameter = cyl.diameter;
  s.height = cyl.height;
  s.particles.reserve(cyl.centres.size());
  for (const Vec3 &x : cyl.centres)
  {
    BallSpec b = ball;
    b.position = x;
    b.radius = radius;
    s.particles.add(b);
  }
  Wall bottom;
  bottom.name = "bottom";
  bottom.direction = Vec3::UnitZ();
  bottom.props = platen;
  Wall top = bottom;
  top.name = "top";
  top.point = Vec3(0, 0, cyl.height);
  top.direction = -Vec3::UnitZ();
  s.bottom = s.walls.add(bottom);
  s.top = s.walls.add(top);
  if (with_lateral)
  {
    Wall side;
    side.name = "lateral";
    side.shape = WallShape::cylinder;
    side.radius = 0.5 * cyl.diameter;
    side.props = lateral;
    s.lateral = s.walls.add(side);
  }
  std::ostringstream d;
  d << "regular " << lattice_name(lattice) << " lattice cylinder of " << cyl.centres.size()
    << " touching balls (a verification stand-in, not the dense random packing of thesis ch. 5)";
  s.description = d.str();
  return s;
}
} // namespace dem
