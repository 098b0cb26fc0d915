// Cut cells: CutCellGeometry (the moments of each cell's part inside a body
// bounded by closed B-splines, from one Green's-theorem sweep per grid row)
// and MomentFitting (non-negative weights for the points of a cut cell with
// the exact moments).
//
// Geometry: polygons (B-splines with a corner at every point are exactly
// straight) against an independent reference, Sutherland-Hodgman clipping of
// the polygon by each cell and the closed-form moments of the clipped
// polygon; curved bodies against the total area oint x dy along the curve
// and a fine sampling; boundaries along grid lines and through grid
// vertices; a body with a hole; 300 random bodies. Fitting: closest to the
// volumes, the fallbacks, and every cut cell of the random polygons.

#include <deal.II/base/quadrature_lib.h>

#include <bsmpm/geometry/b_spline_curve.h>
#include <bsmpm/geometry/curve_cell_intersection.h>
#include <bsmpm/geometry/cut_cell_geometry.h>
#include <bsmpm/quadrature/moment_fitting.h>

#include <array>
#include <cmath>
#include <vector>

// tests.h uses deallog unqualified: the using directive must come first.
using namespace dealii;

#include "../tests.h"

#include "../unit_test.h"

using namespace bsmpm;

namespace
{
  using Moments = CutCellGeometry::Moments;

  struct Body
  {
    std::vector<std::unique_ptr<BSplineCurve>> curves;
    std::vector<std::vector<CurvePiece>>       pieces;

    CutCellGeometry::Boundary
    boundary() const
    {
      CutCellGeometry::Boundary b;
      for (unsigned int c = 0; c < curves.size(); ++c)
        {
          b.curves.push_back(curves[c].get());
          b.pieces.push_back(&pieces[c]);
        }
      return b;
    }
  };

  /** A closed curve through @p points, straight between them if
   * @p polygon, cut by @p grid, added to @p body. */
  void
  add_curve(Body                        &body,
            const std::vector<Point<2>> &points,
            const bool                   polygon,
            const UniformGrid           &grid)
  {
    std::vector<unsigned int> corners;
    if (polygon)
      for (unsigned int i = 0; i < points.size(); ++i)
        corners.push_back(i);
    body.curves.push_back(
      std::make_unique<BSplineCurve>(points, true, corners));
    body.pieces.push_back(
      CurveCellIntersection::cut(*body.curves.back(), grid));
  }

  /** oint x dy over the curves: the enclosed area. */
  double
  enclosed_area(const Body &body)
  {
    const QGauss<1> gauss(6);
    double          area = 0;
    for (const auto &curve : body.curves)
      for (unsigned int k = 0; k < curve->n_segments(); ++k)
        {
          const auto range = curve->segment_parameters(k);
          for (unsigned int q = 0; q < gauss.size(); ++q)
            {
              const double u =
                range[0] + gauss.point(q)[0] * (range[1] - range[0]);
              area += curve->value(u)[0] * curve->derivative(u)[1] *
                      (range[1] - range[0]) * gauss.weight(q);
            }
        }
    return area;
  }

  /** The polygon @p polygon clipped by the cell (Sutherland-Hodgman), in
   * the cell's local coordinates. */
  std::vector<Point<2>>
  clip(const std::vector<Point<2>>       &polygon,
       const UniformGrid                 &grid,
       const std::array<unsigned int, 2> &cell)
  {
    std::vector<Point<2>> out;
    for (const auto &p : polygon)
      out.emplace_back((p[0] - grid.lower_left[0]) / grid.cell_size[0] -
                         cell[0],
                       (p[1] - grid.lower_left[1]) / grid.cell_size[1] -
                         cell[1]);
    for (unsigned int side = 0; side < 4 && !out.empty(); ++side)
      {
        const unsigned int d     = side / 2;
        const double       limit = side % 2;
        // Inside: x_d >= 0 (side 0, 2) or x_d <= 1 (side 1, 3).
        const auto inside = [&](const Point<2> &p) {
          return side % 2 == 0 ? p[d] >= limit : p[d] <= limit;
        };
        std::vector<Point<2>> in = out;
        out.clear();
        for (unsigned int i = 0; i < in.size(); ++i)
          {
            const Point<2> &a = in[i], &b = in[(i + 1) % in.size()];
            const bool      ia = inside(a), ib = inside(b);
            if (ia)
              out.push_back(a);
            if (ia != ib)
              {
                const double f = (limit - a[d]) / (b[d] - a[d]);
                out.push_back(a + f * (b - a));
              }
          }
      }
    return out;
  }

