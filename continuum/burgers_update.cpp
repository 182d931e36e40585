#include "continuum/burgers_update.h"

namespace continuum
{
TrapezoidalChain::TrapezoidalChain(const BurgersChain &chain, double dt)
  : dt_(dt), kelvin_dashpot_(chain.kelvin_dashpot)
{
  const double x = chain.kelvin_spring * dt / (2 * chain.kelvin_dashpot);
  a_ = 1 + x;
  b_ = 1 - x;
  const double kelvin = dt / (2 * chain.kelvin_dashpot * a_), dashpot = dt / (2 * chain.maxwell_dashpot);
  c_ = kelvin + 1 / chain.maxwell_spring + dashpot;
  d_ = kelvin - 1 / chain.maxwell_spring + dashpot;
}

namespace
{
std::optional<TrapezoidalChain> volumetric_chain(const BurgersSolid &solid, double dt)
{
  if (solid.bulk == BulkResponse::elastic)
    return std::nullopt;
  return TrapezoidalChain(solid.bulk_chain(), dt);
}

const Tensor3 identity = dealii::unit_symmetric_tensor<3>();
} // namespace

SolidStep::SolidStep(const BurgersSolid &solid, double dt)
  : deviatoric_(solid.shear().scaled(2), dt), volumetric_(volumetric_chain(solid, dt)),
    elastic_bulk_(solid.bulk_modulus())
{
}

double SolidStep::bulk_stiffness() const { return volumetric_ ? volumetric_->stiffness() : elastic_bulk_; }

Tensor3 SolidStep::stress(const Tensor3 &strain) const
{
  return shear_stiffness() * dealii::deviator(strain) + bulk_stiffness() * dealii::trace(strain) * identity;
}

Tensor3 SolidStep::history(const PointState &old, const PointSources &sources) const
{
  using dealii::deviator;
  using dealii::trace;
  Tensor3 h = deviatoric_.history(deviator(old.strain), deviator(old.kelvin), deviator(old.stress),
                                  deviator(sources.kelvin), deviator(sources.dashpot));
  if (volumetric_)
    h += volumetric_->history(trace(old.strain), trace(old.kelvin), trace(old.stress) / 3, trace(sources.kelvin),
                              trace(sources.dashpot)) *
         identity;
  return h;
}

PointState SolidStep::advance(const PointState &old, const Tensor3 &strain, const PointSources &sources) const
{
  using dealii::deviator;
  using dealii::trace;
  PointState next;
  next.strain = strain;
  next.stress = stress(strain) + history(old, sources);
  next.kelvin =
    deviatoric_.kelvin(deviator(old.kelvin), deviator(old.stress), deviator(next.stress), deviator(sources.kelvin));
  if (volumetric_)
    next.kelvin +=
      volumetric_->kelvin(trace(old.kelvin), trace(old.stress) / 3, trace(next.stress) / 3, trace(sources.kelvin)) / 3 *
      identity;
  return next;
}
} // namespace continuum
