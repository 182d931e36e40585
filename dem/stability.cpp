#include "dem/stability.h"

#include "dem/simulation.h"

#include <Eigen/Core>
#include <gsl/gsl_eigen.h>
#include <gsl/gsl_matrix.h>

#include <cmath>
#include <memory>
#include <vector>

namespace dem
{
namespace
{
Eigen::Matrix3d cross_matrix(const Vec3 &v)
{
  Eigen::Matrix3d m;
  m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return m;
}

/// Adds B^T D B for one contact.  Relative displacement at the contact point
/// (second minus first): delta = u_B + a_B [n]x theta_B - u_A + a_A [n]x theta_A,
/// so B = [-I, a_A [n]x, I, a_B [n]x] on (u_A, theta_A, u_B, theta_B).
void add_contact(gsl_matrix &K, int first, int second, const Vec3 &n, double arm_first, double arm_second, double kn,
                 double ks)
{
  const Eigen::Matrix3d P = Eigen::Matrix3d::Identity() - n * n.transpose();
  const Eigen::Matrix3d D = kn * n * n.transpose() + ks * P;
  Eigen::Matrix<double, 3, 12> B = Eigen::Matrix<double, 3, 12>::Zero();
  B.block<3, 3>(0, 0) = -Eigen::Matrix3d::Identity();
  B.block<3, 3>(0, 3) = arm_first * cross_matrix(n);
  B.block<3, 3>(0, 6) = Eigen::Matrix3d::Identity();
  B.block<3, 3>(0, 9) = arm_second * cross_matrix(n);
  const Eigen::Matrix<double, 12, 12> k = B.transpose() * D * B;
  const int base[2] = {6 * first, 6 * second};
  for (int a = 0; a < 2; ++a)
    for (int b = 0; b < 2; ++b)
      if (base[a] >= 0 && base[b] >= 0)
        for (int i = 0; i < 6; ++i)
          for (int j = 0; j < 6; ++j)
            *gsl_matrix_ptr(&K, base[a] + i, base[b] + j) += k(6 * a + i, 6 * b + j);
}

struct MatrixFree
{
  void operator()(gsl_matrix *m) const { gsl_matrix_free(m); }
};
struct VectorFree
{
  void operator()(gsl_vector *v) const { gsl_vector_free(v); }
};
struct WorkspaceFree
{
  void operator()(gsl_eigen_symm_workspace *w) const { gsl_eigen_symm_free(w); }
};
} // namespace

double exact_max_eigenvalue(const Simulation &sim)
{
  const ParticleStore &p = sim.particles();
  const int n = p.size();
  if (n == 0)
    return 0;
  const std::unique_ptr<gsl_matrix, MatrixFree> stiffness(gsl_matrix_calloc(6 * n, 6 * n));
  gsl_matrix &K = *stiffness;
  for (const Contact &c : sim.contacts().entries())
  {
    if (!c.state.touching())
      continue;
    const ContactParams k = sim.model().tangent_stiffness(sim.contacts().params(c));
    const Vec3 d = p.position[c.second] - p.position[c.first];
    const double overlap = p.radius[c.first] + p.radius[c.second] - d.norm();
    add_contact(K, c.first, c.second, d.normalized(), p.radius[c.first] - 0.5 * overlap,
                p.radius[c.second] - 0.5 * overlap, k.kn, k.ks);
  }
  const WallSet &walls = sim.walls();
  for (WallIndex w = 0; w < walls.size(); ++w)
    for (Index b = 0; b < n; ++b)
    {
      const ContactState &s = walls.state(w, b);
      if (!walls[w].enabled || !s.touching())
        continue;
      const ContactGeometry g = walls.touch(w, p.position[b], p.radius[b], p.velocity[b], p.spin[b]).geometry;
      // The wall is the first entity; index -1 drops its (infinite-mass) dofs.
      add_contact(K, -1, b, g.normal, 0, g.arm_second, in_series(p.kn[b], walls[w].props.kn),
                  in_series(p.ks[b], walls[w].props.ks));
    }
  // A = M^-1/2 K M^-1/2 on the free dofs, in place; GSL's symmetric
  // eigensolver (Householder tridiagonalisation, implicit QL) then gives
  // every eigenvalue.
  std::vector<double> scale(6 * n);
  for (int b = 0; b < n; ++b)
    for (int k = 0; k < 3; ++k)
    {
      scale[6 * b + k] = std::sqrt(p.inv_mass[b]);
      scale[6 * b + 3 + k] = std::sqrt(p.inv_inertia[b]);
    }
  for (int i = 0; i < 6 * n; ++i)
    for (int j = 0; j < 6 * n; ++j)
      *gsl_matrix_ptr(&K, i, j) *= scale[i] * scale[j];
  const std::unique_ptr<gsl_vector, VectorFree> eigenvalues(gsl_vector_alloc(6 * n));
  const std::unique_ptr<gsl_eigen_symm_workspace, WorkspaceFree> workspace(gsl_eigen_symm_alloc(6 * n));
  gsl_eigen_symm(&K, eigenvalues.get(), workspace.get());
  return gsl_vector_max(eigenvalues.get());
}

double exact_stability_limit(const Simulation &sim) { return critical_step(exact_max_eigenvalue(sim)); }
} // namespace dem
