#ifndef bsmpm_contact_pattern_h
#define bsmpm_contact_pattern_h

#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>

#include <bsmpm/geometry/background_grid.h>

#include <array>
#include <vector>

namespace bsmpm
{
  using namespace dealii;

  /**
   * The pattern of the Newton tangent where contact has mortar pressures
   * (NodalContactTerms): a node's stiffness eps / W_a c_a c_a^T couples
   * the DoFs of the cells on either side of its crossing, DoFs up to two
   * cells apart, which the cell pattern of the system matrix does not
   * hold. The tangent then gets a pattern of its own: the system's, with
   * the DoFs of every cell within two cells of the contact's cells coupled
   * with those of the 3 x 3 cells round it. The margin of two cells lets a
   * contact that moves by less than a cell per increment keep its pattern;
   * a new one is made only where the contact leaves the cells covered.
   */
  class ContactPattern
  {
  public:
    /** Whether the pattern made last covers the couplings of @p cells (the
     * cells that hold the contact's Gauss points, of all processes). */
    bool
    covers(const BackgroundGrid                           &grid,
           const std::vector<std::array<unsigned int, 2>> &cells) const;

    /** Keeps the system matrix's pattern @p system (with the rows of ghost
     * DoFs that the cells' assembly adds to), after its distribution. */
    void
    keep(const DynamicSparsityPattern &system);

    /** Gives @p tangent the pattern kept last widened round @p cells (the
     * same list on every process). Collective. */
    void
    widen(const BackgroundGrid                           &grid,
          const std::vector<std::array<unsigned int, 2>> &cells,
          TrilinosWrappers::SparseMatrix                 &tangent);

  private:
    /** Per cell of the grid (i + j n_x): whether the pattern couples its
     * DoFs with those of the cells round it. */
    std::vector<bool> covered;
    /** The rows of the system matrix's pattern: (row, columns). */
    std::vector<
      std::pair<types::global_dof_index, std::vector<types::global_dof_index>>>
                            system_rows;
    IndexSet                system_row_set;
    types::global_dof_index n_dofs = 0;
  };
} // namespace bsmpm

#endif
