#include <bsmpm/geometry/curve_cell_intersection.h>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace bsmpm
{
  namespace
  {
    /** Value and derivative of a cubic in Bernstein form. */
    std::array<double, 2>
    bernstein(const std::array<double, 4> &c, const double t)
    {
      const double s = 1 - t;
      return {{s * s * s * c[0] + 3 * s * s * t * c[1] + 3 * s * t * t * c[2] +
                 t * t * t * c[3],
               3 * (s * s * (c[1] - c[0]) + 2 * s * t * (c[2] - c[1]) +
                    t * t * (c[3] - c[2]))}};
    }



    /**
     * The parameters in [0, 1] where the cubic with Bernstein coefficients
     * @p c is zero, given that |c| <= @p tolerance does not hold for all
     * coefficients. Values within @p tolerance of zero at the turning points
     * and ends count as zero.
     */
    void
    add_roots(const std::array<double, 4> &c,
              const std::vector<double>   &turning_points,
              const double                 tolerance,
              std::vector<double>         &roots)
    {
      std::vector<double> t = {0.};
      t.insert(t.end(), turning_points.begin(), turning_points.end());
      t.push_back(1.);
      std::vector<double> g(t.size());
      for (unsigned int i = 0; i < t.size(); ++i)
        {
          g[i] = bernstein(c, t[i])[0];
          if (std::abs(g[i]) <= tolerance)
            g[i] = 0;
        }
      // The cubic is monotone between neighbouring entries of t.
      for (unsigned int i = 0; i + 1 < t.size(); ++i)
        if (g[i] == 0)
          roots.push_back(t[i]);
        else if (g[i + 1] != 0 && (g[i] < 0) != (g[i + 1] < 0))
          roots.push_back(internal::safeguarded_newton(
            [&c](const double s) { return bernstein(c, s); }, t[i], t[i + 1]));
      if (g.back() == 0)
        roots.push_back(1.);
    }
  } // namespace



  std::vector<CurvePiece>
  CurveCellIntersection::cut(const BSplineCurve &curve, const UniformGrid &grid)
  {
    const Point<2>     &x0 = grid.lower_left;
    const Tensor<1, 2> &h  = grid.cell_size;

    // A coordinate within `tolerance` of a grid line is on it: round-off of
    // the grid's own coordinates.
    std::array<double, 2> tolerance;
    for (unsigned int d = 0; d < 2; ++d)
      tolerance[d] =
        1e-13 * (h[d] + std::max(std::abs(x0[d]),
                                 std::abs(x0[d] + grid.n_cells[d] * h[d])));

    const auto box = curve.bounding_box().get_boundary_points();
    for (unsigned int d = 0; d < 2; ++d)
      if (box.first[d] < x0[d] - tolerance[d] ||
          box.second[d] > x0[d] + grid.n_cells[d] * h[d] + tolerance[d])
        {
          std::ostringstream message;
          message << "The boundary curve leaves the background grid: it "
                  << "spans [" << box.first << "] to [" << box.second
                  << "], the grid [" << x0 << "] to ["
                  << x0 + Tensor<1, 2>(
                            {grid.n_cells[0] * h[0], grid.n_cells[1] * h[1]})
                  << "].";
          AssertThrow(false, ExcMessage(message.str()));
        }

    std::vector<CurvePiece> pieces;
    for (unsigned int k = 0; k < curve.n_segments(); ++k)
      {
        const auto &P = curve.bezier_control_points(k);

        std::vector<double> roots;
        for (unsigned int d = 0; d < 2; ++d)
          {
            const std::array<double, 4> c = {
              {P[0][d], P[1][d], P[2][d], P[3][d]}};
            const std::vector<double> turning_points =
              internal::bezier_turning_points(c);
            const double c_min = *std::min_element(c.begin(), c.end()),
                         c_max = *std::max_element(c.begin(), c.end());
            // Only lines that meet the control polygon can meet the segment.
            const int first =
              std::max(0.,
                       std::ceil((c_min - tolerance[d] - x0[d]) / h[d]) - 1);
            const int last =
              std::min(double(grid.n_cells[d]),
                       std::floor((c_max + tolerance[d] - x0[d]) / h[d]) + 1);
            for (int i = first; i <= last; ++i)
              {
                const double line = x0[d] + i * h[d];
                if (c_min > line + tolerance[d] || c_max < line - tolerance[d])
                  continue;
                const std::array<double, 4> g = {
                  {c[0] - line, c[1] - line, c[2] - line, c[3] - line}};
                // A segment that runs along the line is not cut by it.
                if (std::all_of(g.begin(), g.end(), [&](const double v) {
                      return std::abs(v) <= tolerance[d];
                    }))
                  continue;
                add_roots(g, turning_points, tolerance[d], roots);
              }
          }

        // The cuts: the ends and the distinct interior roots.
        std::sort(roots.begin(), roots.end());
        const double        merge = 1e-13;
        std::vector<double> t     = {0.};
        for (const double r : roots)
          if (r > t.back() + merge && r < 1 - merge)
            t.push_back(r);
        t.push_back(1.);

        const std::array<double, 2> u    = curve.segment_parameters(k);
        const auto                  u_of = [&u](const double s) {
          return s == 1 ? u[1] : u[0] + s * (u[1] - u[0]);
        };
        for (unsigned int p = 0; p + 1 < t.size(); ++p)
          {
            const double       u_begin = u_of(t[p]), u_end = u_of(t[p + 1]);
            const double       u_mid  = 0.5 * (u_begin + u_end);
            const Point<2>     mid    = curve.value(u_mid);
            const Tensor<1, 2> inward = -curve.outward_normal(u_mid);

            std::array<unsigned int, 2> cell;
            for (unsigned int d = 0; d < 2; ++d)
              {
                const double s = (mid[d] - x0[d]) / h[d];
                const double j = std::round(s);
                double       i = std::floor(s);
                if (std::abs(mid[d] - (x0[d] + j * h[d])) <= tolerance[d])
                  i = (inward[d] > 0 ? j : j - 1);
                if (i < 0 || i >= grid.n_cells[d])
                  {
                    // Name the place: which segment (between which boundary
                    // points), where, and whether it runs along the grid's
                    // edge with the body outside or lies beyond it.
                    const bool on_edge =
                      std::abs(mid[d] - (x0[d] + j * h[d])) <= tolerance[d];
                    std::ostringstream message;
                    message << "The boundary curve's segment " << k
                            << " (between its points " << k << " and " << k + 1
                            << ", counted from 0) at (" << mid << ") ";
                    if (on_edge)
                      message << "runs along the background grid's edge "
                              << (d == 0 ? "x = " : "y = ") << x0[d] + j * h[d]
                              << " with the body outside the grid (the "
                                 "curve's outward normal there is ("
                              << -inward[0] + 0. << ' ' << -inward[1] + 0.
                              << ")): a curve on the grid's edge "
                              << "must have the body inside, or the grid "
                              << "must be larger.";
                    else
                      message << "lies outside the background grid, which "
                              << "spans [" << x0 << "] to ["
                              << x0 + Tensor<1, 2>({grid.n_cells[0] * h[0],
                                                    grid.n_cells[1] * h[1]})
                              << "].";
                    AssertThrow(false, ExcMessage(message.str()));
                  }
                cell[d] = static_cast<unsigned int>(i);
              }

            if (p > 0 && pieces.back().cell == cell)
              pieces.back().u_end = u_end;
            else
              pieces.push_back({cell, u_begin, u_end, k});
          }
      }
    return pieces;
  }
} // namespace bsmpm
