#include <deal.II/base/exceptions.h>

#include <bsmpm/cell_scatter.h>

#include <Epetra_CrsMatrix.h>

#include <algorithm>

namespace bsmpm
{
  void
  CellScatter::clear()
  {
    first_position.clear();
    positions.clear();
    local_rows.clear();
    matrix_id = nullptr;
    n_entries = 0;
  }



  void
  CellScatter::reinit(const TrilinosWrappers::SparseMatrix &matrix,
                      const DoFHandler<2>                  &dof_handler)
  {
    clear();
    const Epetra_CrsMatrix &A         = matrix.trilinos_matrix();
    int                    *row_start = nullptr, *columns = nullptr;
    double                 *values = nullptr;
    // Without Epetra's contiguous storage there is no one value array to
    // point into: then every cell goes through AffineConstraints.
    if (A.ExtractCrsDataPointers(row_start, columns, values) != 0)
      return;

    const unsigned int n     = dof_handler.get_fe().n_dofs_per_cell();
    const IndexSet    &owned = dof_handler.locally_owned_dofs();
    std::vector<types::global_dof_index> dof_indices(n);
    first_position.assign(dof_handler.get_triangulation().n_active_cells(),
                          numbers::invalid_unsigned_int);
    for (const auto &cell : dof_handler.active_cell_iterators())
      {
        if (!cell->is_locally_owned())
          continue;
        cell->get_dof_indices(dof_indices);
        if (!std::all_of(dof_indices.begin(),
                         dof_indices.end(),
                         [&](const auto i) { return owned.is_element(i); }))
          continue;
        first_position[cell->active_cell_index()] = positions.size();
        for (unsigned int i = 0; i < n; ++i)
          {
            const int row = A.LRID(
              static_cast<TrilinosWrappers::types::int_type>(dof_indices[i]));
            local_rows.push_back(row);
            for (unsigned int j = 0; j < n; ++j)
              {
                const int column =
                  A.LCID(static_cast<TrilinosWrappers::types::int_type>(
                    dof_indices[j]));
                const int *begin = columns + row_start[row];
                const int *end   = columns + row_start[row + 1];
                const int *found = std::find(begin, end, column);
                AssertThrow(found != end,
                            ExcMessage("CellScatter: the matrix's pattern "
                                       "lacks a coupling of a cell."));
                positions.push_back(static_cast<int>(found - columns));
              }
          }
      }
    matrix_id = &A;
    n_entries = A.NumMyNonzeros();
  }



  bool
  CellScatter::serves(const TrilinosWrappers::SparseMatrix &matrix) const
  {
    return matrix_id == &matrix.trilinos_matrix() &&
           n_entries ==
             static_cast<std::size_t>(matrix.trilinos_matrix().NumMyNonzeros());
  }



  void
  CellScatter::add(const unsigned int                          cell_index,
                   const FullMatrix<double>                   &cell_matrix,
                   const Vector<double>                       &cell_rhs,
                   const std::vector<types::global_dof_index> &dof_indices,
                   const AffineConstraints<double>            &constraints,
                   TrilinosWrappers::SparseMatrix             &matrix,
                   TrilinosWrappers::MPI::Vector              &rhs) const
  {
    const unsigned int n     = dof_indices.size();
    const unsigned int first = first_position.empty() ?
                                 numbers::invalid_unsigned_int :
                                 first_position[cell_index];
    const bool         direct =
      first != numbers::invalid_unsigned_int &&
      std::none_of(dof_indices.begin(), dof_indices.end(), [&](const auto i) {
        return constraints.is_constrained(i);
      });
    if (!direct)
      {
        constraints.distribute_local_to_global(
          cell_matrix, cell_rhs, dof_indices, matrix, rhs);
        return;
      }
    Assert(serves(matrix), ExcInternalError());
    int    *row_start = nullptr, *columns = nullptr;
    double *values = nullptr;
    matrix.trilinos_matrix().ExtractCrsDataPointers(row_start, columns, values);
    const int *position = positions.data() + first;
    for (unsigned int i = 0; i < n; ++i)
      for (unsigned int j = 0; j < n; ++j, ++position)
        values[*position] += cell_matrix(i, j);
    // The right-hand side has the matrix's row layout (both are made from
    // the owned DoFs): its local indices are the rows'.
    double    *b   = rhs.trilinos_vector()[0];
    const int *row = local_rows.data() + first / n;
    Assert(rhs.trilinos_vector().Map().LID(
             static_cast<TrilinosWrappers::types::int_type>(dof_indices[0])) ==
             row[0],
           ExcInternalError());
    for (unsigned int i = 0; i < n; ++i)
      b[row[i]] += cell_rhs(i);
  }
} // namespace bsmpm
