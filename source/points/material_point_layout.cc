#include <bsmpm/base/parameter_tools.h>
#include <bsmpm/geometry/polygon_area.h>
#include <bsmpm/points/material_point_layout.h>

#include <array>
#include <cmath>
#include <vector>

namespace bsmpm
{
  namespace
  {
    /** Whether a point at @p p of a layout not tied to the cells is
     * wanted: outside the grid (for the caller to reject) or in a wanted
     * cell. */
    bool
    in_wanted_cell(
      const BackgroundGrid &grid,
      const std::function<bool(const MaterialPointLayout::CellIndex &)>
                     &wanted_cell,
      const Point<2> &p)
    {
      return !grid.contains(p) || wanted_cell(grid.cell_index(p));
    }



    /** The cell with lower left corner @p o and size @p h clipped by each
     * side of the convex quadrilateral @p corners (counter-clockwise), by
     * Sutherland-Hodgman: the cell's part of a (rotated) rectangle. */
    std::vector<Point<2>>
    clip_cell_to_body(const Point<2>                &o,
                      const Tensor<1, 2>            &h,
                      const std::array<Point<2>, 4> &corners)
    {
      std::vector<Point<2>> polygon = {o,
                                       o + Tensor<1, 2>({h[0], 0}),
                                       o + h,
                                       o + Tensor<1, 2>({0, h[1]})};
      for (unsigned int k = 0; k < 4 && !polygon.empty(); ++k)
        {
          const Point<2> a = corners[k], b = corners[(k + 1) % 4];
          const auto     side = [&](const Point<2> &p) {
            return cross_product_2d(b - a) * (p - a);
          };
          std::vector<Point<2>> clipped;
          for (unsigned int m = 0; m < polygon.size(); ++m)
            {
              const Point<2> &p = polygon[m];
              const Point<2> &q = polygon[(m + 1) % polygon.size()];
              // Inside: to the left of a -> b, i.e. side <= 0 for
              // the clockwise-turned edge normal.
              const double sp = -side(p), sq = -side(q);
              if (sp >= 0)
                clipped.push_back(p);
              if ((sp >= 0) != (sq >= 0))
                clipped.push_back(p + sp / (sp - sq) * (q - p));
            }
          polygon = clipped;
        }
      return polygon;
    }
  } // namespace



