#include "continuum/viscoelastic_cylinder.h"

#include "continuum/numerical_failure.h"

#include <deal.II/base/mpi.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/manifold_lib.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/sparsity_tools.h>
#include <deal.II/numerics/data_out.h>

#include <algorithm>
#include <cmath>

namespace continuum
{
using namespace dealii;

namespace
{
constexpr double pi = numbers::PI;

/// Number of coarse cells along the axis: even, so that z = H/2 is a vertex
/// layer, and about R tall.
unsigned int axial_cells(const CylinderShape &s)
{
  return 2 * std::max(1u, static_cast<unsigned int>(std::lround(s.height / (2 * s.radius))));
}

/// Boundary parts by face centre (the coarse mesh; children inherit them).
template <int dim>
void mark_boundary(Triangulation<dim> &tria, const CylinderShape &s)
{
  const double tol = 1e-8 * s.radius;
  for (const auto &cell : tria.active_cell_iterators())
    for (const auto &face : cell->face_iterators())
    {
      if (!face->at_boundary())
        continue;
      const Point<dim> c = face->center();
      if (std::abs(c[dim - 1]) < tol)
        face->set_boundary_id(boundary::bottom);
      else if (std::abs(c[dim - 1] - s.height) < tol)
        face->set_boundary_id(boundary::top);
      else if (std::abs(c[0]) < tol)
        face->set_boundary_id(boundary::symmetry_x);
      else if (dim == 3 && std::abs(c[1]) < tol)
        face->set_boundary_id(boundary::symmetry_y);
      else
        face->set_boundary_id(boundary::lateral);
    }
}

void coarse_mesh(Triangulation<2> &tria, const CylinderShape &s)
{
  GridGenerator::subdivided_hyper_rectangle(tria, {1u, axial_cells(s)}, Point<2>(0, 0), Point<2>(s.radius, s.height));
  mark_boundary(tria, s);
}

void coarse_mesh(Triangulation<3> &tria, const CylinderShape &s)
{
  Triangulation<2> quarter;
  GridGenerator::quarter_hyper_ball(quarter, Point<2>(), s.radius);
  const unsigned int layers = axial_cells(s);
  std::vector<double> z(layers + 1);
  for (unsigned int k = 0; k <= layers; ++k)
    z[k] = s.height * k / layers;
  GridGenerator::extrude_triangulation(quarter, z, tria);
  mark_boundary(tria, s);
  // The cells' interiors follow a transfinite interpolation of their
  // boundaries; the lateral faces (and their edges) lie on the cylinder r = R.
  tria.set_all_manifold_ids(2);
  for (const auto &cell : tria.active_cell_iterators())
    for (const auto &face : cell->face_iterators())
      if (face->at_boundary() && face->boundary_id() == boundary::lateral)
        face->set_all_manifold_ids(1);
}

void attach_manifold(Triangulation<2> & /*tria*/) {}

void attach_manifold(Triangulation<3> &tria)
{
  tria.set_manifold(1, CylindricalManifold<3>(Tensor<1, 3>({0., 0., 1.}), Point<3>()));
  TransfiniteInterpolationManifold<3> interior;
  interior.initialize(tria);
  tria.set_manifold(2, interior);
}

bool finite(const Tensor3 &t)
{
  for (unsigned int i = 0; i < Tensor3::n_independent_components; ++i)
    if (!std::isfinite(t.access_raw_entry(i)))
      return false;
  return true;
}
} // namespace

template <>
Tensor3 strain3d<2>(const SymmetricTensor<2, 2> &gradient, const Tensor<1, 2> &value, const Point<2> &x)
{
  Tensor3 e; // (r, theta, z)
  e[0][0] = gradient[0][0];
  e[1][1] = value[0] / x[0];
  e[2][2] = gradient[1][1];
  e[0][2] = gradient[0][1];
  return e;
}

template <>
Tensor3 strain3d<3>(const SymmetricTensor<2, 3> &gradient, const Tensor<1, 3> & /*value*/, const Point<3> & /*x*/)
{
  return gradient;
}

template <>
double volume_weight<2>(const Point<2> &x)
{
  return 2 * pi * x[0];
}

template <>
double volume_weight<3>(const Point<3> & /*x*/)
{
  return 1;
}

// @sect3{Construction: mesh and degrees of freedom}

template <int dim>
ViscoelasticCylinder<dim>::ViscoelasticCylinder(const CylinderShape &shape, const BurgersSolid &solid,
                                                const Discretisation &discretisation, const Loading<dim> &loading,
                                                MPI_Comm communicator)
  : shape_(shape), solid_(solid), discretisation_(discretisation), loading_(loading), communicator_(communicator),
    triangulation_(communicator), fe_(FE_Q<dim>(discretisation.degree), dim), mapping_(discretisation.degree),
    dof_handler_(triangulation_), quadrature_(discretisation.degree + 1)
{
  make_grid();
  setup_system();
}

template <int dim>
void ViscoelasticCylinder<dim>::make_grid()
{
  // The coarse mesh is built serially (identical on every rank) and copied
  // into the distributed triangulation, which then refines and partitions.
  Triangulation<dim> coarse;
  coarse_mesh(coarse, shape_);
  triangulation_.copy_triangulation(coarse);
  attach_manifold(triangulation_);
  triangulation_.refine_global(discretisation_.refinements);
}

template <int dim>
void ViscoelasticCylinder<dim>::setup_system()
{
  dof_handler_.distribute_dofs(fe_);
  locally_owned_ = dof_handler_.locally_owned_dofs();
  DoFTools::extract_locally_relevant_dofs(dof_handler_, locally_relevant_);
  ComponentMask axial(dim, false);
  axial.set(dim - 1, true);
  top_axial_dofs_ = DoFTools::extract_boundary_dofs(dof_handler_, axial, {boundary::top});

  make_constraints(0);
  DynamicSparsityPattern dsp(locally_relevant_);
  DoFTools::make_sparsity_pattern(dof_handler_, dsp, constraints_, false);
  SparsityTools::distribute_sparsity_pattern(dsp, locally_owned_, communicator_, locally_relevant_);
  system_matrix_.reinit(locally_owned_, locally_owned_, dsp, communicator_);

  system_rhs_.reinit(locally_owned_, communicator_);
  owned_solution_.reinit(locally_owned_, communicator_);
  accepted_solution_.reinit(locally_owned_, communicator_);
  previous_solution_.reinit(locally_owned_, communicator_);
  solution_.reinit(locally_owned_, locally_relevant_, communicator_);
  states_.assign(triangulation_.n_active_cells() * quadrature_.size(), PointState());
}

template <int dim>
void ViscoelasticCylinder<dim>::make_constraints(double time)
{
  constraints_.clear();
  constraints_.reinit(locally_relevant_);
  loading_.constrain(mapping_, dof_handler_, time, constraints_);
  constraints_.close();
}

// @sect3{Assembly}

template <int dim>
void ViscoelasticCylinder<dim>::shape_strains(const FEValues<dim> &fe_values, unsigned int q,
                                              std::vector<Tensor3> &strains) const
{
  const Point<dim> &x = fe_values.quadrature_point(q);
  for (unsigned int i = 0; i < fe_.n_dofs_per_cell(); ++i)
    strains[i] =
      strain3d<dim>(fe_values[displacement_].symmetric_gradient(i, q), fe_values[displacement_].value(i, q), x);
}

template <int dim>
void ViscoelasticCylinder<dim>::cell_matrix(const FEValues<dim> &fe_values, FullMatrix<double> &matrix) const
{
  const unsigned int n = fe_.n_dofs_per_cell();
  std::vector<Tensor3> strains(n), stresses(n);
  matrix = 0;
  for (unsigned int q = 0; q < quadrature_.size(); ++q)
  {
    const double w = fe_values.JxW(q) * volume_weight(fe_values.quadrature_point(q));
    shape_strains(fe_values, q, strains);
    for (unsigned int j = 0; j < n; ++j)
      stresses[j] = step_->stress(strains[j]);
    for (unsigned int i = 0; i < n; ++i)
      for (unsigned int j = 0; j <= i; ++j)
        matrix(i, j) += strains[i] * stresses[j] * w;
  }
  for (unsigned int i = 0; i < n; ++i)
    for (unsigned int j = 0; j < i; ++j)
      matrix(j, i) = matrix(i, j);
}

template <int dim>
void ViscoelasticCylinder<dim>::assemble_system()
{
  system_matrix_ = 0;
  FEValues<dim> fe_values(mapping_, fe_, quadrature_,
                          update_values | update_gradients | update_quadrature_points | update_JxW_values);
  FullMatrix<double> matrix(fe_.n_dofs_per_cell(), fe_.n_dofs_per_cell());
  std::vector<types::global_dof_index> dofs(fe_.n_dofs_per_cell());
  for (const auto &cell : dof_handler_.active_cell_iterators())
    if (cell->is_locally_owned())
    {
      fe_values.reinit(cell);
      cell_matrix(fe_values, matrix);
      cell->get_dof_indices(dofs);
      constraints_.distribute_local_to_global(matrix, dofs, system_matrix_);
    }
  system_matrix_.compress(VectorOperation::add);

  TrilinosWrappers::PreconditionAMG::AdditionalData amg;
  DoFTools::extract_constant_modes(dof_handler_, ComponentMask(), amg.constant_modes);
  amg.elliptic = true;
  amg.higher_order_elements = fe_.degree > 1;
  amg.smoother_sweeps = 2;
  amg.aggregation_threshold = 0.02;
  preconditioner_.initialize(system_matrix_, amg);
}

template <int dim>
PointSources ViscoelasticCylinder<dim>::sources(const Point<dim> &x, double old_time, double new_time) const
{
  if (!loading_.has_sources())
    return {};
  const PointSources a = loading_.internal_sources(x, old_time), b = loading_.internal_sources(x, new_time);
  return {0.5 * (a.kelvin + b.kelvin), 0.5 * (a.dashpot + b.dashpot)};
}

template <int dim>
void ViscoelasticCylinder<dim>::assemble_rhs(double old_time, double new_time)
{
  system_rhs_ = 0;
  FEValues<dim> fe_values(mapping_, fe_, quadrature_,
                          update_values | update_gradients | update_quadrature_points | update_JxW_values);
  const unsigned int n = fe_.n_dofs_per_cell();
  Vector<double> rhs(n);
  FullMatrix<double> matrix(n, n);
  std::vector<types::global_dof_index> dofs(n);
  std::vector<Tensor3> strains(n);
  for (const auto &cell : dof_handler_.active_cell_iterators())
    if (cell->is_locally_owned())
    {
      fe_values.reinit(cell);
      rhs = 0;
      for (unsigned int q = 0; q < quadrature_.size(); ++q)
      {
        const Point<dim> &x = fe_values.quadrature_point(q);
        const double w = fe_values.JxW(q) * volume_weight(x);
        const Tensor3 history = step_->history(state(cell, q), sources(x, old_time, new_time));
        const Tensor<1, dim> b = loading_.body_force(x, new_time);
        shape_strains(fe_values, q, strains);
        for (unsigned int i = 0; i < n; ++i)
          rhs(i) += (fe_values[displacement_].value(i, q) * b - strains[i] * history) * w;
      }
      cell->get_dof_indices(dofs);
      const bool inhomogeneous =
        std::any_of(dofs.begin(), dofs.end(),
                    [&](types::global_dof_index i) { return constraints_.is_inhomogeneously_constrained(i); });
      if (inhomogeneous)
      {
        // Prescribed displacements enter the right-hand side through the
        // cell matrix (AffineConstraints eliminates them).
        cell_matrix(fe_values, matrix);
        constraints_.distribute_local_to_global(rhs, dofs, system_rhs_, matrix);
      }
      else
        constraints_.distribute_local_to_global(rhs, dofs, system_rhs_);
    }
  system_rhs_.compress(VectorOperation::add);
  // A constrained row of the matrix is decoupled, with a diagonal entry of
  // AffineConstraints' choice; give it the right-hand side that makes the
  // prescribed value its solution, so that CG spends no work on it.
  for (const types::global_dof_index i : locally_owned_)
    if (constraints_.is_constrained(i))
      system_rhs_(i) = system_matrix_.diag_element(i) * constraints_.get_inhomogeneity(i);
  system_rhs_.compress(VectorOperation::insert);
}

// @sect3{Solution and history update}

template <int dim>
void ViscoelasticCylinder<dim>::solve_timestep(long step)
{
  // Initial guess: linear extrapolation of the last two solutions.
  TrilinosWrappers::MPI::Vector guess(accepted_solution_);
  guess *= 2;
  guess -= previous_solution_;
  owned_solution_ = guess;
  constraints_.distribute(owned_solution_);

  SolverControl control(std::max<unsigned int>(1000, dof_handler_.n_dofs()),
                        discretisation_.solver_tolerance * system_rhs_.l2_norm(), false, false);
  SolverCG<TrilinosWrappers::MPI::Vector> cg(control);
  try
  {
    cg.solve(system_matrix_, owned_solution_, system_rhs_, preconditioner_);
  }
  catch (const SolverControl::NoConvergence &e)
  {
    throw NumericalFailure(time_, step,
                           "the conjugate-gradient solver did not reach the relative residual " +
                             std::to_string(discretisation_.solver_tolerance) + " in " + std::to_string(e.last_step) +
                             " iterations (residual " + std::to_string(e.last_residual) + ")");
  }
  constraints_.distribute(owned_solution_);
  solution_ = owned_solution_;
  last_iterations_ = control.last_step();
}

template <int dim>
void ViscoelasticCylinder<dim>::update_quadrature_point_history(double old_time, double new_time, long step)
{
  FEValues<dim> fe_values(mapping_, fe_, quadrature_, update_values | update_gradients | update_quadrature_points);
  std::vector<SymmetricTensor<2, dim>> gradients(quadrature_.size());
  std::vector<Tensor<1, dim>> values(quadrature_.size());
  for (const auto &cell : dof_handler_.active_cell_iterators())
    if (cell->is_locally_owned())
    {
      fe_values.reinit(cell);
      fe_values[displacement_].get_function_symmetric_gradients(solution_, gradients);
      fe_values[displacement_].get_function_values(solution_, values);
      for (unsigned int q = 0; q < quadrature_.size(); ++q)
      {
        const Point<dim> &x = fe_values.quadrature_point(q);
        PointState &s = state(cell, q);
        s = step_->advance(s, strain3d<dim>(gradients[q], values[q], x), sources(x, old_time, new_time));
        if (!finite(s.stress))
          throw NumericalFailure(new_time, step,
                                 "a stress is not finite at x = " + std::to_string(x[0]) + ", " +
                                   std::to_string(x[dim - 1]) + " m");
      }
    }
}

template <int dim>
void ViscoelasticCylinder<dim>::run(unsigned int steps, double dt, const std::function<void(unsigned int)> &after_step)
{
  for (unsigned int n = 1; n <= steps; ++n)
  {
    solve_trial(dt);
    accept_trial(dt);
    after_step(n);
  }
}

template <int dim>
void ViscoelasticCylinder<dim>::solve_trial(double dt)
{
  if (dt != assembled_dt_)
  {
    step_ = std::make_unique<SolidStep>(solid_, dt);
    assemble_system();
    assembled_dt_ = dt;
  }
  const double old_time = time_, new_time = time_ + dt;
  make_constraints(new_time);
  assemble_rhs(old_time, new_time);
  solve_timestep(static_cast<long>(std::lround(new_time / dt)));
}

template <int dim>
void ViscoelasticCylinder<dim>::accept_trial(double dt)
{
  const double old_time = time_, new_time = time_ + dt;
  update_quadrature_point_history(old_time, new_time, static_cast<long>(std::lround(new_time / dt)));
  previous_solution_ = accepted_solution_;
  accepted_solution_ = owned_solution_;
  time_ = new_time;
}

// @sect3{Measurements}

template <int dim>
PointState &ViscoelasticCylinder<dim>::state(const typename DoFHandler<dim>::active_cell_iterator &cell, unsigned int q)
{
  return states_[cell->active_cell_index() * quadrature_.size() + q];
}

template <int dim>
const PointState &ViscoelasticCylinder<dim>::state(const typename DoFHandler<dim>::active_cell_iterator &cell,
                                                   unsigned int q) const
{
  return states_[cell->active_cell_index() * quadrature_.size() + q];
}

template <int dim>
unsigned long ViscoelasticCylinder<dim>::n_cells() const
{
  return triangulation_.n_global_active_cells();
}

template <int dim>
double ViscoelasticCylinder<dim>::cell_size() const
{
  return std::pow(GridTools::volume(triangulation_, mapping_) / n_cells(), 1.0 / dim);
}

template <int dim>
double ViscoelasticCylinder<dim>::platen_force() const
{
  return platen_reaction(
    [this](const auto &cell, const FEValues<dim> &, std::vector<Tensor3> &stresses)
    {
      for (unsigned int q = 0; q < quadrature_.size(); ++q)
        stresses[q] = state(cell, q).stress;
    });
}

template <int dim>
double ViscoelasticCylinder<dim>::trial_platen_force() const
{
  std::vector<SymmetricTensor<2, dim>> gradients(quadrature_.size());
  std::vector<Tensor<1, dim>> values(quadrature_.size());
  const double old_time = time_, new_time = time_ + assembled_dt_;
  return platen_reaction(
    [&](const auto &cell, const FEValues<dim> &fe_values, std::vector<Tensor3> &stresses)
    {
      fe_values[displacement_].get_function_symmetric_gradients(solution_, gradients);
      fe_values[displacement_].get_function_values(solution_, values);
      for (unsigned int q = 0; q < quadrature_.size(); ++q)
      {
        const Point<dim> &x = fe_values.quadrature_point(q);
        stresses[q] =
          step_->advance(state(cell, q), strain3d<dim>(gradients[q], values[q], x), sources(x, old_time, new_time))
            .stress;
      }
    });
}

template <int dim>
double ViscoelasticCylinder<dim>::platen_reaction(const StressAtPoints &stress_at) const
{
  FEValues<dim> fe_values(mapping_, fe_, quadrature_,
                          update_values | update_gradients | update_quadrature_points | update_JxW_values);
  const unsigned int n = fe_.n_dofs_per_cell();
  std::vector<types::global_dof_index> dofs(n);
  std::vector<Tensor3> strains(n), stresses(quadrature_.size());
  double force = 0;
  for (const auto &cell : dof_handler_.active_cell_iterators())
    if (cell->is_locally_owned())
    {
      cell->get_dof_indices(dofs);
      if (std::none_of(dofs.begin(), dofs.end(), [&](auto i) { return top_axial_dofs_.is_element(i); }))
        continue;
      fe_values.reinit(cell);
      stress_at(cell, fe_values, stresses);
      for (unsigned int q = 0; q < quadrature_.size(); ++q)
      {
        const double w = fe_values.JxW(q) * volume_weight(fe_values.quadrature_point(q));
        shape_strains(fe_values, q, strains);
        for (unsigned int i = 0; i < n; ++i)
          if (top_axial_dofs_.is_element(dofs[i]))
            force += strains[i] * stresses[q] * w;
      }
    }
  return Utilities::MPI::sum(force, communicator_);
}

template <int dim>
double ViscoelasticCylinder<dim>::platen_area() const
{
  const QGauss<dim - 1> face_quadrature(fe_.degree + 1);
  FEFaceValues<dim> fe_face(mapping_, fe_, face_quadrature, update_quadrature_points | update_JxW_values);
  double area = 0;
  for (const auto &cell : dof_handler_.active_cell_iterators())
    if (cell->is_locally_owned())
      for (const unsigned int f : cell->face_indices())
        if (cell->face(f)->at_boundary() && cell->face(f)->boundary_id() == boundary::top)
        {
          fe_face.reinit(cell, f);
          for (unsigned int q = 0; q < face_quadrature.size(); ++q)
            area += fe_face.JxW(q) * (dim == 2 ? 2 * pi * fe_face.quadrature_point(q)[0] : 1.0);
        }
  return Utilities::MPI::sum(area, communicator_);
}

template <int dim>
double ViscoelasticCylinder<dim>::mid_height_radial_displacement() const
{
  const double tol = 1e-8 * shape_.radius;
  double sum = 0, count = 0;
  for (const auto &cell : dof_handler_.active_cell_iterators())
    if (cell->is_locally_owned())
      for (const unsigned int v : cell->vertex_indices())
      {
        const Point<dim> &x = cell->vertex(v);
        const bool on_line = dim == 2 || std::abs(x[1]) < tol;
        if (on_line && std::abs(x[0] - shape_.radius) < tol && std::abs(x[dim - 1] - shape_.height / 2) < tol)
        {
          sum += solution_(cell->vertex_dof_index(v, 0));
          count += 1;
        }
      }
  sum = Utilities::MPI::sum(sum, communicator_);
  count = Utilities::MPI::sum(count, communicator_);
  return count > 0 ? sum / count : std::nan("");
}

template <int dim>
void ViscoelasticCylinder<dim>::for_each_point(
  const std::function<void(const Point<dim> &, double, const PointState &)> &f) const
{
  FEValues<dim> fe_values(mapping_, fe_, quadrature_, update_quadrature_points | update_JxW_values);
  for (const auto &cell : dof_handler_.active_cell_iterators())
    if (cell->is_locally_owned())
    {
      fe_values.reinit(cell);
      for (unsigned int q = 0; q < quadrature_.size(); ++q)
      {
        const Point<dim> &x = fe_values.quadrature_point(q);
        f(x, fe_values.JxW(q) * volume_weight(x), state(cell, q));
      }
    }
}

template <int dim>
std::string ViscoelasticCylinder<dim>::output_results(const std::string &directory, unsigned int counter) const
{
  // Cell averages of the stress (compression positive axial stress,
  // tension positive components) and of the Kelvin strain's magnitude.
  Vector<float> axial(triangulation_.n_active_cells()), radial(axial), hoop(axial), kelvin(axial), ranks(axial);
  for (const auto &cell : dof_handler_.active_cell_iterators())
    if (cell->is_locally_owned())
    {
      Tensor3 stress, strain;
      for (unsigned int q = 0; q < quadrature_.size(); ++q)
      {
        stress += state(cell, q).stress / quadrature_.size();
        strain += state(cell, q).kelvin / quadrature_.size();
      }
      const auto k = cell->active_cell_index();
      axial(k) = -stress[2][2];
      radial(k) = stress[0][0];
      hoop(k) = stress[1][1];
      kelvin(k) = strain.norm();
      ranks(k) = triangulation_.locally_owned_subdomain();
    }
  DataOut<dim> out;
  out.attach_dof_handler(dof_handler_);
  const std::vector<DataComponentInterpretation::DataComponentInterpretation> vector(
    dim, DataComponentInterpretation::component_is_part_of_vector);
  out.add_data_vector(solution_, std::vector<std::string>(dim, "displacement_m"), DataOut<dim>::type_dof_data, vector);
  out.add_data_vector(axial, "axial_stress_compression_pa");
  out.add_data_vector(radial, dim == 2 ? "radial_stress_pa" : "stress_xx_pa");
  out.add_data_vector(hoop, dim == 2 ? "hoop_stress_pa" : "stress_yy_pa");
  out.add_data_vector(kelvin, "kelvin_strain_norm");
  out.add_data_vector(ranks, "mpi_rank");
  out.build_patches(mapping_, fe_.degree);
  return out.write_vtu_with_pvtu_record(directory + "/", "cylinder", counter, communicator_, 4);
}

template class ViscoelasticCylinder<2>;
template class ViscoelasticCylinder<3>;
} // namespace continuum
