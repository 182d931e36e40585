#include "continuum/cylinder.h"

#include "continuum/viscoelastic_cylinder.h"

#include <deal.II/base/data_out_base.h>
#include <deal.II/base/function.h>
#include <deal.II/base/mpi.h>
#include <deal.II/numerics/vector_tools.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace continuum
{
using namespace dealii;

ParallelInfo parallel_info()
{
  int initialised = 0;
  MPI_Initialized(&initialised);
  if (!initialised)
  {
    // The demvv executable and the tests do not start MPI themselves: the
    // first continuum computation does, for the life of the process (one
    // rank without mpirun).  Threads: one per rank, so that ranks x
    // threads never exceeds the cores mpirun was given.
    //
    // deal.II's MPI_InitFinalize is deliberately never destroyed: its
    // destructor empties deal.II's vector pools, function-local statics
    // that are created later and so destroyed earlier at exit.  MPI itself
    // is finalised by an exit handler registered now, which runs after
    // every static created later (those pools included) is gone.
    static int argc = 1;
    static char name[] = "demvv";
    static char *args[] = {name, nullptr};
    static char **argv = args;
    new Utilities::MPI::MPI_InitFinalize(argc, argv, 1);
    std::atexit(
      []
      {
        int finalised = 0;
        MPI_Finalized(&finalised);
        if (!finalised)
          MPI_Finalize();
      });
  }
  return {Utilities::MPI::this_mpi_process(MPI_COMM_WORLD), Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD)};
}

namespace
{
/// Platens: the bottom fixed, the top moved down by H x strain rate x t, by
/// H eps(t), or to where set_top put it (force control); bonded platens
/// also hold the in-plane displacement; symmetry on the axis (and on the
/// quarter's planes in 3D).
template <int dim>
class PlatenLoading : public Loading<dim>
{
public:
  explicit PlatenLoading(const CylinderSpec &spec) : spec_(spec) {}

  void constrain(const Mapping<dim> & /*mapping*/, const DoFHandler<dim> &dof_handler, double time,
                 AffineConstraints<double> &c) const override
  {
    const auto fix = [&](types::boundary_id id, unsigned int component, double value)
    {
      ComponentMask mask(dim, false);
      mask.set(component, true);
      VectorTools::interpolate_boundary_values(dof_handler, id, Functions::ConstantFunction<dim>(value, dim), c, mask);
    };
    fix(boundary::symmetry_x, 0, 0);
    if (dim == 3)
      fix(boundary::symmetry_y, 1, 0);
    fix(boundary::bottom, dim - 1, 0);
    fix(boundary::top, dim - 1, top_displacement(time));
    if (spec_.platens == Platens::bonded)
      for (unsigned int d = 0; d + 1 < dim; ++d)
      {
        fix(boundary::bottom, d, 0);
        fix(boundary::top, d, 0);
      }
  }

  /// Axial displacement of the top platen at time t [m], tension positive.
  double top_displacement(double time) const
  {
    if (spec_.axial_stress_history)
      return chosen_top_;
    if (spec_.axial_strain_history)
      return -spec_.height * spec_.axial_strain_history(time);
    return -spec_.strain_rate * spec_.height * time;
  }
  /// Force control: the top displacement of the coming solve [m].
  void set_top(double displacement) { chosen_top_ = displacement; }

private:
  CylinderSpec spec_;
  double chosen_top_ = 0;
};

/// Writes `text` to `path` through a temporary file and a rename, so that
/// a reader never sees half of it.
void write_whole_file(const std::string &path, const std::string &text)
{
  const std::string tmp = path + ".tmp";
  std::ofstream out(tmp);
  out << text;
  out.close();
  if (!out || std::rename(tmp.c_str(), path.c_str()) != 0)
    throw std::runtime_error(path + ": cannot write the ParaView time series");
}
} // namespace

class CompressionTest::Impl
{
public:
  virtual ~Impl() = default;
  virtual void run(const std::function<void(const CylinderStep &)> &on_step) = 0;
  virtual std::string mesh_edges_csv() const = 0;
  CylinderMesh mesh;
};

namespace
{
template <int dim>
class CompressionTestFor : public CompressionTest::Impl
{
public:
  explicit CompressionTestFor(const CylinderSpec &spec)
    : spec_(spec), loading_(spec),
      cylinder_({spec.radius, spec.height}, spec.solid, {spec.degree, spec.refinements, spec.solver_tolerance},
                loading_, MPI_COMM_WORLD)
  {
    // The quarter model carries a quarter of the force.
    quarters_ = dim == 3 ? 4 : 1;
    mesh.cells = cylinder_.n_cells();
    mesh.dofs = cylinder_.n_dofs();
    mesh.cell_size = cylinder_.cell_size();
    mesh.platen_area = numbers::PI * spec.radius * spec.radius;
    mesh.mesh_platen_area = quarters_ * cylinder_.platen_area();
    const bool history = spec.axial_strain_history || spec.axial_stress_history;
    mesh.time_step = (history ? spec.duration : spec.final_strain / spec.strain_rate) / spec.time_steps;
    mesh.ranks = Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD);
  }

