#include <deal.II/base/exceptions.h>
#include <deal.II/base/quadrature_lib.h>

#include <bsmpm/geometry/cut_cell_geometry.h>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace bsmpm
{
  const CutCellGeometry::Moments CutCellGeometry::full_cell_moments = {
    {1., 1. / 2, 1. / 2, 1. / 3, 1. / 4, 1. / 3}};
  const CutCellGeometry::Moments CutCellGeometry::no_moments = {
    {0., 0., 0., 0., 0., 0.}};

  namespace
  {
    /** Exponents (a, b) of the moments, in the order of Moments. */
    constexpr std::array<std::array<unsigned int, 2>, 6> exponents = {
      {{{0, 0}}, {{1, 0}}, {{0, 1}}, {{2, 0}}, {{1, 1}}, {{0, 2}}}};

    double
    clamp01(const double x)
    {
      return std::min(std::max(x, 0.), 1.);
    }

    /** What one piece adds to the cells of its row. */
    struct PieceContribution
    {
      unsigned int column;
      unsigned int row;
      /** int c(s)^(a+1) t^b t' du / (a+1): to its own cell. */
      CutCellGeometry::Moments own;
      /** [t^(b+1)]_begin^end / (b+1), b = 0, 1, 2: to the cells left of it,
       * each divided by a+1 there. */
      std::array<double, 3> flux;
    };
  } // namespace



  void
  CutCellGeometry::reinit(const Boundary    &boundary,
                          const UniformGrid &grid,
                          const double       tolerance)
  {
    AssertDimension(boundary.curves.size(), boundary.pieces.size());
    n_cells = grid.n_cells;
    slot.assign(std::size_t(n_cells[0]) * n_cells[1], empty_slot);
    cut_moments.clear();
    body_area = 0;

    // The contribution of every piece, grouped by row.
    const QGauss<1>                             gauss(6);
    std::vector<std::vector<PieceContribution>> rows(n_cells[1]);
    for (unsigned int c = 0; c < boundary.curves.size(); ++c)
      {
        const BSplineCurve &curve = *boundary.curves[c];
        for (const CurvePiece &piece : *boundary.pieces[c])
          {
            const Point<2> origin(grid.lower_left[0] +
                                    piece.cell[0] * grid.cell_size[0],
                                  grid.lower_left[1] +
                                    piece.cell[1] * grid.cell_size[1]);
            const auto     local = [&](const double u) {
              const Point<2> x = curve.value(u);
              return Point<2>(clamp01((x[0] - origin[0]) / grid.cell_size[0]),
                              clamp01((x[1] - origin[1]) / grid.cell_size[1]));
            };
            PieceContribution p;
            p.column = piece.cell[0];
            p.row    = piece.cell[1];

            const double t0 = local(piece.u_begin)[1];
            const double t1 = local(piece.u_end)[1];
            for (unsigned int b = 0; b < 3; ++b)
              p.flux[b] = (std::pow(t1, b + 1) - std::pow(t0, b + 1)) / (b + 1);

            p.own.fill(0.);
            const double du = piece.u_end - piece.u_begin;
            for (unsigned int q = 0; q < gauss.size(); ++q)
              {
                const double   u  = piece.u_begin + gauss.point(q)[0] * du;
                const Point<2> st = local(u);
                // dt/du; t was clamped, but a piece lies in its row, so the
                // clamp only removes round-off.
                const double dt =
                  curve.derivative(u)[1] / grid.cell_size[1] * du;
                for (unsigned int k = 0; k < 6; ++k)
                  {
                    const auto [a, b] = exponents[k];
                    p.own[k] += gauss.weight(q) * std::pow(st[0], a + 1) /
                                (a + 1) * std::pow(st[1], b) * dt;
                  }
              }
            rows[p.row].push_back(p);
          }
      }

    // Sweep each row from right to left.
    std::vector<Moments>               own(n_cells[0]);
    std::vector<std::array<double, 3>> flux(n_cells[0]);
    std::vector<bool>                  has_piece(n_cells[0]);
    for (unsigned int j = 0; j < n_cells[1]; ++j)
      {
        if (rows[j].empty())
          continue;
        std::fill(own.begin(), own.end(), no_moments);
        std::fill(flux.begin(), flux.end(), std::array<double, 3>{});
        std::fill(has_piece.begin(), has_piece.end(), false);
        for (const PieceContribution &p : rows[j])
          {
            for (unsigned int k = 0; k < 6; ++k)
              own[p.column][k] += p.own[k];
            for (unsigned int b = 0; b < 3; ++b)
              flux[p.column][b] += p.flux[b];
            has_piece[p.column] = true;
          }

        std::array<double, 3> right{}; // flux of the pieces right of i
        for (unsigned int i = n_cells[0]; i-- > 0;)
          {
            Moments mu;
            for (unsigned int k = 0; k < 6; ++k)
              {
                const auto [a, b] = exponents[k];
                mu[k]             = own[i][k] + right[b] / (a + 1);
              }
            for (unsigned int b = 0; b < 3; ++b)
              right[b] += flux[i][b];

            const double f = mu[0];
            if (!has_piece[i])
              {
                // Without a piece the cell is wholly inside or outside.
                AssertThrow(std::abs(f) < 1e-8 || std::abs(f - 1) < 1e-8,
                            ExcMessage(
                              "Cut-cell geometry: the boundary curves do not "
                              "close round the body (cell " +
                              std::to_string(i) + ", " + std::to_string(j) +
                              " is " + std::to_string(f) + " filled)."));
              }
            const std::size_t c = std::size_t(j) * n_cells[0] + i;
            if (f >= 1 - tolerance)
              {
                slot[c] = full_slot;
                body_area += 1;
              }
            else if (f > tolerance)
              {
                slot[c] = cut_moments.size();
                cut_moments.push_back(mu);
                body_area += f;
              }
          }
        // Left of every piece the flux of a closed boundary cancels.
        AssertThrow(std::abs(right[0]) < 1e-8,
                    ExcMessage("Cut-cell geometry: the boundary curves do not "
                               "close round the body (row " +
                               std::to_string(j) + " of the grid)."));
      }
    body_area *= grid.cell_size[0] * grid.cell_size[1];
  }
} // namespace bsmpm
