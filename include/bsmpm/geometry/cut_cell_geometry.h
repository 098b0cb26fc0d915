#ifndef bsmpm_cut_cell_geometry_h
#define bsmpm_cut_cell_geometry_h

#include <deal.II/base/point.h>

#include <bsmpm/geometry/b_spline_curve.h>
#include <bsmpm/geometry/curve_cell_intersection.h>

#include <array>
#include <string>
#include <vector>

namespace bsmpm
{
  using namespace dealii;

  /**
   * The part K ∩ Ω of every cell K of a uniform grid that lies inside a body
   * Ω bounded by closed B-spline curves: its area and the five higher
   * moments that the Q1 kernel needs (method-notes Secs. 8, 9), computed from
   * integrals along the curves alone.
   *
   * In the local coordinates (s, t) in [0, 1]^2 of a cell K, let
   *
   *   P(s, t) = chi(0 <= t <= 1) c(s)^(a+1) / (a+1) t^b,
   *   c(s) = min(max(s, 0), 1),
   *
   * over the whole plane. Then dP/ds = s^a t^b inside K and 0 outside, and P
   * is continuous in s, so Green's theorem on Ω gives
   *
   *   mu_ab(K) = int_{K ∩ Ω} s^a t^b ds dt = oint_{∂Ω} P dt,
   *
   * with ∂Ω oriented counter-clockwise round the body (body on the left).
   * Only curve pieces in K's row of cells contribute (elsewhere P = 0): a
   * piece in K itself by int c(s)^(a+1) t^b t'(u) du / (a+1), which is a
   * polynomial of degree at most 11 in the curve parameter and exact with 6
   * Gauss points; a piece in a cell to the right of K by
   * [t^(b+1)]_begin^end / ((a+1)(b+1)), whatever its column; a piece to the
   * left not at all. A sweep over each row from right to left therefore
   * gives the moments of every cell, full, empty or cut, in one pass over
   * the pieces: no inside test, no clipping of cell edges, and boundaries
   * along grid lines need no special case (P is continuous in s).
   *
   * For a closed boundary the pieces of every row sum to zero flux in t;
   * a row that does not is reported as an open boundary.
   */
  class CutCellGeometry
  {
  public:
    /** mu_ab of a cell divided by its area, in the order
     * 1, s, t, s^2, s t, t^2. */
    using Moments = std::array<double, 6>;

    enum class Fill : unsigned char
    {
      empty,
      cut,
      full
    };

    /** One closed boundary: curves whose pieces together form closed loops,
     * each with the body on its left. */
    struct Boundary
    {
      std::vector<const BSplineCurve *>            curves;
      std::vector<const std::vector<CurvePiece> *> pieces;
    };

    /**
     * Computes the geometry of the body bounded by @p boundary on @p grid.
     * A cell whose fraction lies within @p tolerance of 0 or 1 counts as
     * empty or full. Throws if the boundary is not closed.
     */
    void
    reinit(const Boundary    &boundary,
           const UniformGrid &grid,
           const double       tolerance = 1e-12);

    /** Whether reinit() was called. */
    bool
    initialized() const
    {
      return !slot.empty();
    }

    Fill
    fill(const std::array<unsigned int, 2> &cell) const
    {
      const int k = slot[index(cell)];
      return k >= 0 ? Fill::cut : (k == full_slot ? Fill::full : Fill::empty);
    }

    /** The moments of a cell (zero if empty, those of the unit square if
     * full). */
    const Moments &
    moments(const std::array<unsigned int, 2> &cell) const
    {
      const int k = slot[index(cell)];
      return k >= 0 ? cut_moments[k] :
                      (k == full_slot ? full_cell_moments : no_moments);
    }

    /** Area fraction of a cell inside the body. */
    double
    fraction(const std::array<unsigned int, 2> &cell) const
    {
      return moments(cell)[0];
    }

    /** Area of the body (sum over all cells). */
    double
    area() const
    {
      return body_area;
    }

    unsigned int
    n_cut_cells() const
    {
      return cut_moments.size();
    }

    /** The moments of the unit square. */
    static const Moments full_cell_moments;

  private:
    static constexpr int empty_slot = -1;
    static constexpr int full_slot  = -2;
    static const Moments no_moments;

    std::size_t
    index(const std::array<unsigned int, 2> &cell) const
    {
      return std::size_t(cell[1]) * n_cells[0] + cell[0];
    }

    std::array<unsigned int, 2> n_cells = {{0, 0}};
    /** Per cell (row-major): index into cut_moments, or empty/full_slot. */
    std::vector<int>     slot;
    std::vector<Moments> cut_moments;
    double               body_area = 0;
  };
} // namespace bsmpm

#endif
