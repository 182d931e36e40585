#include "continuum/mms.h"

#include "continuum/viscoelastic_cylinder.h"

#include <deal.II/base/convergence_table.h>
#include <deal.II/base/function.h>
#include <deal.II/base/mpi.h>
#include <deal.II/numerics/vector_tools.h>

#include <cmath>
#include <functional>
#include <memory>
#include <sstream>

namespace continuum
{
using namespace dealii;

namespace
{
// @sect3{Spatial profiles}

/// A smooth displacement field [m]: value, gradient and its 3-D strain
/// ((r, theta, z) for dim = 2).
template <int dim>
class Profile
{
public:
  virtual ~Profile() = default;
  virtual Tensor<1, dim> value(const Point<dim> &x) const = 0;
  virtual Tensor<2, dim> gradient(const Point<dim> &x) const = 0;
  virtual Tensor3 strain(const Point<dim> &x) const = 0;
};

/// u_r = A r cos(a r) sin(b z + c), u_z = A L cos(a r) cos(b z + c): odd in
/// r for u_r, even for u_z, so regular on the axis; the hoop strain
/// A cos(a r) sin(b z + c) is written out (no division by r).
class AxisymmetricWave : public Profile<2>
{
public:
  AxisymmetricWave(double A, double L, double a, double b, double c) : A_(A), L_(L), a_(a), b_(b), c_(c) {}

  Tensor<1, 2> value(const Point<2> &x) const override
  {
    const double r = x[0], z = x[1];
    return Tensor<1, 2>(
      {A_ * r * std::cos(a_ * r) * std::sin(b_ * z + c_), A_ * L_ * std::cos(a_ * r) * std::cos(b_ * z + c_)});
  }

  Tensor<2, 2> gradient(const Point<2> &x) const override
  {
    const double r = x[0], z = x[1];
    const double ca = std::cos(a_ * r), sa = std::sin(a_ * r), sb = std::sin(b_ * z + c_), cb = std::cos(b_ * z + c_);
    Tensor<2, 2> g;
    g[0][0] = A_ * sb * (ca - a_ * r * sa);
    g[0][1] = A_ * r * ca * b_ * cb;
    g[1][0] = -A_ * L_ * a_ * sa * cb;
    g[1][1] = -A_ * L_ * b_ * ca * sb;
    return g;
  }

  Tensor3 strain(const Point<2> &x) const override
  {
    const Tensor<2, 2> g = gradient(x);
    Tensor3 e;
    e[0][0] = g[0][0];
    e[1][1] = A_ * std::cos(a_ * x[0]) * std::sin(b_ * x[1] + c_);
    e[2][2] = g[1][1];
    e[0][2] = 0.5 * (g[0][1] + g[1][0]);
    return e;
  }

private:
  double A_, L_, a_, b_, c_;
};

/// u_i = A L sin(k_i . x + c_i).
class CartesianWave : public Profile<3>
{
public:
  CartesianWave(double A, double L, const std::array<Tensor<1, 3>, 3> &k, const std::array<double, 3> &c)
    : A_(A), L_(L), k_(k), c_(c)
  {
  }

  Tensor<1, 3> value(const Point<3> &x) const override
  {
    Tensor<1, 3> u;
    for (unsigned int i = 0; i < 3; ++i)
      u[i] = A_ * L_ * std::sin(k_[i] * x + c_[i]);
    return u;
  }

  Tensor<2, 3> gradient(const Point<3> &x) const override
  {
    Tensor<2, 3> g;
    for (unsigned int i = 0; i < 3; ++i)
      g[i] = A_ * L_ * std::cos(k_[i] * x + c_[i]) * k_[i];
    return g;
  }

