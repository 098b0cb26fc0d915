#include <deal.II/base/quadrature_lib.h>

#include <deal.II/lac/la_parallel_vector.h>

#include <bsmpm/ghost_penalty.h>

namespace bsmpm
{
  void
  GhostPenalty::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Ghost penalty");
    prm.declare_entry("Enable",
                      "false",
                      Patterns::Bool(),
                      "Stabilise partly filled cells by the jump of the "
                      "normal derivative across their faces.");
    prm.declare_entry("Penalty",
                      "0.01",
                      Patterns::Double(0.),
                      "gamma in gamma E h int [du/dn] . [dv/dn]. 0.01 keeps "
                      "the condition number of a cell filled to 1e-10 below "
                      "3e3 and changes the plate's errors by 10-20% "
                      "(doc/stability.md).");
    prm.declare_entry("Fill threshold",
                      "0.99",
                      Patterns::Double(0., 1.),
                      "A cell filled to less than this fraction of its area "
                      "counts as partly filled.");
    prm.leave_subsection();
  }



  void
  GhostPenalty::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Ghost penalty");
    use       = prm.get_bool("Enable");
    penalty   = prm.get_double("Penalty");
    threshold = prm.get_double("Fill threshold");
    prm.leave_subsection();
  }



  void
  GhostPenalty::assemble(
    const BackgroundGrid                             &grid,
    const Q1CellKernel                               &kernel,
    const double                                      youngs_modulus,
    const std::vector<double>                        &fraction,
    const LinearAlgebra::distributed::Vector<double> *prescribed,
    const AffineConstraints<double>                  &constraints,
    TrilinosWrappers::SparseMatrix                   &matrix,
    TrilinosWrappers::MPI::Vector                    &rhs) const
  {
    constexpr unsigned int n = Q1CellKernel::dofs_per_cell;
    faces                    = 0;

    // The neighbours' fill fractions, owned or ghost, by global cell index.
    const auto                                &tria = grid.triangulation();
    LinearAlgebra::distributed::Vector<double> fill(
      tria.global_active_cell_index_partitioner().lock());
    for (const auto &cell : tria.active_cell_iterators())
      if (cell->is_locally_owned())
        fill[cell->global_active_cell_index()] =
          fraction[cell->active_cell_index()];
    fill.update_ghost_values();

    const QGauss<1>                      gauss(2);
    const double                         h = grid.min_cell_size();
    FullMatrix<double>                   face_matrix(2 * n, 2 * n);
    Vector<double>                       face_rhs(2 * n), da(2 * n);
    std::vector<types::global_dof_index> dof_indices(2 * n), dofs_here(n),
      dofs_there(n);
    std::array<Tensor<1, 2>, 2 * n> jump; // d phi_i / dn, one-sided, signed

    for (const auto &cell : grid.dof_handler().active_cell_iterators())
      {
        if (!cell->is_locally_owned())
          continue;
        const double here = fill[cell->global_active_cell_index()];
        if (here == 0.)
          continue;
        for (const unsigned int f : cell->face_indices())
          {
            if (cell->at_boundary(f))
              continue;
            const auto   neighbor = cell->neighbor(f);
            const double there    = fill[neighbor->global_active_cell_index()];
            // Each face once (by the cell of smaller index), between two
            // cells with material, one of them partly filled.
            if (neighbor->global_active_cell_index() <
                  cell->global_active_cell_index() ||
                there == 0. || (here >= threshold && there >= threshold))
              continue;
            ++faces;

            // Faces 0, 1: x = const; 2, 3: y = const.
            const unsigned int d = f / 2;
            Tensor<1, 2>       normal;
            normal[d]               = (f % 2 == 0) ? -1. : 1.;
            const auto     ij_here  = grid.cell_index(cell);
            const auto     ij_there = grid.cell_index(neighbor);
            const Point<2> corner =
              grid.cell_origin(ij_here) +
              ((f % 2 == 1) ? grid.cell_size()[d] : 0.) *
                Tensor<1, 2>(d == 0 ? Tensor<1, 2>({1., 0.}) :
                                      Tensor<1, 2>({0., 1.}));
            Tensor<1, 2> along;
            along[1 - d]      = grid.cell_size()[1 - d];
            const double area = along.norm();

            cell->get_dof_indices(dofs_here);
            neighbor->get_dof_indices(dofs_there);
            std::copy(dofs_here.begin(), dofs_here.end(), dof_indices.begin());
            std::copy(dofs_there.begin(),
                      dofs_there.end(),
                      dof_indices.begin() + n);

            face_matrix = 0;
            for (unsigned int q = 0; q < gauss.size(); ++q)
              {
                const Point<2> x = corner + gauss.point(q)[0] * along;
                const Point<2> a = grid.local_coordinates(x, ij_here);
                const Point<2> b = grid.local_coordinates(x, ij_there);
                for (unsigned int i = 0; i < n; ++i)
                  {
                    jump[i]     = kernel.shape_gradient(i, a) * normal;
                    jump[n + i] = -(kernel.shape_gradient(i, b) * normal);
                  }
                const double w =
                  penalty * youngs_modulus * h * area * gauss.weight(q);
                for (unsigned int i = 0; i < 2 * n; ++i)
                  for (unsigned int j = 0; j < 2 * n; ++j)
                    face_matrix(i, j) += w * (jump[i] * jump[j]);
              }
            face_rhs = 0;
            if (prescribed)
              {
                for (unsigned int i = 0; i < 2 * n; ++i)
                  da[i] = (*prescribed)(dof_indices[i]);
                face_matrix.vmult(face_rhs, da);
                face_rhs *= -1.;
              }
            constraints.distribute_local_to_global(
              face_matrix, face_rhs, dof_indices, matrix, rhs);
          }
      }
  }
} // namespace bsmpm
