#ifndef bsmpm_geometric_multigrid_h
#define bsmpm_geometric_multigrid_h

#include <deal.II/base/subscriptor.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <Epetra_CrsMatrix.h>

#include <memory>
#include <string>

namespace bsmpm
{
  using namespace dealii;

  /**
   * Whether the locally owned row @p row (a local index) of @p matrix has a
   * nonzero entry off the diagonal. A row without one is decoupled: a
   * constrained DoF, or a DoF of cells without material. Entries that
   * happen to vanish in a coupled row do not count.
   */
  bool
  couples_off_diagonal(const Epetra_CrsMatrix &matrix, const int row);

  /**
   * A geometric multigrid V-cycle for the Q1 elasticity systems of a
   * uniform background grid (FESystem(FE_Q(1), 2) on a grid of equal
   * rectangular cells, refined globally from a coarse rectangle), used as a
   * preconditioner of CG or GMRES.
   *
   * The levels are the grids with half the cells per direction, as long as
   * both counts are even and the finer level has more than 'coarse size'
   * unknowns. The prolongation P from a level to the next finer one is the
   * bilinear interpolation of the coarse nodal values, except that the rows
   * of fine unknowns without coupling (no nonzero off the diagonal: cells
   * without material, constrained DoFs) are zero: such unknowns are left to
   * the smoother, and a coarse function does not leak into the empty part of
   * the grid. The coarse operators are the Galerkin products P^T A P, not a
   * rediscretisation: the fine matrix holds cut-cell moments, implicit
   * boundary or Nitsche terms and a ghost penalty that the coarse grids do
   * not know, and the Galerkin product carries all of them down exactly.
   * With these operators each level's correction is the A-orthogonal
   * projection onto the coarse space (the variational property of
   * multigrid, Hackbusch, Multi-Grid Methods and Applications, 1985, ch. 3).
   *
   * The smoother is a Chebyshev polynomial in the Jacobi-preconditioned
   * operator D^-1 A (or B A with B a patch-wise additive Schwarz method,
   * VertexPatchSmoother, see Blocks) that damps the upper part [lambda_max /
   * range, lambda_max] of its spectrum (Adams, Brezina, Hu and Tuminaro,
   * "Parallel multigrid smoothing: polynomial versus Gauss-Seidel", J. Comput.
   * Phys. 188 (2003): as effective as Gauss-Seidel, but made of matrix-vector
   * products only, hence the same at any number of processes). The
   * coarsest level is factorised (KLU), or, when it is still large because
   * a count of cells is odd, approximated by one ML V-cycle. The V-cycle
   * uses the same polynomial before and after the coarse correction, so the
   * preconditioner is symmetric and CG applies.
   *
   * Numbering of the coarse levels: the unknown of component c at vertex
   * (i, j) of a level with nx cells in x is 2 (i + (nx + 1) j) + c, the same
   * at every number of processes; it is owned by the process that owns the
   * fine DoF at the same place (vertex (2^l i, 2^l j) of the fine grid), so
   * the restriction needs no data from other processes beyond P's own
   * columns. The index sets are therefore not contiguous per process.
   */
  class GeometricMultigrid : public Subscriptor
  {
  public:
    /** What the Chebyshev smoother is preconditioned by on a level: the
     * inverse diagonal (point Jacobi) or the additive Schwarz method of a
     * VertexPatchSmoother over vertex patches (the 2 x 2 cells around each
     * vertex), cell patches (the 4 vertices of each cell) or large
     * patches (the 3 x 3 cells around each cell). */
    enum class Blocks
    {
      point,
      vertex_patch,
      cell_patch,
      large_patch
    };

    struct AdditionalData
    {
      /** Degree of the Chebyshev smoother (matrix-vector products per
       * smoothing step). */
      unsigned int smoother_degree = 3;
      /** The smoother damps [lambda_max / range, lambda_max] of D^-1 A. */
      double smoothing_range = 15.;
      /** Stop coarsening at or below this many unknowns. */
      unsigned int coarse_size = 2000;
      /** A coarsest level larger than this is approximated by ML instead of
       * factorised. */
      unsigned int direct_size = 40000;
      /** The smoother's blocks on the finest 'patch_levels' levels (all
       * smoothed levels if 0); point Jacobi on the coarser ones. */
      Blocks       blocks       = Blocks::point;
      unsigned int patch_levels = 0;
    };

    GeometricMultigrid();
    ~GeometricMultigrid();

    /** Builds the hierarchy: the prolongations from the geometry of
     * @p dof_handler's triangulation and the decoupled rows of @p matrix,
     * then the coarse operators and smoothers. */
    void
    initialize(const TrilinosWrappers::SparseMatrix &matrix,
               const DoFHandler<2>                  &dof_handler,
               const AdditionalData                 &data);

    /** The matrix has new values but the same structure (the same
     * decoupled rows): keep the prolongations and recompute the Galerkin
     * products, smoothers and the coarse factorisation. */
    void
    reinit(const TrilinosWrappers::SparseMatrix &matrix);

    /** Points the finest level to @p matrix (of the structure it was built
     * for) without recomputing anything: a hierarchy kept as a whole
     * across load steps smooths with the current fine matrix. */
    void
    set_fine_matrix(const TrilinosWrappers::SparseMatrix &matrix);

    /** One V-cycle with zero initial guess: dst = B src. */
    void
    vmult(TrilinosWrappers::MPI::Vector       &dst,
          const TrilinosWrappers::MPI::Vector &src) const;

    unsigned int
    n_levels() const;

    /** How many levels coarser than @p dof_handler's grid initialize()
     * would make: 0 if the grid cannot be coarsened (an odd count of
     * cells) or is already at most 'coarse size' unknowns. */
    static unsigned int
    n_coarse_levels(const DoFHandler<2>  &dof_handler,
                    const AdditionalData &data);

    /** Unknowns per level, finest first, e.g. "33282 8450 2178 578". */
    std::string
    level_sizes() const;

  private:
    /** The levels (Epetra matrices and Trilinos vectors) and the coarse
     * solver, in source/linear_algebra/geometric_multigrid.cc. */
    struct Implementation;
    std::unique_ptr<Implementation> impl;
  };
} // namespace bsmpm

#endif