  Tensor3 strain(const Point<3> &x) const override { return symmetrize(gradient(x)); }

private:
  double A_, L_;
  std::array<Tensor<1, 3>, 3> k_;
  std::array<double, 3> c_;
};

/// u = G x.  In the axisymmetric model G must be diagonal (u_r = G_00 r),
/// so that the hoop strain is G_00 and the field is regular.
template <int dim>
class Affine : public Profile<dim>
{
public:
  explicit Affine(const Tensor<2, dim> &G) : G_(G) {}
  Tensor<1, dim> value(const Point<dim> &x) const override { return G_ * x; }
  Tensor<2, dim> gradient(const Point<dim> & /*x*/) const override { return G_; }
  Tensor3 strain(const Point<dim> &x) const override
  {
    if constexpr (dim == 2)
    {
      Tensor3 e;
      e[0][0] = e[1][1] = G_[0][0];
      e[2][2] = G_[1][1];
      (void)x;
      return e;
    }
    else
    {
      (void)x;
      return symmetrize(G_);
    }
  }

private:
  Tensor<2, dim> G_;
};

// @sect3{Time functions}

/// f(t) with f(0) = 0 and its derivative.
struct TimeFunction
{
  std::function<double(double)> value;
  std::function<double(double)> derivative;
};

/// c1 s + c2 s^2, s = t / T: integrated exactly by the trapezoidal update.
TimeFunction quadratic(double c1, double c2, double T)
{
  return {[=](double t) { return c1 * t / T + c2 * (t / T) * (t / T); },
          [=](double t) { return (c1 + 2 * c2 * t / T) / T; }};
}

/// sin(w s) + c (1 - exp(-k s)), s = t / T: not a polynomial.
TimeFunction transcendental(double w, double c, double k, double T)
{
  return {[=](double t) { return std::sin(w * t / T) + c * (1 - std::exp(-k * t / T)); },
          [=](double t) { return (w * std::cos(w * t / T) + c * k * std::exp(-k * t / T)) / T; }};
}

// @sect3{The manufactured solution}

template <int dim>
class Manufactured
{
public:
  Manufactured(const BurgersSolid &solid, std::unique_ptr<Profile<dim>> u, std::unique_ptr<Profile<dim>> kelvin,
               std::unique_ptr<Profile<dim>> dashpot, std::array<TimeFunction, 3> time, double length)
    : solid_(solid), shear_(solid.shear()), bulk_(solid.bulk_chain()), u_(std::move(u)), kelvin_(std::move(kelvin)),
      dashpot_(std::move(dashpot)), time_(std::move(time)), difference_step_(1e-3 * length)
  {
  }

  Tensor<1, dim> displacement(const Point<dim> &x, double t) const { return time_[0].value(t) * u_->value(x); }
  Tensor<2, dim> gradient(const Point<dim> &x, double t) const { return time_[0].value(t) * u_->gradient(x); }
  Tensor3 kelvin(const Point<dim> &x, double t) const { return time_[1].value(t) * internal(kelvin_->strain(x)); }
  Tensor3 dashpot(const Point<dim> &x, double t) const { return time_[2].value(t) * internal(dashpot_->strain(x)); }

  /// sigma = C0 : (eps(u) - eps_k - eps_v), instantaneous moduli [Pa].
  Tensor3 stress(const Point<dim> &x, double t) const
  {
    const Tensor3 elastic = time_[0].value(t) * u_->strain(x) - kelvin(x, t) - dashpot(x, t);
    return 2 * shear_.maxwell_spring * deviator(elastic) +
           solid_.bulk_modulus() * trace(elastic) * unit_symmetric_tensor<3>();
  }

  /// g = d eps/dt minus the model's rate at the manufactured state [1/s].
  PointSources sources(const Point<dim> &x, double t) const
  {
    const Tensor3 s = stress(x, t), eps_k = kelvin(x, t);
    const Tensor3 I = unit_symmetric_tensor<3>();
    Tensor3 kelvin_rate = (deviator(s) - 2 * shear_.kelvin_spring * deviator(eps_k)) / (2 * shear_.kelvin_dashpot);
    Tensor3 dashpot_rate = deviator(s) / (2 * shear_.maxwell_dashpot);
    if (solid_.bulk == BulkResponse::same_shape)
    {
      const double p = trace(s) / 3;
      kelvin_rate += (p - bulk_.kelvin_spring * trace(eps_k)) / bulk_.kelvin_dashpot / 3 * I;
      dashpot_rate += p / bulk_.maxwell_dashpot / 3 * I;
    }
    return {time_[1].derivative(t) * internal(kelvin_->strain(x)) - kelvin_rate,
            time_[2].derivative(t) * internal(dashpot_->strain(x)) - dashpot_rate};
  }

