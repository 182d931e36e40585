#include "app/io/section.h"

#include <cmath>

namespace demvv
{
std::vector<SectionCircle> vertical_section(const dem::ParticleStore &balls)
{
  std::vector<SectionCircle> cut;
  for (dem::Index p = 0; p < balls.size(); ++p)
  {
    const double y = std::abs(balls.position[p].y()), r = balls.radius[p];
    if (y < r)
      cut.push_back({balls.position[p].x(), balls.position[p].z(), std::sqrt(r * r - y * y)});
  }
  return cut;
}

const std::vector<std::string> &section_columns()
{
  static const std::vector<std::string> columns = {"x_m", "z_m", "section_radius_m"};
  return columns;
}

std::string section_note()
{
  return "the balls the plane y = 0 (through the cell's axis) cuts: centre (x, z) and the radius sqrt(R^2 - y^2) "
         "of the circle each leaves on the plane";
}
} // namespace demvv