  void run(const std::function<void(const CylinderStep &)> &on_step) override
  {
    const bool paraview = !spec_.paraview_directory.empty();
    if (paraview && Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
      std::filesystem::create_directories(spec_.paraview_directory);
    MPI_Barrier(MPI_COMM_WORLD);
    report(0, on_step);
    if (paraview)
      write_frame(0);
    const auto after_step = [&](unsigned int n)
    {
      report(n, on_step);
      if (paraview && (n == spec_.time_steps || (spec_.paraview_every > 0 && n % spec_.paraview_every == 0)))
        write_frame(n);
    };
    if (spec_.axial_stress_history)
      run_force_controlled(after_step);
    else
      cylinder_.run(spec_.time_steps, mesh.time_step, after_step);
  }

  std::string mesh_edges_csv() const override
  {
    std::ostringstream o;
    o.precision(17);
    o << "# cell edges: " << (dim == 2 ? "r" : "x") << " [m], z [m]; one edge per block\n";
    for (const auto &cell : cylinder_.triangulation().active_cell_iterators())
      if (cell->is_locally_owned())
        for (unsigned int l = 0; l < GeometryInfo<dim>::lines_per_cell; ++l)
        {
          const auto line = cell->line(l);
          for (unsigned int v = 0; v < 2; ++v)
            o << line->vertex(v)[0] << "," << line->vertex(v)[dim - 1] << "\n";
          o << "\n";
        }
    return o.str();
  }

private:
  /// Each step: a trial at the extrapolated platen displacement, then the
  /// solve at the displacement whose force is the prescribed one (the force
  /// is affine in it, with the step's platen stiffness found once).
  void run_force_controlled(const std::function<void(unsigned int)> &after_step)
  {
    const double dt = mesh.time_step;
    double stiffness = 0, last = 0, before_last = 0;
    for (unsigned int n = 1; n <= spec_.time_steps; ++n)
    {
      const double target = -spec_.axial_stress_history(cylinder_.time() + dt) * mesh.platen_area / quarters_;
      const double guess = 2 * last - before_last;
      loading_.set_top(guess);
      cylinder_.solve_trial(dt);
      const double force = cylinder_.trial_platen_force();
      if (stiffness == 0)
      {
        const double probe = -1e-6 * spec_.height;
        loading_.set_top(guess + probe);
        cylinder_.solve_trial(dt);
        stiffness = (cylinder_.trial_platen_force() - force) / probe;
      }
      before_last = last;
      last = guess + (target - force) / stiffness;
      loading_.set_top(last);
      cylinder_.solve_trial(dt);
      cylinder_.accept_trial(dt);
      after_step(n);
    }
  }

  void report(unsigned int n, const std::function<void(const CylinderStep &)> &on_step) const
  {
    CylinderStep s;
    s.step = n;
    s.time = cylinder_.time();
    const bool history = spec_.axial_strain_history || spec_.axial_stress_history;
    s.axial_strain = history ? -loading_.top_displacement(s.time) / spec_.height + 0.0 : spec_.strain_rate * s.time;
    // (+ 0.0 turns the -0 of the unloaded state into 0 in the outputs.)
    s.axial_stress = -quarters_ * cylinder_.platen_force() / mesh.platen_area + 0.0;
    s.radial_strain = -cylinder_.mid_height_radial_displacement() / spec_.radius + 0.0;
    s.iterations = n > 0 ? cylinder_.last_iterations() : 0;
    on_step(s);
  }

  void write_frame(unsigned int n)
  {
    const std::string record = cylinder_.output_results(spec_.paraview_directory, n);
    frames_.emplace_back(cylinder_.time(), record);
    if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
    {
      std::ostringstream pvd;
      DataOutBase::write_pvd_record(pvd, frames_);
      write_whole_file(spec_.paraview_directory + "/cylinder.pvd", pvd.str());
    }
  }

  CylinderSpec spec_;
  PlatenLoading<dim> loading_;
  ViscoelasticCylinder<dim> cylinder_;
  double quarters_ = 1;
  std::vector<std::pair<double, std::string>> frames_;
};

std::unique_ptr<CompressionTest::Impl> make_test(const CylinderSpec &spec)
{
  parallel_info();
  if (spec.geometry == Geometry::axisymmetric)
    return std::make_unique<CompressionTestFor<2>>(spec);
  return std::make_unique<CompressionTestFor<3>>(spec);
}
} // namespace

CompressionTest::CompressionTest(const CylinderSpec &spec) : impl_(make_test(spec)) {}
CompressionTest::~CompressionTest() = default;
const CylinderMesh &CompressionTest::mesh() const { return impl_->mesh; }
void CompressionTest::run(const std::function<void(const CylinderStep &)> &on_step) { impl_->run(on_step); }
std::string CompressionTest::mesh_edges_csv() const { return impl_->mesh_edges_csv(); }
} // namespace continuum
