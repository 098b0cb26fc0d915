#include <deal.II/base/quadrature_lib.h>

#include <bsmpm/base/parameter_tools.h>
#include <bsmpm/boundary/curve_piece_values.h>
#include <bsmpm/boundary/nitsche_boundary.h>

#include <algorithm>
#include <limits>

namespace bsmpm
{
  namespace
  {
    /** Traction sigma n of a Voigt stress. */
    Tensor<1, 2>
    traction(const Voigt &sigma, const Tensor<1, 2> &n)
    {
      return Tensor<1, 2>(
        {sigma[0] * n[0] + sigma[2] * n[1], sigma[2] * n[0] + sigma[1] * n[1]});
    }
  } // namespace



  BSMPM_REGISTER_SUPPORT_METHOD(NitscheBoundary, "nitsche")



  NitscheBoundary::NitscheBoundary()
    : SupportMethod("nitsche")
  {}



  void
  NitscheBoundary::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Nitsche");
    prm.declare_entry(
      "Penalty",
      "100",
      Patterns::Double(0.),
      "gamma in the penalty gamma max(E, kappa) / h of Nitsche's method, "
      "kappa = lambda + mu the in-plane bulk modulus (E unless the material "
      "is nearly incompressible in plane strain, nu > 0.3). The method is "
      "consistent, so gamma only has to be large enough for coercivity: keep "
      "the default; far larger values raise the condition number, far smaller "
      "ones lose coercivity (doc/implicit-boundary.md).");
    prm.declare_entry("Gauss points per piece",
                      "4",
                      Patterns::Integer(1, 100),
                      "Gauss points on each piece of a supported curve, as "
                      "for the loads; more where the curve bends strongly "
                      "within a cell.");
    prm.leave_subsection();
  }



  void
  NitscheBoundary::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Nitsche");
    penalty        = prm.get_double("Penalty");
    n_gauss_points = prm.get_integer("Gauss points per piece");
    prm.leave_subsection();
  }



  void
  NitscheBoundary::assemble(
    const Context       &context,
    const LoadIncrement &increment,
    const LinearAlgebra::distributed::Vector<double> * /*prescribed*/,
    const std::vector<CellMoments>  *moments,
    const AffineConstraints<double> &constraints,
    TrilinosWrappers::SparseMatrix  &matrix,
    TrilinosWrappers::MPI::Vector   &rhs,
    const BoundaryCurve             *only)
  {
    const BackgroundGrid  &grid   = context.grid;
    const Q1CellKernel    &kernel = context.kernel;
    const ExactSolution   *exact  = context.exact_solution;
    std::string            problem;
    constexpr unsigned int n = Q1CellKernel::dofs_per_cell;
    const QGauss<1>        gauss(n_gauss_points);
    // The consistency term pairs the traction of the material's stiffest
    // mode with the boundary: for an isotropic material the volumetric one,
    // 2 kappa, which grows without bound as nu -> 0.5 in plane strain. The
    // penalty must outgrow it to keep the form coercive: scale it by
    // max(E, kappa) (doc/b-bar.md).
    const double beta =
      penalty * context.material.penalty_modulus() / grid.min_cell_size();

    std::array<Tensor<1, 2>, n> value, stress_n;

    // The Nitsche terms of one piece.
    const auto piece_terms = [&](const CurvePieceValues &values,
                                 FullMatrix<double>     &cell_matrix,
                                 Vector<double>         &cell_rhs) {
      const LocallyOwnedCurvePiece &piece     = values.get_piece();
      const CurveCondition         *condition = piece.condition;
      // A roller and a prescribed normal displacement hold the normal
      // component only.
      const bool roller = condition->holds_normal_component_only();
      // B-bar: the volumetric strain at the centroid of the cell's
      // material; without moments the point's own (the standard stress).
      const std::optional<Point<2>> centroid = bbar_point(moments, piece);

      for (unsigned int q = 0; q < gauss.size(); ++q)
        {
          const double        u  = values.parameter(q);
          const Point<2>     &x  = values.position(q);
          const Tensor<1, 2> &nv = values.normal(q);
          const double        ds = values.JxW(q);
          const Point<2>     &st = values.local_coordinates(q);

          // For a roller, all products are taken along n only.
          const auto project = [&](const Tensor<1, 2> &v) {
            return roller ? Tensor<1, 2>((v * nv) * nv) : v;
          };
          for (unsigned int i = 0; i < n; ++i)
            {
              value[i] = kernel.shape_value(i, st);
              stress_n[i] =
                traction(kernel.stress_column(i, st, centroid.value_or(st)),
                         nv);
            }
          // Finite strain: the consistency term and the reaction come
          // per Newton iteration (add_finite_strain_terms()).
          const double consistency = context.finite_strain ? 0. : 1.;
          for (unsigned int i = 0; i < n; ++i)
            for (unsigned int j = 0; j < n; ++j)
              cell_matrix(i, j) +=
                ds * (-consistency * project(stress_n[j]) * value[i] -
                      project(stress_n[i]) * value[j] +
                      beta * project(value[i]) * value[j]);

          // Reaction of the previous steps.
          const Tensor<1, 2> reaction =
            consistency *
            project(traction(piece.curve->stress_at(piece.segment, u), nv));

          // The prescribed increment; for a normal displacement
          // g = g_n n, so that the projected terms give
          // (u . n - g_n) (v . n).
          Tensor<1, 2> g;
          if (condition->kind == CurveCondition::Kind::displacement)
            g = condition->function ?
                  condition->displacement_increment(x, increment, problem) :
                  increment.share() * exact->displacement(x);
          else if (condition->kind == CurveCondition::Kind::normal_displacement)
            g = (condition->function ?
                   condition->normal_displacement_increment(x,
                                                            increment,
                                                            problem) :
                   increment.share() * (exact->displacement(x) * nv)) *
                nv;
          for (unsigned int i = 0; i < n; ++i)
            cell_rhs[i] += ds * (reaction * value[i] - stress_n[i] * g +
                                 beta * value[i] * g);
        }
    };
    add_piece_terms(
      context, gauss, only, constraints, &matrix, rhs, piece_terms);
    ParameterTools::throw_if_any(problem, grid.mpi_communicator());
  }



  void
  NitscheBoundary::add_finite_strain_terms(
    const Context                                    &context,
    const LinearAlgebra::distributed::Vector<double> &increment,
    const SupportStress                              &stress,
    const AffineConstraints<double>                  &constraints,
    TrilinosWrappers::SparseMatrix                   *tangent,
    TrilinosWrappers::MPI::Vector                    &internal_force,
    const BoundaryCurve                              *only) const
  {
    const Q1CellKernel    &kernel = context.kernel;
    constexpr unsigned int n      = Q1CellKernel::dofs_per_cell;
    const QGauss<1>        gauss(n_gauss_points);

    Q1CellKernel::LocalVector   d;
    std::array<Tensor<1, 2>, n> value;
    std::array<Tensor<2, 2>, n> G;

    // The consistency term of one piece, at the increment d on its cell.
    const auto piece_terms = [&](const CurvePieceValues &values,
                                 FullMatrix<double>     &cell_matrix,
                                 Vector<double>         &cell_force) {
      const LocallyOwnedCurvePiece &piece = values.get_piece();
      for (unsigned int i = 0; i < n; ++i)
        d[i] = increment(values.dof_indices()[i]);
      const bool roller = piece.condition->holds_normal_component_only();

      for (unsigned int q = 0; q < gauss.size(); ++q)
        {
          const double        u       = values.parameter(q);
          const Tensor<1, 2> &nv      = values.normal(q);
          const double        ds      = values.JxW(q);
          const Point<2>     &st      = values.local_coordinates(q);
          const auto          project = [&](const Tensor<1, 2> &v) {
            return roller ? Tensor<1, 2>((v * nv) * nv) : v;
          };
          Tensor<2, 2> f = unit_symmetric_tensor<2>();
          for (unsigned int i = 0; i < n; ++i)
            {
              value[i] = kernel.shape_value(i, st);
              G[i]     = kernel.shape_gradient(i, st);
              f += d[i] * G[i];
            }
          const std::vector<double> props =
            piece.curve->state_at(piece.segment, u);
          Tensor<2, 2> P;
          Tensor<4, 2> A;
          if (!stress(
                ArrayView<const double>(props.data(), props.size()), f, P, A))
            continue; // inverted: reported by @p stress to the solver
          // The nominal traction P n on the curve of the step's start.
          const Tensor<1, 2> traction_n = project(P * nv);
          for (unsigned int i = 0; i < n; ++i)
            cell_force[i] -= ds * (value[i] * traction_n);
          if (tangent == nullptr)
            continue;
          for (unsigned int j = 0; j < n; ++j)
            {
              const Tensor<1, 2> dt = project(contract(A, G[j]) * nv);
              for (unsigned int i = 0; i < n; ++i)
                cell_matrix(i, j) -= ds * (value[i] * dt);
            }
        }
    };
    add_piece_terms(
      context, gauss, only, constraints, tangent, internal_force, piece_terms);
  }
} // namespace bsmpm
