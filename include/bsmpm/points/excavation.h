#ifndef bsmpm_excavation_h
#define bsmpm_excavation_h

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>
#include <deal.II/base/types.h>

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/trilinos_vector.h>

#include <bsmpm/geometry/background_grid.h>
#include <bsmpm/points/q1_cell_kernel.h>

#include <array>
#include <vector>

namespace bsmpm
{
  using namespace dealii;

  class MaterialPoints;

  /**
   * The material removed by a stage (section "Stages", doc/stages.md): the
   * material points inside a polygon leave the body at the stage's start,
   * and the forces they exerted on the rest are released over the stage's
   * steps.
   *
   * Before the removal the body is in balance, F_ext - F_int = 0 at every
   * node. Without the removed points the rest would see at once the
   * out-of-balance force f = F_ext(removed) - F_int(removed) = sum over the
   * removed points of V (N^T b - B^T sigma): the forces the removed
   * material exerted on the rest, at the nodes they shared. The stage adds
   * (1 - s) f to the loads, s its own factor, so that the rest starts in
   * balance and carries the cut's unloading gradually; a cut that cannot
   * stand collapses part way (the collapse detector's limit load factor is
   * the fraction released).
   *
   * The forces are taken from the removed points' cell moments (the Q1
   * kernel integrates B^T sigma over them exactly): their volumes and
   * Cauchy stresses as they are, and in finite strain their masses from
   * the volumes at the start.
   */
  class Excavation
  {
  public:
    /**
     * Removes the material points inside @p polygon from @p points and
     * keeps the forces they exerted on the rest under the gravity
     * @p gravity (times its load multiplier; the points' masses from their
     * bodies' densities; @p finite_strain: ConstitutiveUpdate's masses).
     * @p kept_points are the positions of the tracked points whose curve
     * does not follow the cut (BoundaryCurves::excavate(): open curves,
     * curves of material points, curves in contact) and of the probe: a
     * polygon that holds one of them, or comes within a cell of one, is
     * refused (the message names @p where). Returns how many points were
     * removed.
     */
    types::particle_index
    remove(const std::vector<Point<2>> &polygon,
           MaterialPoints              &points,
           const BackgroundGrid        &grid,
           const Q1CellKernel          &kernel,
           const Tensor<1, 2>          &gravity,
           const bool                   finite_strain,
           const std::vector<Point<2>> &kept_points,
           const std::string           &where);

    /** Whether a removal left forces to release. */
    bool
    releases() const
    {
      return !forces.empty();
    }

    /** Adds @p factor times the released forces to @p rhs, with
     * @p constraints. */
    void
    add_released_forces(const double                     factor,
                        const AffineConstraints<double> &constraints,
                        TrilinosWrappers::MPI::Vector   &rhs) const;


  private:
    /** A locally owned cell that lost points: its DoFs and the forces on
     * them. */
    struct CellForces
    {
      std::array<types::global_dof_index, 8> dofs;
      std::array<double, 8>                  forces;
    };
    std::vector<CellForces> forces;
  };
} // namespace bsmpm

#endif
