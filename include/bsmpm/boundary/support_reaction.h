#ifndef bsmpm_support_reaction_h
#define bsmpm_support_reaction_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/tensor.h>

#include <deal.II/lac/trilinos_vector.h>

#include <bsmpm/geometry/background_grid.h>

#include <functional>
#include <map>
#include <string>
#include <vector>

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
    /** Section "Reactions": which curves' reactions are reported. */
    static void
    declare_parameters(ParameterHandler &prm);

    void
    parse_parameters(ParameterHandler &prm);

    /** Curves (0-based) whose support forces are reported. */
    const std::vector<unsigned int> &
    curves() const
    {
      return reported_curves;
    }

    /**
     * Sets the quantities curve<k>_force_x and _y in @p quantities for
     * every reported curve k, from the nodal forces that
     * @p support_forces(curve) gives (SystemAssembly::support_forces()).
     */
    void
    record(
      const BackgroundGrid &grid,
      const std::function<TrilinosWrappers::MPI::Vector(const unsigned int)>
                                    &support_forces,
      std::map<std::string, double> &quantities) const;

    /**
     * The sum over all processes of the x and y components of the nodal
     * forces @p support_forces (locally owned DoFs of @p grid).
     */
    static Tensor<1, 2>
    resultant(const BackgroundGrid                &grid,
              const TrilinosWrappers::MPI::Vector &support_forces);

  private:
    std::vector<unsigned int> reported_curves;
  };
} // namespace bsmpm

#endif