  void
  MaterialPointLayout::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Material points");
    prm.declare_entry("Layout",
                      "per cell",
                      Patterns::Selection(
                        "per cell|lattice|polar|cell centroid"),
                      "per cell: n x n points in every grid cell; lattice: "
                      "nx x ny points over a rectangle; polar: n_r x n_theta "
                      "points over an annulus-sector body; cell centroid: one "
                      "point per cell at the centroid of the cell's part "
                      "inside a (rotated) rectangle, with that part's area.");
    prm.declare_entry("Points per cell",
                      "2",
                      Patterns::Integer(1),
                      "per cell: number n of points per cell and direction.");
    prm.declare_entry("Lattice points",
                      "1, 1",
                      Patterns::List(Patterns::Integer(1), 2, 2, ","),
                      "lattice: nx, ny.");
    prm.declare_entry("Lattice lower left corner",
                      "",
                      Patterns::Anything(),
                      "lattice: lower left corner of the lattice rectangle; "
                      "empty means that of the body's bounding box.");
    prm.declare_entry("Lattice upper right corner",
                      "",
                      Patterns::Anything(),
                      "lattice: upper right corner of the lattice rectangle; "
                      "empty means that of the body's bounding box.");
    prm.declare_entry("Polar points",
                      "1, 1",
                      Patterns::List(Patterns::Integer(1), 2, 2, ","),
                      "polar: number of points across the radius and along "
                      "the arc.");
    prm.leave_subsection();
  }



  void
  MaterialPointLayout::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Material points");
    const std::string kind = prm.get("Layout");
    layout                 = kind == "per cell" ?
                               Kind::per_cell :
                               (kind == "lattice" ?
                                  Kind::lattice :
                                  (kind == "polar" ? Kind::polar : Kind::cell_centroid));
    points_per_cell        = prm.get_integer("Points per cell");
    const auto lattice  = ParameterTools::get_unsigned(prm, "Lattice points");
    lattice_points      = {{lattice[0], lattice[1]}};
    lattice_lower_left  = prm.get("Lattice lower left corner");
    lattice_upper_right = prm.get("Lattice upper right corner");
    if (!lattice_lower_left.empty())
      ParameterTools::get_point(prm, "Lattice lower left corner");
    if (!lattice_upper_right.empty())
      ParameterTools::get_point(prm, "Lattice upper right corner");
    const auto polar = ParameterTools::get_unsigned(prm, "Polar points");
    polar_points     = {{polar[0], polar[1]}};
    prm.leave_subsection();
  }



  void
  MaterialPointLayout::for_each_point(
    const BackgroundGrid                         &grid,
    const BodyRegion                             &region,
    const std::function<bool(const CellIndex &)> &wanted_cell,
    const std::function<void(const Point<2> &, double, unsigned long)> &f) const
  {
    // One function per layout: each generates its points and their
    // volumes, which must sum to the body's area.
    switch (layout)
      {
        case Kind::per_cell:
          for_each_point_per_cell(grid, region, wanted_cell, f);
          break;
        case Kind::lattice:
          for_each_lattice_point(grid, region, wanted_cell, f);
          break;
        case Kind::cell_centroid:
          for_each_cell_centroid(grid, region, wanted_cell, f);
          break;
        case Kind::polar:
          for_each_polar_point(grid, region, wanted_cell, f);
          break;
      }
  }



  void
  MaterialPointLayout::for_each_point_per_cell(const BackgroundGrid &grid,
                                               const BodyRegion     &region,
                                               const WantedCell   &wanted_cell,
                                               const PointVisitor &f) const
  {
    const unsigned int  n      = points_per_cell;
    const Tensor<1, 2> &h      = grid.cell_size();
    const double        volume = h[0] * h[1] / (n * n);
    for (unsigned int j = 0; j < grid.n_cells(1); ++j)
      for (unsigned int i = 0; i < grid.n_cells(0); ++i)
        {
          if (!wanted_cell({{i, j}}))
            continue;
          const Point<2>      origin = grid.cell_origin({{i, j}});
          const unsigned long first =
            (static_cast<unsigned long>(j) * grid.n_cells(0) + i) * n * n;
          for (unsigned int b = 0; b < n; ++b)
            for (unsigned int a = 0; a < n; ++a)
              {
                const Point<2> p(origin[0] + (a + 0.5) * h[0] / n,
                                 origin[1] + (b + 0.5) * h[1] / n);
                if (region.contains(p))
                  f(p, volume, first + b * n + a);
              }
        }
  }



  void
  MaterialPointLayout::for_each_lattice_point(const BackgroundGrid &grid,
                                              const BodyRegion     &region,
                                              const WantedCell     &wanted_cell,
                                              const PointVisitor   &f) const
  {
    const BoundingBox<2> box      = region.bounding_box();
    const auto           to_point = [](const std::string &text,
                             const Point<2>    &fallback) {
      if (text.empty())
        return fallback;
      const auto v =
        Utilities::string_to_double(Utilities::split_string_list(text, ','));
      return Point<2>(v[0], v[1]);
    };
    const Point<2> lower =
      to_point(lattice_lower_left, box.get_boundary_points().first);
    const Point<2> upper =
      to_point(lattice_upper_right, box.get_boundary_points().second);
    const double dx = (upper[0] - lower[0]) / lattice_points[0];
    const double dy = (upper[1] - lower[1]) / lattice_points[1];
    AssertThrow(dx > 0 && dy > 0,
                ExcMessage("Material points: the lattice rectangle "
                           "is empty."));
    for (unsigned int j = 0; j < lattice_points[1]; ++j)
      for (unsigned int i = 0; i < lattice_points[0]; ++i)
        {
          const Point<2> p(lower[0] + (i + 0.5) * dx,
                           lower[1] + (j + 0.5) * dy);
          if (region.contains(p) && in_wanted_cell(grid, wanted_cell, p))
            f(p,
              dx * dy,
              static_cast<unsigned long>(j) * lattice_points[0] + i);
        }
  }



  void
  MaterialPointLayout::for_each_cell_centroid(const BackgroundGrid &grid,
                                              const BodyRegion     &region,
                                              const WantedCell     &wanted_cell,
                                              const PointVisitor   &f) const
  {
    AssertThrow(region.shape() == BodyRegion::Shape::rectangle ||
                  region.shape() == BodyRegion::Shape::rotated_rectangle,
                ExcMessage("Material points: the cell centroid "
                           "layout needs a (rotated) rectangular "
                           "body region."));
    const auto corners = region.corners();
    for (unsigned int j = 0; j < grid.n_cells(1); ++j)
      for (unsigned int i = 0; i < grid.n_cells(0); ++i)
        {
          if (!wanted_cell({{i, j}}))
            continue;
          // The part of the cell inside the body, then its area and
          // centroid.
          const Point<2>              o = grid.cell_origin({{i, j}});
          const Tensor<1, 2>         &h = grid.cell_size();
          const std::vector<Point<2>> polygon =
            clip_cell_to_body(o, h, corners);
          const auto [area, moment] = polygon_area_and_moment(polygon);
          if (area > 1e-12 * h[0] * h[1])
            f(Point<2>(moment / area),
              area,
              static_cast<unsigned long>(j) * grid.n_cells(0) + i);
        }
  }



  void
  MaterialPointLayout::for_each_polar_point(const BackgroundGrid &grid,
                                            const BodyRegion     &region,
                                            const WantedCell     &wanted_cell,
                                            const PointVisitor   &f) const
  {
    AssertThrow(region.shape() == BodyRegion::Shape::annulus_sector,
                ExcMessage("Material points: the polar layout needs "
                           "an annulus sector body region."));
    const auto  &s      = region.sector();
    const double dr     = (s.outer_radius - s.inner_radius) / polar_points[0];
    const double dtheta = (s.end_angle - s.start_angle) / polar_points[1];
    for (unsigned int j = 0; j < polar_points[1]; ++j)
      for (unsigned int i = 0; i < polar_points[0]; ++i)
        {
          const double   r0 = s.inner_radius + i * dr, r1 = r0 + dr;
          const double   r     = (r0 + r1) / 2;
          const double   theta = s.start_angle + (j + 0.5) * dtheta;
          const Point<2> p(s.center[0] + r * std::cos(theta),
                           s.center[1] + r * std::sin(theta));
          if (in_wanted_cell(grid, wanted_cell, p))
            f(p,
              (r1 * r1 - r0 * r0) / 2 * dtheta,
              static_cast<unsigned long>(j) * polar_points[0] + i);
        }
  }



  unsigned long
  MaterialPointLayout::n_candidates(const BackgroundGrid &grid) const
  {
    const unsigned long cells =
      static_cast<unsigned long>(grid.n_cells(0)) * grid.n_cells(1);
    switch (layout)
      {
        case Kind::per_cell:
          return cells * points_per_cell * points_per_cell;
        case Kind::lattice:
          return static_cast<unsigned long>(lattice_points[0]) *
                 lattice_points[1];
        case Kind::polar:
          return static_cast<unsigned long>(polar_points[0]) * polar_points[1];
        case Kind::cell_centroid:
          return cells;
      }
    return 0;
  }
} // namespace bsmpm
