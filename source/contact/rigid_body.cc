#include <deal.II/base/numbers.h>

#include <bsmpm/base/parameter_tools.h>
#include <bsmpm/contact/rigid_body.h>
#include <bsmpm/contact/rigid_shapes.h>
#include <bsmpm/geometry/b_spline_curve.h>
#include <bsmpm/geometry/polygon_area.h>

#include <cmath>
#include <limits>

namespace bsmpm
{
  namespace
  {
    std::string
    body_section(const unsigned int b)
    {
      return "Rigid body " + std::to_string(b + 1);
    }



    /** Twice the signed area of a polygon (> 0 counter-clockwise). */
    double
    twice_signed_area(const std::vector<Point<2>> &v)
    {
      double a = 0;
      for (unsigned int k = 0; k < v.size(); ++k)
        {
          const Point<2> &p = v[k];
          const Point<2> &q = v[(k + 1) % v.size()];
          a += p[0] * q[1] - q[0] * p[1];
        }
      return a;
    }
  } // namespace



  void
  RigidBody::declare_parameters(ParameterHandler &prm)
  {
    for (unsigned int b = 0; b < max_bodies; ++b)
      {
        prm.enter_subsection(body_section(b));
        prm.declare_entry(
          "Shape",
          "none",
          Patterns::Selection("none|polygon|circle|spline"),
          "A rigid body that the boundary curves of the body come into "
          "contact with (doc/contact.md): none, a polygon (Vertices, "
          "Corner radius), a circle (Center, Radius) or a closed cubic "
          "B-spline through the Vertices (Corners). Every free stretch "
          "of every boundary curve takes contact with it where it touches; "
          "curve stretches with a load or support do not.");
        prm.declare_entry("Vertices",
                          "0, 0; 1, 0; 1, 1; 0, 1",
                          Patterns::Anything(),
                          "polygon: its vertices 'x0, y0; x1, y1; ...' in m "
                          "(at least 3, counter-clockwise, the last joins "
                          "the first), in the body's place at load factor 0; "
                          "spline: the points the outline passes through, "
                          "given the same way.");
        prm.declare_entry("Corners",
                          "",
                          Patterns::List(Patterns::Integer(0)),
                          "spline: indices (from 0) of Vertices where the "
                          "outline keeps a sharp corner, besides those "
                          "detected where the points are straight on both "
                          "sides of a change of direction.");
        prm.declare_entry("Corner radius",
                          "0",
                          Patterns::Double(0.),
                          "polygon: the body is the polygon grown by this "
                          "radius in m (its corners rounded, its edges moved "
                          "out by it); 0 keeps sharp corners.");
        prm.declare_entry("Center",
                          "0, 0",
                          ParameterTools::point_pattern(),
                          "circle: its centre in m at load factor 0.");
        prm.declare_entry("Radius",
                          "1",
                          Patterns::Double(0.),
                          "circle: its radius in m.");
        prm.declare_entry(
          "Displacement",
          "0; 0",
          Patterns::Anything(),
          "The body's translation 'ux; uy' in m, each component either an "
          "expression of the load factor t (0 at the start, 1 at the end of "
          "the load steps), for example '0; -0.1*t', or a load, unload and "
          "lift: '0; if(t < 0.5, -0.2*t, -0.2 + 0.3*t)'; or 'free': that "
          "component is force-controlled, solved for so that the contact "
          "forces balance the Force (a footing pushed down by a force and "
          "held horizontally: '0; free'). A free component needs contact "
          "that resists it: the body must touch a boundary curve, or reach "
          "one within two cells in the direction of its Force, at the "
          "first step (doc/contact.md).");
        prm.declare_entry(
          "Force",
          "0; 0",
          Patterns::Anything(),
          "The force 'fx; fy' in N/m (per unit thickness) applied to the "
          "body in its free (force-controlled) components, as expressions "
          "of the load factor t, for example '0; -500*t' for a footing "
          "pushed down by 500 N/m at the end of the load. A component with "
          "a prescribed Displacement must have the force 0 here: a "
          "component is either displacement- or force-controlled.");
        prm.declare_entry("Friction",
                          "smooth",
                          Patterns::Selection("smooth|frictional|rough"),
                          "smooth: no tangential traction; frictional: "
                          "Coulomb friction with the Friction coefficient "
                          "(sticking while |t_T| <= mu p_N, sliding "
                          "beyond); rough: Coulomb friction with mu = 10, "
                          "smoothed (t_T = 10 p tanh(t_trial / 10 p)): no "
                          "sliding where it presses, a traction that stays "
                          "continuous where the body starts or stops "
                          "touching, and no kink between sticking and "
                          "sliding (doc/contact.md).");
        prm.declare_entry("Friction coefficient",
                          "0.3",
                          Patterns::Double(0.),
                          "Coulomb's coefficient mu of a frictional surface.");
        prm.leave_subsection();
      }
  }



