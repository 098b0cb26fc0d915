#include <bsmpm/newton_solver.h>

#include <cmath>

namespace bsmpm
{
  void
  NewtonSolver::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Nonlinear solver");
    prm.declare_entry("Maximum iterations",
                      "20",
                      Patterns::Integer(1, 1000),
                      "Newton iterations per load increment before the "
                      "increment counts as failed and is cut.");
    prm.declare_entry("Residual tolerance",
                      "1e-9",
                      Patterns::Double(0, 1),
                      "Converged when the residual has fallen below this "
                      "fraction of its value at the start of the "
                      "increment.");
    prm.declare_entry("Maximum step cuts",
                      "6",
                      Patterns::Integer(0, 30),
                      "How many times a load increment that does not "
                      "converge may be halved before the run stops.");
    prm.declare_entry("Line search steps",
                      "5",
                      Patterns::Integer(0, 30),
                      "How many times a Newton correction that does not "
                      "lower the residual may be halved (0: full steps).");
    prm.leave_subsection();
  }



  void
  NewtonSolver::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Nonlinear solver");
    max_iterations = prm.get_integer("Maximum iterations");
    tolerance      = prm.get_double("Residual tolerance");
    max_cuts       = prm.get_integer("Maximum step cuts");
    line_search    = prm.get_integer("Line search steps");
    prm.leave_subsection();
  }



  NewtonSolver::Result
  NewtonSolver::solve(
    const double                                            reference,
    const std::function<double()>                          &residual,
    const std::function<std::pair<double, unsigned int>()> &correct,
    const std::function<void(const double)>                &step_back) const
  {
    Result       result;
    const double initial = reference;
    double       norm    = residual();
    for (unsigned int k = 0;; ++k)
      {
        Iteration iteration;
        iteration.relative_residual = initial > 0 ? norm / initial : 0.;
        if (!std::isfinite(norm))
          {
            result.iterations.push_back(iteration);
            result.failure = "the residual is not finite";
            return result;
          }
        // Converged, or nothing to do (no load increment and no stress to
        // balance).
        if (norm <= tolerance * initial || initial == 0.)
          {
            result.iterations.push_back(iteration);
            result.converged = true;
            return result;
          }
        if (k == max_iterations)
          {
            result.iterations.push_back(iteration);
            result.failure = "no convergence in " +
                             std::to_string(max_iterations) + " iterations";
            return result;
          }
        const auto [correction, linear_iterations] = correct();
        iteration.relative_correction              = correction;
        iteration.linear_iterations                = linear_iterations;
        // Backtracking: halve a correction that does not lower |R|.
        const double previous = norm;
        norm                  = residual();
        for (unsigned int l = 0; l < line_search && !(norm < previous); ++l)
          {
            iteration.step_length /= 2;
            step_back(iteration.step_length);
            norm = residual();
          }
        result.iterations.push_back(iteration);
      }
  }
} // namespace bsmpm
