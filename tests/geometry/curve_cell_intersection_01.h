// CurveCellIntersection: the pieces of a curve cut by a uniform grid cover
// the curve exactly once, in order, each inside its cell. Special cases
// (grid vertices, lines along and tangent to grid lines), the paper's
// Sec. 4.4 boundary on grids h = 2^-1..2^-6, and 1000 random closed curves.
#ifndef bsmpm_tests_curve_cell_intersection_01_h
#define bsmpm_tests_curve_cell_intersection_01_h

#include <bsmpm/geometry/curve_cell_intersection.h>

#include <memory>
#include <random>
#include <set>
#include <sstream>

// tests.h uses deallog unqualified: the using directive must come first.
using namespace dealii;

#include "../tests.h"

#include "test_curves.h"

using namespace bsmpm;

namespace curve_cell_intersection_01
{
  namespace
  {
    std::string
    cell_name(const std::array<unsigned int, 2> &cell)
    {
      return "(" + std::to_string(cell[0]) + "," + std::to_string(cell[1]) +
             ")";
    }

    struct Check
    {
      unsigned int                          n_pieces = 0;
      std::set<std::array<unsigned int, 2>> cells;
      // Relative difference of the summed piece lengths to the curve length.
      double length_defect = 0;
      // Largest distance of a sample point of a piece outside its cell.
      double outside = 0;
      // Pieces in order, without gaps, each within its segment.
      bool joined = true;
      // Consecutive pieces in touching cells.
      bool neighbours = true;
      // Pieces shorter than 1e-9 h, along a grid line, and steps from one
      // piece to the next across a grid vertex.
      unsigned int n_short = 0, n_along = 0, n_diagonal = 0;

      bool
      ok() const
      {
        return length_defect < 1e-12 && outside < 1e-12 && joined && neighbours;
      }
    };

    Check
    check(const BSplineCurve            &curve,
          const UniformGrid             &grid,
          const std::vector<CurvePiece> &pieces)
    {
      Check c;
      c.n_pieces = pieces.size();
      c.joined   = !pieces.empty() && pieces.front().u_begin == 0 &&
                 pieces.back().u_end == 1;
      const double h   = std::min(grid.cell_size[0], grid.cell_size[1]);
      double       sum = 0;
      for (unsigned int p = 0; p < pieces.size(); ++p)
        {
          const CurvePiece &piece = pieces[p];
          c.cells.insert(piece.cell);
          const auto u = curve.segment_parameters(piece.segment);
          c.joined     = c.joined && piece.u_begin < piece.u_end &&
                     u[0] <= piece.u_begin && piece.u_end <= u[1];
          if (p > 0)
            {
              c.joined = c.joined && pieces[p - 1].u_end == piece.u_begin;
              for (unsigned int d = 0; d < 2; ++d)
                c.neighbours =
                  c.neighbours && std::abs(int(piece.cell[d]) -
                                           int(pieces[p - 1].cell[d])) <= 1;
              if (piece.cell[0] != pieces[p - 1].cell[0] &&
                  piece.cell[1] != pieces[p - 1].cell[1])
                ++c.n_diagonal;
            }
          const double length = curve.length(piece.u_begin, piece.u_end);
          sum += length;
          if (length < 1e-9 * h)
            ++c.n_short;

          bool along = false;
          for (unsigned int j = 0; j <= 10; ++j)
            {
              const double u =
                j == 10 ?
                  piece.u_end :
                  piece.u_begin + (piece.u_end - piece.u_begin) * j / 10;
              const Point<2> x = curve.value(u);
              for (unsigned int d = 0; d < 2; ++d)
                {
                  const double lo =
                    grid.lower_left[d] + piece.cell[d] * grid.cell_size[d];
                  const double hi = lo + grid.cell_size[d];
                  c.outside       = std::max({c.outside, lo - x[d], x[d] - hi});
                }
            }
          const Point<2> mid = curve.value(0.5 * (piece.u_begin + piece.u_end));
          for (unsigned int d = 0; d < 2; ++d)
            {
              const double s =
                (mid[d] - grid.lower_left[d]) / grid.cell_size[d];
              along = along || std::abs(s - std::round(s)) < 1e-12;
            }
          if (along)
            ++c.n_along;
        }
      c.length_defect = std::abs(sum - curve.length()) / curve.length();
      return c;
    }

