#ifndef bsmpm_linear_solver_h
#define bsmpm_linear_solver_h

#include <deal.II/base/parameter_handler.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <bsmpm/linear_algebra/direct_solver.h>
#include <bsmpm/linear_algebra/geometric_multigrid.h>

#include <cstdint>
#include <memory>
#include <string>

namespace bsmpm
{
  using namespace dealii;

  /**
   * Solves the linear system of a load step: a sparse direct solver (MUMPS
   * through Amesos, KLU where MUMPS is missing), or CG preconditioned by
   * Trilinos ML's algebraic multigrid with the two translations of plane
   * elasticity as near-null space, or CG preconditioned by a geometric
   * multigrid on the uniform grid (GeometricMultigrid). "automatic" takes the
   * direct solver up to a number of unknowns and CG beyond, with the
   * geometric multigrid where the grid can be coarsened and ML elsewhere.
   *
   * In automatic mode a solve does not end the run while a method is left:
   * if the geometric multigrid cannot be set up or CG with it does not
   * converge, CG with ML takes over (method "cg amg, gmg failed", for every
   * solve of a matrix of the same structure); if CG does not converge with
   * ML either, the direct solver (method "direct (...), cg failed", for
   * this and every later solve). A failure of the direct solver itself
   * (a singular system, or too little memory after MUMPS was given more
   * workspace) ends the run with one message that says what it means.
   */
  class LinearSolver
  {
  public:
    enum class Method
    {
      direct,
      cg_amg,
      cg_gmg,
      automatic
    };

    struct Report
    {
      std::string method;
      /** CG iterations (0 for a direct solve). */
      unsigned int iterations = 0;
      /** Steps of iterative refinement after a direct solve. */
      unsigned int refinement_steps = 0;
      /** ||K x - b|| / ||b|| after the solve. */
      double relative_residual = 0;
      /** cg amg, cg gmg: whether the multigrid hierarchy of an earlier solve
       * served again (see 'Preconditioner reuse'). */
      bool reused_preconditioner = false;
    };

    static void
    declare_parameters(ParameterHandler &prm);
    void
    parse_parameters(ParameterHandler &prm);

    /** Solves; in automatic mode, a CG failure makes this and every later
     * solve direct. An unsymmetric @p matrix (not @p symmetric) is solved
     * by GMRES with the same preconditioner instead of CG.
     *
     * @p enough: the residual ||K x - b|| the caller needs from a direct
     * solve, which refines its solution only while the residual is above
     * it (0: as far as the factors reduce it). A Newton correction needs
     * little: the next iteration's residual corrects whatever the solve
     * leaves. */
    Report
    solve(const TrilinosWrappers::SparseMatrix &matrix,
          TrilinosWrappers::MPI::Vector        &solution,
          const TrilinosWrappers::MPI::Vector  &rhs,
          const DoFHandler<2>                  &dof_handler,
          const bool                            symmetric = true,
          const double                          enough    = 0.) const;

    /** As solve(), for the @p matrix of the last solve() unchanged since:
     * the direct solver's factors serve as they are, with no new
     * factorisation (the further right-hand sides of a bordered system,
     * RigidBodyMotion). */
    Report
    solve_unchanged(const TrilinosWrappers::SparseMatrix &matrix,
                    TrilinosWrappers::MPI::Vector        &solution,
                    const TrilinosWrappers::MPI::Vector  &rhs,
                    const DoFHandler<2>                  &dof_handler,
                    const bool symmetric = true) const;

    /**
     * An estimate of the spectral condition number of @p matrix: the ratio
     * of the extreme eigenvalues of the Lanczos tridiagonal matrix that
     * unpreconditioned CG builds on the system (at most 'Condition estimate
     * iterations' steps; fewer steps give a lower bound). Only when
     * 'Estimate condition number' is on (see estimates_condition()).
     */
    double
    estimate_condition_number(const TrilinosWrappers::SparseMatrix &matrix,
                              const TrilinosWrappers::MPI::Vector  &rhs) const;

    bool
    estimates_condition() const
    {
      return estimate_condition;
    }

    /**
     * Drops what later solves would take over from earlier ones: the
     * factors and their symbolic analysis, the multigrid hierarchies, CG's
     * first guess (the last solution) and the geometric multigrid's
     * failure. A run resumed from a checkpoint has none of them, and the
     * solves' round-off depends on them (a reused AMG hierarchy, a CG
     * started from the last solution): the run that writes the checkpoint
     * drops them there, so that it and a run resumed from it go on alike.
     */
    void
    drop_reused_state() const;

    /** For checkpoints: the automatic method's choice of the run's later
     * solves (CG failed or was slow: direct from then on), which a resumed
     * run keeps. */
    template <class Archive>
    void
    serialize(Archive &archive, const unsigned int)
    {
      archive &cg_failed &cg_slow &cg_slow_said;
    }

  private:
    /** Automatic mode: the CG iterations above which a system of @p n
     * unknowns is factorised faster ('Automatic iteration limit' at 100 k
     * unknowns, scaled as sqrt(n), not below half of it). */
    unsigned int
    iteration_limit(const types::global_dof_index n) const;