  /** Closed-form moments 1, s, t, s^2, s t, t^2 of a polygon. */
  Moments
  polygon_moments(const std::vector<Point<2>> &p)
  {
    Moments m{};
    for (unsigned int i = 0; i < p.size(); ++i)
      {
        const double x0 = p[i][0], y0 = p[i][1];
        const double x1 = p[(i + 1) % p.size()][0],
                     y1 = p[(i + 1) % p.size()][1];
        const double c  = x0 * y1 - x1 * y0;
        m[0] += c / 2;
        m[1] += (x0 + x1) * c / 6;
        m[2] += (y0 + y1) * c / 6;
        m[3] += (x0 * x0 + x0 * x1 + x1 * x1) * c / 12;
        m[4] += (x0 * y1 + 2 * x0 * y0 + 2 * x1 * y1 + x1 * y0) * c / 24;
        m[5] += (y0 * y0 + y0 * y1 + y1 * y1) * c / 12;
      }
    return m;
  }

  /** Largest difference of the geometry's moments to the clipping
   * reference over all cells of the grid. */
  double
  polygon_defect(const CutCellGeometry       &geometry,
                 const std::vector<Point<2>> &polygon,
                 const UniformGrid           &grid)
  {
    double defect = 0;
    for (unsigned int j = 0; j < grid.n_cells[1]; ++j)
      for (unsigned int i = 0; i < grid.n_cells[0]; ++i)
        {
          const Moments  ref = polygon_moments(clip(polygon, grid, {{i, j}}));
          const Moments &m   = geometry.moments({{i, j}});
          for (unsigned int k = 0; k < 6; ++k)
            defect = std::max(defect, std::abs(m[k] - ref[k]));
        }
    return defect;
  }

  std::vector<Point<2>>
  random_star(Random        &random,
              const Point<2> center,
              const double   radius,
              const unsigned n,
              const double   spread)
  {
    std::vector<double> angles;
    for (unsigned int k = 0; k < n; ++k)
      angles.push_back(2 * numbers::PI * (k + random(0.1, 0.9)) / n);
    std::vector<Point<2>> points;
    for (const double a : angles)
      {
        const double r = radius * random(1 - spread, 1);
        points.emplace_back(center[0] + r * std::cos(a),
                            center[1] + r * std::sin(a));
      }
    return points;
  }

  /** The regular n x n points of each cell that lie in the polygon. */
  bool
  inside_polygon(const std::vector<Point<2>> &polygon, const Point<2> &x)
  {
    bool in = false;
    for (unsigned int i = 0, j = polygon.size() - 1; i < polygon.size();
         j = i++)
      if ((polygon[i][1] > x[1]) != (polygon[j][1] > x[1]) &&
          x[0] < (polygon[j][0] - polygon[i][0]) * (x[1] - polygon[i][1]) /
                     (polygon[j][1] - polygon[i][1]) +
                   polygon[i][0])
        in = !in;
    return in;
  }

