#ifndef bsmpm_curve_cell_intersection_h
#define bsmpm_curve_cell_intersection_h

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <bsmpm/geometry/b_spline_curve.h>

#include <array>
#include <vector>

namespace bsmpm
{
  using namespace dealii;

  /**
   * An axis-aligned grid of n_cells[0] x n_cells[1] equal cells as plain
   * data. Its lines are x_i = lower_left[0] + i cell_size[0] and
   * y_j = lower_left[1] + j cell_size[1]; cell (i, j) lies between x_i and
   * x_{i+1}, y_j and y_{j+1}.
   */
  struct UniformGrid
  {
    Point<2>                    lower_left;
    Tensor<1, 2>                cell_size;
    std::array<unsigned int, 2> n_cells;
  };



  /** The part of a curve between u_begin < u_end; it lies in one cell. */
  struct CurvePiece
  {
    std::array<unsigned int, 2> cell;
    double                      u_begin;
    double                      u_end;
    /** The Bezier segment of the curve that holds the piece. */
    unsigned int segment;
  };



  /**
   * Cuts a BSplineCurve by the lines of a uniform grid into pieces that each
   * lie in one cell, so that boundary integrals can be done cell by cell
   * (paper Sec. 3.3; method-notes Sec. 3).
   *
   * Each Bezier segment is cut separately. A grid line x = x_i can only meet
   * the segment if it meets the segment's control polygon (convex hull
   * property). Between the turning points of the coordinate x(t) the
   * segment is monotone in x, so each such interval holds at most one
   * crossing, which a sign test detects and safeguarded Newton finds to
   * machine precision. A turning point that lies on the line (within
   * round-off) is a tangential touch and is kept as a single cut. Cuts closer
   * than 1e-13 in the segment's local parameter are merged, so a curve
   * through a grid vertex is cut once there. Each piece goes to the cell
   * holding its midpoint; if that midpoint lies on a grid line, as for a
   * piece that runs along the line, to the cell on the body's side of it
   * (left of the tangent, see BSplineCurve). Neighbouring pieces of one
   * segment that land in the same cell are joined again.
   */
  class CurveCellIntersection
  {
  public:
    /**
     * The pieces of @p curve in order of increasing u: the first starts at
     * u = 0, each ends where the next begins, the last ends at u = 1.
     * Throws if the curve leaves @p grid.
     */
    static std::vector<CurvePiece>
    cut(const BSplineCurve &curve, const UniformGrid &grid);
  };
} // namespace bsmpm

#endif
