#include <deal.II/dofs/dof_tools.h>

#include <deal.II/lac/precondition.h>
#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_solver.h>

#include <bsmpm/linear_solver.h>

#include <limits>
#include <memory>

namespace bsmpm
{
  void
  LinearSolver::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Linear solver");
    prm.declare_entry("Method",
                      "automatic",
                      Patterns::Selection("direct|cg amg|automatic"),
                      "direct: sparse LU (MUMPS, else KLU); cg amg: conjugate "
                      "gradients with algebraic multigrid; automatic: direct "
                      "up to 'Automatic threshold' unknowns, cg amg above "
                      "(and direct if CG does not converge).");
    prm.declare_entry("Tolerance",
                      "1e-12",
                      Patterns::Double(1e-15),
                      "cg amg: stop when the residual is below this fraction "
                      "of the right-hand side; at least 1e-15 (below "
                      "round-off CG would iterate on into underflow and a "
                      "division by zero).");
    prm.declare_entry("Maximum iterations",
                      "10000",
                      Patterns::Integer(1),
                      "cg amg: iteration limit.");
    prm.declare_entry("Automatic threshold",
                      "1000",
                      Patterns::Integer(0),
                      "automatic: number of unknowns above which CG + AMG "
                      "replaces the direct solver (measured crossover on the "
                      "plate scene: AMG 1.2x faster at 1250 unknowns, 3.3x "
                      "at 74k, doc/benchmarks.md).");
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
                      "the residual at least.");
    prm.leave_subsection();
  }



  void
  LinearSolver::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Linear solver");
    const std::string m  = prm.get("Method");
    method               = m == "direct" ?
                             Method::direct :
                             (m == "cg amg" ? Method::cg_amg : Method::automatic);
    tolerance            = prm.get_double("Tolerance");
    max_iterations       = prm.get_integer("Maximum iterations");
    automatic_threshold  = prm.get_integer("Automatic threshold");
    max_refinements      = prm.get_integer("Refinement steps");
    estimate_condition   = prm.get_bool("Estimate condition number");
    condition_iterations = prm.get_integer("Condition estimate iterations");
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



  LinearSolver::Report
  LinearSolver::solve_direct(const TrilinosWrappers::SparseMatrix &matrix,
                             TrilinosWrappers::MPI::Vector        &solution,
                             const TrilinosWrappers::MPI::Vector  &rhs) const
  {
    Report        report;
    const double  rhs_norm = rhs.l2_norm();
    SolverControl control(1, 0);
    // MUMPS is the fastest direct solver in Debian's Trilinos; fall back
    // to KLU where it is missing.
    std::unique_ptr<TrilinosWrappers::SolverDirect> solver;
    for (const std::string name : {"Amesos_Mumps", "Amesos_Klu"})
      {
        try
          {
            solver = std::make_unique<TrilinosWrappers::SolverDirect>(
              control,
              TrilinosWrappers::SolverDirect::AdditionalData(false, name));
            solver->initialize(matrix);
            report.method =
              name == "Amesos_Mumps" ? "direct (MUMPS)" : "direct (KLU)";
            break;
          }
        catch (const ExceptionBase &)
          {
            // MUMPS missing, or the factorisation failed: try KLU; if that
            // fails too, the matrix is singular.
            AssertThrow(name != "Amesos_Klu", ExcMessage(singular_message));
          }
      }
    try
      {
        solver->solve(solution, rhs);
      }
    catch (const ExceptionBase &)
      {
        AssertThrow(false, ExcMessage(singular_message));
      }

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
        if (norm >= 0.5 * previous || norm <= 1e-15 * rhs_norm)
          break;
        previous = norm;
        solver->solve(correction, residual);
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



  LinearSolver::Report
  LinearSolver::solve(const TrilinosWrappers::SparseMatrix &matrix,
                      TrilinosWrappers::MPI::Vector        &solution,
                      const TrilinosWrappers::MPI::Vector  &rhs,
                      const DoFHandler<2>                  &dof_handler) const
  {
    Report       report;
    const double rhs_norm = rhs.l2_norm();
    if (rhs_norm == 0.)
      {
        solution      = 0;
        report.method = "none (zero right-hand side)";
        return report;
      }

    const bool use_direct = method == Method::direct ||
                            (method == Method::automatic &&
                             (matrix.m() <= automatic_threshold || cg_failed));

    if (use_direct)
      return solve_direct(matrix, solution, rhs);
    else
      {
        TrilinosWrappers::PreconditionAMG::AdditionalData amg;
        amg.elliptic              = true;
        amg.higher_order_elements = false;
        amg.smoother_sweeps       = 2;
        amg.aggregation_threshold = 0.02;
        DoFTools::extract_constant_modes(dof_handler,
                                         ComponentMask(2, true),
                                         amg.constant_modes);
        TrilinosWrappers::PreconditionAMG preconditioner;
        preconditioner.initialize(matrix, amg);

        // In automatic mode CG gets a few hundred iterations: a system that
        // needs more (a thin IBM band holding both components in cut cells:
        // 1607 iterations on scene 4b at h = 1/32) is factorised faster.
        SolverControl control(method == Method::automatic ?
                                std::min(max_iterations, 300u) :
                                max_iterations,
                              tolerance * rhs_norm);
        SolverCG<TrilinosWrappers::MPI::Vector> cg(control);
        try
          {
            cg.solve(matrix, solution, rhs, preconditioner);
          }
        catch (const SolverControl::NoConvergence &e)
          {
            if (method == Method::automatic)
              {
                // Factorise, now and in the following load steps.
                cg_failed     = true;
                Report direct = solve_direct(matrix, solution, rhs);
                direct.method += ", cg failed";
                return direct;
              }
            AssertThrow(false,
                        ExcMessage(
                          "Linear solver: CG + AMG did not converge in " +
                          std::to_string(e.last_step) +
                          " iterations (residual " +
                          std::to_string(e.last_residual / rhs_norm) +
                          " of the right-hand side). The system may "
                          "be ill-conditioned: try Method = direct."));
          }
        report.method     = "cg amg";
        report.iterations = control.last_step();
      }

    report.relative_residual = relative_residual(matrix, solution, rhs);
    return report;
  }
} // namespace bsmpm
