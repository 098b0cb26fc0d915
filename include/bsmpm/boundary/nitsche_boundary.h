#ifndef bsmpm_nitsche_boundary_h
#define bsmpm_nitsche_boundary_h

#include <deal.II/base/parameter_handler.h>

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <bsmpm/boundary/boundary_curves.h>
#include <bsmpm/geometry/background_grid.h>
#include <bsmpm/materials/material.h>
#include <bsmpm/points/q1_cell_kernel.h>
#include <bsmpm/verification/exact_solution.h>

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
   */
  class NitscheBoundary
  {
  public:
    static void
    declare_parameters(ParameterHandler &prm);
    void
    parse_parameters(ParameterHandler &prm);

    /**
     * Adds the Nitsche terms of all Nitsche supports on locally owned cells.
     * @p increment_factor scales the prescribed displacement to the
     * increment of this step. With a B-bar @p kernel, @p moments (by
     * active_cell_index) give each cell's centroid: the consistency terms
     * take the B-bar stress, the one the cell's stiffness is made of.
     */
    void
    assemble(const BoundaryCurves            &curves,
             const BackgroundGrid            &grid,
             const Q1CellKernel              &kernel,
             const LinearElasticMaterial     &material,
             const ExactSolution             *exact,
             const double                     increment_factor,
             const AffineConstraints<double> &constraints,
             TrilinosWrappers::SparseMatrix  &matrix,
             TrilinosWrappers::MPI::Vector   &rhs,
             const BoundaryCurve             *only    = nullptr,
             const std::vector<CellMoments>  *moments = nullptr) const;

  private:
    double       penalty        = 100;
    unsigned int n_gauss_points = 4;
  };
} // namespace bsmpm

#endif
