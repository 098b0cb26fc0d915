#ifndef bsmpm_cell_scatter_h
#define bsmpm_cell_scatter_h

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/lac/vector.h>

#include <vector>

namespace bsmpm
{
  using namespace dealii;

  /**
   * Adds the matrices of the grid's cells into a Trilinos matrix through
   * positions found once. The pattern of the system matrix holds every
   * cell's couplings and changes only when the matrix is rebuilt, so where
   * each entry of a cell matrix goes in Epetra's value array can be kept:
   * an assembly then only adds (AffineConstraints::distribute_local_to_
   * global() looks every entry up again, by a search in its row: 18 of the
   * 42 ms of a material-point assembly of 1 M points in
   * benchmarks/assembly_benchmark).
   *
   * A cell is covered when all its DoFs are owned by this process (the rows
   * of ghost DoFs go through Trilinos's exchange in compress()). The
   * additions are those distribute_local_to_global() makes for a cell none
   * of whose DoFs is constrained, in the same order: the matrix is the same
   * to the last bit. Cells with a constrained DoF are left to
   * AffineConstraints (see add()).
   */
  class CellScatter
  {
  public:
    /** Finds the positions of the cells' entries in @p matrix, whose
     * pattern must hold every cell's couplings. */
    void
    reinit(const TrilinosWrappers::SparseMatrix &matrix,
           const DoFHandler<2>                  &dof_handler);

    /** Forgets the positions (the matrix was rebuilt). */
    void
    clear();

    /** Whether reinit() was called for @p matrix (the same Epetra object
     * and the same number of entries) and not cleared since. */
    bool
    serves(const TrilinosWrappers::SparseMatrix &matrix) const;

    /**
     * Adds @p cell_matrix and @p cell_rhs of the cell with active index
     * @p cell_index and DoFs @p dof_indices to @p matrix (the one of
     * reinit()) and @p rhs, directly if the cell is covered and none of its
     * DoFs is constrained, and through @p constraints otherwise.
     */
    void
    add(const unsigned int                          cell_index,
        const FullMatrix<double>                   &cell_matrix,
        const Vector<double>                       &cell_rhs,
        const std::vector<types::global_dof_index> &dof_indices,
        const AffineConstraints<double>            &constraints,
        TrilinosWrappers::SparseMatrix             &matrix,
        TrilinosWrappers::MPI::Vector              &rhs) const;

  private:
    /** For each active cell, the index of its first entry in positions, or
     * invalid if it is not covered. */
    std::vector<unsigned int> first_position;
    /** Offsets of the entries of covered cells' matrices in Epetra's value
     * array, row by row (dofs_per_cell^2 per cell), and the local indices
     * of their DoFs in the right-hand side (dofs_per_cell per cell). */
    std::vector<int> positions;
    std::vector<int> local_rows;
    const void      *matrix_id = nullptr;
    std::size_t      n_entries = 0;
  };
} // namespace bsmpm

#endif
