#include <deal.II/dofs/dof_tools.h>

#include <deal.II/lac/precondition.h>
#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/solver_gmres.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_solver.h>

#include <bsmpm/linear_algebra/direct_solver.h>
#include <bsmpm/linear_algebra/linear_solver.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <string>

namespace bsmpm
{
  void
  LinearSolver::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Linear solver");
    prm.declare_entry(
      "Method",
      "automatic",
      Patterns::Selection("direct|cg amg|cg gmg|automatic"),
      "direct: a sparse factorisation (MUMPS: L D L^T of symmetric systems, "
      "LU of others; KLU where MUMPS is missing; on several processes each "
      "factorises its own unknowns and process 0 the seams); cg amg: "
      "conjugate gradients with algebraic multigrid (Trilinos ML); cg gmg: "
      "conjugate gradients with a geometric multigrid V-cycle on the uniform "
      "grid (coarse grids of half the cells per direction while both counts "
      "are even, Galerkin coarse operators, Chebyshev-Jacobi smoother); "
      "automatic (the default): direct up to 'Automatic threshold' unknowns, "
      "above cg gmg if the grid can be coarsened at least once (even cell "
      "counts, more than 'Multigrid coarse size' unknowns), else cg amg, and "
      "direct if CG does not converge or needs more than 'Automatic iteration "
      "limit' (a multigrid that fails to set up or converge hands the solve "
      "to cg amg; the step table says which). Unsymmetric systems take GMRES "
      "with the same preconditioner. Choose direct for small or "
      "ill-conditioned systems, an iterative method where the factors would "
      "not fit in memory (doc/linear-solvers.md).");
    prm.declare_entry(
      "Tolerance",
      "automatic",
      Patterns::Anything(),
      "cg amg, cg gmg: stop when the residual is below this fraction of the "
      "right-hand side: a number of at least 1e-15 (below round-off CG would "
      "iterate on into underflow), or automatic (the default): tied to the "
      "discretisation error, min(1e-8, 1.5e-3 (h/L)^2) with h the diameter of "
      "a cell and L that of the grid, so that the algebraic error stays far "
      "below the discretisation error. A number for studies of the algebraic "
      "error (doc/linear-solvers.md).");
    prm.declare_entry("Preconditioner reuse",
                      "whole",
                      Patterns::Selection("none|aggregates|whole"),
                      "cg amg, cg gmg: what a solve takes over from the "
                      "multigrid hierarchy of the previous one when the "
                      "matrix has the same nonzero structure (the same active "
                      "cells and constraints): none (a new hierarchy every "
                      "solve), aggregates (ML's aggregates, or the geometric "
                      "prolongations, kept, the coarse operators and "
                      "smoothers recomputed from the new values) or whole "
                      "(the default: the previous preconditioner as it is). A "
                      "reused one that needs many more iterations than when "
                      "it was new is replaced, so whole rarely costs more "
                      "than the others; aggregates or none where the matrix's "
                      "values change much between solves.");
    prm.declare_entry("Maximum iterations",
                      "10000",
                      Patterns::Integer(1),
                      "cg amg, cg gmg: the iteration limit of a solve; in "
                      "automatic mode a solve that does not converge within "
                      "it hands over to the next method (cg amg, then "
                      "direct).");
    prm.declare_entry("Multigrid smoother degree",
                      "3",
                      Patterns::Integer(1, 20),
                      "cg gmg: degree of the Chebyshev smoother "
                      "(matrix-vector products per smoothing step on each "
                      "level). Higher degrees take fewer CG iterations at a "
                      "higher cost each.");
    prm.declare_entry(
      "Multigrid smoother",
      "jacobi",
      Patterns::Selection("jacobi|vertex patch|cell patch|large patch"),
      "cg gmg: what the Chebyshev smoother is preconditioned by on each "
      "level: jacobi (the inverse diagonal, the default), or additive Schwarz "
      "over patches whose blocks of the level's matrix are inverted at "
      "set-up: vertex patch (the 2 x 2 cells around each vertex, 18 "
      "unknowns), cell patch (the 4 vertices of each cell, 8 unknowns) or "
      "large patch (the 3 x 3 cells around each cell, 32 unknowns). The "
      "patches need several times fewer CG iterations on the tangents of "
      "yielding material but cost more per iteration; choose one for such "
      "runs that must stay iterative (Method = cg gmg, no memory for "
      "factors), else keep jacobi (doc/linear-solvers.md).");
    prm.declare_entry("Multigrid patch levels",
                      "0",
                      Patterns::Integer(0),
                      "cg gmg with a patch smoother: the patches on the "
                      "finest this many levels, point Jacobi on the coarser "
                      "ones; 0: on every smoothed level.");
    prm.declare_entry("Multigrid coarse size",
                      "2000",
                      Patterns::Integer(1),
                      "cg gmg: a level with at most this many unknowns is not "
                      "coarsened further but factorised (KLU). Larger values "
                      "make fewer, more expensive levels.");
    prm.declare_entry(
      "Automatic threshold",
      "1000",
      Patterns::Integer(0),
      "automatic: the number of unknowns above which CG with a multigrid "
      "replaces the direct solver; below it a factorisation is the cheaper "
      "solve. Rarely worth changing (doc/linear-solvers.md).");
    prm.declare_entry(
      "Automatic iteration limit",
      "50",
      Patterns::Integer(0),
      "automatic: a CG (GMRES) solve of 100 k unknowns that needs more than "
      "this many iterations makes the later solves of the run direct, up to a "
      "million unknowns (the step table says 'cg slow' once); for n unknowns "
      "the limit is scaled by sqrt(n / 100 k), as a two-dimensional "
      "factorisation (about n^1.5) against a CG iteration (about n) suggests, "
      "and not below half of it. Linear scenes stay iterative; the nearly "
      "singular tangents of yielding material go direct after their first "
      "slow solve. 0: never switch (to keep a run iterative, e.g. for "
      "memory); lower it to leave CG sooner (doc/linear-solvers.md).");
    prm.declare_entry("Estimate condition number",
                      "false",
                      Patterns::Bool(),
                      "Estimate the condition number of the assembled system "
                      "in every load step from the Lanczos process of "
                      "unpreconditioned CG, and report the largest as "
                      "quantity condition_estimate (costs extra iterations).");
    prm.declare_entry("Condition estimate iterations",
                      "2000",
                      Patterns::Integer(2),
                      "Iteration limit of the condition estimate; with fewer "
                      "iterations than CG needs the estimate is a lower "
                      "bound.");
    prm.declare_entry("Refinement steps",
                      "3",
                      Patterns::Integer(0),
                      "direct: at most this many steps of iterative "
                      "refinement with the same factors, while each halves "
                      "the residual at least (a Newton correction's only "
                      "while its residual is above a thousandth of the "
                      "Newton tolerance's force).");
    prm.leave_subsection();
  }



  void
  LinearSolver::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Linear solver");
    const std::string m = prm.get("Method");
    method              = m == "direct" ? Method::direct :
                          m == "cg amg" ? Method::cg_amg :
                          m == "cg gmg" ? Method::cg_gmg :
                                          Method::automatic;
    const std::string t = Utilities::trim(prm.get("Tolerance"));
    if (t == "automatic")
      tolerance = 0;
    else
      {
        std::size_t end = 0;
        try
          {
            tolerance = std::stod(t, &end);
          }
        catch (const std::exception &)
          {
            end = 0;
          }
        AssertThrow(end == t.size() && end > 0 && tolerance >= 1e-15 &&
                      std::isfinite(tolerance),
                    ExcMessage("Linear solver/Tolerance: '" + t +
                               "' is neither 'automatic' nor a number of at "
                               "least 1e-15 (below round-off CG would "
                               "iterate on into underflow)."));
      }
    const std::string r       = prm.get("Preconditioner reuse");
    reuse                     = r == "none" ?
                                  Reuse::none :
                                  (r == "aggregates" ? Reuse::aggregates : Reuse::whole);
    max_iterations            = prm.get_integer("Maximum iterations");
    automatic_threshold       = prm.get_integer("Automatic threshold");
    automatic_iteration_limit = prm.get_integer("Automatic iteration limit");
    max_refinements           = prm.get_integer("Refinement steps");
    estimate_condition        = prm.get_bool("Estimate condition number");
    condition_iterations     = prm.get_integer("Condition estimate iterations");
    gmg_data.smoother_degree = prm.get_integer("Multigrid smoother degree");
    gmg_data.coarse_size     = prm.get_integer("Multigrid coarse size");
    const std::string blocks = prm.get("Multigrid smoother");
    gmg_data.blocks =
      blocks == "vertex patch" ?
        GeometricMultigrid::Blocks::vertex_patch :
        (blocks == "cell patch" ?
           GeometricMultigrid::Blocks::cell_patch :
           (blocks == "large patch" ? GeometricMultigrid::Blocks::large_patch :
                                      GeometricMultigrid::Blocks::point));
    gmg_data.patch_levels = prm.get_integer("Multigrid patch levels");
    prm.leave_subsection();
  }



  namespace
  {
    const char *singular_message =
      "Linear solver: the direct solver found the system singular. Part of "
      "the body is not held against rigid motion (a support missing, or a "
      "roller alone where a fixed point is needed), or a cell holds too "
      "little material (Ghost penalty/Enable = true stabilises such cells).";

    /** ||A x - b|| / ||b||. */
    double
    relative_residual(const TrilinosWrappers::SparseMatrix &A,
                      const TrilinosWrappers::MPI::Vector  &x,
                      const TrilinosWrappers::MPI::Vector  &b)
    {
      TrilinosWrappers::MPI::Vector r(b);
      A.vmult(r, x);
      r -= b;
      return r.l2_norm() / b.l2_norm();
    }
  } // namespace



  namespace
  {
    std::uint64_t
    matrix_structure(const TrilinosWrappers::SparseMatrix &matrix);
  }



  LinearSolver::Report
  LinearSolver::solve_unchanged(const TrilinosWrappers::SparseMatrix &matrix,
                                TrilinosWrappers::MPI::Vector        &solution,
                                const TrilinosWrappers::MPI::Vector  &rhs,
                                const DoFHandler<2> &dof_handler,
                                const bool           symmetric) const
  {
    unchanged_matrix = true;
    try
      {
        const Report report =
          solve(matrix, solution, rhs, dof_handler, symmetric);
        unchanged_matrix = false;
        return report;
      }
    catch (...)
      {
        unchanged_matrix = false;
        throw;
      }
  }



  LinearSolver::Report
  LinearSolver::solve_direct(const TrilinosWrappers::SparseMatrix &matrix,
                             TrilinosWrappers::MPI::Vector        &solution,
                             const TrilinosWrappers::MPI::Vector  &rhs,
                             const bool                            symmetric,
                             const double                          enough) const
  {
    Report                  report;
    const double            rhs_norm  = rhs.l2_norm();
    const Epetra_CrsMatrix &A         = matrix.trilinos_matrix();
    const std::uint64_t     structure = matrix_structure(matrix);
    // The ordering and symbolic analysis of the last factorisation serve a
    // matrix of the same structure (Newton's tangents within a load step):
    // in 2D they cost about as much as the numeric factorisation (0.09 s
    // each at 29 k unknowns, doc/benchmarks.md).
    // Both decisions on every process alike: the factorisations are
    // collective.
    const MPI_Comm comm = matrix.get_mpi_communicator();
    const bool     same_structure =
      direct_factors && Utilities::MPI::min((direct_matrix == &A &&
                                             direct_structure == structure &&
                                             direct_symmetric == symmetric) ?
                                              1 :
                                              0,
                                            comm) == 1;
    // The matrix of the last factorisation, unchanged (solve_unchanged()):
    // its factors serve.
    if (same_structure && unchanged_matrix)
      report.method = direct_method;
    else if (same_structure &&
             Utilities::MPI::min(direct_factors->refactorize(A) ==
                                     DirectSolver::Status::success ?
                                   1 :
                                   0,
                                 comm) == 1)
      report.method = direct_method;
    DirectSolver::Status mumps = DirectSolver::Status::unavailable;
    DirectSolver::Status klu   = DirectSolver::Status::unavailable;
    if (report.method.empty())
      {
        // MUMPS is the fastest direct solver in Debian's Trilinos; KLU
        // where it is missing or fails for want of memory or otherwise, with
        // the reason in the step table. A system that MUMPS finds singular
        // (null pivots) is singular: KLU would factorise it with a pivot of
        // round-off and return displacements without meaning.
        direct_factors   = std::make_unique<DirectSolver>();
        direct_matrix    = &A;
        direct_structure = structure;
        direct_symmetric = symmetric;
        mumps            = direct_factors->factorize(A, "MUMPS", symmetric);
        if (mumps == DirectSolver::Status::success)
          report.method = "direct (MUMPS)";
        else if (mumps != DirectSolver::Status::singular)
          {
            klu = direct_factors->factorize(A, "Amesos_Klu", symmetric);
            if (klu == DirectSolver::Status::success)
              report.method = mumps == DirectSolver::Status::unavailable ?
                                "direct (KLU)" :
                              mumps == DirectSolver::Status::out_of_memory ?
                                "direct (KLU, MUMPS out of memory)" :
                                "direct (KLU, MUMPS failed)";
          }
        direct_method = report.method;
      }
    DirectSolver     &direct = *direct_factors;
    const std::string size   = std::to_string(matrix.m());
    AssertThrow(
      !report.method.empty(),
      ExcMessage(
        mumps == DirectSolver::Status::out_of_memory ?
          "Linear solver: the direct solver ran out of memory factorising "
          "the system of " +
            size +
            " unknowns (MUMPS, even with 17 times the workspace it "
            "estimated, and KLU). Use CG (Linear solver/Method = cg amg or "
            "cg gmg, a fraction of the memory), a coarser grid, or more "
            "processes or memory." :
        (mumps == DirectSolver::Status::singular ||
         klu == DirectSolver::Status::singular) ?
          std::string(singular_message) :
          "Linear solver: the direct solver (MUMPS, KLU) could not "
          "factorise the system of " +
            size +
            " unknowns, although it found it neither singular nor too "
            "large for the memory. Try Linear solver/Method = cg amg."));
    AssertThrow(direct.solve(solution, rhs), ExcMessage(singular_message));

    // Iterative refinement with the same factors: a back-substitution
    // costs little next to the factorisation, and it brings the residual
    // to round-off even for the ill-conditioned systems of a thin IBM band.
    TrilinosWrappers::MPI::Vector residual(rhs), correction(rhs);
    double                        previous = std::numeric_limits<double>::max();
    for (unsigned int k = 0; k < max_refinements; ++k)
      {
        matrix.vmult(residual, solution);
        residual.sadd(-1., 1., rhs);
        const double norm = residual.l2_norm();
        if (norm >= 0.5 * previous ||
            norm <= std::max(enough, 1e-15 * rhs_norm))
          break;
        previous = norm;
        AssertThrow(direct.solve(correction, residual),
                    ExcMessage(singular_message));
        solution += correction;
        ++report.refinement_steps;
      }

    report.relative_residual = relative_residual(matrix, solution, rhs);
    return report;
  }



  double
  LinearSolver::estimate_condition_number(
    const TrilinosWrappers::SparseMatrix &matrix,
    const TrilinosWrappers::MPI::Vector  &rhs) const
  {
    double                                  estimate = 1.;
    SolverControl                           control(condition_iterations,
                          1e-14 * rhs.l2_norm(),
                          false,
                          false);
    SolverCG<TrilinosWrappers::MPI::Vector> cg(control);
    cg.connect_condition_number_slot(
      [&estimate](const double c) { estimate = c; }, false);
    TrilinosWrappers::MPI::Vector x(rhs);
    x = 0;
    try
      {
        cg.solve(matrix, x, rhs, PreconditionIdentity());
      }
    catch (const SolverControl::NoConvergence &)
      {
        // The estimate of the iterations done is still an estimate.
      }
    return estimate;
  }



  namespace
  {
    /** A fingerprint of the structure of the locally owned rows of
     * @p matrix: its sparsity pattern and which rows are decoupled (no
     * nonzero entry off the diagonal: the constrained DoFs, those of cells
     * without material). Entries that happen to vanish in a coupled row
     * (symmetric point layouts) do not count. FNV-1a. */
    std::uint64_t
    matrix_structure(const TrilinosWrappers::SparseMatrix &matrix)
    {
      const Epetra_CrsMatrix &A    = matrix.trilinos_matrix();
      std::uint64_t           hash = 1469598103934665603ull;
      const auto              mix  = [&hash](const std::uint64_t v) {
        hash ^= v;
        hash *= 1099511628211ull;
      };
      for (int row = 0; row < A.NumMyRows(); ++row)
        {
          int     n;
          double *values;
          int    *columns;
          A.ExtractMyRowView(row, n, values, columns);
          for (int k = 0; k < n; ++k)
            mix(columns[k]);
          mix(couples_off_diagonal(A, row) ? 0xc0ull : 0xdeull);
        }
      return hash;
    }
  } // namespace



  bool
  LinearSolver::geometric_multigrid(const DoFHandler<2> &dof_handler) const
  {
    if (method == Method::cg_gmg)
      return true;
    if (method != Method::automatic)
      return false;
    // A grid that coarsens at least once gets the geometric multigrid
    // (iterations independent of h and of the cut fractions); one with odd
    // cell counts, which the geometric levels cannot halve, ML.
    return GeometricMultigrid::n_coarse_levels(dof_handler, gmg_data) > 0;
  }



  void
  LinearSolver::prepare_preconditioner(
    const TrilinosWrappers::SparseMatrix &matrix,
    const DoFHandler<2>                  &dof_handler,
    const bool                            geometric,
    Report                               &report) const
  {
    // The hierarchy can serve again if it was built on this matrix object
    // (ML keeps a pointer to it) with the same nonzero structure on every
    // process: then only the values changed, as between load steps and
    // Newton iterations while the same cells are active.
    const std::uint64_t structure =
      reuse == Reuse::none ? 0 : matrix_structure(matrix);
    const bool same =
      (geometric ? bool(gmg) : bool(amg)) && reuse != Reuse::none &&
      Utilities::MPI::min((amg_matrix == &matrix.trilinos_matrix() &&
                           amg_structure == structure) ?
                            1 :
                            0,
                          dof_handler.get_communicator()) == 1;
    if (same)
      {
        if (geometric)
          {
            // The same matrix object: the finest level smooths with its
            // current values either way.
            if (reuse == Reuse::aggregates)
              gmg->reinit(matrix);
            else
              gmg->set_fine_matrix(matrix);
          }
        else if (reuse == Reuse::aggregates)
          amg->reinit();
        report.reused_preconditioner = true;
        return;
      }

    reset_preconditioner();
    if (geometric)
      {
        gmg = std::make_unique<GeometricMultigrid>();
        gmg->initialize(matrix, dof_handler, gmg_data);
        amg_matrix    = &matrix.trilinos_matrix();
        amg_structure = structure;
        return;
      }

    TrilinosWrappers::PreconditionAMG::AdditionalData data;
    data.elliptic              = true;
    data.higher_order_elements = false;
    data.smoother_sweeps       = 2;
    data.aggregation_threshold = 0.02;
    DoFTools::extract_constant_modes(dof_handler,
                                     ComponentMask(2, true),
                                     data.constant_modes);
    amg = std::make_unique<TrilinosWrappers::PreconditionAMG>();
    amg->initialize(matrix, data);
    amg_matrix    = &matrix.trilinos_matrix();
    amg_structure = structure;
  }



  double
  LinearSolver::relative_tolerance(const DoFHandler<2> &dof_handler) const
  {
    if (tolerance > 0)
      return tolerance;
    // Automatic: at a fixed tolerance the errors of a scene move away from
    // those of an exact solve about 3 times further per halving of h
    // (measured down to h/L = 1/384, doc/benchmarks.md), at 1e-8 by at
    // most 8e-7 of themselves there; finer grids get a tolerance that
    // falls 4 times per halving.
    const auto &tria = dof_handler.get_triangulation();
    if (tria.n_global_levels() != cached_levels)
      {
        // A uniform grid of equal coarse cells refined globally: the
        // diameters from the coarse cells, which every process holds.
        cached_levels  = tria.n_global_levels();
        Point<2> lower = tria.begin(0)->vertex(0), upper = lower;
        for (const auto &cell : tria.cell_iterators_on_level(0))
          for (const unsigned int v : cell->vertex_indices())
            for (unsigned int d = 0; d < 2; ++d)
              {
                lower[d] = std::min(lower[d], cell->vertex(v)[d]);
                upper[d] = std::max(upper[d], cell->vertex(v)[d]);
              }
        const double h =
          tria.begin(0)->diameter() / std::pow(2., cached_levels - 1.);
        const double ratio  = h / lower.distance(upper);
        automatic_tolerance = std::min(1e-8, 1.5e-3 * ratio * ratio);
      }
    return automatic_tolerance;
  }



  namespace
  {
    /** Why CG with a multigrid did not give a solution. */
    struct IterativeFailure
    {
      std::string what;
    };
  } // namespace



  LinearSolver::Report
  LinearSolver::solve_iterative(const TrilinosWrappers::SparseMatrix &matrix,
                                TrilinosWrappers::MPI::Vector        &solution,
                                const TrilinosWrappers::MPI::Vector  &rhs,
                                const DoFHandler<2> &dof_handler,
                                const bool           symmetric,
                                const bool           geometric) const
  {
    Report report;
    // CG for symmetric systems; GMRES with the same multigrid for the
    // unsymmetric tangents of finite strain (F-bar, follower pressure) and
    // of non-associated flow.
    const auto iterate = [&](SolverControl &control) {
      if (symmetric)
        {
          SolverCG<TrilinosWrappers::MPI::Vector> cg(control);
          if (gmg)
            cg.solve(matrix, solution, rhs, *gmg);
          else
            cg.solve(matrix, solution, rhs, *amg);
        }
      else
        {
          // Right preconditioning: the stopping test sees the true
          // residual (left-preconditioned GMRES stopped with |b - A x| 18
          // times |b| on the finite-strain cantilever at h = 0.375).
          SolverGMRES<TrilinosWrappers::MPI::Vector> gmres(
            control,
            SolverGMRES<TrilinosWrappers::MPI::Vector>::AdditionalData(
              100, /*right_preconditioning=*/true));
          if (gmg)
            gmres.solve(matrix, solution, rhs, *gmg);
          else
            gmres.solve(matrix, solution, rhs, *amg);
        }
    };
    const std::string name = geometric ? "GMG" : "AMG";
    // A preconditioner that cannot be set up or applied (a Trilinos error:
    // a factorisation that fails, an operator ML cannot coarsen) is a
    // failure of this method, not of the run.
    // The decision is taken together: a factorisation's error may be
    // reported on one process only.
    const auto prepare = [&]() {
      bool failed = false;
      try
        {
          prepare_preconditioner(matrix, dof_handler, geometric, report);
        }
      catch (const ExceptionBase &)
        {
          failed = true;
        }
      if (Utilities::MPI::max(failed ? 1 : 0, dof_handler.get_communicator()) ==
          1)
        {
          reset_preconditioner();
          throw IterativeFailure{"the " + name + " set-up failed"};
        }
    };
    const double rhs_norm = rhs.l2_norm();
    prepare();

    // The previous solution is the first guess when it leaves a smaller
    // residual than zero does (consecutive load steps of similar
    // systems); the stopping test stays relative to ||b||.
    solution = 0;
    if (last_solution.size() == solution.size() &&
        last_solution.locally_owned_elements() ==
          solution.locally_owned_elements())
      {
        TrilinosWrappers::MPI::Vector residual(rhs);
        matrix.vmult(residual, last_solution);
        residual.sadd(-1., 1., rhs);
        if (residual.l2_norm() < rhs_norm)
          solution = last_solution;
      }

    // In automatic mode CG gets a few hundred iterations: a system that
    // needs more (a thin IBM band holding both components in cut cells:
    // 1607 iterations on scene 4b at h = 1/32) is factorised faster.
    const unsigned int limit  = method == Method::automatic ?
                                  std::min(max_iterations, 300u) :
                                  max_iterations;
    const double       target = relative_tolerance(dof_handler) * rhs_norm;
    // A reused hierarchy gets twice the iterations of the solve it was
    // built for; if that is not enough, a new one continues.
    unsigned int iterations = 0;
    if (report.reused_preconditioner)
      {
        SolverControl control(std::min(limit, 2 * fresh_iterations + 10),
                              target);
        bool          replace = false;
        try
          {
            iterate(control);
            report.iterations = control.last_step();
          }
        catch (const SolverControl::NoConvergence &)
          {
            iterations = control.last_step();
            replace    = true;
          }
        catch (const ExceptionBase &)
          {
            // The kept hierarchy failed to apply: a new one from zero.
            iterations = control.last_step();
            replace    = true;
            solution   = 0;
          }
        if (replace)
          {
            reset_preconditioner();
            report.reused_preconditioner = false;
            prepare();
          }
      }
    if (!report.reused_preconditioner)
      {
        SolverControl control(limit - std::min(limit - 1, iterations), target);
        try
          {
            iterate(control);
          }
        catch (const SolverControl::NoConvergence &e)
          {
            reset_preconditioner();
            last_solution.clear();
            throw IterativeFailure{"CG + " + name + " did not converge in " +
                                   std::to_string(iterations + e.last_step) +
                                   " iterations (residual " +
                                   std::to_string(e.last_residual / rhs_norm) +
                                   " of the right-hand side)"};
          }
        catch (const ExceptionBase &)
          {
            reset_preconditioner();
            last_solution.clear();
            throw IterativeFailure{"the " + name + " V-cycle failed"};
          }
        report.iterations = iterations + control.last_step();
        fresh_iterations  = control.last_step();
      }
    // A hierarchy that has become much slower than when it was new is
    // rebuilt for the next solve.
    else if (report.iterations > (3 * fresh_iterations) / 2 + 2)
      reset_preconditioner();

    report.method =
      std::string(symmetric ? "cg" : "gmres") + (geometric ? " gmg" : " amg");
    last_solution            = solution;
    report.relative_residual = relative_residual(matrix, solution, rhs);
    return report;
  }



  unsigned int
  LinearSolver::iteration_limit(const types::global_dof_index n) const
  {
    // A 2D factorisation costs about n^1.5, a CG iteration about n: the
    // number of iterations a factorisation is worth grows as sqrt(n).
    // Not below half the limit: at a few thousand unknowns MUMPS' fixed
    // costs weigh (AMG was 1.2x faster than MUMPS at 1250 unknowns with
    // about 8 iterations, 'Automatic threshold').
    const double scaled =
      automatic_iteration_limit * std::sqrt(static_cast<double>(n) / 1e5);
    return static_cast<unsigned int>(
      std::max(scaled, static_cast<double>(automatic_iteration_limit) / 2));
  }



  void
  LinearSolver::drop_reused_state() const
  {
    reset_preconditioner();
    amg_matrix       = nullptr;
    amg_structure    = 0;
    fresh_iterations = 0;
    direct_factors.reset();
    unchanged_matrix = false;
    direct_matrix    = nullptr;
    direct_structure = 0;
    direct_method.clear();
    gmg_failed           = false;
    gmg_failed_matrix    = nullptr;
    gmg_failed_structure = 0;
    last_solution.clear();
  }



  LinearSolver::Report
  LinearSolver::solve(const TrilinosWrappers::SparseMatrix &matrix,
                      TrilinosWrappers::MPI::Vector        &solution,
                      const TrilinosWrappers::MPI::Vector  &rhs,
                      const DoFHandler<2>                  &dof_handler,
                      const bool                            symmetric,
                      const double                          enough) const
  {
    if (rhs.l2_norm() == 0.)
      {
        Report report;
        solution      = 0;
        report.method = "none (zero right-hand side)";
        return report;
      }

    const bool use_direct =
      method == Method::direct ||
      (method == Method::automatic &&
       (matrix.m() <= automatic_threshold || cg_failed || cg_slow));
    if (use_direct)
      {
        Report report = solve_direct(matrix, solution, rhs, symmetric, enough);
        if (cg_slow && !cg_slow_said && !cg_failed)
          {
            report.method += ", cg slow";
            cg_slow_said = true;
          }
        return report;
      }

    bool geometric = geometric_multigrid(dof_handler);
    // Automatic mode: a matrix of the structure on which the geometric
    // multigrid failed goes to ML directly (the same decoupled rows make
    // the same coarse operators), until the structure changes.
    if (geometric && gmg_failed)
      geometric =
        Utilities::MPI::min((gmg_failed_matrix == &matrix.trilinos_matrix() &&
                             gmg_failed_structure == matrix_structure(matrix)) ?
                              0 :
                              1,
                            dof_handler.get_communicator()) == 1;
    const bool fell_back = method == Method::automatic && gmg_failed &&
                           !geometric && geometric_multigrid(dof_handler);
    if (geometric)
      gmg_failed = false;

    try
      {
        Report report = solve_iterative(
          matrix, solution, rhs, dof_handler, symmetric, geometric);
        if (fell_back)
          report.method += ", gmg failed";
        // A factorisation is the cheaper solve of such tangents (see the
        // parameter); the same on every process, as the count is.
        if (method == Method::automatic && automatic_iteration_limit > 0 &&
            report.iterations > iteration_limit(matrix.m()) &&
            matrix.m() <= 1000000)
          cg_slow = true;
        return report;
      }
    catch (const IterativeFailure &failure)
      {
        AssertThrow(method == Method::automatic,
                    ExcMessage("Linear solver: " + failure.what +
                               ". The system may be ill-conditioned: try "
                               "Method = " +
                               (geometric ? "cg amg or " : "") + "direct."));
        if (geometric)
          {
            // ML next, for this matrix and every matrix of its structure.
            gmg_failed           = true;
            gmg_failed_matrix    = &matrix.trilinos_matrix();
            gmg_failed_structure = matrix_structure(matrix);
            return solve(matrix, solution, rhs, dof_handler, symmetric, enough);
          }
      }
    // Factorise, now and in the following load steps.
    cg_failed     = true;
    Report direct = solve_direct(matrix, solution, rhs, symmetric, enough);
    direct.method += ", cg failed";
    return direct;
  }
} // namespace bsmpm
