#ifndef bsmpm_excavation_h
#define bsmpm_excavation_h

#include <deal.II/base/point.h>
#include <deal.II/base/types.h>

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/trilinos_vector.h>

#include <bsmpm/geometry/background_grid.h>

#include <string>
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
   * node. Without the removed points (and with the cut cells along the new
   * face integrated over their new part in the body) the rest is not: its
   * out-of-balance force R = F_ext - F_int is, but for the Newton
   * tolerance of the step before, minus the forces the removed material
   * exerted on it, sum over the removed points of V (N^T b - B^T sigma),
   * plus what the new quadrature of the cut cells changes. The stage adds
   * f = -R times (1 - s) to the loads, s its own factor, so that the rest
   * starts in balance and carries the cut's unloading gradually; a cut that
   * cannot stand collapses part way (the collapse detector's limit load
   * factor is the fraction released). R is the system's own residual at a
   * zero increment (LoadStepper::out_of_balance()), in small and finite
   * strain alike.
   */
  class Excavation
  {
  public:
    /**
     * Removes the material points inside @p polygon from @p points.
     * @p kept_points are the positions of the tracked points whose curve
     * does not follow the cut (BoundaryCurves::excavate(): open curves,
     * curves of material points, curves in contact) and of the probe: a
     * polygon that holds one of them, or comes within a cell of one, is
     * refused (the message names @p where). Forgets the forces of an
     * earlier removal. Returns how many points were removed.
     */
    types::particle_index
    remove(const std::vector<Point<2>> &polygon,
           MaterialPoints              &points,
           const BackgroundGrid        &grid,
           const std::vector<Point<2>> &kept_points,
           const std::string           &where);

    /** The region of @p points (Stages/Stage k/Excavation) as a polygon:
     * the points themselves, or with @p spline the closed cubic B-spline
     * through them, sampled at most @p spacing apart (the message of bad
     * input names @p where). */
    static std::vector<Point<2>>
    region_outline(const std::vector<Point<2>> &points,
                   const bool                   spline,
                   const double                 spacing,
                   const std::string           &where);

    /** Keeps the forces to release: minus @p out_of_balance, the rest's
     * out-of-balance force after the removal. */
    void
    release(const TrilinosWrappers::MPI::Vector &out_of_balance);

    /** Adds @p factor times the released forces to @p rhs (compressed),
     * but for the rows that @p constraints constrain (among them the DoFs
     * of no cell with material). */
    void
    add_released_forces(const double                     factor,
                        const AffineConstraints<double> &constraints,
                        TrilinosWrappers::MPI::Vector   &rhs) const;

  private:
    TrilinosWrappers::MPI::Vector forces;
  };
} // namespace bsmpm

#endif
