#include <bsmpm/solver/increment_solver.h>

#include <cmath>
#include <utility>

namespace bsmpm
{
  IncrementSolver::IncrementSolver(const Parts &parts, TimerOutput &timer)
    : parts(parts)
    , timer(timer)
  {}



  LinearSolver::Report
  IncrementSolver::solve_linear(
    const unsigned int                          step,
    LinearAlgebra::distributed::Vector<double> &increment) const
  {
    TimerOutput::Scope    t(timer, "solve");
    const BackgroundGrid &grid     = parts.grid;
    SystemAssembly       &assembly = parts.assembly;
    assembly.check_loads_finite(step);
    TrilinosWrappers::MPI::Vector solution(grid.locally_owned_dofs(),
                                           grid.mpi_communicator());
    const auto report = parts.linear_solver.solve(assembly.matrix(),
                                                  solution,
                                                  assembly.rhs(),
                                                  grid.dof_handler());
    assembly.constraints().distribute(solution);
    AssertThrow(std::isfinite(solution.l2_norm()),
                ExcMessage("The linear solver returned a displacement that is "
                           "not finite in load step " +
                           std::to_string(step) +
                           " although the loads are finite: the system is "
                           "singular (a body that is not held against rigid "
                           "motion, or cells without stabilisation: Ghost "
                           "penalty/Enable)."));

    for (const auto i : grid.locally_owned_dofs())
      increment(i) = solution(i);
    increment.update_ghost_values();
    return report;
  }



  NewtonSolver::Result
  IncrementSolver::solve_newton(
    const double                                      delta,
    const LinearAlgebra::distributed::Vector<double> *prescribed,
    LinearAlgebra::distributed::Vector<double>       &increment,
    LinearSolves                                     &solves)
  {
    const BackgroundGrid     &grid     = parts.grid;
    SystemAssembly           &assembly = parts.assembly;
    const ConstitutiveUpdate &update   = *parts.constitutive_update;
    const MaterialPoints     &points   = parts.points;

    TrilinosWrappers::MPI::Vector last_correction;
    // Start from the last converged increment scaled to this one: points
    // that yielded then are evaluated on the plastic branch from the first
    // iteration, where a start from zero would see them on the yield surface
    // with the elastic tangent and overshoot.
    // Zeroing a ghosted vector leaves it without ghost values: import the
    // zeros, or the cells next to another process read ghosts it does not
    // have.
    increment = 0;
    increment.update_ghost_values();
    const double reference =
      assembly.newton_system(update, points, increment, prescribed);
    // |R| of the system the assembly holds, that of the start.
    double start_norm = reference;
    if (previous_delta > 0 && previous_increment.size() == increment.size())
      {
        increment.add(delta / previous_delta, previous_increment);
        assembly.constraints().set_zero(increment);
        increment.update_ghost_values();
        // Where the last increment is a poor guess (finite rotations, a
        // load path that turns), start from zero after all. The residual
        // weighs the stiff modes most, so a guess that is closer in
        // displacement may still leave a larger one: only one ten times
        // larger than that of zero is dropped (cantilever in finite
        // strain: 26 times in step 3).
        start_norm =
          assembly.newton_system(update, points, increment, prescribed);
        if (!(start_norm < 10 * reference))
          {
            increment = 0;
            increment.update_ghost_values();
            start_norm = -1; // the held system is not that of zero
          }
      }
    return parts.newton.solve(
      reference,
      [&]() {
        return assembly.newton_system(update, points, increment, prescribed);
      },
      [&]() {
        TimerOutput::Scope            t(timer, "solve");
        TrilinosWrappers::MPI::Vector correction(grid.locally_owned_dofs(),
                                                 grid.mpi_communicator());
        // A pressure that follows the boundary within the step (finite
        // strain) has an unsymmetric load stiffness.
        const bool symmetric =
          update.symmetric_tangent() &&
          !(update.kinematics() ==
              ConstitutiveUpdate::Kinematics::finite_strain &&
            parts.boundary_curves.has_loads());
        const auto report = parts.linear_solver.solve(assembly.tangent(),
                                                      correction,
                                                      assembly.residual(),
                                                      grid.dof_handler(),
                                                      symmetric);
        assembly.constraints().distribute(correction);
        for (const auto i : grid.locally_owned_dofs())
          increment(i) += correction(i);
        increment.update_ghost_values();
        ++solves.n_solves;
        solves.method = report.method;
        solves.iterations += report.iterations;
        solves.refinement_steps += report.refinement_steps;
        solves.relative_residual = report.relative_residual;
        const double size        = increment.l2_norm();
        last_correction          = correction;
        return std::make_pair(size > 0 ? correction.l2_norm() / size : 0.,
                              report.iterations);
      },
      [&](const double alpha) {
        // From x + a dx to x + (a - alpha) dx.
        for (const auto i : grid.locally_owned_dofs())
          increment(i) -= alpha * last_correction(i);
        increment.update_ghost_values();
      },
      // dx . R(x): the slope of the potential along dx, for the line search.
      [&]() { return last_correction * assembly.residual(); },
      start_norm);
  }



  void
  IncrementSolver::accept(
    const LinearAlgebra::distributed::Vector<double> &increment,
    const double                                      delta)
  {
    previous_increment = increment;
    previous_delta     = delta;
  }
} // namespace bsmpm