  std::vector<RigidBody>
  RigidBody::create_all(ParameterHandler &prm)
  {
    std::vector<RigidBody> bodies;
    for (unsigned int b = 0; b < max_bodies; ++b)
      {
        prm.enter_subsection(body_section(b));
        const std::string where = body_section(b);
        const std::string kind  = prm.get("Shape");
        if (kind == "none")
          {
            prm.leave_subsection();
            continue;
          }
        RigidBody body;
        body.body_name = "rigid_body_" + std::to_string(b + 1);
        if (kind == "circle")
          {
            const double radius = prm.get_double("Radius");
            AssertThrow(radius > 0,
                        ExcMessage(where + "/Radius must be positive."));
            body.shape =
              RigidShapes::circle(ParameterTools::get_point(prm, "Center"),
                                  radius);
          }
        else
          {
            const std::string text = prm.get("Vertices");
            const std::string form = where +
                                     "/Vertices: give at least 3 vertices as "
                                     "'x0, y0; x1, y1; x2, y2', not '" +
                                     text + "'.";
            std::vector<Point<2>> vertices;
            for (const auto &vertex : Utilities::split_string_list(text, ';'))
              {
                const auto xy = Utilities::split_string_list(vertex, ',');
                AssertThrow(xy.size() == 2, ExcMessage(form));
                Point<2> p;
                for (unsigned int d = 0; d < 2; ++d)
                  {
                    try
                      {
                        p[d] = Utilities::string_to_double(xy[d]);
                      }
                    catch (...)
                      {
                        AssertThrow(false, ExcMessage(form));
                      }
                    ParameterTools::require_finite(p[d], where + "/Vertices");
                  }
                vertices.push_back(p);
              }
            AssertThrow(vertices.size() >= 3, ExcMessage(form));
            AssertThrow(twice_signed_area(vertices) > 0,
                        ExcMessage(where +
                                   "/Vertices must run counter-clockwise "
                                   "round a polygon of positive area."));
            if (kind == "polygon")
              body.shape =
                RigidShapes::polygon(vertices, prm.get_double("Corner radius"));
            else
              {
                std::vector<unsigned int> corners;
                for (const auto i :
                     ParameterTools::get_unsigned(prm, "Corners"))
                  {
                    AssertThrow(i < vertices.size(),
                                ExcMessage(where +
                                           "/Corners: " + std::to_string(i) +
                                           " is not the index of one of the " +
                                           std::to_string(vertices.size()) +
                                           " Vertices (from 0)."));
                    corners.push_back(i);
                  }
                AssertThrow(
                  !BSplineCurve(vertices, true, corners).is_self_intersecting(),
                  ExcMessage(where + ": the spline through the Vertices "
                                     "crosses itself."));
                body.shape = RigidShapes::spline(vertices, corners);
              }
          }

        read_motion(prm, where, body);
        const std::string friction = prm.get("Friction");
        body.surface_friction      = friction == "smooth" ? Friction::smooth :
                                     friction == "frictional" ?
                                                            Friction::frictional :
                                                            Friction::rough;
        body.mu                    = prm.get_double("Friction coefficient");
        prm.leave_subsection();
        bodies.push_back(std::move(body));
      }
    return bodies;
  }