    /** Sparse LU (L D L^T of a @p symmetric matrix) with iterative
     * refinement: MUMPS, with more workspace if it runs short, else KLU. Throws
     * a message (no error numbers of Trilinos or MUMPS) if neither factorises
     * the matrix. */
    Report
    solve_direct(const TrilinosWrappers::SparseMatrix &matrix,
                 TrilinosWrappers::MPI::Vector        &solution,
                 const TrilinosWrappers::MPI::Vector  &rhs,
                 const bool                            symmetric,
                 const double                          enough) const;

    /** cg amg, cg gmg: the multigrid preconditioner (geometric or ML),
     * kept for later solves. */
    void
    prepare_preconditioner(const TrilinosWrappers::SparseMatrix &matrix,
                           const DoFHandler<2>                  &dof_handler,
                           const bool                            geometric,
                           Report                               &report) const;

    /** CG (GMRES) with the geometric multigrid or ML. Throws
     * IterativeFailure if the preconditioner cannot be set up or applied,
     * or the iterations do not converge. */
    Report
    solve_iterative(const TrilinosWrappers::SparseMatrix &matrix,
                    TrilinosWrappers::MPI::Vector        &solution,
                    const TrilinosWrappers::MPI::Vector  &rhs,
                    const DoFHandler<2>                  &dof_handler,
                    const bool                            symmetric,
                    const bool                            geometric) const;

    /** Whether CG takes the geometric multigrid (cg gmg, or automatic on
     * a grid that coarsens at least once) rather than ML. */
    bool
    geometric_multigrid(const DoFHandler<2> &dof_handler) const;

    /** Forgets the multigrid hierarchy (AMG or GMG). */
    void
    reset_preconditioner() const
    {
      amg.reset();
      gmg.reset();
    }

    /** The relative tolerance of CG ('Tolerance', or the automatic one). */
    double
    relative_tolerance(const DoFHandler<2> &dof_handler) const;

    enum class Reuse
    {
      none,
      aggregates,
      whole
    };

    Method       method              = Method::automatic;
    double       tolerance           = 0;
    Reuse        reuse               = Reuse::whole;
    unsigned int max_iterations      = 10000;
    unsigned int automatic_threshold = 100000;
    unsigned int max_refinements     = 3;
    bool         estimate_condition  = false;
    /** Automatic mode: CG did not converge in an earlier load step. */
    mutable bool cg_failed = false;
    /** Automatic mode: an iterative solve needed more than
     * automatic_iteration_limit iterations; cg_slow_said once the step
     * table has said so. */
    unsigned int automatic_iteration_limit = 50;
    mutable bool cg_slow                   = false;
    mutable bool cg_slow_said              = false;
    /** Automatic mode: the geometric multigrid failed (set-up or
     * iterations) on the matrix object gmg_failed_matrix with the structure
     * gmg_failed_structure; ML serves matrices of that structure. */
    mutable bool          gmg_failed           = false;
    mutable const void   *gmg_failed_matrix    = nullptr;
    mutable std::uint64_t gmg_failed_structure = 0;
    unsigned int          condition_iterations = 2000;

    /** The factors of the last direct solve, the matrix object they were
     * computed for, its structure (matrix_structure()) and the method's
     * name: a matrix of the same structure is factorised again with the
     * same symbolic analysis. */
    mutable std::unique_ptr<DirectSolver> direct_factors;
    /** Within solve_unchanged(): the kept factors are those of the
     * matrix. */
    mutable bool          unchanged_matrix = false;
    mutable const void   *direct_matrix    = nullptr;
    mutable std::uint64_t direct_structure = 0;
    mutable bool          direct_symmetric = false;
    mutable std::string   direct_method;

    /** The AMG hierarchy of the last CG solve, the matrix it was built on
     * and a fingerprint of that matrix's structure (the pattern and the
     * decoupled rows: constrained DoFs). A matrix rebuilt with another
     * pattern, even at the same address, has another fingerprint. */
    mutable std::unique_ptr<TrilinosWrappers::PreconditionAMG> amg;
    mutable const void   *amg_matrix    = nullptr;
    mutable std::uint64_t amg_structure = 0;
    /** cg gmg: the geometric multigrid, kept like the AMG (amg_matrix and
     * amg_structure describe the matrix either was built on). */
    mutable std::unique_ptr<GeometricMultigrid> gmg;
    GeometricMultigrid::AdditionalData          gmg_data;
    /** CG iterations of the solve for which the hierarchy was built. */
    mutable unsigned int fresh_iterations = 0;
    /** The automatic tolerance and the grid it was computed for. */
    mutable double       automatic_tolerance = 1e-8;
    mutable unsigned int cached_levels       = 0;
    /** The last CG solution: the first guess of the next solve if it is a
     * better one than zero. */
    mutable TrilinosWrappers::MPI::Vector last_solution;
  };
} // namespace bsmpm

#endif
