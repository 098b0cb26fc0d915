#ifndef bsmpm_contact_pattern_h
#define bsmpm_contact_pattern_h

#include <deal.II/lac/trilinos_sparse_matrix.h>

#include <bsmpm/geometry/background_grid.h>

#include <array>
#include <vector>

namespace bsmpm
{
  using namespace dealii;

  /**
   * The pattern of the Newton tangent where contact has pressures at the
   * grid nodes (NodalContactTerms): a node's stiffness eps / W_a c_a c_a^T
   * couples the DoFs of all the cells round its vertex, DoFs up to two
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

    /** Gives @p tangent the pattern of @p system widened round @p cells
     * (the same list on every process). Collective. */
    void
    widen(const BackgroundGrid                           &grid,
          const std::vector<std::array<unsigned int, 2>> &cells,
          const TrilinosWrappers::SparseMatrix           &system,
          TrilinosWrappers::SparseMatrix                 &tangent);

  private:
    /** Per cell of the grid (i + j n_x): whether the pattern couples its
     * DoFs with those of the cells round it. */
    std::vector<bool> covered;
  };
} // namespace bsmpm

#endif
