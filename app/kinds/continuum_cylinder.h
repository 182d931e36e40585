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
// verification study (check V22): one run per level in level_<N>/
// and Roache's GCI (continuum_gci.h) on the peak stress and the stress at
// 1 % strain in summary.json.
//
// Under mpirun every rank computes; rank 0 writes.
#pragma once

#include "app/decks/deck.h"
#include "app/decks/loading_history.h"
#include "app/io/series.h"
#include "app/kinds/continuum_gci.h"
#include "app/run/run.h"

#include "continuum/burgers_ode.h"
#include "continuum/cylinder.h"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace demvv
{
void declare_cylinder(DeckSchema &s);
/// subsection "geometry": radius and height (shared with mms decks).
void declare_cylinder_geometry(DeckSchema &s);

/// The cylinder's size [m]; the height lies between R/4 and 16 R, where
/// the coarse mesh, whose cells are about R wide, still resolves it.
struct CylinderGeometry
{
  double radius = 0; ///< R [m]
  double height = 0; ///< H [m]
};

CylinderGeometry parse_cylinder_geometry(const Deck &deck);

/// A loading history as the CVODE chain takes it (strain, or stress under
/// force control for creep).
continuum::History ode_history(const LoadingHistory &history);
inline continuum::Control ode_control(const LoadingHistory &history)
{
  return history.stress_controlled() ? continuum::Control::force : continuum::Control::displacement;
}
/// Gives the cylinder the history (a schedule and the duration); a
/// constant-rate history without a ramp keeps the cylinder's own rate.
void apply_history(const LoadingHistory &history, continuum::CylinderSpec &cylinder);

/// A cylinder deck, parsed and validated: the compression test at the
/// deck's own refinement level and what the run makes of it (a single run,
/// or one run per GCI level with the refinements overridden).
struct CylinderDeckSpec
{
  DeckRecord deck;
  std::string title;
  /// The test at discretisation/refinements, with the material's solid;
  /// its paraview_directory is empty (the run sets it under its output
  /// directory when paraview is on).
  continuum::CylinderSpec test;
  nlohmann::json material; ///< the material's route, inputs and moduli (summary.json)
  LoadingHistory history;  ///< the loading (test carries its schedule)
  /// Refinement levels of a GCI study, increasing (empty: one run at
  /// test.refinements; else three or four levels).
  std::vector<unsigned int> gci_levels;
  double gci_safety_factor = 1.25; ///< Fs [-]
  double fit_from = 0, fit_to = 0; ///< axial strain window of the elastic fit [-]
  bool paraview = false;           ///< write ParaView frames every test.paraview_every steps
};

/// Reads and validates every key of a cylinder deck (geometry, material,
/// loading, discretisation, study levels, fit window, output).
CylinderDeckSpec parse_cylinder(const Deck &deck);

struct CylinderResult
{
  Series series; ///< the run's (the finest level's in a GCI study)
  nlohmann::json summary;
  RunStatus status;
  continuum::CylinderMesh mesh;
  std::vector<GciResult> gci; ///< GCI study only: peak stress, stress at 1 % strain
};

CylinderResult run_cylinder(const CylinderDeckSpec &spec, const RunOptions &options);
/// parse_cylinder then run_cylinder.
CylinderResult run_cylinder(const Deck &deck, const RunOptions &options);

/// The deck keyword of a discretisation model ("axisymmetric" or "3d").
const char *geometry_keyword(continuum::Geometry geometry);

/// Linear interpolation of y at x in a series with increasing xs; NaN outside.
double interpolate(const std::vector<double> &xs, const std::vector<double> &ys, double x);
} // namespace demvv