  void
  check_polygons()
  {
    deallog.push("polygons");
    // A square rotated by 30 degrees, and the paper's 45-degree square.
    for (const double angle : {30., 45.})
      {
        const UniformGrid     grid{Point<2>(0, 0),
                               Tensor<1, 2>({0.01, 0.01}),
                               {{15, 15}}};
        std::vector<Point<2>> square;
        const double          a = angle * numbers::PI / 180;
        for (const auto &c : {Point<2>(-0.05, -0.05),
                              Point<2>(0.05, -0.05),
                              Point<2>(0.05, 0.05),
                              Point<2>(-0.05, 0.05)})
          square.emplace_back(0.075 + std::cos(a) * c[0] - std::sin(a) * c[1],
                              0.075 + std::sin(a) * c[0] + std::cos(a) * c[1]);
        Body body;
        add_curve(body, square, true, grid);
        CutCellGeometry geometry;
        geometry.reinit(body.boundary(), grid);
        deallog << angle << " degrees: " << geometry.n_cut_cells()
                << " cut cells, area = 0.01 to 1e-14: "
                << yes_no(std::abs(geometry.area() - 0.01) < 1e-14)
                << ", moments equal the clipped polygon's to 1e-14: "
                << yes_no(polygon_defect(geometry, square, grid) < 1e-14)
                << std::endl;
      }

    // Boundaries along grid lines and through grid vertices: a square on
    // grid lines, and a diamond through vertices.
    {
      const UniformGrid     grid{Point<2>(0, 0),
                             Tensor<1, 2>({0.25, 0.25}),
                             {{8, 8}}};
      std::vector<Point<2>> square = {Point<2>(0.5, 0.25),
                                      Point<2>(1.5, 0.25),
                                      Point<2>(1.5, 1.75),
                                      Point<2>(0.5, 1.75)};
      Body                  body;
      add_curve(body, square, true, grid);
      CutCellGeometry geometry;
      geometry.reinit(body.boundary(), grid);
      unsigned int n_full = 0;
      for (unsigned int j = 0; j < 8; ++j)
        for (unsigned int i = 0; i < 8; ++i)
          n_full += geometry.fill({{i, j}}) == CutCellGeometry::Fill::full;
      deallog << "square on grid lines: cut cells " << geometry.n_cut_cells()
              << ", full cells " << n_full << ", area "
              << filter_roundoff(geometry.area() - 1.5) + 1.5 << std::endl;

      std::vector<Point<2>> diamond = {Point<2>(1, 0.25),
                                       Point<2>(1.75, 1),
                                       Point<2>(1, 1.75),
                                       Point<2>(0.25, 1)};
      Body                  body2;
      add_curve(body2, diamond, true, grid);
      geometry.reinit(body2.boundary(), grid);
      deallog << "diamond through grid vertices: cut cells "
              << geometry.n_cut_cells() << ", area = 1.125 to 1e-14: "
              << yes_no(std::abs(geometry.area() - 1.125) < 1e-14)
              << ", moments equal the clipped polygon's to 1e-14: "
              << yes_no(polygon_defect(geometry, diamond, grid) < 1e-14)
              << std::endl;
    }

    // 200 random star-shaped polygons on random grids.
    Random       random(31);
    double       worst_area = 0, worst_moment = 0;
    unsigned int n_cut = 0;
    for (unsigned int trial = 0; trial < 200; ++trial)
      {
        const double      h  = random(0.05, 0.3);
        const double      hy = h * random(0.5, 2);
        const UniformGrid grid{Point<2>(random(-0.1, 0), random(-0.1, 0)),
                               Tensor<1, 2>({h, hy}),
                               {{static_cast<unsigned int>(2.1 / h) + 1,
                                 static_cast<unsigned int>(2.1 / hy) + 1}}};
        const auto        polygon = random_star(
          random, Point<2>(1.0, 1.0), 0.9, 3 + trial % 20, random(0, 0.8));
        Body body;
        add_curve(body, polygon, true, grid);
        CutCellGeometry geometry;
        geometry.reinit(body.boundary(), grid);
        worst_area =
          std::max(worst_area,
                   std::abs(geometry.area() - polygon_moments(polygon)[0]) /
                     polygon_moments(polygon)[0]);
        worst_moment =
          std::max(worst_moment, polygon_defect(geometry, polygon, grid));
        n_cut += geometry.n_cut_cells();
      }
    deallog << "200 random polygons, " << n_cut
            << " cut cells: areas sum to the polygon's to 1e-12: "
            << yes_no(worst_area < 1e-12)
            << ", every cell's moments equal the clipped polygon's to "
               "1e-13: "
            << yes_no(worst_moment < 1e-13) << std::endl;
    deallog.pop();
  }

