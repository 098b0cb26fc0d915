#ifndef bsmpm_mumps_factorization_h
#define bsmpm_mumps_factorization_h

#include <bsmpm/linear_algebra/direct_solver.h>

#include <dmumps_c.h>

#include <vector>

namespace bsmpm
{
  /**
   * One MUMPS instance on the calling process alone (MPI_COMM_SELF),
   * through MUMPS' C interface: the analysis of a matrix given as
   * triplets, its numeric factorisation (again for new values of the same
   * structure), and solves. A symmetric matrix is given as one triangle
   * and factorised as L D L^T with 1 x 1 and 2 x 2 pivots (SYM = 2): the
   * tangents of plastic and contact scenes need not be definite.
   *
   * Optionally the last unknowns are kept out of the factorisation as a
   * Schur complement (ICNTL(19)): factorize() then returns
   * S = A_ss - A_si A_ii^-1 A_is dense, and a solve runs in two halves,
   * reduce() (the right-hand side condensed onto those unknowns) and
   * expand() (the rest of the solution once theirs is known). The
   * subdomain solver of several processes is built from this.
   */
  class MumpsFactorization
  {
  public:
    explicit MumpsFactorization(const bool symmetric);
    ~MumpsFactorization();

    MumpsFactorization(const MumpsFactorization &) = delete;
    MumpsFactorization &
    operator=(const MumpsFactorization &) = delete;

    /** Ordering and symbolic analysis of the n x n matrix whose entries
     * are at (@p rows[k], @p columns[k]), counted from 1 (one triangle if
     * symmetric; entries given twice are summed). The last @p schur_size
     * unknowns are kept as a Schur complement; then MUMPS' maximum
     * transversal and scaling are off (it cannot have them with one). */
    DirectSolver::Status
    analyse(const int               n,
            const std::vector<int> &rows,
            const std::vector<int> &columns,
            const int               schur_size = 0);

    /** Pivots below @p relative times the matrix's largest entry count as
     * null (ICNTL(24) = 1, CNTL(3) < 0), and the matrix as singular.
     * MUMPS' own threshold tells the exact null pivots of a sparse
     * factorisation, not those of a dense Schur complement summed from
     * pieces: the pure Neumann Laplacian's S at np = 2 left a pivot above
     * it (tests/linear_algebra/direct_solver). */
    void
    set_null_pivot_threshold(const double relative)
    {
      mumps.icntl[24 - 1] = 1;
      mumps.cntl[3 - 1]   = -relative;
    }

    /** The numeric factorisation of @p values (in the order of the
     * analysed triplets; kept, MUMPS reads them in place), with more
     * workspace where the pivoting needs it. */
    DirectSolver::Status
    factorize(std::vector<double> &values);

    /** x = A^-1 b in place (@p rhs of length n). Not with a Schur
     * complement. */
    bool
    solve(double *rhs);

    /** With a Schur complement: @p rhs (length n) eliminated onto the
     * Schur unknowns, @p reduced = b_s - A_si A_ii^-1 b_i (length
     * schur_size). @p rhs is kept for expand(). */
    bool
    reduce(double *rhs, double *reduced);

    /** After reduce(@p rhs, ...): the whole solution in @p rhs, given the
     * Schur unknowns' values in @p reduced. */
    bool
    expand(double *rhs, double *reduced);

    /** The Schur complement of the last factorize(), dense by rows
     * (schur_size^2 entries; of a symmetric matrix only the lower triangle,
     * entries (i, j <= i), holds values). */
    const std::vector<double> &
    schur_complement() const
    {
      return schur;
    }

  private:
    bool
    run_solve(double *rhs, double *reduced, const int schur_phase);

    DMUMPS_STRUC_C      mumps{};
    bool                initialised = false;
    bool                analysed    = false;
    const bool          symmetric;
    std::vector<int>    rows, columns, schur_variables;
    std::vector<double> schur;
  };
} // namespace bsmpm

#endif