  /// b = -div sigma [N/m^3], cylindrical for dim = 2.  The derivatives of
  /// the (analytic) stress are fourth-order central differences with step
  /// 1e-3 of the radius: truncation ~ (k delta)^4 / 30 ~ 1e-12 relative for
  /// the wave numbers used, round-off ~ 1e-16 / (k delta) ~ 1e-13, both far
  /// below the discretisation errors measured (>= 1e-9).
  Tensor<1, dim> body_force(const Point<dim> &x, double t) const
  {
    const double h = difference_step_;
    const auto derivative = [&](unsigned int j)
    {
      Tensor<1, dim> e;
      e[j] = h;
      return (stress(x - 2 * e, t) - 8 * stress(x - e, t) + 8 * stress(x + e, t) - stress(x + 2 * e, t)) / (12 * h);
    };
    Tensor<1, dim> b;
    if constexpr (dim == 2)
    {
      // (r, theta, z): div sigma_r = d_r s_rr + d_z s_rz + (s_rr - s_tt)/r,
      //                div sigma_z = d_r s_rz + d_z s_zz + s_rz / r.
      const Tensor3 s = stress(x, t), dr = derivative(0), dz = derivative(1);
      b[0] = -(dr[0][0] + dz[0][2] + (s[0][0] - s[1][1]) / x[0]);
      b[1] = -(dr[0][2] + dz[2][2] + s[0][2] / x[0]);
    }
    else
      for (unsigned int j = 0; j < dim; ++j)
      {
        const Tensor3 d = derivative(j);
        for (unsigned int i = 0; i < dim; ++i)
          b[i] -= d[i][j];
      }
    return b;
  }

private:
  /// Internal strains are deviatoric when the bulk response is elastic.
  Tensor3 internal(const Tensor3 &e) const { return solid_.bulk == BulkResponse::elastic ? deviator(e) : e; }

  BurgersSolid solid_;
  BurgersChain shear_, bulk_;
  std::unique_ptr<Profile<dim>> u_, kelvin_, dashpot_;
  std::array<TimeFunction, 3> time_; ///< phi, psi_k, psi_v
  double difference_step_;
};

/// The manufactured displacement as a deal.II Function (boundary values, error norms).
template <int dim>
class ExactDisplacement : public Function<dim>
{
public:
  explicit ExactDisplacement(const Manufactured<dim> &m) : Function<dim>(dim), m_(m) {}
  double value(const Point<dim> &x, unsigned int component) const override
  {
    return m_.displacement(x, this->get_time())[component];
  }
  Tensor<1, dim> gradient(const Point<dim> &x, unsigned int component) const override
  {
    return m_.gradient(x, this->get_time())[component];
  }

private:
  const Manufactured<dim> &m_;
};

template <int dim>
class ManufacturedLoading : public Loading<dim>
{
public:
  explicit ManufacturedLoading(const Manufactured<dim> &m) : m_(m) {}

  void constrain(const Mapping<dim> &mapping, const DoFHandler<dim> &dof_handler, double time,
                 AffineConstraints<double> &c) const override
  {
    ExactDisplacement<dim> exact(m_);
    exact.set_time(time);
    std::map<types::boundary_id, const Function<dim> *> full{
      {boundary::bottom, &exact}, {boundary::top, &exact}, {boundary::lateral, &exact}};
    if (dim == 3)
    {
      full[boundary::symmetry_x] = &exact;
      full[boundary::symmetry_y] = &exact;
    }
    else
    {
      // The axis: u_r = 0 only; u_z is free (its natural condition is met
      // by any regular axisymmetric field).
      ComponentMask radial(dim, false);
      radial.set(0, true);
      VectorTools::interpolate_boundary_values(mapping, dof_handler, boundary::symmetry_x,
                                               Functions::ZeroFunction<dim>(dim), c, radial);
    }
    VectorTools::interpolate_boundary_values(mapping, dof_handler, full, c);
  }

