#include <deal.II/base/exceptions.h>

#include <bsmpm/assembly/cell_scatter.h>

#include <Epetra_CrsMatrix.h>

#include <algorithm>

namespace bsmpm
{
  void
  CellScatter::clear()
  {
    slot.clear();
    rows.clear();
    places.clear();
    matrix_id = nullptr;
    n_entries = 0;
  }



  void
  CellScatter::reinit(const TrilinosWrappers::SparseMatrix &matrix,
                      const unsigned int                    n_cells)
  {
    clear();
    const Epetra_CrsMatrix &A         = matrix.trilinos_matrix();
    int                    *row_start = nullptr, *columns = nullptr;
    double                 *values = nullptr;
    // Without Epetra's contiguous storage there is no value array to point
    // into: then every cell goes through AffineConstraints.
    const bool usable =
      A.ExtractCrsDataPointers(row_start, columns, values) == 0;
    slot.assign(n_cells, usable ? unknown : uncovered);
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



  unsigned int
  CellScatter::locate(const std::vector<types::global_dof_index> &dof_indices,
                      const TrilinosWrappers::SparseMatrix       &matrix)
  {
    using Index                       = TrilinosWrappers::types::int_type;
    const Epetra_CrsMatrix &A         = matrix.trilinos_matrix();
    const unsigned int      n         = dof_indices.size();
    int                    *row_start = nullptr, *columns = nullptr;
    double                 *values = nullptr;
    A.ExtractCrsDataPointers(row_start, columns, values);

    std::vector<int>          cell_rows(n);
    std::vector<std::uint8_t> cell_places(n * n);
    for (unsigned int i = 0; i < n; ++i)
      {
        cell_rows[i] = A.LRID(static_cast<Index>(dof_indices[i]));
        if (cell_rows[i] < 0)
          return uncovered;
        const int *begin = columns + row_start[cell_rows[i]];
        const int *end   = columns + row_start[cell_rows[i] + 1];
        // Epetra sorts a row's columns when the matrix is completed.
        const bool sorted = std::is_sorted(begin, end);
        for (unsigned int j = 0; j < n; ++j)
          {
            const int  column = A.LCID(static_cast<Index>(dof_indices[j]));
            const int *found  = sorted ? std::lower_bound(begin, end, column) :
                                         std::find(begin, end, column);
            AssertThrow(column >= 0 && found != end && *found == column,
                        ExcMessage("CellScatter: the matrix's pattern lacks "
                                   "a coupling of a cell."));
            if (found - begin > 255)
              return uncovered;
            cell_places[i * n + j] = static_cast<std::uint8_t>(found - begin);
          }
      }
    rows.insert(rows.end(), cell_rows.begin(), cell_rows.end());
    places.insert(places.end(), cell_places.begin(), cell_places.end());
    return rows.size() / n - 1;
  }



  void
  CellScatter::add(const unsigned int                          cell_index,
                   const FullMatrix<double>                   &cell_matrix,
                   const Vector<double>                       &cell_rhs,
                   const std::vector<types::global_dof_index> &dof_indices,
                   const AffineConstraints<double>            &constraints,
                   TrilinosWrappers::SparseMatrix             &matrix,
                   TrilinosWrappers::MPI::Vector              &rhs)
  {
    Assert(serves(matrix), ExcInternalError());
    const unsigned int n = dof_indices.size();
    const bool         free =
      std::none_of(dof_indices.begin(), dof_indices.end(), [&](const auto i) {
        return constraints.is_constrained(i);
      });
    if (free && slot[cell_index] == unknown)
      slot[cell_index] = locate(dof_indices, matrix);
    if (!free || slot[cell_index] == uncovered)
      {
        constraints.distribute_local_to_global(
          cell_matrix, cell_rhs, dof_indices, matrix, rhs);
        return;
      }

    int    *row_start = nullptr, *columns = nullptr;
    double *values = nullptr;
    matrix.trilinos_matrix().ExtractCrsDataPointers(row_start, columns, values);
    const int          *row = rows.data() + std::size_t(slot[cell_index]) * n;
    const std::uint8_t *place =
      places.data() + std::size_t(slot[cell_index]) * n * n;
    for (unsigned int i = 0; i < n; ++i)
      {
        double *row_values = values + row_start[row[i]];
        for (unsigned int j = 0; j < n; ++j, ++place)
          row_values[*place] += cell_matrix(i, j);
      }
    // The right-hand side has the matrix's row layout (both are made from
    // the owned DoFs): its local indices are the rows'.
    double *b = rhs.trilinos_vector()[0];
    Assert(rhs.trilinos_vector().Map().LID(
             static_cast<TrilinosWrappers::types::int_type>(dof_indices[0])) ==
             row[0],
           ExcInternalError());
    for (unsigned int i = 0; i < n; ++i)
      b[row[i]] += cell_rhs(i);
  }
} // namespace bsmpm
