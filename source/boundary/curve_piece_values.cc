#include <bsmpm/boundary/curve_piece_values.h>
#include <bsmpm/points/q1_cell_kernel.h>

namespace bsmpm
{
  CurvePieceValues::CurvePieceValues(const BackgroundGrid &grid,
                                     const Quadrature<1>  &quadrature)
    : grid(grid)
    , quadrature(quadrature)
    , parameters(quadrature.size())
    , positions(quadrature.size())
    , lengths(quadrature.size())
    , normals(quadrature.size())
    , tangents(quadrature.size())
    , cell_coordinates(quadrature.size())
    , cell_dof_indices(Q1CellKernel::dofs_per_cell)
  {}



  std::vector<LocallyOwnedCurvePiece>
  CurvePieceValues::pieces(const BoundaryCurves &curves,
                           const Filter         &filter) const
  {
    std::vector<LocallyOwnedCurvePiece> result;
    const auto                         &all = curves.get_curves();
    for (unsigned int c = 0; c < all.size(); ++c)
      for (const auto &piece : all[c].pieces)
        {
          const CurveCondition *condition =
            all[c].condition_of_segment(piece.segment);
          if (!filter(all[c], condition))
            continue;
          const auto cell = grid.locally_owned_cell(piece.cell);
          if (cell != grid.dof_handler().end())
            result.push_back({piece, &all[c], c, condition, cell});
        }
    return result;
  }



  CurvePieceValues::Filter
  CurvePieceValues::supports_by(const std::string   &method,
                                const BoundaryCurve *only)
  {
    return [method, only](const BoundaryCurve  &curve,
                          const CurveCondition *condition) {
      return condition != nullptr && condition->is_support() &&
             curve.dirichlet_method == method &&
             (only == nullptr || &curve == only);
    };
  }



  CurvePieceValues::Filter
  CurvePieceValues::free_pieces()
  {
    return [](const BoundaryCurve &, const CurveCondition *condition) {
      return condition == nullptr;
    };
  }



  void
  CurvePieceValues::reinit(const LocallyOwnedCurvePiece &piece)
  {
    current                   = piece;
    const BSplineCurve &curve = *piece.curve->spline;
    const double        du    = piece.u_end - piece.u_begin;
    for (unsigned int q = 0; q < quadrature.size(); ++q)
      {
        const double       u = piece.u_begin + quadrature.point(q)[0] * du;
        const Tensor<1, 2> d = curve.derivative(u);
        parameters[q]        = u;
        positions[q]         = curve.value(u);
        lengths[q]           = d.norm() * du * quadrature.weight(q);
        normals[q]           = curve.outward_normal(u);
        tangents[q]          = d / d.norm();
        cell_coordinates[q]  = grid.local_coordinates(positions[q], piece.cell);
      }
    piece.owned_cell->get_dof_indices(cell_dof_indices);
  }
} // namespace bsmpm
