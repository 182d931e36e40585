#include "continuum/homogenisation.h"

namespace continuum
{
namespace
{
constexpr double pi = 3.14159265358979323846;
}

ElasticModuli affine_moduli(const PackingGeometry &packing, double normal_stiffness, double shear_stiffness)
{
  const double density = packing.solid_fraction * packing.coordination / (pi * packing.radius); // phi Z / (pi R)
  ElasticModuli m;
  m.bulk = density * normal_stiffness / 6;
  m.shear = density * (2 * normal_stiffness + 3 * shear_stiffness) / 20;
  m.young = 9 * m.bulk * m.shear / (3 * m.bulk + m.shear);
  m.poisson = (normal_stiffness - shear_stiffness) / (4 * normal_stiffness + shear_stiffness);
  return m;
}

BurgersSolid affine_burgers_solid(const BurgersChain &normal_contact, double shear_ratio,
                                  const PackingGeometry &packing)
{
  const ElasticModuli unit = affine_moduli(packing, 1.0, shear_ratio);
  BurgersSolid solid;
  solid.young = normal_contact.scaled(unit.young);
  solid.poisson = unit.poisson;
  solid.bulk = BulkResponse::same_shape;
  return solid;
}

BurgersSolid calibrated_burgers_solid(const BurgersChain &normal_contact, double young, double poisson,
                                      double reference_normal_stiffness)
{
  BurgersSolid solid;
  solid.young = normal_contact.scaled(young / reference_normal_stiffness);
  solid.poisson = poisson;
  solid.bulk = BulkResponse::same_shape;
  return solid;
}
} // namespace continuum
