#ifndef bsmpm_direct_solver_h
#define bsmpm_direct_solver_h

#include <deal.II/lac/trilinos_vector.h>

#include <Epetra_CrsMatrix.h>
#include <Epetra_LinearProblem.h>

#include <memory>
#include <string>

class Amesos_BaseSolver;

namespace bsmpm
{
  class SubdomainMumps;
}

namespace bsmpm
{
  using namespace dealii;

  /**
   * A sparse factorisation, by MUMPS (its C interface) or by KLU (through
   * Amesos), that says why it failed instead of passing on the error
   * numbers of Trilinos or MUMPS, and keeps the solvers' own lines off the
   * terminal.
   *
   * A symmetric matrix goes to MUMPS as its lower triangle and is
   * factorised as L D L^T with pivoting (SYM = 2): the Newton tangents of
   * the small-strain plastic scenes are symmetric but need not be
   * definite. Against MUMPS' LU of the same matrices, half the entries in
   * the factors and about 0.55 of the factorisation's time (plastic footing,
   * 29 k unknowns, doc/benchmarks.md).
   *
   * MUMPS sizes its workspace from the estimate of its analysis enlarged
   * by ICNTL(14) percent (20 by default). Where that is too little for the
   * pivoting of the factorisation (INFOG(1) = -8, -9, -11, -14, -15, -17
   * or -20, MUMPS users' guide, "Error diagnostics"; -9 at 83 k unknowns on
   * two processes, issue 27), the factorisation is repeated with
   * ICNTL(14) = 100, 400 and 1600.
   *
   * MUMPS on several processes gives results that differ in the last bits
   * from one run to the next (its fronts' contributions are added in the
   * order their messages arrive, and it chooses helpers for large fronts
   * by their load): two identical runs of the deep penetration at np = 2
   * parted at 5e-15 .. 3e-13 within the first 4 steps (doc/contact.md),
   * enough to flip any decision that sits on a threshold. So MUMPS always
   * runs on one process (MPI_COMM_SELF): on several processes each
   * factorises its own unknowns and process 0 the seams between them
   * (SubdomainMumps), which gives the same bits in every run; where that
   * cannot be had (a seam too long for its dense Schur complement) the
   * matrix is gathered on process 0 and factorised there. (Debian's Amesos
   * cannot give MUMPS fewer processes than the matrix has: it lacks
   * MPI_Comm_c2f.) KLU gathers the matrix on process 0 itself.
   */
  class DirectSolver
  {
  public:
    enum class Status
    {
      success,
      /** The solver is not in this Trilinos. */
      unavailable,
      /** Structurally or numerically singular. */
      singular,
      /** Not enough memory, even with more workspace. */
      out_of_memory,
      other
    };

    DirectSolver();
    ~DirectSolver();

    /** Factorises @p matrix with "MUMPS" or "Amesos_Klu" (a copy of its
     * values: the factors may outlive the caller's matrix, and Amesos
     * reads the matrix when it lets go of them). A @p symmetric matrix
     * gives MUMPS only its lower triangle. */
    Status
    factorize(const Epetra_CrsMatrix &matrix,
              const std::string      &name,
              const bool              symmetric);

    /** Factorises @p matrix, whose structure is that of the last
     * factorize(), reusing the symbolic analysis. */
    Status
    refactorize(const Epetra_CrsMatrix &matrix);

    /** x = A^-1 b with the factors; false if the solver failed. */
    bool
    solve(TrilinosWrappers::MPI::Vector       &x,
          const TrilinosWrappers::MPI::Vector &b);

    /** Whether the last factorize() split the matrix into the processes'
     * subdomains (SubdomainMumps) rather than gathering it on process 0. */
    bool
    on_subdomains() const
    {
      return subdomains != nullptr;
    }

  private:
    /** MUMPS on process 0 alone. */
    class HostMumps;

    std::unique_ptr<HostMumps>         mumps;
    std::unique_ptr<SubdomainMumps>    subdomains;
    std::unique_ptr<Epetra_CrsMatrix>  matrix_copy;
    Epetra_LinearProblem               problem;
    std::unique_ptr<Amesos_BaseSolver> solver;
  };
} // namespace bsmpm

#endif
