#ifndef bsmpm_nitsche_boundary_h
#define bsmpm_nitsche_boundary_h

#include <deal.II/base/parameter_handler.h>

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/la_parallel_vector.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <bsmpm/boundary/boundary_curves.h>
#include <bsmpm/boundary/support_method.h>
#include <bsmpm/boundary/support_stress.h>
#include <bsmpm/geometry/background_grid.h>
#include <bsmpm/materials/material.h>
#include <bsmpm/points/q1_cell_kernel.h>
#include <bsmpm/verification/exact_solution.h>

#include <memory>
#include <vector>

namespace bsmpm
{
  using namespace dealii;

  /**
   * Supports on the B-spline boundary by Nitsche's method, a consistent and
   * well-conditioned rival of the implicit boundary method (method-notes
   * Sec. 7). On a support curve Gamma with outward normal n, symmetric
   * Nitsche adds to the weak form
   *
   *   - int (sigma(u) n) . v - int (sigma(v) n) . (u - g)
   *   + beta int (u - g) . v,            beta = gamma E / h,
   *
   * with every product projected on n for a roller and for a prescribed
   * normal displacement (g = g_n n). In the incremental form
   * of a load step, u - g is the increment and the traction sigma_n n of the
   * previous steps, read from the curve's points, enters the right-hand
   * side: it is the support's reaction so far.
   *
   * A SupportMethod, registered as "nitsche".
   */
  class NitscheBoundary : public SupportMethod
  {
  public:
    NitscheBoundary();

    static void
    declare_parameters(ParameterHandler &prm);
    void
    parse_parameters(ParameterHandler &prm) override;

    /**
     * Adds the Nitsche terms of all Nitsche supports on locally owned cells.
     * @p increment_factor scales the prescribed displacement to the
     * increment of this step (no fitted @p prescribed: Nitsche imposes the
     * prescribed values themselves). With a B-bar kernel, @p moments (by
     * active_cell_index) give each cell's centroid: the consistency terms
     * take the B-bar stress, the one the cell's stiffness is made of.
     *
     * In finite strain the consistency term - int (sigma(u) n) . v
     * and the reaction of the previous steps are left out: they depend on
     * the stress of the step's deformation and join the Newton system per
     * iteration (add_finite_strain_terms()). The symmetric term, which
     * multiplies u - g, keeps the elastic stiffness, and the penalty stays.
     */
    void
    assemble(const Context                                    &context,
             const LoadIncrement                              &increment,
             const LinearAlgebra::distributed::Vector<double> *prescribed,
             const std::vector<CellMoments>                   *moments,
             const AffineConstraints<double>                  &constraints,
             TrilinosWrappers::SparseMatrix                   &matrix,
             TrilinosWrappers::MPI::Vector                    &rhs,
             const BoundaryCurve *only = nullptr) override;

    /**
     * Finite strain (doc/finite-strain.md, "Supports in finite strain"):
     * the consistency term at the step's increment @p increment (with
     * ghost values) as an internal force, for DoF i
     *
     *   f_i = - int N_i . (P(f) n) ds,
     *
     * on the curve at the step's start (outward normal n, projected on n
     * for a roller or a normal displacement), f = 1 + grad w the grid's
     * relative deformation gradient and P the first Piola stress of
     * @p stress with the curve's state there (the nominal traction P n
     * replaces sigma_n n + C eps(u) n); added to @p internal_force, its
     * derivative to @p tangent unless nullptr, through @p constraints.
     * With @p only, that curve's supports alone.
     */
    void
    add_finite_strain_terms(
      const Context                                    &context,
      const LinearAlgebra::distributed::Vector<double> &increment,
      const SupportStress                              &stress,
      const AffineConstraints<double>                  &constraints,
      TrilinosWrappers::SparseMatrix                   *tangent,
      TrilinosWrappers::MPI::Vector                    &internal_force,
      const BoundaryCurve *only = nullptr) const override;

  private:
    double       penalty        = 100;
    unsigned int n_gauss_points = 4;
  };
} // namespace bsmpm

#endif
