#ifndef bsmpm_rigid_body_placement_h
#define bsmpm_rigid_body_placement_h

#include <deal.II/base/mpi.h>
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <bsmpm/boundary/boundary_curves.h>
#include <bsmpm/contact/rigid_body.h>
#include <bsmpm/points/material_points.h>

#include <limits>
#include <vector>

namespace bsmpm
{
  using namespace dealii;

  /**
   * Where the rigid bodies start (doc/contact.md, "Where a rigid body
   * starts"): outside the body and outside each other, touching at most.
   * Contact acts only on the boundary curves, so a rigid body placed inside
   * the body's material goes unnoticed (or acts on a stretch of curve that
   * happens to cross it), and one placed across the surface pushes the
   * curve out by the whole overlap in the first increment; two rigid
   * bodies that overlap are a shape the input cannot mean. All three are
   * refused before the first step.
   *
   * A body that starts touching, or overlapping by round-off or up to a
   * twentieth of a cell (a footing placed on a surface given to a few
   * digits), is accepted: contact resolves that much within an increment,
   * as it does the motion of every increment.
   */
  class RigidBodyPlacement
  {
  public:
    /** How deep points lie inside a rigid body, and the deepest of them. */
    struct Overlap
    {
      /** Minus the gap of the deepest point: > 0 inside the body. */
      double   depth = -std::numeric_limits<double>::infinity();
      Point<2> where;
    };

    /** The deepest of @p points inside @p body, translated by
     * @p translation (depth <= 0: none inside). */
    static Overlap
    deepest(const RigidBody             &body,
            const Tensor<1, 2>          &translation,
            const std::vector<Point<2>> &points);

    /** The closed polyline @p outline with points added so that no two
     * neighbours are further apart than @p spacing: the points at which
     * one outline is tested against another body. */
    static std::vector<Point<2>>
    densified(const std::vector<Point<2>> &outline, const double spacing);

    /**
     * Throws, naming every offending body by its parameter section, the
     * depth and where, if a rigid body (at the @p places, its translations
     * at load factor 0) overlaps the body's material (its material points
     * and the @p curves' points and segment midpoints) or another rigid
     * body by more than a twentieth of @p cell_size. Collective over
     * @p communicator (the material points are distributed).
     */
    static void
    check(const std::vector<RigidBody>    &bodies,
          const std::vector<Tensor<1, 2>> &places,
          const BoundaryCurves            &curves,
          const MaterialPoints            &points,
          const double                     cell_size,
          const MPI_Comm                   communicator);

    /**
     * Throws, naming the body, the face and the parameters to change, if a
     * rigid body reaches through a fixed face of @p grid and its prescribed
     * translation (sampled at load factors 0 .. @p last_load_factor)
     * moves it along that face towards material points that lie within a
     * cell of the face and of the body: the face holds that material in
     * place, so the body would have to pass through it (a wall translated
     * into soil on a fixed base), a problem without a solution. A roller
     * face lets the material slide and is not refused. Collective.
     */
    static void
    check_motion_along_faces(const std::vector<RigidBody> &bodies,
                             const BackgroundGrid         &grid,
                             const MaterialPoints         &points,
                             const double                  last_load_factor);
  };
} // namespace bsmpm

#endif
