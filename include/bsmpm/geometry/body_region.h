#ifndef bsmpm_body_region_h
#define bsmpm_body_region_h

#include <deal.II/base/bounding_box.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>

#include <functional>
#include <string>
#include <vector>

namespace bsmpm
{
  using namespace dealii;

  /**
   * The region of the plane that the body occupies at the start of a run:
   * where material points are generated. Shapes: an axis-aligned rectangle,
   * a rotated rectangle, an annulus sector, a rectangle minus a disc, a
   * simple polygon (vertices counter-clockwise; its edges are "edge 0" from
   * vertex 0 to vertex 1, ..., "edge n-1" from the last vertex back to
   * vertex 0). A polygon has no holes: a hole is cut out of the points by a
   * closed boundary curve with "Trim material points", or the body is given
   * as a polygon whose boundary runs round the hole and back along a slit.
   */
  class BodyRegion
  {
  public:
    enum class Shape
    {
      rectangle,
      rotated_rectangle,
      annulus_sector,
      rectangle_minus_disc,
      polygon
    };

    static void
    declare_parameters(ParameterHandler &prm);
    void
    parse_parameters(ParameterHandler &prm);

    /** The axis-aligned rectangle from @p lower_left to @p upper_right. */
    static BodyRegion
    rectangle(const Point<2> &lower_left, const Point<2> &upper_right);

    /** Whether @p p lies in the closed region. */
    bool
    contains(const Point<2> &p) const;

    /** Exact area of the region. */
    double
    area() const;

    /** Smallest axis-aligned box holding the region. */
    BoundingBox<2>
    bounding_box() const;

    Shape
    shape() const
    {
      return region_shape;
    }

    /** Corners of a rotated rectangle (or rectangle), counter-clockwise,
     * starting at the lower left corner before rotation. */
    std::array<Point<2>, 4>
    corners() const;

    /** Points along a part of the region's boundary, ordered so that the
     * body lies to their left. */
    struct BoundaryPoints
    {
      std::vector<Point<2>>     points;
      bool                      closed = false;
      std::vector<unsigned int> corners;
    };

    /**
     * @p n_points equally spaced points (by length) along part @p edge of the
     * boundary, both ends included: for (rotated) rectangles "bottom",
     * "right", "top", "left" (in the rectangle's own frame); for annulus
     * sectors "inner arc", "outer arc", "start edge", "end edge"; for both
     * "boundary", the whole closed boundary with @p n_points per side and its
     * corners marked.
     */
    BoundaryPoints
    boundary_points(const std::string &edge, const unsigned int n_points) const;

    /**
     * Refuses an @p edge that boundary_points() does not know for this
     * shape (an edge of another shape, a misspelt one), with a message that
     * starts with @p where (the parameter) and lists the edges there are.
     */
    void
    check_edge(const std::string &edge, const std::string &where) const;

    /** The shape's name, as in the parameter file. */
    std::string
    shape_name() const;

    /** Names of the parts of the boundary that boundary_points() knows, in
     * counter-clockwise order round the body (a name twice where a hole
     * splits an edge). */
    std::vector<std::string>
    boundary_part_names() const
    {
      std::vector<std::string>                           names;
      std::vector<std::function<Point<2>(const double)>> parts;
      boundary_parts(names, parts);
      return names;
    }

    /** Data of an annulus sector (angles in radians). */
    struct Sector
    {
      Point<2> center;
      double   inner_radius, outer_radius, start_angle, end_angle;
    };
    const Sector &
    sector() const
    {
      return annulus;
    }

  private:
    /** The checks of parse_parameters(), one per shape: each refuses what
     * makes no region, with a message that names the entry (the angles in
     * degrees, as given). */
    void
    check_rectangle() const;
    void
    check_rotated_rectangle(const double angle_degrees) const;
    void
    check_annulus_sector(const double start_degrees,
                         const double end_degrees) const;
    /** At least three vertices, no two neighbours coincide, no two edges
     * cross (a simple polygon), counter-clockwise. */
    void
    check_polygon() const;

    /** The parts of the boundary, each a map from [0, 1] along it, with
     * their names, in counter-clockwise order round the body. */
    void
    boundary_parts(
      std::vector<std::string>                           &names,
      std::vector<std::function<Point<2>(const double)>> &parts) const;

    Shape    region_shape = Shape::rectangle;
    Point<2> lower_left, upper_right; // rectangle (and rectangle minus disc)
    Point<2> center;                  // rotated rectangle
    double   width = 1, height = 1, angle = 0;
    Sector   annulus;
    Point<2> disc_center;
    double   disc_radius = 0;
    /** Polygon: its vertices, counter-clockwise. */
    std::vector<Point<2>> vertices;
  };

  /** Whether @p p lies in the closed polygon @p vertices (a point on an
   * edge counts as inside). */
  bool
  polygon_contains(const std::vector<Point<2>> &vertices, const Point<2> &p);

  /** The point of the boundary of the closed polygon @p vertices nearest
   * to a point: where it is, how far, and its arc length along the
   * boundary from vertex 0 through vertices 1, 2, ... */
  struct PolygonEdgePoint
  {
    Point<2> point;
    double   distance   = 0;
    double   arc_length = 0;
  };

  /** The point of the boundary of the closed polygon @p vertices nearest
   * to @p p. */
  PolygonEdgePoint
  nearest_on_polygon(const std::vector<Point<2>> &vertices, const Point<2> &p);
} // namespace bsmpm

#endif
