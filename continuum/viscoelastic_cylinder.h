// The viscoelastic cylinder: a quasi-static finite element model of a
// Burger's solid (burgers_update.h) in the layout of deal.II's step-18
// (setup_system, assemble_system, solve_timestep,
// update_quadrature_point_history, output_results).
//
// Geometry: a cylinder of radius R and height H [m], axis along the last
// coordinate, z in [0, H].
//  - dim = 2: axisymmetric, coordinates (r, z) on the meridian [0, R] x
//    [0, H].  The strain carries the hoop component u_r / r and every
//    integral the weight 2 pi r, so forces are those of the whole cylinder.
//  - dim = 3: the quarter x, y >= 0 with symmetry planes, curved face on a
//    cylindrical manifold, cell interiors by transfinite interpolation (a
//    smooth mesh family: with flat interiors the Q2 manufactured solution
//    stays pre-asymptotic, orders 0.15 above theory at 80k unknowns),
//    isoparametric mapping of the element's degree.
// Stresses and strains are three-dimensional tensors, (r, theta, z) or
// (x, y, z), tension positive inside this class.
//
// Equilibrium at t_{n+1} without inertia, weak form
//   int sigma^{n+1} : eps(v) dV = int b . v dV     for all admissible v,
// with sigma^{n+1} = C_alg : eps(u^{n+1}) + sigma_hist (burgers_update.h):
// a linear elasticity problem whose matrix depends only on dt (assembled
// once per dt) and whose right-hand side carries the history.  The
// quadrature-point states are then advanced with the same update.  The
// scheme in time is the trapezoidal rule (second order; exact for
// internal strains quadratic in time).
//
// Parallel: a distributed triangulation (p4est), Trilinos vectors and
// matrix, conjugate gradients with an algebraic multigrid preconditioner,
// stopped at a relative residual `solver_tolerance`.  Every rank computes
// its own cells; measurements are summed over ranks.
//
// What drives the problem (Dirichlet data, body force, sources of the
// internal-strain equations) is a Loading: platens for the compression test
// (cylinder.cpp), a manufactured solution for code verification (mms.cpp).
#pragma once

#include "continuum/burgers_update.h"

