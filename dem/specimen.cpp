#include "dem/specimen.h"

#include <sstream>

namespace dem
{
void add_cell_walls(Specimen &s, double diameter, double height, const WallProps &platen, const WallProps &lateral,
                    bool with_lateral)
{
  Wall bottom;
  bottom.name = "bottom";
  bottom.direction = Vec3::UnitZ();
  bottom.props = platen;
  Wall top = bottom;
  top.name = "top";
  top.point = Vec3(0, 0, height);
  top.direction = -Vec3::UnitZ();
  s.bottom = s.walls.add(bottom);
  s.top = s.walls.add(top);
  if (with_lateral)
  {
    Wall side;
    side.name = "lateral";
    side.shape = WallShape::cylinder;
    side.radius = 0.5 * diameter;
    side.props = lateral;
    s.lateral = s.walls.add(side);
  }
  s.diameter = diameter;
  s.height = height;
}

Specimen lattice_specimen(Lattice lattice, double radius, double diameter, double height, const BallSpec &ball,
                          const WallProps &platen, const WallProps &lateral, bool with_lateral)
{
  const LatticeCylinder cyl = lattice_cylinder(lattice, radius, diameter, height);
  Specimen s;
  s.particles.reserve(cyl.centres.size());
  for (const Vec3 &x : cyl.centres)
  {
    BallSpec b = ball;
    b.position = x;
    b.radius = radius;
    s.particles.add(b);
  }
  add_cell_walls(s, cyl.diameter, cyl.height, platen, lateral, with_lateral);
  std::ostringstream d;
  d << "regular " << lattice_name(lattice) << " lattice cylinder of " << cyl.centres.size()
    << " touching balls (a verification stand-in, not the dense random packing of thesis ch. 5)";
  s.description = d.str();
  return s;
}
} // namespace dem
