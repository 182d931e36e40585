// The constant-strain-rate compression test of a viscoelastic cylinder:
// the public face of ViscoelasticCylinder<dim> (which this header hides,
// with all of deal.II, from its users).
//
// The bottom platen is fixed, the top one moves down at H x strain rate,
// or follows a prescribed axial strain history eps(t) (top displacement
// -H eps(t)), or carries a prescribed nominal stress sigma(t): a rigid
// force-controlled platen (creep).  The problem is linear, so the platen
// force is affine in the platen displacement at every step; the platen
// stiffness of the step (a constant for a fixed dt) is found from two
// trial solves once, then each step is one trial solve and one solve at the
// displacement that gives the prescribed force.
// Frictionless platens constrain only the axial displacement, so the
// cylinder stays homogeneous and must reproduce the 1-D closed form
// (check V20); bonded platens also hold the radial displacement, and
// the cylinder barrels (no closed form; check V22 estimates its
// discretisation error).
//
// Every step reports, compression positive: axial strain (platen
// displacement / H), nominal axial stress (top platen force / (pi R^2)),
// and the radial strain -u_r/R at the surface at mid-height.
//
// MPI: the test runs on every rank of MPI_COMM_WORLD (initialised here if
// the program has not done so) and every rank gets the same numbers.
#pragma once

#include "continuum/burgers_chain.h"

#include <functional>
#include <memory>
#include <string>

namespace continuum
{
enum class Platens
{
  frictionless,
  bonded,
};

enum class Geometry
{
  axisymmetric,      ///< (r, z) meridian, weight 2 pi r
  three_dimensional, ///< quarter cylinder with symmetry planes
};

struct CylinderSpec
{
  double radius = 0.01555; ///< R [m]
  double height = 0.0311;  ///< H [m]
  BurgersSolid solid;      ///< material
  Platens platens = Platens::frictionless;
  double strain_rate = 0.005; ///< [1/s], compression positive
  double final_strain = 0.02; ///< [-]
  /// Prescribed axial strain at time t [-] (empty: strain_rate x t to the final strain).
  std::function<double(double)> axial_strain_history;
  /// Prescribed nominal axial stress at time t [Pa], compression positive (creep; overrides the strain).
  std::function<double(double)> axial_stress_history;
  double duration = 0;           ///< [s], with a history: the test ends there
  unsigned int time_steps = 100; ///< uniform steps to the final strain (or over the duration)
  Geometry geometry = Geometry::axisymmetric;
  unsigned int degree = 2;          ///< Q_p
  unsigned int refinements = 2;     ///< global refinements (coarse cells about R wide)
  double solver_tolerance = 1e-12;  ///< relative CG residual
  std::string paraview_directory;   ///< empty: no ParaView output
  unsigned int paraview_every = 10; ///< steps between ParaView frames (and the last step)
};

struct CylinderStep
{
  unsigned int step = 0;
  double time = 0;             ///< [s]
  double axial_strain = 0;     ///< compression positive [-]
  double axial_stress = 0;     ///< nominal, compression positive [Pa]
  double radial_strain = 0;    ///< -u_r/R at mid-height [-]
  unsigned int iterations = 0; ///< CG iterations of this step
};

struct CylinderMesh
{
  unsigned long cells = 0;
  unsigned long dofs = 0;
  double cell_size = 0;        ///< (volume / cells)^(1/dim) [m]
  double platen_area = 0;      ///< nominal platen area the stress refers to [m^2]
  double mesh_platen_area = 0; ///< the mesh's own top area (the quarter's x 4 in 3D) [m^2]
  double time_step = 0;        ///< [s]
  unsigned int ranks = 1;
};

struct ParallelInfo
{
  unsigned int rank = 0;
  unsigned int ranks = 1;
};

/// Rank and size of MPI_COMM_WORLD, initialising MPI (and deal.II's
/// companions) on first use.
ParallelInfo parallel_info();

class CompressionTest
{
public:
  explicit CompressionTest(const CylinderSpec &spec);
  ~CompressionTest();
  CompressionTest(const CompressionTest &) = delete;
  CompressionTest &operator=(const CompressionTest &) = delete;

  const CylinderMesh &mesh() const;
  /// Runs every step; calls on_step at t = 0 and after each step.  Throws
  /// NumericalFailure (outputs of earlier steps stay valid).
  void run(const std::function<void(const CylinderStep &)> &on_step);
  /// The edges of this rank's cells as CSV: a comment line, then one edge
  /// per block of two rows "radial or x [m],axial z [m]" and a blank line
  /// (gnuplot draws each block as one segment).  In 3-D the edges are
  /// projected on the x-z plane.
  std::string mesh_edges_csv() const;

  class Impl;

private:
  std::unique_ptr<Impl> impl_;
};
} // namespace continuum
