#ifndef bsmpm_vertex_patch_smoother_h
#define bsmpm_vertex_patch_smoother_h

#include <deal.II/base/subscriptor.h>

#include <deal.II/lac/trilinos_vector.h>

#include <Epetra_CrsMatrix.h>
#include <Epetra_Map.h>

#include <array>
#include <cstddef>
#include <vector>

namespace bsmpm
{
  using namespace dealii;

  /**
   * An additive Schwarz preconditioner over small patches of a level of the
   * geometric multigrid: B r = sum_p R_p^T A_p^-1 R_p r, where R_p picks the
   * unknowns of patch p and A_p = R_p A R_p^T is the principal block of the
   * level's matrix on them, inverted once at set-up. It serves as the
   * preconditioner of the Chebyshev smoother in place of the inverse
   * diagonal (point Jacobi is the special case of one unknown per patch):
   * a point-wise smoother cannot reduce the error modes of a yielding
   * (perfectly plastic, nearly isochoric) tangent, whose stiffness is small
   * only for displacements that move several vertices together; a patch
   * solves those couplings exactly. The overlap (each unknown lies in
   * several patches) scales B A's spectrum by about the number of patches
   * that share an unknown, which the Chebyshev smoother's eigenvalue
   * estimate takes care of: no partition-of-unity weights, so that B stays
   * symmetric (CG).
   *
   * Two kinds of patch, on a level of Q1 elasticity unknowns (two per
   * vertex) on a grid of nx x ny equal cells:
   * - vertex: for every vertex, the unknowns of the 3 x 3 vertices of the
   *   2 x 2 cells around it (18 for an interior vertex);
   * - cell: for every cell, the unknowns of its 4 vertices (8), whose
   *   basis functions live on the 3 x 3 cells around it.
   * - large: for every cell, the unknowns of the 4 x 4 vertices of the
   *   3 x 3 cells around it (32).
   *
   * Only unknowns whose row couples off the diagonal enter a patch; the
   * others (constrained unknowns, empty cells) get the inverse diagonal.
   * With several processes a patch holds the locally owned unknowns only
   * (a block Jacobi between processes, still symmetric).
   */
  class VertexPatchSmoother : public Subscriptor
  {
  public:
    enum class Patch
    {
      vertex,
      cell,
      large
    };

    /** Builds the patches and inverts their blocks. @p place gives for
     * each locally owned unknown of @p map (in the map's local order) its
     * vertex (i, j) on the grid of @p nx x @p ny cells and its component;
     * @p matrix has the unknowns of @p map among its rows. */
    void
    initialize(const Epetra_CrsMatrix                         &matrix,
               const Epetra_Map                               &map,
               const std::vector<std::array<unsigned int, 3>> &place,
               const unsigned int                              nx,
               const unsigned int                              ny,
               const Patch                                     patch);

    /** dst = B src. */
    void
    vmult(TrilinosWrappers::MPI::Vector       &dst,
          const TrilinosWrappers::MPI::Vector &src) const;

    std::size_t
    n_patches() const
    {
      return patch_start.empty() ? 0 : patch_start.size() - 1;
    }

  private:
    /** Patch p holds the local unknowns patch_unknowns[patch_start[p] ..
     * patch_start[p + 1]). */
    std::vector<std::size_t> patch_start;
    std::vector<int>         patch_unknowns;
    /** A_p^-1 of each patch, row by row, at inverse_start[p], in single
     * precision: the application streams these blocks (38 MB for the
     * vertex patches of 29 k unknowns), and a preconditioner needs no more
     * than float's 7 digits. */
    std::vector<std::size_t> inverse_start;
    std::vector<float>       inverses;
    /** Unknowns in no patch and their inverse diagonal (0 where the
     * diagonal is). */
    std::vector<int>    single_unknowns;
    std::vector<double> single_inverse;
  };
} // namespace bsmpm

#endif