    void
    report(const std::string  &name,
           const BSplineCurve &curve,
           const UniformGrid  &grid,
           const bool          list_pieces)
    {
      const std::vector<CurvePiece> pieces =
        CurveCellIntersection::cut(curve, grid);
      const Check c = check(curve, grid, pieces);
      deallog << name << ": " << c.n_pieces << " pieces in " << c.cells.size()
              << " cells, lengths sum to 1e-12: "
              << yes_no(c.length_defect < 1e-12)
              << ", inside cells to 1e-12: " << yes_no(c.outside < 1e-12)
              << ", joined: " << yes_no(c.joined)
              << ", neighbours: " << yes_no(c.neighbours)
              << ", shorter than 1e-9 h: " << c.n_short
              << ", diagonal steps: " << c.n_diagonal << std::endl;
      if (list_pieces)
        for (const CurvePiece &piece : pieces)
          deallog << "  segment " << piece.segment << " cell "
                  << cell_name(piece.cell) << " u " << piece.u_begin << " to "
                  << piece.u_end << std::endl;
    }

    UniformGrid
    unit_square(const unsigned int n)
    {
      return {Point<2>(0, 0), Tensor<1, 2>({1. / n, 1. / n}), {{n, n}}};
    }


  } // namespace



  void
  run()
  {
    // Through grid vertices.
    {
      deallog.push("vertex");
      // The diagonal through three vertices of a 4 x 4 grid.
      report("diagonal",
             BSplineCurve({Point<2>(0.1, 0.1), Point<2>(0.9, 0.9)}, false),
             unit_square(4),
             true);
      // Slope 1/2 through the vertex (0.5, 0.5), which x and y reach at
      // parameters that differ by round-off: no sliver in (1,2) or (2,1).
      report("slope 1/2",
             BSplineCurve({Point<2>(0.1, 0.3), Point<2>(0.9, 0.7)}, false),
             unit_square(4),
             true);
      // A grid placed so that one of its vertices is the curve's point at
      // u = 0.3, inside a segment.
      const BSplineCurve curve(paper_points(), false);
      const double       h = 0.125;
      const Point<2>     v = curve.value(0.3);
      report("paper curve, vertex at u = 0.3",
             curve,
             {v - Tensor<1, 2>({12 * h, 12 * h}),
              Tensor<1, 2>({h, h}),
              {{24, 24}}},
             false);
      deallog.pop();
    }

    // Along grid lines: the piece goes to the cell on the body's side, to the
    // left of the direction of travel.
    {
      deallog.push("along");
      const std::vector<Point<2>> line = {Point<2>(0.1, 0.5),
                                          Point<2>(0.6, 0.5),
                                          Point<2>(0.9, 0.5)};
      report("rightwards", BSplineCurve(line, false), unit_square(4), true);
      report("leftwards",
             BSplineCurve({line.rbegin(), line.rend()}, false),
             unit_square(4),
             true);
      report("square on grid lines",
             BSplineCurve({Point<2>(0.25, 0.25),
                           Point<2>(0.75, 0.25),
                           Point<2>(0.75, 0.75),
                           Point<2>(0.25, 0.75)},
                          true,
                          {0, 1, 2, 3}),
             unit_square(4),
             true);
      // Along the grid's own edges, the body inside the grid.
      report("square on the grid's edges",
             BSplineCurve(
               {Point<2>(0, 0), Point<2>(1, 0), Point<2>(1, 1), Point<2>(0, 1)},
               true,
               {0, 1, 2, 3}),
             unit_square(2),
             true);
      report("along, then away",
             BSplineCurve({Point<2>(0.1, 0.5),
                           Point<2>(0.35, 0.5),
                           Point<2>(0.6, 0.5),
                           Point<2>(0.8, 0.7),
                           Point<2>(0.9, 0.95)},
                          false,
                          {2}),
             unit_square(4),
             true);
      deallog.pop();
    }

    // Tangent to grid lines.
    {
      deallog.push("tangent");
      // A circle inscribed in cell (1,1) touches its four sides at knots.
      const double          r = 0.125, c = 0.375, a = r / std::sqrt(2.);
      std::vector<Point<2>> inscribed = {Point<2>(c + r, c),
                                         Point<2>(c + a, c + a),
                                         Point<2>(c, c + r),
                                         Point<2>(c - a, c + a),
                                         Point<2>(c - r, c),
                                         Point<2>(c - a, c - a),
                                         Point<2>(c, c - r),
                                         Point<2>(c + a, c - a)};
      report("inscribed circle, h = 1/4",
             BSplineCurve(inscribed, true),
             unit_square(4),
             true);
      // On the finer grid its centre is a vertex: it crosses two lines at
      // right angles and touches four.
      report("same circle, h = 1/8",
             BSplineCurve(inscribed, true),
             unit_square(8),
             true);

      // Grid lines through the top and right extremes of the paper's curve,
      // which lie inside segments: the curve touches them from one side.
      const BSplineCurve curve(paper_points(), false);
      const auto         box = curve.bounding_box().get_boundary_points();
      const double       h   = 0.125;
      const UniformGrid  grid{box.second - Tensor<1, 2>({20 * h, 20 * h}),
                             Tensor<1, 2>({h, h}),
                             {{21, 21}}};
      const auto         pieces = CurveCellIntersection::cut(curve, grid);
      bool               beyond = false;
      for (const CurvePiece &piece : pieces)
        beyond = beyond || piece.cell[0] == 20 || piece.cell[1] == 20;
      report("paper curve, lines through its extremes", curve, grid, false);
      deallog << "no piece beyond the touched lines: " << yes_no(!beyond)
              << std::endl;
      deallog.pop();
    }

    // A circle, and the paper's Sec. 4.4 boundary as an open chain.
    {
      deallog.push("circle");
      report("r = 0.3, 32 points, h = 1/8",
             BSplineCurve(circle_points(32, Point<2>(0.5, 0.5), 0.3), true),
             unit_square(8),
             false);
      deallog.pop();
      deallog.push("paper curve");
      const BSplineCurve curve(paper_points(), false);
      for (unsigned int level = 1; level <= 6; ++level)
        {
          const double h = std::pow(0.5, level);
          report("h = 2^-" + std::to_string(level),
                 curve,
                 {Point<2>(0, 0),
                  Tensor<1, 2>({h, h}),
                  {{5u << (level - 1), 5u << (level - 1)}}},
                 false);
        }
      deallog.pop();
    }

    // Curves that leave the grid.
    {
      deallog.push("outside");
      const auto expect_throw = [](const std::string  &name,
                                   const BSplineCurve &curve) {
        try
          {
            CurveCellIntersection::cut(curve, unit_square(4));
            deallog << name << ": not thrown" << std::endl;
          }
        catch (const ExceptionBase &e)
          {
            std::ostringstream message;
            e.print_info(message);
            std::string text = message.str();
            text             = text.substr(text.find_first_not_of(' '));
            text.erase(text.find_last_not_of("\n ") + 1);
            deallog << name << ": thrown: " << text << std::endl;
          }
      };
      expect_throw("crossing the right edge",
                   BSplineCurve(circle_points(8, Point<2>(0.8, 0.5), 0.3),
                                true));
      // Clockwise along the grid's edges: the body would be outside.
      expect_throw("clockwise along the edges",
                   BSplineCurve({Point<2>(0, 0),
                                 Point<2>(0, 0.5),
                                 Point<2>(0.5, 0.5),
                                 Point<2>(0.5, 0)},
                                true,
                                {0, 1, 2, 3}));
      deallog.pop();
    }

    // 1000 random star-shaped closed curves in random grids; some points are
    // moved onto grid lines and vertices, some are marked corners, so that
    // curves pass through vertices, touch grid lines and run along them.
    {
      deallog.push("random");
      std::mt19937 generator(20190401);
      const auto   uniform = [&generator](const double a, const double b) {
        return std::uniform_real_distribution<double>(a, b)(generator);
      };
      const auto integer = [&generator](const int a, const int b) {
        return std::uniform_int_distribution<int>(a, b)(generator);
      };

      unsigned int n_checked = 0, n_failed = 0, n_pieces = 0, n_short = 0,
                   n_along = 0, n_touching = 0, n_beyond = 0;
      double worst_defect = 0, worst_outside = 0;
      while (n_checked < 1000)
        {
          UniformGrid grid;
          for (unsigned int d = 0; d < 2; ++d)
            {
              grid.lower_left[d] = uniform(-1, 1);
              grid.cell_size[d]  = uniform(0.05, 0.5);
              grid.n_cells[d]    = integer(4, 40);
            }
          const Tensor<1, 2> extent({grid.n_cells[0] * grid.cell_size[0],
                                     grid.n_cells[1] * grid.cell_size[1]});
          const Point<2>     center =
            grid.lower_left + 0.5 * extent +
            Tensor<1, 2>(
              {uniform(-0.1, 0.1) * extent[0], uniform(-0.1, 0.1) * extent[1]});
          const double R = 0.3 * std::min(extent[0], extent[1]);

          const unsigned int        n = integer(5, 20);
          std::vector<Point<2>>     points;
          std::vector<unsigned int> corners;
          for (unsigned int i = 0; i < n; ++i)
            {
              const double phi = 2 * numbers::PI * (i + uniform(-0.4, 0.4)) / n;
              const double r   = uniform(0.3, 1) * R;
              Point<2>     p =
                center + r * Tensor<1, 2>({std::cos(phi), std::sin(phi)});
              for (unsigned int d = 0; d < 2; ++d)
                if (uniform(0, 1) < 0.3)
                  p[d] = grid.lower_left[d] +
                         std::round((p[d] - grid.lower_left[d]) /
                                    grid.cell_size[d]) *
                           grid.cell_size[d];
              points.push_back(p);
              if (uniform(0, 1) < 0.3)
                corners.push_back(i);
            }

          // Moving points onto grid lines may fold the polygon: keep it
          // star-shaped around the centre, counter-clockwise.
          double winding = 0;
          bool   turning = true;
          for (unsigned int i = 0; i < n; ++i)
            {
              const Tensor<1, 2> a = points[i] - center,
                                 b = points[(i + 1) % n] - center;
              const double c       = a[0] * b[1] - a[1] * b[0];
              turning              = turning && c > 0;
              winding += std::atan2(c, a * b);
            }
          if (!turning || std::abs(winding - 2 * numbers::PI) > 1e-6)
            continue;

          std::unique_ptr<BSplineCurve> curve;
          try
            {
              curve = std::make_unique<BSplineCurve>(points, true, corners);
            }
          catch (const ExceptionBase &)
            {
              continue; // two points moved onto the same vertex
            }
          // Every third curve: move the grid so that lines pass through the
          // curve's rightmost and lowest points, where the curve touches them.
          const auto         box = curve->bounding_box().get_boundary_points();
          std::array<int, 2> touched = {{-1, -1}};
          if (n_checked % 3 == 0)
            for (unsigned int d = 0; d < 2; ++d)
              {
                const double x = (d == 0 ? box.second[0] : box.first[1]);
                const double line =
                  std::round((x - grid.lower_left[d]) / grid.cell_size[d]);
                grid.lower_left[d] +=
                  x - (grid.lower_left[d] + line * grid.cell_size[d]);
                touched[d] = line;
              }
          if (box.first[0] < grid.lower_left[0] ||
              box.first[1] < grid.lower_left[1] ||
              box.second[0] > grid.lower_left[0] + extent[0] ||
              box.second[1] > grid.lower_left[1] + extent[1])
            continue;

          const std::vector<CurvePiece> pieces =
            CurveCellIntersection::cut(*curve, grid);
          const Check c = check(*curve, grid, pieces);
          ++n_checked;
          if (touched[0] >= 0)
            {
              ++n_touching;
              for (const CurvePiece &piece : pieces)
                if (int(piece.cell[0]) >= touched[0] ||
                    int(piece.cell[1]) < touched[1])
                  ++n_beyond;
            }
          if (!c.ok())
            ++n_failed;
          n_pieces += c.n_pieces;
          n_short += c.n_short;
          n_along += c.n_along;
          worst_defect  = std::max(worst_defect, c.length_defect);
          worst_outside = std::max(worst_outside, c.outside);
        }
      deallog << "curves checked: " << n_checked << ", failed: " << n_failed
              << std::endl;
      deallog << "pieces: " << n_pieces << ", along grid lines: " << n_along
              << ", shorter than 1e-9 h: " << n_short << std::endl;
      deallog << "curves touching grid lines at their extremes: " << n_touching
              << ", pieces beyond the touched lines: " << n_beyond << std::endl;
      deallog << "worst relative length defect: " << std::setprecision(2)
              << worst_defect
              << " (below 1e-12: " << yes_no(worst_defect < 1e-12) << ")"
              << std::endl;
      deallog << "worst distance outside the cell: " << worst_outside
              << " (below 1e-12: " << yes_no(worst_outside < 1e-12) << ")"
              << std::endl;
      deallog.pop();
    }
  }
} // namespace curve_cell_intersection_01

#endif
