#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>

#include <bsmpm/base/parameter_tools.h>
#include <bsmpm/boundary/curve_piece_values.h>
#include <bsmpm/boundary/neumann_loads.h>

namespace bsmpm
{
  void
  NeumannLoads::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Boundary curves");
    prm.declare_entry("Gauss points per piece",
                      "4",
                      Patterns::Integer(1, 100),
                      "Gauss points on every piece of a loaded curve in a "
                      "grid cell (the paper uses 4). More for tractions that "
                      "vary strongly within a cell or curves that bend "
                      "strongly within one.");
    prm.leave_subsection();
  }



  void
  NeumannLoads::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Boundary curves");
    n_gauss_points = prm.get_integer("Gauss points per piece");
    prm.leave_subsection();
  }



  void
  NeumannLoads::assemble(const BoundaryCurves            &curves,
                         const BackgroundGrid            &grid,
                         const Q1CellKernel              &kernel,
                         const ExactSolution             *exact,
                         const double                     load_factor,
                         const AffineConstraints<double> &constraints,
                         TrilinosWrappers::MPI::Vector   &rhs,
                         TrilinosWrappers::SparseMatrix  *follower)
  {
    points.clear();
    std::string        problem;
    const QGauss<1>    gauss(n_gauss_points);
    Vector<double>     cell_rhs(Q1CellKernel::dofs_per_cell);
    FullMatrix<double> cell_matrix(Q1CellKernel::dofs_per_cell,
                                   Q1CellKernel::dofs_per_cell);
    CurvePieceValues   values(grid, gauss);

    for (const auto &piece : values.pieces(
           curves, [](const BoundaryCurve &, const CurveCondition *condition) {
             return condition != nullptr && condition->is_load();
           }))
      {
        values.reinit(piece);
        const CurveCondition *condition = piece.condition;
        AssertThrow(condition->kind != CurveCondition::Kind::exact_traction ||
                      exact != nullptr,
                    ExcMessage("Boundary curves/" + piece.curve->name +
                               ": 'exact traction' needs an exact solution "
                               "in the 'Exact solution' section."));
        cell_rhs    = 0;
        cell_matrix = 0;
        const bool follows =
          follower && condition->kind == CurveCondition::Kind::pressure;
        for (unsigned int q = 0; q < gauss.size(); ++q)
          {
            const Point<2>     &x  = values.position(q);
            const double        dl = values.JxW(q);
            const Tensor<1, 2> &n  = values.normal(q);

            const Tensor<1, 2> t =
              condition->kind == CurveCondition::Kind::exact_traction ?
                load_factor * exact->traction(x, n) :
                condition->load_traction(x, n, load_factor, problem);
            points.push_back({x, t, dl});

            const Point<2> &st = values.local_coordinates(q);
            for (unsigned int i = 0; i < Q1CellKernel::dofs_per_cell; ++i)
              cell_rhs[i] += kernel.shape_value(i, st) * t * dl;
            if (follows)
              {
                // R rotates the unit tangent onto the outward normal.
                const Tensor<1, 2> &tangent = values.tangent(q);
                const double        sign =
                  n[0] * tangent[1] - n[1] * tangent[0] > 0 ? 1. : -1.;
                const double p = condition->pressure_at(load_factor) * dl;
                for (unsigned int j = 0; j < Q1CellKernel::dofs_per_cell; ++j)
                  {
                    // (grad N_j) t, then R of it: R (a, b) = sign (b, -a).
                    const Tensor<1, 2> Gt =
                      kernel.shape_gradient(j, st) * tangent;
                    const Tensor<1, 2> RGt({sign * Gt[1], -sign * Gt[0]});
                    for (unsigned int i = 0; i < Q1CellKernel::dofs_per_cell;
                         ++i)
                      cell_matrix(i, j) +=
                        p * (kernel.shape_value(i, st) * RGt);
                  }
              }
          }
        if (follows)
          constraints.distribute_local_to_global(
            cell_matrix, cell_rhs, values.dof_indices(), *follower, rhs);
        else
          constraints.distribute_local_to_global(cell_rhs,
                                                 values.dof_indices(),
                                                 rhs);
      }
    ParameterTools::throw_if_any(problem, grid.mpi_communicator());
  }



  Tensor<1, 2>
  NeumannLoads::resultant(const MPI_Comm communicator) const
  {
    Tensor<1, 2> force;
    for (const auto &p : points)
      force += p.weight * p.traction;
    return Utilities::MPI::sum(force, communicator);
  }
} // namespace bsmpm
