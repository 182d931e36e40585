// Uniaxial decks: compression of a bonded cylinder between frictionless
// platens (thesis §6.1-6.3) at constant strain rate, or under another
// loading history (creep, relaxation, cyclic strain: loading_history.h).
//
// The sample is a prepared packing (thesis ch. 5: a sample file, or a
// prepare deck whose sample is prepared once and cached), or a regular
// lattice cylinder (simple cubic or FCC), a verification sample with
// closed-form porosity and coordination; every output says which.
//
// Outputs: series.csv (time, axial strain, nominal stress top/bottom/mean,
// radial strain, bond breakage, coordination, porosity, unbalanced force,
// inertial number, energies; a row every `output/strain interval` of axial
// strain), summary.json (peak stress, strain at peak, strain at the maximum
// breakage rate, initial modulus and Poisson's ratio fitted over the stated
// strain window, counts, timings, provenance), bond_breaks.csv, section.csv
// (the balls the plane through the axis cuts, at the end: app/io/section.h),
// deck.prm and optional ParaView frames.
#pragma once

#include "app/decks/deck.h"
#include "app/decks/deck_sections.h"
#include "app/decks/loading_history.h"
#include "app/io/sample_file.h"
#include "app/io/series.h"
#include "app/run/analysis.h"
#include "app/run/dem_driver.h"
#include "app/run/run.h"

#include "dem/bonds.h"
#include "dem/sample_lattice.h"
#include "dem/simulation.h"

#include <nlohmann/json.hpp>

#include <memory>

namespace demvv
{
void declare_uniaxial(DeckSchema &s);

/// A uniaxial deck, parsed and validated.
struct UniaxialSpec
{
  DeckRecord deck;
  std::string title;
  // sample
  bool from_file = false;  ///< a prepared sample (else a lattice)
  std::string sample_file; ///< resolved against the deck
  std::string sample_name; ///< as the deck writes it (for descriptions)
  dem::Lattice lattice = dem::Lattice::face_centred_cubic;
  double ball_radius = 0;          ///< m
  double diameter = 0, height = 0; ///< m, lattice target size
  // contacts
  dem::BallSpec balls; ///< as written (not yet rate-scaled)
  LawSpec law;
  BondSpec bonds;
  dem::WallProps platens;
  // loading
  bool by_platen_speed = true;
  double platen_speed = 0; ///< m/s
  double strain_rate = 0;  ///< 1/s
  double ramp_time = 0;    ///< s
  double final_strain = 0; ///< -
  bool both_platens = false;
  LoadingHistory history;   ///< its strain rate is set by resolve_loading once the sample's height is known
  double time_interval = 0; ///< s between rows of a history other than constant rate (0: 1/500 of it)
  RateSpec rate;
  dem::SimulationSettings motion;
  // measurement
  double gauge_thickness = 0; ///< fraction of the height
  double sphere_radius = 0;   ///< fraction of the diameter
  std::vector<double> gauge_study;
  double fit_from = 0, fit_to = 0; ///< axial strain window of the elastic fit
  DemOutputSpec output;            ///< clock: axial strain [-] at constant rate, else time [s]
  /// summary.json's uncertainty/input_calibration: u_input of each
  /// calibrated quantity when calibration/record names the calibration that
  /// fitted the deck (app/run/input_uncertainty.h)
  nlohmann::json input_uncertainty;
};

UniaxialSpec parse_uniaxial(const Deck &deck);

/// A test's loading resolved once against its sample's height: the one
/// strain rate that the rate scaling, the platens' schedule, summary.json
/// (loading/strain_rate_per_s) and the continuum side of a comparison all
/// use, and the deck's history at that rate.
struct ResolvedLoading
{
  double strain_rate = 0; ///< 1/s: the platen speed over the sample height, or the deck's strain rate
  LoadingHistory history; ///< the deck's, at that strain rate
};

ResolvedLoading resolve_loading(const UniaxialSpec &spec, double sample_height);

struct UniaxialResult
{
  std::unique_ptr<dem::Simulation> sim;
  Series series;
  nlohmann::json summary;
  RunStatus status;
  ResolvedLoading loading;
  double sample_diameter = 0, sample_height = 0; ///< m, the test's cell
  ElasticFit elastic;                            ///< over the deck's fit window, as summary.json states it
};

UniaxialResult run_uniaxial(const UniaxialSpec &spec, const RunOptions &options);
/// parse_uniaxial then run_uniaxial.
UniaxialResult run_uniaxial(const Deck &deck, const RunOptions &options);

/// A prepared sample made ready for a test: every ball gets `ball`'s
/// properties and the platens `platens`, the lateral wall goes (thesis
/// §5.3.4), the clock restarts at zero.  Uniaxial runs and the bench share it.
struct TestSample
{
  std::unique_ptr<dem::Simulation> sim;
  dem::Specimen cell;
};
TestSample open_test_sample(SampleFile file, const dem::BallSpec &ball, const dem::WallProps &platens,
                            std::unique_ptr<dem::ContactModel> law, const dem::SimulationSettings &motion);
} // namespace demvv