  void
  check_curves()
  {
    deallog.push("curves");
    // 100 random smooth bodies: the cells' areas sum to oint x dy; every
    // fraction lies in [0, 1] and every centroid in its cell.
    Random       random(77);
    double       worst_area = 0;
    bool         bounded    = true;
    unsigned int n_cut      = 0;
    for (unsigned int trial = 0; trial < 100; ++trial)
      {
        const double      h  = random(0.04, 0.25);
        const double      hy = h * random(0.5, 2);
        const UniformGrid grid{Point<2>(random(-0.1, 0), random(-0.1, 0)),
                               Tensor<1, 2>({h, hy}),
                               {{static_cast<unsigned int>(2.5 / h) + 1,
                                 static_cast<unsigned int>(2.5 / hy) + 1}}};
        Body              body;
        add_curve(body,
                  random_star(random, Point<2>(1.2, 1.2), 1, 12, 0.4),
                  false,
                  grid);
        CutCellGeometry geometry;
        geometry.reinit(body.boundary(), grid);
        const double exact = enclosed_area(body);
        worst_area =
          std::max(worst_area, std::abs(geometry.area() - exact) / exact);
        n_cut += geometry.n_cut_cells();
        for (unsigned int j = 0; j < grid.n_cells[1]; ++j)
          for (unsigned int i = 0; i < grid.n_cells[0]; ++i)
            {
              const Moments &m = geometry.moments({{i, j}});
              bounded = bounded && m[0] >= 0 && m[0] <= 1 && m[1] >= -1e-15 &&
                        m[1] <= m[0] + 1e-15 && m[2] >= -1e-15 &&
                        m[2] <= m[0] + 1e-15 && m[3] <= m[1] + 1e-15 &&
                        m[5] <= m[2] + 1e-15;
            }
      }
    deallog << "100 random curved bodies, " << n_cut
            << " cut cells: areas sum to oint x dy to 1e-12: "
            << yes_no(worst_area < 1e-12)
            << ", fractions in [0, 1], centroids and second moments within "
               "their cells: "
            << yes_no(bounded) << std::endl;

    // A disc of radius 0.7 (64 points) against a sampling of 400^2 points
    // per cell with an inside test on the spline.
    {
      const UniformGrid     grid{Point<2>(0, 0),
                             Tensor<1, 2>({0.25, 0.25}),
                             {{8, 8}}};
      std::vector<Point<2>> circle;
      for (unsigned int k = 0; k < 64; ++k)
        circle.emplace_back(1.03 + 0.7 * std::cos(2 * numbers::PI * k / 64),
                            0.98 + 0.7 * std::sin(2 * numbers::PI * k / 64));
      Body body;
      add_curve(body, circle, false, grid);
      CutCellGeometry geometry;
      geometry.reinit(body.boundary(), grid);
      // The spline as a fine polyline; each sampling row's crossings with
      // it decide inside and outside.
      std::vector<Point<2>> fine;
      for (unsigned int k = 0; k < 64 * 64; ++k)
        fine.push_back(body.curves[0]->value(k / (64. * 64)));
      double       worst = 0;
      const int    n     = 400;
      unsigned int cut   = 0;
      for (unsigned int j = 0; j < 8; ++j)
        for (unsigned int i = 0; i < 8; ++i)
          {
            if (geometry.fill({{i, j}}) != CutCellGeometry::Fill::cut)
              continue;
            ++cut;
            Moments ref{};
            for (int b = 0; b < n; ++b)
              {
                const double        t = (b + 0.5) / n, y = 0.25 * (j + t);
                std::vector<double> crossings;
                for (unsigned int e = 0; e < fine.size(); ++e)
                  {
                    const Point<2> &p = fine[e],
                                   &q = fine[(e + 1) % fine.size()];
                    if ((p[1] > y) != (q[1] > y))
                      crossings.push_back(p[0] + (y - p[1]) * (q[0] - p[0]) /
                                                   (q[1] - p[1]));
                  }
                for (int a = 0; a < n; ++a)
                  {
                    const double s = (a + 0.5) / n, x = 0.25 * (i + s);
                    unsigned int left = 0;
                    for (const double c : crossings)
                      left += c < x;
                    if (left % 2 == 0)
                      continue;
                    const double w = 1. / (n * n);
                    ref[0] += w;
                    ref[1] += w * s;
                    ref[2] += w * t;
                    ref[3] += w * s * s;
                    ref[4] += w * s * t;
                    ref[5] += w * t * t;
                  }
              }
            for (unsigned int k = 0; k < 6; ++k)
              worst =
                std::max(worst,
                         std::abs(ref[k] - geometry.moments({{i, j}})[k]));
          }
      deallog << "disc: " << cut
              << " cut cells, moments equal a 400^2 sampling to 2e-3: "
              << yes_no(worst < 2e-3) << std::endl;
    }

    // An annulus: outer loop counter-clockwise, hole clockwise.
    {
      const UniformGrid     grid{Point<2>(-1.1, -1.1),
                             Tensor<1, 2>({0.1, 0.1}),
                             {{22, 22}}};
      std::vector<Point<2>> outer, inner;
      for (unsigned int k = 0; k < 48; ++k)
        {
          const double a = 2 * numbers::PI * k / 48;
          outer.emplace_back(std::cos(a), std::sin(a));
          inner.emplace_back(0.43 * std::cos(-a) + 0.013,
                             0.43 * std::sin(-a) - 0.021);
        }
      Body body;
      add_curve(body, outer, false, grid);
      add_curve(body, inner, false, grid);
      CutCellGeometry geometry;
      geometry.reinit(body.boundary(), grid);
      const double exact = enclosed_area(body);
      deallog << "annulus: area " << geometry.area()
              << ", equals oint x dy to 1e-12: "
              << yes_no(std::abs(geometry.area() - exact) < 1e-12 * exact)
              << ", within 1e-5 of pi (1 - 0.43^2): "
              << yes_no(std::abs(geometry.area() -
                                 numbers::PI * (1 - 0.43 * 0.43)) < 1e-5)
              << std::endl;
    }

    // An open boundary is reported.
    {
      const UniformGrid grid{Point<2>(0, 0),
                             Tensor<1, 2>({0.5, 0.5}),
                             {{4, 4}}};
      Body              body;
      body.curves.push_back(std::make_unique<BSplineCurve>(
        std::vector<Point<2>>{Point<2>(0.3, 0.4),
                              Point<2>(1.6, 0.6),
                              Point<2>(1.2, 1.7)},
        false));
      body.pieces.push_back(
        CurveCellIntersection::cut(*body.curves.back(), grid));
      CutCellGeometry geometry;
      bool            thrown = false;
      try
        {
          geometry.reinit(body.boundary(), grid);
        }
      catch (const ExceptionBase &)
        {
          thrown = true;
        }
      deallog << "open boundary reported: " << yes_no(thrown) << std::endl;
    }
    deallog.pop();
  }

