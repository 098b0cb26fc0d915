#ifndef bsmpm_rigid_body_h
#define bsmpm_rigid_body_h

#include <deal.II/base/function_parser.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <bsmpm/contact/contact_law.h>

#include <array>
#include <limits>
#include <memory>
#include <string>
#include <vector>

namespace bsmpm
{
  using namespace dealii;

  /**
   * The nearest point of a rigid outline to a point x, and what contact
   * needs of it (doc/contact.md).
   */
  struct SurfacePoint
  {
    /** Signed distance of x from the outline: > 0 outside the rigid body,
     * < 0 inside it (penetration). */
    double gap = 0;
    /** Outward unit normal of the rigid body at the nearest point: the
     * gradient of the gap with respect to x. */
    Tensor<1, 2> normal;
    /** Distance from x to the centre about which the normal turns as x
     * moves (|x - c| for a circle of centre c or at a corner); infinite
     * on a straight edge, where the normal does not turn. The derivative
     * of the normal by x is (I - n n) / radius. */
    double turning_radius = std::numeric_limits<double>::infinity();
    /** Which part of the outline is nearest: 2 k for the inside of edge k
     * of a polygon, 2 k + 1 for its vertex k; 0 for a circle. Contact
     * keeps one pressure per part and cell, so that a cell that holds the
     * edge of a footing does not average the footing's base with the free
     * surface beside it. */
    unsigned int feature = 0;
  };



  /**
   * The outline of a rigid body in its starting place: a polygon (corners
   * rounded by a radius if wanted), a circle or a closed B-spline
   * (rigid_shapes.h). Rigid bodies translate only,
   * so the outline never changes shape.
   */
  class RigidShape
  {
  public:
    virtual ~RigidShape() = default;

    /** The nearest point of the outline to @p x. */
    virtual SurfacePoint
    nearest(const Point<2> &x) const = 0;

    /** As nearest(), measured to one part of the outline (@p feature of
     * SurfacePoint), extended beyond its ends: the straight line of an
     * edge, the circle round a corner. Contact measures the gap of a
     * point in a load increment to the part that was nearest at the
     * increment's start: a body pushed deep into a corner of a footing
     * would otherwise find the footing's side nearer than its base and
     * be pushed sideways. */
    virtual SurfacePoint
    to_feature(const Point<2> &x, const unsigned int feature) const = 0;

    /** Points along the outline, counter-clockwise, closed (the last equals
     * the first), for output. */
    virtual std::vector<Point<2>>
    outline() const = 0;

    /** The largest distance of the outline from its first point: with it,
     * a cheap bound skips points far from the body. */
    virtual double
    size() const = 0;

    /** A point of the body (for the bound of size()). */
    virtual Point<2>
    reference_point() const = 0;
  };



  /**
   * A rigid body of a scene (subsection "Rigid body N"): its shape, its
   * motion (per component of its translation either prescribed as a
   * function of the load factor, or free under an applied force and solved
   * for: RigidBodyMotion), and the friction of its surface with the body's
   * boundary curves.
   */
  class RigidBody
  {
  public:
    /** Most rigid bodies in a scene. */
    static constexpr unsigned int max_bodies = 4;

    /** How the body's surface resists sliding (the contact law's). */
    using Friction = ContactLaw::Friction;

    /** Declares subsections "Rigid body 1" .. "Rigid body 4". */
    static void
    declare_parameters(ParameterHandler &prm);

    /** The rigid bodies that @p prm defines (Shape other than none). */
    static std::vector<RigidBody>
    create_all(ParameterHandler &prm);

    /** Name for messages and summary.json ("rigid_body_1"). */
    const std::string &
    name() const
    {
      return body_name;
    }

    /** The parameter section that defines it ("Rigid body 1"), for
     * messages that say what to change. */
    std::string
    section() const
    {
      return "Rigid body " + body_name.substr(body_name.rfind('_') + 1);
    }

    /** Whether component @p d (0: x, 1: y) of the body's translation is
     * force-controlled ('free' in Displacement): solved for, so that the
     * contact forces balance the applied Force (RigidBodyMotion). */
    bool
    force_controlled(const unsigned int d) const
    {
      return free_component[d];
    }

    /** Whether any component is force-controlled. */
    bool
    has_free_motion() const
    {
      return free_component[0] || free_component[1];
    }

    /** Whether the load factor moves the body: a prescribed component
     * whose translation differs between load factors 0, 1/4, .., 1 (a
     * component held in place, '0', does not; with only held and
     * force-controlled components the load factor scales forces, and a
     * run under it can reach a limit load: CollapseDetector). */
    bool
    moves_with_load() const;

    /** The prescribed translation at load factor @p t (zero in the
     * force-controlled components). */
    Tensor<1, 2>
    displacement(const double t) const;

    /** The applied force on the body at load factor @p t, N/m (zero in the
     * displacement-controlled components). */
    Tensor<1, 2>
    applied_force(const double t) const;

    /** The nearest point of the body's outline, translated by
     * @p translation, to @p x. */
    SurfacePoint
    nearest(const Point<2> &x, const Tensor<1, 2> &translation) const
    {
      return shape->nearest(x - translation);
    }

    /** As nearest(), to part @p feature of the outline (RigidShape::
     * to_feature()). */
    SurfacePoint
    to_feature(const Point<2>     &x,
               const Tensor<1, 2> &translation,
               const unsigned int  feature) const
    {
      return shape->to_feature(x - translation, feature);
    }

    /** Whether @p x lies further than @p distance from the body translated
     * by @p translation (a cheap test that may answer false for far
     * points). */
    bool
    surely_further_than(const Point<2>     &x,
                        const Tensor<1, 2> &translation,
                        const double        distance) const;

    /** The outline translated by @p translation (closed polyline). */
    std::vector<Point<2>>
    outline(const Tensor<1, 2> &translation) const;

    /** The centroid of the area inside that outline: where the moments of
     * the contact forces on the body are taken. */
    Point<2>
    centroid(const Tensor<1, 2> &translation) const;

    Friction
    friction() const
    {
      return surface_friction;
    }

    /** Coulomb's coefficient mu (frictional surfaces). */
    double
    friction_coefficient() const
    {
      return mu;
    }

  private:
    /** Reads Displacement and Force of the subsection @p where into
     * @p body. */
    static void
    read_motion(ParameterHandler  &prm,
                const std::string &where,
                RigidBody         &body);

    std::string                        body_name;
    std::shared_ptr<const RigidShape>  shape;
    std::shared_ptr<FunctionParser<1>> motion;
    /** The applied force, 'fx; fy' of the load factor. */
    std::shared_ptr<FunctionParser<1>> force;
    std::array<bool, 2>                free_component   = {{false, false}};
    Friction                           surface_friction = Friction::smooth;
    double                             mu               = 0;
  };
} // namespace bsmpm

#endif
