#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/symmetric_tensor.h>

#include <deal.II/lac/la_parallel_vector.h>

#include <bsmpm/boundary/ghost_penalty.h>

namespace bsmpm
{
  void
  GhostPenalty::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Ghost penalty");
    prm.declare_entry("Enable",
                      "true",
                      Patterns::Bool(),
                      "Stabilise cells whose material holds their DoFs weakly "
                      "(slivers, cells with one or few points, cells that a "
                      "support crosses after their points have left) by the "
                      "jump of the normal derivative across their faces. On "
                      "by default; turn it off only to reproduce the paper's "
                      "method or to study the unstabilised system, whose "
                      "condition number grows like 1 / (fill fraction) "
                      "(doc/stability.md).");
    prm.declare_entry("Penalty",
                      "0.02",
                      Patterns::Double(0.),
                      "gamma in gamma (1 - q / q0) E h int [du/dn] . [dv/dn] "
                      "on the faces of a cell with a vertex whose support "
                      "quality q is below the quality threshold q0: it ties "
                      "the field of cells that their material holds weakly to "
                      "their neighbours', fading to 0 at the threshold. The "
                      "default keeps the condition number of slivers near "
                      "that of a full grid with a small bias on the results; "
                      "a larger gamma holds weak vertices harder at a larger "
                      "bias (doc/stability.md).");
    prm.declare_entry("Quality threshold",
                      "0.005",
                      Patterns::Double(0., 1.),
                      "q0: a vertex whose support quality (int |grad N|^2 "
                      "over the material round it, against four full cells; "
                      "in nonlinear runs scaled by how much the points' "
                      "tangent holds) is below this is stabilised. The "
                      "default lies where a sliver would raise the condition "
                      "number tenfold; raise it where weakly held vertices "
                      "still stall Newton or let points leave the grid (every "
                      "cut increment raises it tenfold for the rest of its "
                      "load step).");
    prm.leave_subsection();
  }



  void
  GhostPenalty::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Ghost penalty");
    use       = prm.get_bool("Enable");
    penalty   = prm.get_double("Penalty");
    threshold = prm.get_double("Quality threshold");
    prm.leave_subsection();
  }



  std::vector<double>
  GhostPenalty::cell_qualities(
    const BackgroundGrid                             &grid,
    const std::vector<CellMoments>                   &moments,
    const AffineConstraints<double>                  &constraints,
    const LinearAlgebra::distributed::Vector<double> *stiffness_ratio)
  {
    const MPI_Comm comm = grid.mpi_communicator();
    const double   area = grid.cell_size()[0] * grid.cell_size()[1];
    const auto    &fe   = grid.fe();
    // int |grad N_v|^2 over the material of the (up to) four cells round
    // each vertex v (per unit cell area, in units of the cell size), on the
    // vertex's first DoF, summed over processes.
    const double rx = grid.cell_size()[1] / grid.cell_size()[0];
    LinearAlgebra::distributed::Vector<double> support(
      grid.locally_owned_dofs(), grid.locally_relevant_dofs(), comm);
    std::vector<types::global_dof_index> dofs(fe.n_dofs_per_cell());
    for (const auto &cell : grid.dof_handler().active_cell_iterators())
      {
        if (!cell->is_locally_owned())
          continue;
        const CellMoments &m = moments[cell->active_cell_index()];
        if (!(m.v > 0))
          continue;
        cell->get_dof_indices(dofs);
        for (unsigned int i = 0; i < dofs.size(); ++i)
          if (fe.system_to_component_index(i).first == 0)
            {
              const unsigned int vertex =
                fe.system_to_component_index(i).second;
              // N = S(s) T(t), S = s or 1 - s, T = t or 1 - t: int T^2 and
              // int S^2 from the moments.
              const double T2 =
                (vertex / 2 == 1) ? m.vtt : m.v - 2 * m.vt + m.vtt;
              const double S2 =
                (vertex % 2 == 1) ? m.vss : m.v - 2 * m.vs + m.vss;
              support(dofs[i]) += (T2 * rx + S2 / rx) / area;
            }
      }
    support.compress(VectorOperation::add);
    // Nonlinear material: the stiffness that the points keep round each
    // vertex (ConstitutiveUpdate::support_stiffness_ratios()): a vertex held
    // by perfectly plastic points that flow in the one direction in which
    // they would hold it is not held, whatever its geometric support.
    if (stiffness_ratio != nullptr)
      for (const auto i : grid.locally_owned_dofs())
        support(i) *= (*stiffness_ratio)(i);
    support.update_ghost_values();
    // Four full cells: 4 (rx + 1 / rx) / 3.
    const double full = 4 * (rx + 1 / rx) / 3;

    std::vector<double> quality(grid.triangulation().n_active_cells(), -1.);
    for (const auto &cell : grid.dof_handler().active_cell_iterators())
      {
        if (!cell->is_locally_owned())
          continue;
        cell->get_dof_indices(dofs);
        std::array<std::array<types::global_dof_index, 2>, 4> vertex_dofs;
        for (unsigned int i = 0; i < dofs.size(); ++i)
          vertex_dofs[fe.system_to_component_index(i).second]
                     [fe.system_to_component_index(i).first] = dofs[i];
        if (!(moments[cell->active_cell_index()].v > 0))
          {
            // A cell without material whose DoFs are free (a support of
            // both components crosses it, SystemAssembly::make_constraints)
            // and one of whose vertices no material holds: a boundary that
            // has moved into a cell that its points have left (a footing's
            // base just above a grid line, the points of the sliver below
            // it already across). Only the support's terms would hold that
            // vertex, and they are not positive without material: the
            // implicit boundary's band replaces a regular stiffness that is
            // not there, Nitsche's consistency term has no material to
            // bound it. Weak, quality 0: the ghost penalty ties the cell's
            // field to its neighbours', so that the support acts on the
            // extension of the material's field. A cell without material
            // whose vertices all touch material needs nothing (and must not
            // be penalised: it may be a gap between two bodies).
            bool all_free = true, unheld = false;
            for (const auto &d : vertex_dofs)
              {
                if (constraints.is_constrained(d[0]) &&
                    constraints.is_constrained(d[1]))
                  all_free = false;
                else if (!(support(d[0]) > 0))
                  unheld = true;
              }
            if (all_free && unheld)
              quality[cell->active_cell_index()] = 0;
            continue;
          }
        double q = 1;
        for (const auto &d : vertex_dofs)
          {
            // A vertex whose both DoFs are held by constraints needs none.
            if (constraints.is_constrained(d[0]) &&
                constraints.is_constrained(d[1]))
              continue;
            q = std::min(q, support(d[0]) / full);
          }
        quality[cell->active_cell_index()] = q;
      }
    return quality;
  }



  std::vector<bool>
  GhostPenalty::weak_cells(const BackgroundGrid      &grid,
                           const std::vector<double> &quality) const
  {
    const auto                                &tria = grid.triangulation();
    LinearAlgebra::distributed::Vector<double> all(
      tria.global_active_cell_index_partitioner().lock());
    for (const auto &cell : tria.active_cell_iterators())
      if (cell->is_locally_owned())
        all[cell->global_active_cell_index()] =
          quality[cell->active_cell_index()];
    all.update_ghost_values();
    std::vector<bool> weak(tria.n_active_cells(), false);
    for (const auto &cell : tria.active_cell_iterators())
      if (!cell->is_artificial())
        {
          const double q = all[cell->global_active_cell_index()];
          weak[cell->active_cell_index()] = q >= 0 && q < threshold;
        }
    return weak;
  }



  void
  GhostPenalty::assemble(
    const BackgroundGrid                             &grid,
    const Q1CellKernel                               &kernel,
    const double                                      youngs_modulus,
    const std::vector<double>                        &quality,
    const LinearAlgebra::distributed::Vector<double> *prescribed,
    const AffineConstraints<double>                  &constraints,
    TrilinosWrappers::SparseMatrix                   &matrix,
    TrilinosWrappers::MPI::Vector                    &rhs) const
  {
    constexpr unsigned int n = Q1CellKernel::dofs_per_cell;
    faces                    = 0;

    // The neighbours' qualities, owned or ghost, by global cell index.
    const auto                                &tria = grid.triangulation();
    LinearAlgebra::distributed::Vector<double> fill(
      tria.global_active_cell_index_partitioner().lock());
    for (const auto &cell : tria.active_cell_iterators())
      if (cell->is_locally_owned())
        fill[cell->global_active_cell_index()] =
          quality[cell->active_cell_index()];
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
        if (here < 0)
          continue;
        for (const unsigned int f : cell->face_indices())
          {
            if (cell->at_boundary(f))
              continue;
            const auto   neighbor = cell->neighbor(f);
            const double there    = fill[neighbor->global_active_cell_index()];
            // Each face once (by the cell of smaller index), between two
            // cells with material, one of them weakly supported.
            if (neighbor->global_active_cell_index() <
                  cell->global_active_cell_index() ||
                there < 0 || (here >= threshold && there >= threshold))
              continue;
            ++faces;
            // The penalty fades from gamma at a cell that holds nothing to
            // zero at the threshold: a cell that nearly holds its DoFs by
            // itself is barely touched.
            const double scale =
              1 - std::min(std::min(here, there) / threshold, 1.);

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
                  scale * penalty * youngs_modulus * h * area * gauss.weight(q);
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