  void
  RigidBody::read_motion(ParameterHandler  &prm,
                         const std::string &where,
                         RigidBody         &body)
  {
    // 'ux; uy' with 'free' for a force-controlled component: the parser
    // reads 0 there.
    const std::string text       = prm.get("Displacement");
    const auto        components = Utilities::split_string_list(text, ';');
    AssertThrow(components.size() == 2,
                ExcMessage(where + "/Displacement = '" + text +
                           "' is not two expressions 'ux; uy' of the load "
                           "factor t ('free' for a force-controlled "
                           "component)."));
    std::string prescribed;
    for (unsigned int d = 0; d < 2; ++d)
      {
        body.free_component[d] = components[d] == "free";
        prescribed +=
          (d == 0 ? "" : ";") + (body.free_component[d] ? "0" : components[d]);
      }

    const auto parse = [&](std::shared_ptr<FunctionParser<1>> &function,
                           const std::string                  &name,
                           const std::string                  &expressions,
                           const std::string                  &form) {
      function = std::make_shared<FunctionParser<1>>(2);
      // The parser finds an unknown name only when it first evaluates.
      try
        {
          // pi as in the curves' conditions (doc/parameters.md).
          function->initialize("t", expressions, {{"pi", numbers::PI}});
          function->value(Point<1>(0.), 0);
          function->value(Point<1>(0.), 1);
        }
      catch (...)
        {
          AssertThrow(false,
                      ExcMessage(where + "/" + name + " = '" + prm.get(name) +
                                 "' is not " + form + "."));
        }
      for (const double t : {0., 0.5, 1.})
        for (unsigned int d = 0; d < 2; ++d)
          AssertThrow(std::isfinite(function->value(Point<1>(t), d)),
                      ExcMessage(where + "/" + name + " is not finite at t = " +
                                 std::to_string(t) + "."));
    };
    parse(body.motion,
          "Displacement",
          prescribed,
          "two expressions 'ux; uy' of the load factor t ('free' for a "
          "force-controlled component)");
    parse(body.force,
          "Force",
          prm.get("Force"),
          "two expressions 'fx; fy' of the load factor t");

    // A component is either displacement- or force-controlled: a force on
    // a prescribed component would be silently ignored.
    const auto forces = Utilities::split_string_list(prm.get("Force"), ';');
    for (unsigned int d = 0; d < 2; ++d)
      if (!body.free_component[d])
        {
          bool zero = true;
          for (const double t : {0., 0.25, 0.5, 0.75, 1.})
            zero = zero && body.force->value(Point<1>(t), d) == 0.;
          AssertThrow(zero,
                      ExcMessage(
                        where + ": the " + (d == 0 ? "x" : "y") +
                        " component has both a Displacement ('" +
                        components[d] + "') and a Force ('" + forces[d] +
                        "'). A component is either displacement-controlled "
                        "(an expression of t in Displacement, Force 0) or "
                        "force-controlled ('free' in Displacement, its "
                        "load in Force)."));
        }
  }



  Tensor<1, 2>
  RigidBody::displacement(const double t) const
  {
    const Point<1> p(t);
    return Tensor<1, 2>({free_component[0] ? 0. : motion->value(p, 0),
                         free_component[1] ? 0. : motion->value(p, 1)});
  }



  bool
  RigidBody::moves_with_load() const
  {
    const Tensor<1, 2> start = displacement(0);
    for (const double t : {0.25, 0.5, 0.75, 1.})
      if ((displacement(t) - start).norm() > 0)
        return true;
    return false;
  }



  Tensor<1, 2>
  RigidBody::applied_force(const double t) const
  {
    const Point<1> p(t);
    return Tensor<1, 2>({free_component[0] ? force->value(p, 0) : 0.,
                         free_component[1] ? force->value(p, 1) : 0.});
  }



  bool
  RigidBody::surely_further_than(const Point<2>     &x,
                                 const Tensor<1, 2> &translation,
                                 const double        distance) const
  {
    const Point<2> c = shape->reference_point() + translation;
    return (x - c).norm() > shape->size() + distance;
  }



  std::vector<Point<2>>
  RigidBody::outline(const Tensor<1, 2> &translation) const
  {
    std::vector<Point<2>> line = shape->outline();
    for (auto &p : line)
      p += translation;
    return line;
  }



  Point<2>
  RigidBody::centroid(const Tensor<1, 2> &translation) const
  {
    // Of the closed polyline (a circle's and a rounded corner's arcs
    // sampled: symmetric samples keep a circle's centre exact).
    const auto [area, moment] = polygon_area_and_moment(outline(translation));
    return Point<2>(moment / area);
  }
} // namespace bsmpm
