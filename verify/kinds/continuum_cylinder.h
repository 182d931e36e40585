// cylinder decks: constant-strain-rate compression of a viscoelastic
// cylinder between frictionless or bonded platens (continuum/cylinder.h),
// with a Burger's solid from the material section (continuum_material.h).
//
// One run writes series.csv (time_s, axial_strain, axial_stress_pa nominal,
// radial_strain at the mid-height surface, the 1-D homogeneous closed form
// of both (eq. 7.18 with the solid's uniaxial chain; exact for frictionless
// platens), CG iterations; compression positive), summary.json (peak stress,
// stress at 1 % strain, initial modulus and Poisson's ratio over the fit
// window, mesh, solver, wall time, provenance), deck.prm and, on request,
// ParaView files in paraview/.
//
// With study/gci refinements set to three levels the deck is a solution
// verification study (VERIFICATION 22): one run per level in level_<N>/
// and Roache's GCI (continuum_gci.h) on the peak stress and the stress at
// 1 % strain in summary.json.
//
// Under mpirun every rank computes; rank 0 writes.
#pragma once

#include "verify/kinds/continuum_gci.h"
#include "verify/decks/deck.h"
#include "verify/run/run.h"
#include "verify/io/series.h"

#include "continuum/cylinder.h"

#include <nlohmann/json.hpp>

#include <vector>

namespace verify
{
void declare_cylinder(DeckSchema &s);
/// subsection "geometry": radius and height (shared with mms decks).
void declare_cylinder_geometry(DeckSchema &s);
void read_cylinder_geometry(const Deck &deck, double &radius, double &height);

/// The compression test a deck describes (at its own refinement level).
continuum::CylinderSpec read_cylinder_spec(const Deck &deck);

struct CylinderResult
{
  Series series; ///< the run's (the finest level's in a GCI study)
  nlohmann::json summary;
  RunStatus status;
  continuum::CylinderMesh mesh;
  std::vector<GciResult> gci; ///< GCI study only: peak stress, stress at 1 % strain
};

/// Validates a cylinder deck without running it: the test, the study
/// levels, the fit window and the material.
continuum::CylinderSpec parse_cylinder(const Deck &deck);

CylinderResult run_cylinder(const Deck &deck, const RunOptions &options);

/// Linear interpolation of y at x in a series with increasing xs; NaN outside.
double interpolate(const std::vector<double> &xs, const std::vector<double> &ys, double x);
} // namespace verify
