// GeometricMultigrid (geometric_multigrid.h) as the preconditioner of CG on
// a small elastic problem: plane-strain elasticity (E = 1, nu = 0.3, Q1) on
// the unit square under its own weight, the bottom held (constrained rows:
// decoupled, no coupling off the diagonal), on uniform grids of 16^2, 32^2
// and 64^2 cells, the levels down to 4^2 cells (50 unknowns, factorised).
// CG to 1e-8 of the right-hand side: the iterations with the multigrid stay
// the same, within one, at every h, where those with point Jacobi grow about
// twice per refinement; the solution is that of Jacobi-preconditioned CG to
// the solver's tolerance; the V-cycle is symmetric (u . B v = v . B u), as
// CG needs; n_coarse_levels() tells the levels initialize() makes, and
// reinit() after the matrix is scaled gives the same iterations.

#include <deal.II/base/quadrature_lib.h>

#include <deal.II/distributed/tria.h>

#include <deal.II/dofs/dof_handler.h>
#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/fe_values.h>

#include <deal.II/grid/grid_generator.h>

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/precondition.h>
#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/sparsity_tools.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <bsmpm/linear_algebra/geometric_multigrid.h>

#include <algorithm>
#include <vector>

// tests.h uses deallog unqualified: the using directive must come first.
using namespace dealii;

#include "../tests.h"

#include "../unit_test.h"

using namespace bsmpm;

namespace
{
  /** The system of elasticity under gravity on @p dofs, u = 0 on the
   * bottom (boundary id 2): constrained rows keep their diagonal. */
  void
  assemble(const DoFHandler<2>            &dofs,
           TrilinosWrappers::SparseMatrix &matrix,
           TrilinosWrappers::MPI::Vector  &rhs)
  {
    const MPI_Comm comm     = dofs.get_communicator();
    const IndexSet owned    = dofs.locally_owned_dofs();
    const IndexSet relevant = DoFTools::extract_locally_relevant_dofs(dofs);
    AffineConstraints<double>        constraints(relevant);
    const FEValuesExtractors::Vector displacement(0);
    for (const auto &cell : dofs.active_cell_iterators())
      for (const auto f : cell->face_indices())
        if (cell->face(f)->at_boundary() && cell->face(f)->boundary_id() == 2)
          {
            std::vector<types::global_dof_index> face_dofs(
              dofs.get_fe().n_dofs_per_face());
            cell->face(f)->get_dof_indices(face_dofs);
            for (const auto i : face_dofs)
              constraints.add_line(i);
          }
    constraints.close();

    DynamicSparsityPattern pattern(relevant);
    DoFTools::make_sparsity_pattern(dofs, pattern, constraints, false);
    SparsityTools::distribute_sparsity_pattern(pattern, owned, comm, relevant);
    matrix.reinit(owned, owned, pattern, comm);
    rhs.reinit(owned, comm);

    const double E = 1., nu = 0.3;
    const double lambda = E * nu / ((1. + nu) * (1. - 2. * nu)),
                 mu     = E / (2. * (1. + nu));
    const FiniteElement<2>              &fe = dofs.get_fe();
    const QGauss<2>                      quadrature(2);
    FEValues<2>                          values(fe,
                       quadrature,
                       update_values | update_gradients | update_JxW_values);
    const unsigned int                   n = fe.n_dofs_per_cell();
    FullMatrix<double>                   cell_matrix(n, n);
    Vector<double>                       cell_rhs(n);
    std::vector<types::global_dof_index> indices(n);
    const Tensor<1, 2>                   gravity({0., -1.});
    for (const auto &cell : dofs.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          values.reinit(cell);
          cell_matrix = 0;
          cell_rhs    = 0;
          for (unsigned int q = 0; q < quadrature.size(); ++q)
            for (unsigned int i = 0; i < n; ++i)
              {
                const auto eps_i =
                  values[displacement].symmetric_gradient(i, q);
                for (unsigned int j = 0; j < n; ++j)
                  {
                    const auto eps_j =
                      values[displacement].symmetric_gradient(j, q);
                    cell_matrix(i, j) +=
                      (lambda * trace(eps_i) * trace(eps_j) +
                       2. * mu * scalar_product(eps_i, eps_j)) *
                      values.JxW(q);
                  }
                cell_rhs(i) +=
                  values[displacement].value(i, q) * gravity * values.JxW(q);
              }
          cell->get_dof_indices(indices);
          constraints.distribute_local_to_global(
            cell_matrix, cell_rhs, indices, matrix, rhs);
        }
    matrix.compress(VectorOperation::add);
    rhs.compress(VectorOperation::add);
  }



