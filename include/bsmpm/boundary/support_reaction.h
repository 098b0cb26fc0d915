#ifndef bsmpm_support_reaction_h
#define bsmpm_support_reaction_h

#include <deal.II/base/tensor.h>

#include <deal.II/lac/trilinos_vector.h>

#include <bsmpm/geometry/background_grid.h>

namespace bsmpm
{
  using namespace dealii;

  /**
   * The force that the supports of a boundary curve exert on the body
   * (doc/newton.md, "Support reactions").
   *
   * The supports (implicit boundary method, Nitsche) enter the discrete
   * equations as terms K_s, r_s of the system; at a converged step their
   * nodal force r_s - K_s x (SystemAssembly::support_forces()) balances
   * everything else that the solver integrates: the internal force with its
   * own quadrature weights, the ghost penalty, the loads. Its sum over the
   * DoFs of each component is the curve's reaction: the work of the
   * supports on a uniform virtual displacement. It is exact for the
   * discrete solution whatever quadrature the cells use; a sum over the
   * points with their volumes is not, and drifted by several per cent
   * whenever cut cells changed (doc/newton.md).
   */
  class SupportReaction
  {
  public:
    /**
     * The sum over all processes of the x and y components of the nodal
     * forces @p support_forces (locally owned DoFs of @p grid).
     */
    static Tensor<1, 2>
    resultant(const BackgroundGrid                &grid,
              const TrilinosWrappers::MPI::Vector &support_forces);
  };
} // namespace bsmpm

#endif