  Tensor<1, dim> body_force(const Point<dim> &x, double time) const override { return m_.body_force(x, time); }
  PointSources internal_sources(const Point<dim> &x, double time) const override { return m_.sources(x, time); }
  bool has_sources() const override { return true; }

private:
  const Manufactured<dim> &m_;
};

// @sect3{The two studies}

std::unique_ptr<Manufactured<2>> make_solution(const MmsSpec &s, std::integral_constant<int, 2>)
{
  const double R = s.radius, H = s.height, T = s.duration;
  if (s.variable == MmsVariable::space)
    return std::make_unique<Manufactured<2>>(
      s.solid, std::make_unique<AxisymmetricWave>(1e-3, R, 1.7 / R, 2.3 / H, 0.4),
      std::make_unique<AxisymmetricWave>(3e-4, R, 1.1 / R, 1.3 / H, 0.9),
      std::make_unique<AxisymmetricWave>(2e-4, R, 2.1 / R, 0.7 / H, -0.3),
      std::array<TimeFunction, 3>{{quadratic(1.0, 0.5, T), quadratic(0.3, 0.4, T), quadratic(0.2, 0.6, T)}}, R);
  const auto diagonal = [](double rr, double zz)
  {
    Tensor<2, 2> G;
    G[0][0] = rr;
    G[1][1] = zz;
    return G;
  };
  return std::make_unique<Manufactured<2>>(
    s.solid, std::make_unique<Affine<2>>(diagonal(0.4e-3, -1e-3)),
    std::make_unique<Affine<2>>(diagonal(0.2e-3, -0.5e-3)), std::make_unique<Affine<2>>(diagonal(-0.1e-3, 0.3e-3)),
    std::array<TimeFunction, 3>{
      {transcendental(1.7, 0.3, 2.3, T), transcendental(1.1, 0.5, 1.3, T), transcendental(2.1, -0.4, 0.7, T)}},
    R);
}

std::unique_ptr<Manufactured<3>> make_solution(const MmsSpec &s, std::integral_constant<int, 3>)
{
  const double R = s.radius, H = s.height, T = s.duration;
  if (s.variable == MmsVariable::space)
  {
    const auto wave = [&](double A, double shift)
    {
      const std::array<Tensor<1, 3>, 3> k = {{Tensor<1, 3>({1.3 / R, 0.6 / R, 0.8 / H}),
                                              Tensor<1, 3>({0.5 / R, 1.4 / R, 1.1 / H}),
                                              Tensor<1, 3>({0.9 / R, 0.7 / R, 1.9 / H})}};
      return std::make_unique<CartesianWave>(A, R, k, std::array<double, 3>{{0.3 + shift, -0.2 + shift, 0.7 + shift}});
    };
    return std::make_unique<Manufactured<3>>(
      s.solid, wave(1e-3, 0), wave(3e-4, 0.5), wave(2e-4, -0.8),
      std::array<TimeFunction, 3>{{quadratic(1.0, 0.5, T), quadratic(0.3, 0.4, T), quadratic(0.2, 0.6, T)}}, R);
  }
  const auto matrix = [](double a, double b, double c, double d)
  {
    Tensor<2, 3> G;
    G[0][0] = a;
    G[1][1] = b;
    G[2][2] = c;
    G[0][1] = G[1][0] = d;
    G[1][2] = 0.5 * d;
    G[0][2] = -0.3 * d;
    return G;
  };
  return std::make_unique<Manufactured<3>>(
    s.solid, std::make_unique<Affine<3>>(matrix(0.4e-3, 0.3e-3, -1e-3, 0.2e-3)),
    std::make_unique<Affine<3>>(matrix(0.2e-3, -0.1e-3, -0.5e-3, 0.1e-3)),
    std::make_unique<Affine<3>>(matrix(-0.1e-3, 0.2e-3, 0.3e-3, -0.1e-3)),
    std::array<TimeFunction, 3>{
      {transcendental(1.7, 0.3, 2.3, T), transcendental(1.1, 0.5, 1.3, T), transcendental(2.1, -0.4, 0.7, T)}},
    R);
}

/// Relative errors of the cylinder's solution against the manufactured one at time t.
template <int dim>
void measure(const ViscoelasticCylinder<dim> &cylinder, const Manufactured<dim> &m, double t, unsigned int degree,
             MmsLevel &level)
{
  ExactDisplacement<dim> exact(m);
  exact.set_time(t);
  const ScalarFunctionFromFunctionObject<dim> weight([](const Point<dim> &x) { return volume_weight(x); });
  const QGauss<dim> quadrature(degree + 2);
  TrilinosWrappers::MPI::Vector zero(cylinder.solution());
  zero = 0;
  const auto norm = [&](const TrilinosWrappers::MPI::Vector &v, VectorTools::NormType type)
  {
    Vector<float> cellwise(cylinder.triangulation().n_active_cells());
    VectorTools::integrate_difference(cylinder.mapping(), cylinder.dof_handler(), v, exact, cellwise, quadrature, type,
                                      &weight);
    return VectorTools::compute_global_error(cylinder.triangulation(), cellwise, type);
  };
  level.displacement_l2 = norm(cylinder.solution(), VectorTools::L2_norm) / norm(zero, VectorTools::L2_norm);
  level.displacement_h1 = norm(cylinder.solution(), VectorTools::H1_seminorm) / norm(zero, VectorTools::H1_seminorm);

  double sums[4] = {0, 0, 0, 0}; // stress error, stress, Kelvin error, Kelvin
  cylinder.for_each_point(
    [&](const Point<dim> &x, double w, const PointState &s)
    {
      const Tensor3 stress = m.stress(x, t), kelvin = m.kelvin(x, t);
      const Tensor3 stress_error = s.stress - stress, kelvin_error = s.kelvin - kelvin;
      sums[0] += stress_error * stress_error * w;
      sums[1] += stress * stress * w;
      sums[2] += kelvin_error * kelvin_error * w;
      sums[3] += kelvin * kelvin * w;
    });
  Utilities::MPI::sum(ArrayView<const double>(sums, 4), cylinder.communicator(), ArrayView<double>(sums, 4));
  level.stress_l2 = std::sqrt(sums[0] / sums[1]);
  level.kelvin_l2 = std::sqrt(sums[2] / sums[3]);
}

template <int dim>
std::vector<MmsLevel> study(const MmsSpec &spec)
{
  const auto solution = make_solution(spec, std::integral_constant<int, dim>());
  const ManufacturedLoading<dim> loading(*solution);
  std::vector<MmsLevel> out;
  for (const unsigned int level : spec.levels)
  {
    const bool space = spec.variable == MmsVariable::space;
    const unsigned int refinements = space ? level : spec.refinements;
    const unsigned int steps = space ? spec.time_steps : spec.time_steps << level;
    ViscoelasticCylinder<dim> cylinder({spec.radius, spec.height}, spec.solid,
                                       {spec.degree, refinements, spec.solver_tolerance}, loading, MPI_COMM_WORLD);
    const double dt = spec.duration / steps;
    cylinder.run(steps, dt, [](unsigned int) {});
    MmsLevel row;
    row.level = level;
    row.cell_size = cylinder.cell_size();
    row.time_step = dt;
    row.cells = cylinder.n_cells();
    row.dofs = cylinder.n_dofs();
    row.steps = steps;
    measure(cylinder, *solution, cylinder.time(), spec.degree, row);
    out.push_back(row);
  }
  return out;
}
} // namespace

std::vector<MmsLevel> run_mms(const MmsSpec &spec)
{
  parallel_info();
  return spec.geometry == Geometry::axisymmetric ? study<2>(spec) : study<3>(spec);
}

std::string mms_convergence_text(const std::vector<MmsLevel> &levels, MmsVariable variable)
{
  ConvergenceTable table;
  const bool space = variable == MmsVariable::space;
  const char *errors[] = {"L2(u)", "H1(u)", "L2(stress)", "L2(kelvin)"};
  for (const MmsLevel &l : levels)
  {
    table.add_value("level", l.level);
    table.add_value("cells", static_cast<unsigned int>(l.cells));
    table.add_value("dofs", static_cast<unsigned int>(l.dofs));
    table.add_value(space ? "h [m]" : "dt [s]", space ? l.cell_size : l.time_step);
    table.add_value(errors[0], l.displacement_l2);
    table.add_value(errors[1], l.displacement_h1);
    table.add_value(errors[2], l.stress_l2);
    table.add_value(errors[3], l.kelvin_l2);
  }
  table.set_scientific(space ? "h [m]" : "dt [s]", true);
  for (const char *e : errors)
  {
    table.set_scientific(e, true);
    table.set_precision(e, 3);
    // Successive levels halve h (global refinement) or dt.
    table.evaluate_convergence_rates(e, ConvergenceTable::reduction_rate_log2);
  }
  std::ostringstream text;
  table.write_text(text, TableHandler::org_mode_table);
  return text.str();
}
} // namespace continuum
