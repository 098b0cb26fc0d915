#include <bsmpm/nonlinear/newton_solver.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

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
                      "increment counts as failed and is cut. More where "
                      "Newton converges slowly but steadily (perfectly "
                      "plastic plateaus).");
    prm.declare_entry("Residual tolerance",
                      "1e-9",
                      Patterns::Double(0, 1),
                      "Converged when the residual has fallen below this "
                      "fraction of its value for a zero increment (the "
                      "out-of-balance force of the load increment). The "
                      "default lies above round-off; a looser one saves "
                      "iterations on perfectly plastic plateaus and moves the "
                      "results with it (doc/newton.md).");
    prm.declare_entry("Maximum step cuts",
                      "6",
                      Patterns::Integer(0, 30),
                      "How many times a load increment that does not converge "
                      "may be halved before the run stops (or, under a "
                      "prescribed load, reports its limit load). More load "
                      "steps are often the better remedy than more cuts.");
    prm.declare_entry(
      "Stall tolerance",
      "1e-2",
      Patterns::Double(0, 1),
      "When the iterations of the last allowed cut still do not converge, "
      "the best iterate of that smallest increment is accepted (and the "
      "step table says so) if its residual is below this fraction of the "
      "largest internal force of the run; the next step's residual "
      "carries what it leaves. Perfectly plastic points and contact "
      "points that switch at the solution make Newton cycle there "
      "(doc/newton.md). 0: never accept.");
    prm.declare_entry("Line search steps",
                      "5",
                      Patterns::Integer(0, 30),
                      "How many times a Newton correction that does not lower "
                      "the residual may be halved (0: full steps). The line "
                      "search keeps Newton from overshooting where points "
                      "unload; keep it on.");
    prm.declare_entry(
      "Check tangent",
      "false",
      Patterns::Bool(),
      "A check for developers: at every Newton iteration, compares the "
      "whole tangent times the correction dx with central differences of "
      "the residual along dx (two more assemblies per iteration); "
      "summary.json records the largest relative difference as "
      "newton_tangent_error (doc/newton.md). Not with force-controlled "
      "rigid bodies.");
    prm.declare_entry(
      "Predictor",
      "automatic",
      Patterns::Selection("automatic|tangent|last increment"),
      "Where the Newton iterations of a load increment start (the first "
      "increment of a run starts from zero). 'tangent': from zero, the first "
      "correction taken with the tangent of the last converged state (the "
      "points that yielded in the last increment load plastically): a forward "
      "Euler step. 'last increment': the last converged increment scaled to "
      "this one (zero where that leaves a residual ten times that of zero). "
      "'automatic' (the default): tangent in small strain, last increment in "
      "finite strain (where the last increment carries the rotations). Change "
      "it only to compare the starts (doc/newton.md).");
    prm.leave_subsection();
  }



  void
  NewtonSolver::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Nonlinear solver");
    max_iterations              = prm.get_integer("Maximum iterations");
    tolerance                   = prm.get_double("Residual tolerance");
    max_cuts                    = prm.get_integer("Maximum step cuts");
    accepted_stall              = prm.get_double("Stall tolerance");
    line_search                 = prm.get_integer("Line search steps");
    check_tangent               = prm.get_bool("Check tangent");
    const std::string predictor = prm.get("Predictor");
    start                       = predictor == "tangent" ? Predictor::tangent :
                                  predictor == "last increment" ? Predictor::last_increment :
                                                                  Predictor::automatic;
    prm.leave_subsection();
  }



  NewtonSolver::Result
  NewtonSolver::solve(
    const double                                            reference,
    const std::function<double()>                          &residual,
    const std::function<std::pair<double, unsigned int>()> &correct,
    const std::function<void(const double)>                &step_back,
    const std::function<double()>                          &slope,
    const double                                            initial_norm,
    const bool                                              positive_tangent,
    const double looser_tolerance) const
  {
    Result       result;
    const double initial   = reference;
    const double tolerance = std::max(this->tolerance, looser_tolerance);
    // The caller may have assembled the system at the start already.
    double norm = initial_norm >= 0 ? initial_norm : residual();
    for (unsigned int k = 0;; ++k)
      {
        Iteration iteration;
        iteration.relative_residual = initial > 0 ? norm / initial : 0.;
        if (!std::isfinite(norm))
          {
            result.iterations.push_back(iteration);
            result.failure    = "the residual is not finite";
            result.not_finite = true;
            return result;
          }
        // Converged, or nothing to do (no load increment and no stress to
        // balance).
        // A residual that stalls within a hundred times the tolerance while
        // the corrections no longer move the increment (ten times the
        // tolerance) is converged: what is left is round-off (a stiff body
        // on a soft one: 1e-11 of the internal force), or a state that
        // switches at the solution (a contact piece whose mean gap sits at
        // zero, a plastic point on its yield surface) at the cost of a
        // force that small.
        const bool stalled =
          k > 0 && norm <= 100 * tolerance * initial &&
          result.iterations.back().relative_correction <= 10 * tolerance;
        if (norm <= tolerance * initial || initial == 0. || stalled)
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
        // g(0) = dx . R(x): positive when dx descends the potential (always
        // for a symmetric positive definite tangent).
        const double g0       = slope ? slope() : 0.;
        const double previous = norm;
        // Round-off: with a positive tangent an exact correction descends
        // (g(0) = R^T K^-1 R > 0). One that does not, close to the
        // tolerance, is the direct solver's error in the nearly free modes
        // of perfectly plastic points: undo it (the held system is still
        // that of x) and stop.
        if (positive_tangent && slope && !(g0 > 0) &&
            norm <= 100 * tolerance * initial)
          {
            step_back(1.);
            iteration.relative_correction = 0;
            iteration.step_length         = 0;
            result.iterations.push_back(iteration);
            result.converged = true;
            return result;
          }
        norm = residual();
        if (g0 > 0 && line_search > 0)
          {
            // Line search on the potential: g(a) = dx . R(x + a dx) is
            // minus its derivative along dx, decreasing in a where the
            // potential is convex. Accept a step where |g| has fallen
            // to half of g(0) (or the full step while g stays positive:
            // the potential still falls there); else the zero of g between
            // the last step with g > 0 and the last with g < 0 by regula
            // falsi (Illinois), kept a tenth of the bracket from its ends.
            double a = 1, g = slope();
            double lo = 0, g_lo = g0, hi = -1, g_hi = 0;
            int    side = 0;
            for (unsigned int l = 0; l < line_search; ++l)
              {
                if (std::isfinite(norm) && std::isfinite(g) &&
                    (std::abs(g) <= 0.5 * g0 || (g > 0 && hi < 0)))
                  break;
                if (std::isfinite(norm) && std::isfinite(g) && g > 0)
                  {
                    lo   = a;
                    g_lo = g;
                    if (side == 1)
                      g_hi /= 2;
                    side = 1;
                  }
                else
                  {
                    hi = a;
                    if (std::isfinite(norm) && std::isfinite(g))
                      {
                        g_hi = g;
                        if (side == -1)
                          g_lo /= 2;
                        side = -1;
                      }
                    else
                      {
                        // Not finite: bisect.
                        g_hi = -g_lo;
                        side = 0;
                      }
                  }
                double next = (lo * g_hi - hi * g_lo) / (g_hi - g_lo);
                next =
                  std::clamp(next, lo + 0.1 * (hi - lo), hi - 0.1 * (hi - lo));
                step_back(a - next);
                a    = next;
                norm = residual();
                g    = slope();
              }
            iteration.step_length = a;
          }
        else
          {
            // Backtracking: halve a correction that does not lower |R|.
            for (unsigned int l = 0; l < line_search && !(norm < previous); ++l)
              {
                iteration.step_length /= 2;
                step_back(iteration.step_length);
                norm = residual();
              }
          }
        result.iterations.push_back(iteration);
      }
  }


  void
  NewtonSolver::log_failure(const Result &result,
                            const double  lambda,
                            const double  delta,
                            std::ostream *log) const
  {
    if (!log)
      return;
    std::ostringstream line;
    line << "       load " << lambda << " + " << delta << ": " << result.failure
         << ", |R_k|/|R_0|" << std::scientific << std::setprecision(1);
    for (const auto &iteration : result.iterations)
      line << ' ' << iteration.relative_residual;
    *log << line.str() << '\n';
  }



  void
  NewtonSolver::report_failure(const Result      &result,
                               const unsigned int step,
                               const double       lambda,
                               const double       delta,
                               const unsigned int cuts,
                               std::ostream      *log,
                               const std::string &hint) const
  {
    log_failure(result, lambda, delta, log);
    // A residual that is not finite however small the increment comes from
    // a singular system, not from the load.
    const std::string cause =
      result.not_finite ?
        ": the system is singular or nearly so (part of the body held by "
        "too few material points, or not held against rigid motion)." :
        ": the body may have reached its limit load, or the increment needs "
        "more cuts (Nonlinear solver/Maximum step cuts).";
    AssertThrow(cuts < max_step_cuts(),
                ExcMessage("Load step " + std::to_string(step) +
                           ": the Newton iterations failed (" + result.failure +
                           ") although the load increment was halved " +
                           std::to_string(cuts) + " times, to " +
                           std::to_string(delta) + " of the load" + cause +
                           " The output of the previous step is intact." +
                           (result.not_finite ? std::string() : hint)));
  }
} // namespace bsmpm
