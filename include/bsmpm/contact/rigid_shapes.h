#ifndef bsmpm_rigid_shapes_h
#define bsmpm_rigid_shapes_h

#include <bsmpm/contact/rigid_body.h>

#include <memory>
#include <vector>

namespace bsmpm
{
  /**
   * The outlines a rigid body can take (RigidShape, doc/contact.md).
   */
  namespace RigidShapes
  {
    /** A polygon through @p vertices (counter-clockwise) grown by
     * @p corner_radius >= 0, which rounds its convex corners. */
    std::shared_ptr<const RigidShape>
    polygon(const std::vector<Point<2>> &vertices, const double corner_radius);

    /** A circle. */
    std::shared_ptr<const RigidShape>
    circle(const Point<2> &center, const double radius);

    /** The closed cubic B-spline through @p points (counter-clockwise, the
     * last joined to the first), built like the boundary curves
     * (BSplineCurve): sharp at @p corners (indices into @p points) and
     * where the points are straight on both sides of a change of
     * direction, smooth elsewhere. */
    std::shared_ptr<const RigidShape>
    spline(const std::vector<Point<2>>     &points,
           const std::vector<unsigned int> &corners);
  } // namespace RigidShapes
} // namespace bsmpm

#endif