  /** CG iterations to 1e-8 |b| with @p preconditioner from zero. */
  template <typename Preconditioner>
  unsigned int
  cg_iterations(const TrilinosWrappers::SparseMatrix &matrix,
                TrilinosWrappers::MPI::Vector        &x,
                const TrilinosWrappers::MPI::Vector  &rhs,
                const Preconditioner                 &preconditioner)
  {
    SolverControl control(10000, 1e-8 * rhs.l2_norm(), false, false);
    SolverCG<TrilinosWrappers::MPI::Vector> cg(control);
    x = 0;
    cg.solve(matrix, x, rhs, preconditioner);
    return control.last_step();
  }



  /** |u . B v - v . B u| / (|u| |B v|) for two fixed vectors. */
  double
  asymmetry(const GeometricMultigrid                   &multigrid,
            const TrilinosWrappers::MPI::Vector        &like,
            const std::vector<types::global_dof_index> &owned)
  {
    TrilinosWrappers::MPI::Vector u(like), v(like), Bu(like), Bv(like);
    for (const auto i : owned)
      {
        u[i] = std::sin(0.37 * i + 1.);
        v[i] = std::cos(0.11 * i * i + 0.5);
      }
    u.compress(VectorOperation::insert);
    v.compress(VectorOperation::insert);
    multigrid.vmult(Bu, u);
    multigrid.vmult(Bv, v);
    return std::abs(u * Bv - v * Bu) / (u.l2_norm() * Bv.l2_norm());
  }
} // namespace



BSMPM_UNIT_TEST("linear_algebra/multigrid_01")
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  initlog();
  const MPI_Comm comm = MPI_COMM_WORLD;

  GeometricMultigrid::AdditionalData data;
  data.coarse_size = 50;
  std::vector<unsigned int> multigrid_iterations;
  for (const unsigned int cells : {16u, 32u, 64u})
    {
      parallel::distributed::Triangulation<2> grid(comm);
      GridGenerator::subdivided_hyper_cube(grid, 4, 0., 1., true);
      grid.refine_global(cells == 16 ? 2 : cells == 32 ? 3 : 4);
      const FESystem<2> fe(FE_Q<2>(1), 2);
      DoFHandler<2>     dofs(grid);
      dofs.distribute_dofs(fe);

      TrilinosWrappers::SparseMatrix matrix;
      TrilinosWrappers::MPI::Vector  rhs, x, y;
      assemble(dofs, matrix, rhs);
      x.reinit(rhs);
      y.reinit(rhs);

      GeometricMultigrid multigrid;
      multigrid.initialize(matrix, dofs, data);
      const unsigned int with_multigrid =
        cg_iterations(matrix, x, rhs, multigrid);
      multigrid_iterations.push_back(with_multigrid);

      TrilinosWrappers::PreconditionJacobi jacobi;
      jacobi.initialize(matrix);
      const unsigned int with_jacobi = cg_iterations(matrix, y, rhs, jacobi);
      y -= x;

      std::vector<types::global_dof_index> owned;
      for (const auto i : dofs.locally_owned_dofs())
        owned.push_back(i);
      const bool same_solution = y.linfty_norm() <= 1e-6 * x.linfty_norm();
      const bool symmetric     = asymmetry(multigrid, rhs, owned) < 1e-12;

      // New values, the same structure: 3 A has the iterations of A.
      matrix *= 3.;
      multigrid.reinit(matrix);
      const unsigned int after_reinit =
        cg_iterations(matrix, x, rhs, multigrid);

      deallog << cells << " x " << cells << " cells, " << dofs.n_dofs()
              << " unknowns: levels " << multigrid.n_levels() << " ("
              << multigrid.level_sizes() << "; n_coarse_levels() "
              << GeometricMultigrid::n_coarse_levels(dofs, data)
              << "), CG iterations with the multigrid " << with_multigrid
              << ", with point Jacobi " << with_jacobi << std::endl;
      deallog << "  the same solution (1e-6): " << yes_no(same_solution)
              << ", symmetric V-cycle (1e-12): " << yes_no(symmetric)
              << ", after reinit() with 3 A: " << after_reinit << " iterations"
              << std::endl;
    }
  const auto [fewest, most] = std::minmax_element(multigrid_iterations.begin(),
                                                  multigrid_iterations.end());
  deallog << "multigrid iterations independent of h (within one): "
          << yes_no(*most - *fewest <= 1) << std::endl;
}
