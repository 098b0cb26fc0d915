#ifndef bsmpm_cell_scatter_h
#define bsmpm_cell_scatter_h

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/lac/vector.h>

#include <cstdint>
#include <vector>

namespace bsmpm
{
  using namespace dealii;

  /**
   * Adds the matrices of the grid's cells into a Trilinos matrix through
   * positions found once. The pattern of the system matrix holds every
   * cell's couplings and changes only when the matrix is rebuilt, so where
   * each entry of a cell matrix goes in Epetra's value array can be kept:
   * later assemblies only add (AffineConstraints::distribute_local_to_
   * global() looks every entry up again: 18 of the 42 ms of a
   * material-point assembly of 1 M points in benchmarks/assembly_benchmark).
   *
   * A cell's positions are found the first time it is added, so that a
   * scene of one load step pays no more than before and cells without
   * material cost nothing: 4 bytes per cell of the grid, and 96 bytes (its
   * rows, and the place of each entry in its row as one byte) per cell
   * added. A cell is covered when all its DoFs are rows of this process
   * (the rows of ghost DoFs go through Trilinos's exchange in compress())
   * and no row is longer than 256 entries. The additions are those that
   * distribute_local_to_global() makes for a cell none of whose DoFs is
   * constrained, in the same order: the matrix is the same to the last bit.
   * Cells with a constrained DoF are left to AffineConstraints (see add()).
   */
  class CellScatter
  {
  public:
    /** Prepares for @p matrix (whose pattern must hold every cell's
     * couplings) on a grid of @p n_cells active cells. */
    void
    reinit(const TrilinosWrappers::SparseMatrix &matrix,
           const unsigned int                    n_cells);

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
        TrilinosWrappers::MPI::Vector              &rhs);

  private:
    /** Finds the rows and places of a cell's entries; returns its slot, or
     * uncovered. */
    unsigned int
    locate(const std::vector<types::global_dof_index> &dof_indices,
           const TrilinosWrappers::SparseMatrix       &matrix);

    static constexpr unsigned int unknown   = static_cast<unsigned int>(-1);
    static constexpr unsigned int uncovered = static_cast<unsigned int>(-2);

    /** For each active cell: its slot, unknown or uncovered. */
    std::vector<unsigned int> slot;
    /** Per slot: the local rows of the cell's DoFs (dofs_per_cell), and the
     * place of each entry of the cell matrix in its row (dofs_per_cell^2,
     * row by row). */
    std::vector<int>          rows;
    std::vector<std::uint8_t> places;
    const void               *matrix_id = nullptr;
    std::size_t               n_entries = 0;
  };
} // namespace bsmpm

#endif
