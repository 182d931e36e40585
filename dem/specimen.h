// Specimen: a cylindrical sample between two platens, ready to test.
//
// Axis z; bottom platen at z = 0 facing up, top platen at z = height facing
// down, and (optionally) the lateral cylinder of the sample's diameter.
// Every test protocol starts from a Specimen, whichever way its balls were
// made (a regular lattice, or a prepared random packing, prep_packing.h).
#pragma once

#include "dem/particles.h"
#include "dem/sample_lattice.h"
#include "dem/walls.h"

#include <string>

namespace dem
{
struct Specimen
{
  ParticleStore particles;
  WallSet walls;
  WallIndex bottom = -1, top = -1, lateral = -1;
  double diameter = 0; ///< m
  double height = 0;   ///< m
  std::string description;

  double area() const { return pi * 0.25 * diameter * diameter; }
};

/// Adds the cell walls to a specimen: platens at z = 0 and z = height
/// (facing each other) with `platen` properties and, if `with_lateral`, the
/// cylinder of the given diameter with `lateral` properties; sets the
/// specimen's wall indices, diameter and height.
void add_cell_walls(Specimen &s, double diameter, double height, const WallProps &platen, const WallProps &lateral,
                    bool with_lateral);

/// A lattice cylinder of balls with the properties of `ball` (position and
/// radius ignored), platens with `platen` properties, and a lateral wall with
/// `lateral` properties if `with_lateral`.
Specimen lattice_specimen(Lattice lattice, double radius, double diameter, double height, const BallSpec &ball,
                          const WallProps &platen, const WallProps &lateral, bool with_lateral);
} // namespace dem
