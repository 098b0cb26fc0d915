#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/sparsity_tools.h>

#include <bsmpm/contact/contact_pattern.h>
#include <bsmpm/points/q1_cell_kernel.h>

#include <map>

namespace bsmpm
{
  void
  ContactPattern::keep(const DynamicSparsityPattern &system)
  {
    n_dofs         = system.n_rows();
    system_row_set = system.row_index_set();
    system_rows.clear();
    covered.clear();
    for (const auto row : system_row_set)
      {
        std::vector<types::global_dof_index> columns;
        for (auto entry = system.begin(row); entry != system.end(row); ++entry)
          columns.push_back(entry->column());
        system_rows.emplace_back(row, std::move(columns));
      }
  }



  bool
  ContactPattern::covers(
    const BackgroundGrid                           &grid,
    const std::vector<std::array<unsigned int, 2>> &cells) const
  {
    const unsigned int n_x = grid.n_cells(0);
    if (covered.size() != n_x * grid.n_cells(1))
      return false;
    for (const auto &cell : cells)
      if (!covered[cell[1] * n_x + cell[0]])
        return false;
    return true;
  }



  void
  ContactPattern::widen(const BackgroundGrid                           &grid,
                        const std::vector<std::array<unsigned int, 2>> &cells,
                        TrilinosWrappers::SparseMatrix                 &tangent)
  {
    const int n_x = grid.n_cells(0), n_y = grid.n_cells(1);
    // The cells within two of the contact's: a contact that moves by less
    // than a cell per increment needs no new pattern.
    covered.assign(n_x * n_y, false);
    for (const auto &cell : cells)
      for (int dj = -2; dj <= 2; ++dj)
        for (int di = -2; di <= 2; ++di)
          {
            const int i = int(cell[0]) + di, j = int(cell[1]) + dj;
            if (i >= 0 && i < n_x && j >= 0 && j < n_y)
              covered[j * n_x + i] = true;
          }
    // The DoFs of the cells this process sees: the cells round a locally
    // owned cell are owned or ghosts.
    std::map<unsigned int, std::vector<types::global_dof_index>> dofs_of;
    for (const auto &cell : grid.dof_handler().active_cell_iterators())
      if (!cell->is_artificial())
        {
          const auto ij   = grid.cell_index(cell);
          auto      &dofs = dofs_of[ij[1] * n_x + ij[0]];
          dofs.resize(Q1CellKernel::dofs_per_cell);
          cell->get_dof_indices(dofs);
        }
    DynamicSparsityPattern dsp(n_dofs, n_dofs, system_row_set);
    for (const auto &[row, columns] : system_rows)
      dsp.add_entries(row, columns.begin(), columns.end(), true);
    // Both ways, so that the pattern stays symmetric.
    for (const auto &[cell, ij] : grid.locally_owned_cells())
      if (covered[ij[1] * n_x + ij[0]])
        {
          const auto &here = dofs_of[ij[1] * n_x + ij[0]];
          for (int dj = -1; dj <= 1; ++dj)
            for (int di = -1; di <= 1; ++di)
              {
                const int i = int(ij[0]) + di, j = int(ij[1]) + dj;
                if (i < 0 || i >= n_x || j < 0 || j >= n_y)
                  continue;
                const auto &there = dofs_of[j * n_x + i];
                for (const auto a : here)
                  for (const auto b : there)
                    {
                      dsp.add(a, b);
                      dsp.add(b, a);
                    }
              }
        }
    SparsityTools::distribute_sparsity_pattern(dsp,
                                               grid.locally_owned_dofs(),
                                               grid.mpi_communicator(),
                                               grid.locally_relevant_dofs());
    tangent.clear();
    tangent.reinit(grid.locally_owned_dofs(),
                   grid.locally_owned_dofs(),
                   dsp,
                   grid.mpi_communicator());
  }
} // namespace bsmpm
