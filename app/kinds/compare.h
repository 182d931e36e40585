// compare decks: the DEM bulk response of a sample beside the continuum
// cylinder built from the same contacts, under the same loading history.
//
// A compare deck is a uniaxial deck (sample, balls, Burger's contact law,
// bonds, platens, loading history, rate, motion, measurement) with a
// "comparison" section.  One run makes, in its run directory:
//   calibration/  the elastic calibration on this sample: the same contacts
//                 with every viscosity x 1e12 (each Burger's element is
//                 then its Maxwell spring on the test's time scale), a
//                 constant-rate test to the calibration strain; E and nu
//                 fitted over the measurement window, with R^2;
//   dem/          the DEM bulk test with the viscoelastic law;
//   compare.csv   per DEM row: the DEM's axial strain, axial stress and
//                 radial strain; the same from the continuum cylinder by the
//                 calibrated route (Young chain = E / K_ref x the normal
//                 contact chain, nu measured: continuum/homogenisation.h)
//                 and by the affine route (Z, phi measured on the same
//                 sample by the measurement spheres, R the mean radius),
//                 interpolated in time; their differences;
//   summary.json  E_DEM / E_affine (the non-affine ratio), nu both ways, the
//                 largest difference of the compared quantity (stress; strain
//                 for creep) over its largest value and where it occurs,
//                 the packing measured, and the numerical uncertainty of both
//                 sides: the continuum's time-step error (the same run at
//                 half the steps, Richardson for order 2) and mesh error
//                 (one refinement coarser: a bound, as the order is not
//                 known), and, on request, the DEM's time-step sensitivity
//                 (the bulk test again at half the time-step safety).
// K_ref is the normal Maxwell stiffness (the modified law: its compression
// stiffness, which carries a compression test).
//
// With same-shape contacts (every shear constant r x the normal one),
// bonds that never break on every touching pair (bonded contacts do not
// slip), frictionless platens and a quasi-static rate, the DEM network is
// linear viscoelastic: by the correspondence principle its bulk stress is
// the calibrated continuum's under every history (check V23).
//
// One process (OpenMP threads for the DEM; the continuum is small).
#pragma once

#include "app/decks/deck.h"
#include "app/io/series.h"
#include "app/kinds/uniaxial.h"
#include "app/run/run.h"

#include <nlohmann/json.hpp>

namespace demvv
{
void declare_compare(DeckSchema &s);

struct CompareSpec
{
  UniaxialSpec dem;                 ///< the DEM bulk test, as a uniaxial deck reads it
  bool bonded_platens = false;      ///< continuum platens; DEM platens then get friction that holds the balls
  double calibration_strain = 0;    ///< axial strain of the elastic calibration [-]
  unsigned int degree = 1;          ///< continuum Q_p
  unsigned int refinements = 2;     ///< continuum global refinements
  unsigned int time_steps = 200;    ///< continuum uniform steps over the history
  bool dem_time_step_study = false; ///< rerun the DEM bulk test at half the time-step safety
  double tolerance = 0.05;          ///< relative difference that passes inside the identity's conditions [-]
};

CompareSpec parse_compare(const Deck &deck);

struct CompareResult
{
  Series series; ///< compare.csv
  nlohmann::json summary;
  RunStatus status;
};

/// The verdict of a comparison: inside the correspondence identity (same-
/// shape chains, no bond broken, no friction slip, frictionless platens,
/// quasi-static: read from the DEM run's summary `bulk`) the relative
/// `difference` of DEM against the calibrated continuum passes or fails
/// against spec.tolerance; outside it, the result is a model-form
/// difference naming every condition that failed, never judged.
nlohmann::json identity_verdict(const CompareSpec &spec, bool same_shape, const nlohmann::json &bulk,
                                double difference);

CompareResult run_compare(const CompareSpec &spec, const RunOptions &options);
CompareResult run_compare(const Deck &deck, const RunOptions &options);
} // namespace demvv