  /** The moments of @p weights at @p points. */
  Moments
  moments_of(const std::vector<Point<2>> &points,
             const std::vector<double>   &weights)
  {
    Moments m{};
    for (unsigned int p = 0; p < points.size(); ++p)
      {
        const double s = points[p][0], t = points[p][1], w = weights[p];
        m[0] += w;
        m[1] += w * s;
        m[2] += w * t;
        m[3] += w * s * s;
        m[4] += w * s * t;
        m[5] += w * t * t;
      }
    return m;
  }

  void
  check_fitting()
  {
    deallog.push("fitting");
    Random random(5);
    // Target = the volumes' own moments: the weights are the volumes.
    {
      std::vector<Point<2>> points;
      std::vector<double>   volumes;
      for (unsigned int p = 0; p < 20; ++p)
        {
          points.emplace_back(random(), random());
          volumes.push_back(random(0.5, 1.5));
        }
      const auto fit =
        MomentFitting::fit(points, volumes, moments_of(points, volumes));
      double change = 0;
      for (unsigned int p = 0; p < 20; ++p)
        change = std::max(change, std::abs(fit.weights[p] - volumes[p]));
      deallog << "consistent volumes: " << fit.n_moments
              << " moments, weights equal the volumes to 1e-14: "
              << yes_no(change < 1e-14) << std::endl;
    }
    // One point: the area only. Three points: area and centroid, if the
    // centroid lies inside their triangle.
    {
      const Moments target = {{0.3, 0.12, 0.09, 0.06, 0.04, 0.035}};
      auto fit = MomentFitting::fit({Point<2>(0.5, 0.5)}, {0.25}, target);
      deallog << "one point: " << fit.n_moments << " moment, weight "
              << fit.weights[0] << std::endl;
      const std::vector<Point<2>> triangle = {Point<2>(0.1, 0.1),
                                              Point<2>(0.9, 0.2),
                                              Point<2>(0.3, 0.7)};
      fit             = MomentFitting::fit(triangle, {0.1, 0.1, 0.1}, target);
      const Moments m = moments_of(triangle, fit.weights);
      deallog << "three points round the centroid: " << fit.n_moments
              << " moments, area and centroid to 1e-14: "
              << yes_no(std::abs(m[0] - 0.3) < 1e-14 &&
                        std::abs(m[1] - 0.12) < 1e-14 &&
                        std::abs(m[2] - 0.09) < 1e-14)
              << std::endl;
      // Points all left of the centroid: only the area can be fitted.
      fit = MomentFitting::fit({Point<2>(0.1, 0.2),
                                Point<2>(0.2, 0.5),
                                Point<2>(0.15, 0.8),
                                Point<2>(0.3, 0.3)},
                               {1, 1, 1, 1},
                               target);
      deallog << "points on one side of the centroid: " << fit.n_moments
              << " moment" << std::endl;
      // Points on a line through the centroid carry the area and the
      // centroid, but no second moment.
      fit = MomentFitting::fit({Point<2>(0.2, 0.1),
                                Point<2>(0.4, 0.3),
                                Point<2>(0.6, 0.5)},
                               {1, 1, 1},
                               target);
      deallog << "points on a line through the centroid: " << fit.n_moments
              << " moments" << std::endl;
    }

    // Every cut cell of random polygons with 2^2 ... 8^2 regular points per
    // cell (those inside): weights non-negative, the fitted moments exact.
    unsigned int count[7] = {0, 0, 0, 0, 0, 0, 0};
    bool         ok       = true;
    for (unsigned int trial = 0; trial < 40; ++trial)
      {
        const double       h       = random(0.1, 0.3);
        const unsigned int n_cells = static_cast<unsigned int>(3 / h) + 1;
        const UniformGrid  grid{Point<2>(0, 0),
                               Tensor<1, 2>({h, h}),
                               {{n_cells, n_cells}}};
        const auto         polygon = random_star(
          random, Point<2>(1.5, 1.5), 1.2, 3 + trial % 10, random(0, 0.6));
        Body body;
        add_curve(body, polygon, true, grid);
        CutCellGeometry geometry;
        geometry.reinit(body.boundary(), grid);
        const unsigned int n = 2 + trial % 7;
        for (unsigned int j = 0; j < n_cells; ++j)
          for (unsigned int i = 0; i < n_cells; ++i)
            {
              if (geometry.fill({{i, j}}) != CutCellGeometry::Fill::cut)
                continue;
              std::vector<Point<2>> points;
              std::vector<double>   volumes;
              for (unsigned int b = 0; b < n; ++b)
                for (unsigned int a = 0; a < n; ++a)
                  {
                    const Point<2> st((a + 0.5) / n, (b + 0.5) / n);
                    if (inside_polygon(
                          polygon, Point<2>(h * (i + st[0]), h * (j + st[1]))))
                      {
                        points.push_back(st);
                        volumes.push_back(1. / (n * n));
                      }
                  }
              const Moments &target = geometry.moments({{i, j}});
              const auto     fit = MomentFitting::fit(points, volumes, target);
              ++count[fit.n_moments];
              if (points.empty())
                continue;
              const Moments m = moments_of(points, fit.weights);
              for (const double w : fit.weights)
                ok = ok && w >= 0;
              for (unsigned int k = 0; k < fit.n_moments; ++k)
                ok = ok && std::abs(m[k] - target[k]) <= 1e-12 * target[0];
            }
      }
    deallog << "cut cells of 40 random polygons: 6 moments " << count[6]
            << ", 3 moments " << count[3] << ", 1 moment " << count[1]
            << ", no point " << count[0]
            << "; weights non-negative and fitted moments exact to 1e-12: "
            << yes_no(ok) << std::endl;
    deallog.pop();
  }
} // namespace



BSMPM_UNIT_TEST("quadrature/cut_cells")
{
  initlog();
  check_polygons();
  check_curves();
  check_fitting();
}
