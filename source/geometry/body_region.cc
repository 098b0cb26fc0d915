#include <deal.II/base/numbers.h>

#include <bsmpm/base/parameter_tools.h>
#include <bsmpm/geometry/body_region.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <sstream>

namespace bsmpm
{
  void
  BodyRegion::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Body region");
    prm.declare_entry("Shape",
                      "rectangle",
                      Patterns::Selection(
                        "rectangle|rotated rectangle|"
                        "annulus sector|rectangle minus disc|polygon"),
                      "Shape of the body at the start of the run. A "
                      "polygon is given by its Vertices; its edges are "
                      "'edge 0' (vertex 0 to 1), 'edge 1', ... for the "
                      "boundary curves.");
    prm.declare_entry("Lower left corner",
                      "0, 0",
                      ParameterTools::point_pattern(),
                      "rectangle, rectangle minus disc: lower left corner.");
    prm.declare_entry("Upper right corner",
                      "1, 1",
                      ParameterTools::point_pattern(),
                      "rectangle, rectangle minus disc: upper right corner.");
    prm.declare_entry("Center",
                      "0, 0",
                      ParameterTools::point_pattern(),
                      "rotated rectangle: its centre; annulus sector: the "
                      "centre of its circles.");
    prm.declare_entry("Width",
                      "1",
                      Patterns::Double(0.),
                      "rotated rectangle: side length along its own x axis.");
    prm.declare_entry("Height",
                      "1",
                      Patterns::Double(0.),
                      "rotated rectangle: side length along its own y axis.");
    prm.declare_entry("Angle",
                      "0",
                      Patterns::Double(),
                      "rotated rectangle: counter-clockwise rotation in "
                      "degrees, in [-360, 360].");
    prm.declare_entry("Inner radius",
                      "1",
                      Patterns::Double(0.),
                      "annulus sector: inner radius; 0 makes a circular "
                      "sector (a disc, a half or a quarter disc), without an "
                      "inner arc.");
    prm.declare_entry("Outer radius",
                      "2",
                      Patterns::Double(0.),
                      "annulus sector: outer radius.");
    prm.declare_entry("Start angle",
                      "0",
                      Patterns::Double(),
                      "annulus sector: first angle in degrees "
                      "(counter-clockwise from the x axis), in [-360, 360].");
    prm.declare_entry("End angle",
                      "90",
                      Patterns::Double(),
                      "annulus sector: last angle in degrees, in (Start "
                      "angle, Start angle + 360].");
    prm.declare_entry("Disc center",
                      "0, 0",
                      ParameterTools::point_pattern(),
                      "rectangle minus disc: centre of the removed disc.");
    prm.declare_entry("Disc radius",
                      "0.5",
                      Patterns::Double(0.),
                      "rectangle minus disc: radius of the removed disc.");
    prm.declare_entry("Vertices",
                      "0, 0; 1, 0; 1, 1; 0, 1",
                      Patterns::Anything(),
                      "polygon: its vertices 'x0, y0; x1, y1; ...' (at "
                      "least 3, counter-clockwise, no edge crossing another; "
                      "the last vertex joins the first). Holes: cut them "
                      "out with a closed boundary curve with 'Trim material "
                      "points = true', or run the polygon round the hole and "
                      "back along a slit.");
    prm.leave_subsection();
  }



  namespace
  {
    /** @p x as in a parameter file (shortest form, no trailing zeros). */
    std::string
    number(const double x)
    {
      std::ostringstream text;
      text << x;
      return text.str();
    }



    /** Refuses an angle of @p degrees in the entry @p entry that is more
     * than a full turn; @p advice: what to give instead. */
    void
    require_at_most_a_turn(const double       degrees,
                           const std::string &entry,
                           const std::string &advice)
    {
      AssertThrow(std::abs(degrees) <= 360,
                  ExcMessage(entry + ": " + number(degrees) +
                             " degrees is more than a full turn; " + advice));
    }



    /** The vertices of "Body region/Vertices", 'x0, y0; x1, y1; ...'. */
    std::vector<Point<2>>
    parse_polygon_vertices(const std::string &vertex_text)
    {
      std::vector<Point<2>> vertices;
      for (const auto &text : Utilities::split_string_list(vertex_text, ';'))
        {
          const auto xy = Utilities::split_string_list(text, ',');
          AssertThrow(xy.size() == 2,
                      ExcMessage("Body region/Vertices: '" + text +
                                 "' is not a point 'x, y'; give the "
                                 "vertices as 'x0, y0; x1, y1; ...'."));
          double x = 0, y = 0;
          try
            {
              x = Utilities::string_to_double(xy[0]);
              y = Utilities::string_to_double(xy[1]);
            }
          catch (...)
            {
              AssertThrow(false,
                          ExcMessage("Body region/Vertices: '" + text +
                                     "' is not a point of two "
                                     "numbers."));
            }
          ParameterTools::require_finite(x, "Body region/Vertices");
          ParameterTools::require_finite(y, "Body region/Vertices");
          vertices.emplace_back(x, y);
        }
      return vertices;
    }
  } // namespace



  BodyRegion
  BodyRegion::rectangle(const Point<2> &lower_left, const Point<2> &upper_right)
  {
    BodyRegion region;
    region.region_shape = Shape::rectangle;
    region.lower_left   = lower_left;
    region.upper_right  = upper_right;
    region.check_rectangle();
    return region;
  }



  void
  BodyRegion::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Body region");
    const std::string shape    = prm.get("Shape");
    region_shape               = shape == "rectangle" ?
                                   Shape::rectangle :
                                   (shape == "rotated rectangle" ?
                                      Shape::rotated_rectangle :
                                      (shape == "annulus sector" ?
                                         Shape::annulus_sector :
                                         (shape == "polygon" ? Shape::polygon :
                                                               Shape::rectangle_minus_disc)));
    const double angle_degrees = prm.get_double("Angle");
    const double start_degrees = prm.get_double("Start angle");
    const double end_degrees   = prm.get_double("End angle");

    lower_left           = ParameterTools::get_point(prm, "Lower left corner");
    upper_right          = ParameterTools::get_point(prm, "Upper right corner");
    center               = ParameterTools::get_point(prm, "Center");
    width                = prm.get_double("Width");
    height               = prm.get_double("Height");
    angle                = angle_degrees * numbers::PI / 180.;
    annulus.center       = center;
    annulus.inner_radius = prm.get_double("Inner radius");
    annulus.outer_radius = prm.get_double("Outer radius");
    annulus.start_angle  = start_degrees * numbers::PI / 180.;
    annulus.end_angle    = end_degrees * numbers::PI / 180.;
    disc_center          = ParameterTools::get_point(prm, "Disc center");
    disc_radius          = prm.get_double("Disc radius");
    const std::string vertex_text = prm.get("Vertices");
    prm.leave_subsection();

    // Each shape refuses what makes no region, with a message that names
    // the entry.
    switch (region_shape)
      {
        case Shape::rectangle:
        case Shape::rectangle_minus_disc:
          check_rectangle();
          break;
        case Shape::rotated_rectangle:
          check_rotated_rectangle(angle_degrees);
          break;
        case Shape::annulus_sector:
          check_annulus_sector(start_degrees, end_degrees);
          break;
        case Shape::polygon:
          vertices = parse_polygon_vertices(vertex_text);
          check_polygon();
          break;
      }
  }



  void
  BodyRegion::check_rectangle() const
  {
    AssertThrow(upper_right[0] > lower_left[0] &&
                  upper_right[1] > lower_left[1],
                ExcMessage("Body region: the upper right corner must lie "
                           "above and to the right of the lower left "
                           "corner."));
    if (region_shape == Shape::rectangle_minus_disc)
      AssertThrow(disc_radius > 0,
                  ExcMessage("Body region: the Disc radius of a "
                             "rectangle minus disc must be positive "
                             "(a rectangle without a hole is the shape "
                             "'rectangle')."));
    if (region_shape == Shape::rectangle_minus_disc)
      for (unsigned int d = 0; d < 2; ++d)
        AssertThrow((disc_center[d] == lower_left[d] ||
                     disc_center[d] - disc_radius >= lower_left[d]) &&
                      (disc_center[d] == upper_right[d] ||
                       disc_center[d] + disc_radius <= upper_right[d]),
                    ExcMessage("Body region: the disc must lie inside "
                               "the rectangle or be centred on its "
                               "edges (as a quarter or half hole)."));
  }



  void
  BodyRegion::check_rotated_rectangle(const double angle_degrees) const
  {
    AssertThrow(width > 0 && height > 0,
                ExcMessage("Body region: width and height of a rotated "
                           "rectangle must be positive."));
    ParameterTools::require_finite(angle_degrees, "Body region/Angle");
    require_at_most_a_turn(angle_degrees,
                           "Body region/Angle",
                           "give the counter-clockwise rotation in degrees in "
                           "[-360, 360] (negative: clockwise).");
  }



  void
  BodyRegion::check_annulus_sector(const double start_degrees,
                                   const double end_degrees) const
  {
    ParameterTools::require_finite(start_degrees, "Body region/Start angle");
    ParameterTools::require_finite(end_degrees, "Body region/End angle");
    require_at_most_a_turn(start_degrees,
                           "Body region/Start angle",
                           "give it in [-360, 360] degrees, and the End angle "
                           "in (Start angle, Start angle + 360].");
    AssertThrow(annulus.outer_radius > annulus.inner_radius &&
                  end_degrees > start_degrees &&
                  end_degrees - start_degrees <= 360,
                ExcMessage("Body region: an annulus sector needs "
                           "inner radius < outer radius and start angle "
                           "< end angle <= start angle + 360 (degrees, "
                           "counter-clockwise), got radii " +
                           number(annulus.inner_radius) + ", " +
                           number(annulus.outer_radius) + " and angles " +
                           number(start_degrees) + ", " + number(end_degrees) +
                           "."));
  }



  void
  BodyRegion::check_polygon() const
  {
    AssertThrow(vertices.size() >= 3,
                ExcMessage("Body region/Vertices: a polygon needs at "
                           "least 3 vertices, got " +
                           std::to_string(vertices.size()) + "."));
    const unsigned int n = vertices.size();
    for (unsigned int i = 0; i < n; ++i)
      AssertThrow(vertices[i].distance(vertices[(i + 1) % n]) > 0,
                  ExcMessage("Body region/Vertices: vertices " +
                             std::to_string(i) + " and " +
                             std::to_string((i + 1) % n) + " coincide."));
    // Two edges that are not neighbours must not meet (a simple
    // polygon), or contains() and area() disagree.
    const auto cross = [](const Tensor<1, 2> &a, const Tensor<1, 2> &b) {
      return a[0] * b[1] - a[1] * b[0];
    };
    for (unsigned int i = 0; i < n; ++i)
      for (unsigned int j = i + 2; j < n; ++j)
        {
          if (i == 0 && j == n - 1)
            continue;
          const Point<2> a = vertices[i], b = vertices[(i + 1) % n],
                         c = vertices[j], d = vertices[(j + 1) % n];
          const double d1 = cross(b - a, c - a), d2 = cross(b - a, d - a),
                       d3 = cross(d - c, a - c), d4 = cross(d - c, b - c);
          AssertThrow(!(d1 * d2 <= 0 && d3 * d4 <= 0),
                      ExcMessage("Body region/Vertices: edge " +
                                 std::to_string(i) + " and edge " +
                                 std::to_string(j) +
                                 " of the polygon cross or touch; "
                                 "the boundary must not cross "
                                 "itself."));
        }
    AssertThrow(area() > 0,
                ExcMessage("Body region/Vertices: the vertices run "
                           "clockwise; give them counter-clockwise "
                           "(the body to the left of every edge)."));
  }



  bool
  BodyRegion::contains(const Point<2> &p) const
  {
    switch (region_shape)
      {
        case Shape::rectangle:
          return p[0] >= lower_left[0] && p[0] <= upper_right[0] &&
                 p[1] >= lower_left[1] && p[1] <= upper_right[1];
        case Shape::rectangle_minus_disc:
          return p[0] >= lower_left[0] && p[0] <= upper_right[0] &&
                 p[1] >= lower_left[1] && p[1] <= upper_right[1] &&
                 p.distance(disc_center) >= disc_radius;
        case Shape::rotated_rectangle:
          {
            const Tensor<1, 2> d = p - center;
            const double       c = std::cos(angle), s = std::sin(angle);
            const double       x = c * d[0] + s * d[1];
            const double       y = -s * d[0] + c * d[1];
            return std::abs(x) <= width / 2 && std::abs(y) <= height / 2;
          }
        case Shape::annulus_sector:
          {
            const Tensor<1, 2> d = p - annulus.center;
            const double       r = d.norm();
            if (r < annulus.inner_radius || r > annulus.outer_radius)
              return false;
            // Angle measured from the start angle, in [0, 2 pi).
            double theta = std::atan2(d[1], d[0]) - annulus.start_angle;
            theta -= 2 * numbers::PI * std::floor(theta / (2 * numbers::PI));
            return theta <= annulus.end_angle - annulus.start_angle;
          }
        case Shape::polygon:
          return polygon_contains(vertices, p);
      }
    return false;
  }



  PolygonEdgePoint
  nearest_on_polygon(const std::vector<Point<2>> &vertices, const Point<2> &p)
  {
    PolygonEdgePoint nearest;
    nearest.distance = std::numeric_limits<double>::infinity();
    double     start = 0;
    const auto n     = vertices.size();
    for (unsigned int i = 0; i < n; ++i)
      {
        const Point<2>    &a = vertices[i], &b = vertices[(i + 1) % n];
        const Tensor<1, 2> e = b - a;
        const double       t =
          std::clamp((p - a) * e / std::max(e.norm_square(), 1e-300), 0., 1.);
        const Point<2> q = a + t * e;
        if (p.distance(q) < nearest.distance)
          nearest = {q, p.distance(q), start + t * e.norm()};
        start += e.norm();
      }
    return nearest;
  }



  bool
  polygon_contains(const std::vector<Point<2>> &vertices, const Point<2> &p)
  {
    // On an edge counts as inside (the closed region) ...
    const unsigned int n = vertices.size();
    for (unsigned int i = 0; i < n; ++i)
      {
        const Point<2>     a = vertices[i], b = vertices[(i + 1) % n];
        const Tensor<1, 2> e = b - a, d = p - a;
        const double       t = (d * e) / (e * e);
        if (t >= 0 && t <= 1 &&
            std::abs(d[0] * e[1] - d[1] * e[0]) <= 1e-12 * e.norm_square())
          return true;
      }
    // ... elsewhere the crossing number of a ray in +x decides.
    bool inside = false;
    for (unsigned int i = 0, j = n - 1; i < n; j = i++)
      {
        const Point<2> &a = vertices[i], &b = vertices[j];
        if ((a[1] > p[1]) != (b[1] > p[1]) &&
            p[0] < a[0] + (p[1] - a[1]) * (b[0] - a[0]) / (b[1] - a[1]))
          inside = !inside;
      }
    return inside;
  }



  double
  BodyRegion::area() const
  {
    switch (region_shape)
      {
        case Shape::rectangle:
          return (upper_right[0] - lower_left[0]) *
                 (upper_right[1] - lower_left[1]);
        case Shape::rectangle_minus_disc:
          {
            // parse_parameters() admits discs inside the rectangle or centred
            // on its edges or corners: a whole, half or quarter hole.
            const double rect = (upper_right[0] - lower_left[0]) *
                                (upper_right[1] - lower_left[1]);
            double fraction = 1.;
            for (unsigned int d = 0; d < 2; ++d)
              if (disc_center[d] == lower_left[d] ||
                  disc_center[d] == upper_right[d])
                fraction /= 2;
            return rect - fraction * numbers::PI * disc_radius * disc_radius;
          }
        case Shape::rotated_rectangle:
          return width * height;
        case Shape::annulus_sector:
          return (annulus.outer_radius * annulus.outer_radius -
                  annulus.inner_radius * annulus.inner_radius) /
                 2 * (annulus.end_angle - annulus.start_angle);
        case Shape::polygon:
          {
            // The shoelace formula: positive for counter-clockwise vertices.
            double             twice = 0;
            const unsigned int n     = vertices.size();
            for (unsigned int i = 0; i < n; ++i)
              twice += vertices[i][0] * vertices[(i + 1) % n][1] -
                       vertices[(i + 1) % n][0] * vertices[i][1];
            return twice / 2;
          }
      }
    return 0;
  }



  std::array<Point<2>, 4>
  BodyRegion::corners() const
  {
    if (region_shape == Shape::rotated_rectangle)
      {
        const double c = std::cos(angle), s = std::sin(angle);
        const auto   corner = [&](const double x, const double y) {
          return center + Tensor<1, 2>({c * x - s * y, s * x + c * y});
        };
        return {{corner(-width / 2, -height / 2),
                 corner(width / 2, -height / 2),
                 corner(width / 2, height / 2),
                 corner(-width / 2, height / 2)}};
      }
    return {{lower_left,
             Point<2>(upper_right[0], lower_left[1]),
             upper_right,
             Point<2>(lower_left[0], upper_right[1])}};
  }



  void
  BodyRegion::boundary_parts(
    std::vector<std::string>                           &names,
    std::vector<std::function<Point<2>(const double)>> &parts) const
  {
    names.clear();
    parts.clear();
    if (region_shape == Shape::annulus_sector)
      {
        const Sector &a = annulus;
        // cos(3 pi / 2) is -1.8e-16, not 0: a sector edge on a grid face
        // would start outside the grid. Directions within round-off of an
        // axis are taken exactly along it.
        const auto at = [a](const double r, const double t) {
          double c = std::cos(t), s = std::sin(t);
          c = std::abs(c) < 1e-15 ? 0. : c;
          s = std::abs(s) < 1e-15 ? 0. : s;
          return Point<2>(a.center[0] + r * c, a.center[1] + r * s);
        };
        const auto arc =
          [at](const double r, const double t0, const double t1) {
            return [=](const double f) { return at(r, t0 + f * (t1 - t0)); };
          };
        const auto ray =
          [at](const double t, const double r0, const double r1) {
            return [=](const double f) { return at(r0 + f * (r1 - r0), t); };
          };
        names = {"start edge", "outer arc", "end edge", "inner arc"};
        parts = {ray(a.start_angle, a.inner_radius, a.outer_radius),
                 arc(a.outer_radius, a.start_angle, a.end_angle),
                 ray(a.end_angle, a.outer_radius, a.inner_radius),
                 arc(a.inner_radius, a.end_angle, a.start_angle)};
        // Inner radius 0: a circular sector, whose edges meet at the centre.
        if (a.inner_radius == 0.)
          {
            names.pop_back();
            parts.pop_back();
          }
      }
    else if (region_shape == Shape::polygon)
      {
        const unsigned int n = vertices.size();
        for (unsigned int k = 0; k < n; ++k)
          {
            const Point<2> p0 = vertices[k], p1 = vertices[(k + 1) % n];
            names.push_back("edge " + std::to_string(k));
            parts.push_back(
              [=](const double f) { return Point<2>(p0 + f * (p1 - p0)); });
          }
      }
    else
      {
        const auto                       c          = corners();
        const std::array<std::string, 4> edge_names = {
          {"bottom", "right", "top", "left"}};
        const auto segment = [](const Point<2> p0, const Point<2> p1) {
          return [=](const double f) { return Point<2>(p0 + f * (p1 - p0)); };
        };
        if (region_shape != Shape::rectangle_minus_disc)
          for (unsigned int k = 0; k < 4; ++k)
            {
              names.push_back(edge_names[k]);
              parts.push_back(segment(c[k], c[(k + 1) % 4]));
            }
        else
          {
            // Walk round the rectangle; where the disc meets an edge, the
            // edge stops at the disc and the hole's arc (clockwise, the
            // body on its left) leads to where the boundary goes on.
            const Point<2> C   = disc_center;
            const double   r   = disc_radius;
            const double   eps = 1e-12 * (upper_right - lower_left).norm();
            const auto     arc = [C, r](const Point<2> a, const Point<2> b) {
              const double t0    = std::atan2(a[1] - C[1], a[0] - C[0]);
              double       sweep = t0 - std::atan2(b[1] - C[1], b[0] - C[0]);
              sweep -= 2 * numbers::PI * std::floor(sweep / (2 * numbers::PI));
              if (sweep == 0)
                sweep = 2 * numbers::PI;
              return [=](const double f) {
                return Point<2>(C[0] + r * std::cos(t0 - f * sweep),
                                C[1] + r * std::sin(t0 - f * sweep));
              };
            };
            bool     open_arc = false; // an arc waits for its end point
            Point<2> arc_start;
            for (unsigned int k = 0; k < 4; ++k)
              {
                const Point<2>     p0 = c[k], p1 = c[(k + 1) % 4];
                const double       L   = p0.distance(p1);
                const Tensor<1, 2> e   = (p1 - p0) / L;
                const Tensor<1, 2> d   = C - p0;
                const double       tau = d * e;
                const bool         on_edge =
                  std::abs(d[0] * e[1] - d[1] * e[0]) < eps && tau > -eps &&
                  tau < L + eps;
                double begin = 0, end = L;
                if (on_edge && tau < eps)
                  begin = r;
                const bool splits = on_edge && tau >= eps && tau <= L - eps;
                const bool ends   = on_edge && tau > L - eps;
                if (open_arc)
                  {
                    names.push_back("hole");
                    parts.push_back(arc(arc_start, p0 + begin * e));
                    open_arc = false;
                  }
                if (splits)
                  {
                    names.push_back(edge_names[k]);
                    parts.push_back(segment(p0, p0 + (tau - r) * e));
                    names.push_back("hole");
                    parts.push_back(
                      arc(p0 + (tau - r) * e, p0 + (tau + r) * e));
                    begin = tau + r;
                  }
                if (ends)
                  end = L - r;
                names.push_back(edge_names[k]);
                parts.push_back(segment(p0 + begin * e, p0 + end * e));
                if (ends)
                  {
                    open_arc  = true;
                    arc_start = p0 + end * e;
                  }
              }
            if (open_arc) // the disc sits on the first corner
              {
                names.insert(names.begin(), "hole");
                parts.insert(parts.begin(),
                             arc(arc_start,
                                 c[0] +
                                   r * (c[1] - c[0]) / c[0].distance(c[1])));
              }
          }
      }
  }



  std::string
  BodyRegion::shape_name() const
  {
    switch (region_shape)
      {
        case Shape::rectangle:
          return "rectangle";
        case Shape::rotated_rectangle:
          return "rotated rectangle";
        case Shape::annulus_sector:
          return "annulus sector";
        case Shape::rectangle_minus_disc:
          return "rectangle minus disc";
        case Shape::polygon:
          return "polygon";
      }
    return "";
  }



  void
  BodyRegion::check_edge(const std::string &edge,
                         const std::string &where) const
  {
    std::vector<std::string> known;
    for (const auto &name : boundary_part_names())
      if (std::find(known.begin(), known.end(), name) == known.end())
        known.push_back(name);
    // A disc inside the rectangle is a hole of its own (boundary_points()).
    if (region_shape == Shape::rectangle_minus_disc &&
        std::find(known.begin(), known.end(), "hole") == known.end())
      known.push_back("hole");
    known.push_back("boundary");
    if (std::find(known.begin(), known.end(), edge) != known.end())
      return;
    std::string list;
    for (unsigned int k = 0; k < known.size(); ++k)
      list += (k == 0                ? "" :
               k + 1 == known.size() ? " and " :
                                       ", ") +
              ("'" + known[k] + "'");
    AssertThrow(false,
                ExcMessage(
                  where + ": the body region (Shape = " + shape_name() +
                  ") has no edge '" + edge + "'; it has " + list + "."));
  }



  BodyRegion::BoundaryPoints
  BodyRegion::boundary_points(const std::string &edge,
                              const unsigned int n) const
  {
    AssertThrow(n >= 2,
                ExcMessage("Boundary curves: at least 2 points per edge are "
                           "needed, got " +
                           std::to_string(n) + "."));
    // The parts of the boundary, each from its first point to its last, in
    // counter-clockwise order round the body.
    std::vector<std::string>                           names;
    std::vector<std::function<Point<2>(const double)>> parts;
    boundary_parts(names, parts);
    // A disc inside the rectangle is a hole of its own: a closed curve.
    if (region_shape == Shape::rectangle_minus_disc && edge == "hole" &&
        std::find(names.begin(), names.end(), "hole") == names.end())
      {
        BoundaryPoints result;
        result.closed = true;
        for (unsigned int i = 0; i + 1 < n; ++i)
          {
            const double t = -2 * numbers::PI * i / (n - 1);
            result.points.emplace_back(disc_center[0] +
                                         disc_radius * std::cos(t),
                                       disc_center[1] +
                                         disc_radius * std::sin(t));
          }
        return result;
      }

    BoundaryPoints result;
    const auto     sample = [n](const auto &part, const bool skip_last) {
      std::vector<Point<2>> points;
      for (unsigned int i = 0; i + (skip_last ? 1 : 0) < n; ++i)
        points.push_back(part(double(i) / (n - 1)));
      return points;
    };
    if (edge == "boundary")
      {
        result.closed = true;
        for (const auto &part : parts)
          {
            result.corners.push_back(result.points.size());
            const auto points = sample(part, true);
            result.points.insert(result.points.end(),
                                 points.begin(),
                                 points.end());
          }
        return result;
      }
    AssertThrow(std::count(names.begin(), names.end(), edge) <= 1,
                ExcMessage("Boundary curves: the hole splits the edge '" +
                           edge +
                           "' of the body region in two; give its parts "
                           "by coordinates, or use 'boundary'."));
    for (unsigned int k = 0; k < names.size(); ++k)
      if (names[k] == edge)
        {
          result.points = sample(parts[k], false);
          return result;
        }
    std::string known;
    for (const auto &name : names)
      known += "'" + name + "', ";
    AssertThrow(false,
                ExcMessage("Boundary curves: the body region has no edge '" +
                           edge + "'; it has " + known + "and 'boundary'."));
    return result;
  }



  BoundingBox<2>
  BodyRegion::bounding_box() const
  {
    switch (region_shape)
      {
        case Shape::annulus_sector:
          {
            // Sample the arcs densely enough and add the extreme points of the
            // circles that the sector contains.
            std::vector<Point<2>> points;
            const unsigned int    n = 720;
            for (unsigned int k = 0; k <= n; ++k)
              {
                const double a =
                  annulus.start_angle +
                  (annulus.end_angle - annulus.start_angle) * k / n;
                for (const double r :
                     {annulus.inner_radius, annulus.outer_radius})
                  points.emplace_back(annulus.center[0] + r * std::cos(a),
                                      annulus.center[1] + r * std::sin(a));
              }
            BoundingBox<2> box(points);
            // Round the sampled extremes outwards by the chord sagitta.
            box.extend(annulus.outer_radius * (1 - std::cos(numbers::PI / n)));
            return box;
          }
        case Shape::polygon:
          return BoundingBox<2>(vertices);
        default:
          {
            const auto corner = corners();
            return BoundingBox<2>(
              std::vector<Point<2>>(corner.begin(), corner.end()));
          }
      }
  }
} // namespace bsmpm
