#ifndef bsmpm_support_reaction_h
#define bsmpm_support_reaction_h

#include <deal.II/base/tensor.h>

#include <bsmpm/background_grid.h>
#include <bsmpm/boundary_curves.h>
#include <bsmpm/material_points.h>
#include <bsmpm/q1_cell_kernel.h>

#include <vector>

namespace bsmpm
{
  using namespace dealii;

  /**
   * The force that the supports of each boundary curve exert on the body, as
   * the work of the points' stresses on a test field (doc/newton.md,
   * "Reaction forces").
   *
   * For any admissible virtual displacement v,
   *   int sigma : eps(v) - int b . v = int_Gamma t . v .
   * With v = e_k on every grid vertex of the cells that a curve's supports
   * cross, and zero elsewhere, v is e_k along those supports and zero at
   * every other support that lies away from them (tractions elsewhere are
   * zero or known): the right side is the k-th component of the force that
   * the supports exert. The left side is a sum over the points of the
   * cells next to those vertices, with the plain MP quadrature.
   */
  class SupportReaction
  {
  public:
    /**
     * One force per curve of @p curves (zero for curves without supports),
     * over all processes, from the points' current stresses at their
     * reference locations in the cells they were last sorted into: call it
     * after the stresses are updated and before the points are re-sorted.
     * @p body_force: the body force per unit volume of the step.
     */
    static std::vector<Tensor<1, 2>>
    compute(const BoundaryCurves &curves,
            const BackgroundGrid &grid,
            const MaterialPoints &points,
            const Q1CellKernel   &kernel,
            const Tensor<1, 2>   &body_force);
  };
} // namespace bsmpm

#endif
