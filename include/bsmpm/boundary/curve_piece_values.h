#ifndef bsmpm_curve_piece_values_h
#define bsmpm_curve_piece_values_h

#include <deal.II/base/quadrature.h>

#include <bsmpm/boundary/boundary_curves.h>
#include <bsmpm/geometry/background_grid.h>

#include <functional>
#include <vector>

namespace bsmpm
{
  using namespace dealii;

  /**
   * One piece of a boundary curve in a locally owned grid cell (its cell
   * index, parameter range and segment, as CurvePiece), with the curve it
   * belongs to, the condition that acts on it and the cell itself: what
   * CurvePieceValues::reinit() takes.
   */
  struct LocallyOwnedCurvePiece : CurvePiece
  {
    const BoundaryCurve *curve = nullptr;
    /** The curve's index in BoundaryCurves::get_curves(). */
    unsigned int curve_index = 0;
    /** The condition of the piece's segment, or nullptr where it is free. */
    const CurveCondition *condition = nullptr;
    /** The locally owned cell that holds the piece (CurvePiece::cell is
     * its index). */
    BackgroundGrid::cell_iterator owned_cell;
  };



  /**
   * Values along the pieces of the boundary curves, in the spirit of
   * deal.II's FEValues: the boundary integrals of the loads (NeumannLoads),
   * the supports (ImplicitBoundary, NitscheBoundary) and contact are all
   * sums over the pieces of a curve in the grid cells (paper Sec. 3.3) of
   * Gauss points along each piece. This class holds that loop once:
   *
   * @code
   *   CurvePieceValues values(grid, QGauss<1>(4));
   *   for (const auto &piece : values.pieces(curves, filter))
   *     {
   *       values.reinit(piece);   // piece.curve, piece.condition, ...
   *       for (unsigned int q = 0; q < values.n_quadrature_points(); ++q)
   *         ... values.position(q), values.JxW(q), values.normal(q),
   *             values.local_coordinates(q) ...
   *       constraints.distribute_local_to_global(...,
   *                                              values.dof_indices(), ...);
   *     }
   * @endcode
   *
   * pieces() picks the pieces of locally owned cells whose curve and
   * condition pass a filter, in the order of the curves and of their pieces
   * along each curve. On a piece [u_a, u_b] of curve C the Gauss points of
   * the quadrature @p quadrature on [0, 1] are u_q = u_a + x_q (u_b - u_a),
   * and the length element is |C'(u_q)| (u_b - u_a) w_q, evaluated in this
   * order (the reference outputs depend on the last bit).
   *
   * Contact (collect_pieces_per_cell()) walks the free pieces the same
   * way: pieces(curves, free_pieces()), with
   * LocallyOwnedCurvePiece::curve_index for its per-curve data, and
   * reinit() only for the pieces near a rigid body.
   */
  class CurvePieceValues
  {
  public:
    /** Which pieces pieces() gives: a curve and the condition on the
     * piece (nullptr where free). */
    using Filter =
      std::function<bool(const BoundaryCurve &, const CurveCondition *)>;

    CurvePieceValues(const BackgroundGrid &grid,
                     const Quadrature<1>  &quadrature);

    /**
     * The pieces of @p curves in locally owned cells that @p filter accepts,
     * curve by curve, each curve's pieces in their order along it.
     */
    std::vector<LocallyOwnedCurvePiece>
    pieces(const BoundaryCurves &curves, const Filter &filter) const;

    /** Filters of pieces() used by several callers. */
    /** The supports imposed by the support method registered as
     * @p method; of the curve @p only alone unless nullptr. */
    static Filter
    supports_by(const std::string &method, const BoundaryCurve *only = nullptr);

    /** The free pieces, on which no condition acts: those that may touch
     * a rigid body (contact). */
    static Filter
    free_pieces();

    /** Evaluates the Gauss points of @p piece and its cell's DoF indices. */
    void
    reinit(const LocallyOwnedCurvePiece &piece);

    unsigned int
    n_quadrature_points() const
    {
      return quadrature.size();
    }

    /** The curve's parameter u_q of Gauss point @p q. */
    double
    parameter(const unsigned int q) const
    {
      return parameters[q];
    }

    /** C(u_q). */
    const Point<2> &
    position(const unsigned int q) const
    {
      return positions[q];
    }

    /** The length element |C'(u_q)| (u_b - u_a) w_q. */
    double
    JxW(const unsigned int q) const
    {
      return lengths[q];
    }

    /** The body's outward unit normal (BSplineCurve::outward_normal()). */
    const Tensor<1, 2> &
    normal(const unsigned int q) const
    {
      return normals[q];
    }

    /** The unit tangent C'(u_q) / |C'(u_q)|, in the direction of
     * increasing u (BSplineCurve::unit_tangent()). */
    const Tensor<1, 2> &
    tangent(const unsigned int q) const
    {
      return tangents[q];
    }

    /** C(u_q) in the coordinates of the piece's cell, [0, 1]^2
     * (BackgroundGrid::local_coordinates()). */
    const Point<2> &
    local_coordinates(const unsigned int q) const
    {
      return cell_coordinates[q];
    }

    /** The DoF indices of the piece's cell. */
    const std::vector<types::global_dof_index> &
    dof_indices() const
    {
      return cell_dof_indices;
    }

    /** The piece of the last reinit(). */
    const LocallyOwnedCurvePiece &
    get_piece() const
    {
      return current;
    }

  private:
    const BackgroundGrid &grid;
    const Quadrature<1>   quadrature;

    LocallyOwnedCurvePiece               current;
    std::vector<double>                  parameters;
    std::vector<Point<2>>                positions;
    std::vector<double>                  lengths;
    std::vector<Tensor<1, 2>>            normals;
    std::vector<Tensor<1, 2>>            tangents;
    std::vector<Point<2>>                cell_coordinates;
    std::vector<types::global_dof_index> cell_dof_indices;
  };
} // namespace bsmpm

#endif
