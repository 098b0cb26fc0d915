#ifndef bsmpm_neumann_loads_h
#define bsmpm_neumann_loads_h

#include <deal.II/base/parameter_handler.h>

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <bsmpm/boundary/boundary_curves.h>
#include <bsmpm/geometry/background_grid.h>
#include <bsmpm/points/q1_cell_kernel.h>
#include <bsmpm/verification/exact_solution.h>

#include <vector>

namespace bsmpm
{
  using namespace dealii;

  /**
   * Tractions integrated along the B-spline boundary, piece by piece in the
   * grid cells (paper Sec. 3.4, eq. 17): on a piece [u_a, u_b] of a curve C
   * in cell K, with Gauss points u_q and weights w_q on [u_a, u_b],
   *
   *   f_K += sum_q N(C(u_q))^T t(C(u_q)) |C'(u_q)| w_q.
   */
  class NeumannLoads
  {
  public:
    /** A Gauss point of a boundary piece, kept for output and checks. */
    struct QuadraturePoint
    {
      Point<2>     position;
      Tensor<1, 2> traction;
      double       weight; ///< length element |C'(u)| w
    };

    static void
    declare_parameters(ParameterHandler &prm);
    void
    parse_parameters(ParameterHandler &prm);

    /**
     * Adds the tractions of all curves, scaled by @p load_factor, to @p rhs
     * on the locally owned cells. @p exact is needed for "exact traction".
     *
     * With @p follower (finite strain), a pressure acts on the curve as
     * the increment d deforms it within the step: on a piece with unit
     * tangent t and outward normal n = R t, n dl becomes
     * R (1 + grad u) t dl, which is linear in d, so its load stiffness
     *
     *   P_ab = lambda p int N_a . R (grad N_b) t dl
     *
     * (unsymmetric) is added to @p follower, K d = r. Other tractions act
     * on the curve at the start of the step.
     */
    void
    assemble(const BoundaryCurves            &curves,
             const BackgroundGrid            &grid,
             const Q1CellKernel              &kernel,
             const ExactSolution             *exact,
             const double                     load_factor,
             const AffineConstraints<double> &constraints,
             TrilinosWrappers::MPI::Vector   &rhs,
             TrilinosWrappers::SparseMatrix  *follower = nullptr);

    /** The Gauss points of the last assemble() on this process. */
    const std::vector<QuadraturePoint> &
    quadrature_points() const
    {
      return points;
    }

    /** Sum over all processes of t w over the Gauss points: the resultant
     * force of the tractions of the last assemble(). */
    Tensor<1, 2>
    resultant(const MPI_Comm communicator) const;

  private:
    unsigned int                 n_gauss_points = 4;
    std::vector<QuadraturePoint> points;
  };
} // namespace bsmpm

#endif