#include <deal.II/base/function.h>
#include <deal.II/base/index_set.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_q.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace continuum
{
namespace boundary
{
/// The axis r = 0 (axisymmetric) or the symmetry plane x = 0 (3D quarter).
constexpr dealii::types::boundary_id symmetry_x = 0;
constexpr dealii::types::boundary_id bottom = 1;     ///< z = 0, the fixed platen
constexpr dealii::types::boundary_id top = 2;        ///< z = H, the moving platen
constexpr dealii::types::boundary_id lateral = 3;    ///< r = R, free surface
constexpr dealii::types::boundary_id symmetry_y = 4; ///< y = 0 (3D quarter only)
} // namespace boundary

struct CylinderShape
{
  double radius = 0; ///< R [m]
  double height = 0; ///< H [m]
};

struct Discretisation
{
  unsigned int degree = 2;         ///< Q_p elements (and mapping)
  unsigned int refinements = 2;    ///< global refinements of the coarse mesh (cells about R wide)
  double solver_tolerance = 1e-12; ///< relative residual at which CG stops
};

/// The three-dimensional strain of a displacement with the given symmetric
/// gradient and value at x: (r, theta, z) with the hoop strain u_r / r for
/// dim = 2, the symmetric gradient for dim = 3.
template <int dim>
Tensor3 strain3d(const dealii::SymmetricTensor<2, dim> &gradient, const dealii::Tensor<1, dim> &value,
                 const dealii::Point<dim> &x);

/// The volume weight of a quadrature point: 2 pi r (dim = 2) or 1.
template <int dim>
double volume_weight(const dealii::Point<dim> &x);

template <int dim>
class Loading
{
public:
  virtual ~Loading() = default;
  /// Adds the Dirichlet conditions at time t.  Which degrees of freedom are
  /// constrained must not depend on t (only the values may).
  virtual void constrain(const dealii::Mapping<dim> &mapping, const dealii::DoFHandler<dim> &dof_handler, double time,
                         dealii::AffineConstraints<double> &constraints) const = 0;
  /// Body force b [N/m^3] at x, t.
  virtual dealii::Tensor<1, dim> body_force(const dealii::Point<dim> & /*x*/, double /*time*/) const { return {}; }
  /// Sources of the Kelvin and Maxwell-dashpot equations [1/s] at x, t.
  virtual PointSources internal_sources(const dealii::Point<dim> & /*x*/, double /*time*/) const { return {}; }
  virtual bool has_sources() const { return false; }
};

template <int dim>
class ViscoelasticCylinder
{
public:
  ViscoelasticCylinder(const CylinderShape &shape, const BurgersSolid &solid, const Discretisation &discretisation,
                       const Loading<dim> &loading, MPI_Comm communicator);

  /// Advances `steps` steps of size dt, calling after_step(n) after step n
  /// (n = 1 ... steps).  Throws NumericalFailure when the solver fails or a
  /// stress is not finite.
  void run(unsigned int steps, double dt, const std::function<void(unsigned int)> &after_step);

  /// One step in two parts, for a loading whose constraints are chosen by
  /// trial (a force-controlled platen): solve_trial solves the step to
  /// time() + dt with the loading's current constraints and may be called
  /// again after the loading changed; accept_trial advances the
  /// quadrature-point states with the last trial and the clock.
  void solve_trial(double dt);
  void accept_trial(double dt);
  /// The platen force of the last trial [N] (as platen_force() would give
  /// after accept_trial).
  double trial_platen_force() const;

  double time() const { return time_; }
  unsigned int last_iterations() const { return last_iterations_; }
  unsigned long n_cells() const;
  unsigned long n_dofs() const { return dof_handler_.n_dofs(); }
  /// (volume / cells)^(1/dim), volume of the meridian (dim = 2) or quarter [m].
  double cell_size() const;

  /// The axial force the top platen exerts on the modelled body [N] (the
  /// whole cylinder for dim = 2, the quarter for dim = 3), tension positive,
  /// from the discrete reaction: int sigma : eps(w) dV with w = e_z on the
  /// top platen's axial degrees of freedom (consistent with the solved
  /// equilibrium, so exact for a homogeneous state).
  double platen_force() const;
  /// The top face area of the mesh, as mapped (pi R^2, or pi R^2 / 4 for the quarter) [m^2].
  double platen_area() const;
  /// u_r at r = R, z = H/2 [m] (a mesh vertex by construction).
  double mid_height_radial_displacement() const;

  /// Calls f(x, weight, state) for every quadrature point of this rank's
  /// cells; weight includes JxW and the volume weight [m^3].
  void for_each_point(const std::function<void(const dealii::Point<dim> &, double, const PointState &)> &f) const;

  const dealii::DoFHandler<dim> &dof_handler() const { return dof_handler_; }
  const dealii::Mapping<dim> &mapping() const { return mapping_; }
  const dealii::TrilinosWrappers::MPI::Vector &solution() const { return solution_; }
  const dealii::Triangulation<dim> &triangulation() const { return triangulation_; }
  MPI_Comm communicator() const { return communicator_; }

  /// Writes the displacement and cell-averaged stresses of this step to
  /// directory/cylinder_<counter>.vtu (one piece per rank) and a .pvtu
  /// record; returns the record's file name.
  std::string output_results(const std::string &directory, unsigned int counter) const;

private:
  void make_grid();
  void setup_system();
  void make_constraints(double time);
  void assemble_system();
  void assemble_rhs(double old_time, double new_time);
  void solve_timestep(long step);
  /// Fills the stresses at a cell's quadrature points (fe_values reinit'ed on the cell).
  using StressAtPoints = std::function<void(const typename dealii::DoFHandler<dim>::active_cell_iterator &,
                                            const dealii::FEValues<dim> &, std::vector<Tensor3> &)>;
  /// The axial force on the top platen of the given point stresses [N].
  double platen_reaction(const StressAtPoints &stress_at) const;
  void update_quadrature_point_history(double old_time, double new_time, long step);

  /// The strains of every shape function at quadrature point q.
  void shape_strains(const dealii::FEValues<dim> &fe_values, unsigned int q, std::vector<Tensor3> &strains) const;
  void cell_matrix(const dealii::FEValues<dim> &fe_values, dealii::FullMatrix<double> &matrix) const;
  PointSources sources(const dealii::Point<dim> &x, double old_time, double new_time) const;
  PointState &state(const typename dealii::DoFHandler<dim>::active_cell_iterator &cell, unsigned int q);
  const PointState &state(const typename dealii::DoFHandler<dim>::active_cell_iterator &cell, unsigned int q) const;

  CylinderShape shape_;
  BurgersSolid solid_;
  Discretisation discretisation_;
  const Loading<dim> &loading_;
  MPI_Comm communicator_;

  dealii::parallel::distributed::Triangulation<dim> triangulation_;
  dealii::FESystem<dim> fe_;
  dealii::MappingQ<dim> mapping_;
  dealii::DoFHandler<dim> dof_handler_;
  const dealii::QGauss<dim> quadrature_;
  const dealii::FEValuesExtractors::Vector displacement_{0};

  dealii::IndexSet locally_owned_, locally_relevant_, top_axial_dofs_;
  dealii::AffineConstraints<double> constraints_;
  dealii::TrilinosWrappers::SparseMatrix system_matrix_;
  dealii::TrilinosWrappers::PreconditionAMG preconditioner_;
  dealii::TrilinosWrappers::MPI::Vector system_rhs_, owned_solution_;
  dealii::TrilinosWrappers::MPI::Vector accepted_solution_, previous_solution_; ///< the last two accepted steps
  dealii::TrilinosWrappers::MPI::Vector solution_;                              ///< ghosted

  std::unique_ptr<SolidStep> step_; ///< the update for the current dt
  double assembled_dt_ = 0;
  std::vector<PointState> states_; ///< per active cell and quadrature point
  double time_ = 0;
  unsigned int last_iterations_ = 0;
};
} // namespace continuum
