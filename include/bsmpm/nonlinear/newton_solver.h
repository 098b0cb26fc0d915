#ifndef bsmpm_newton_solver_h
#define bsmpm_newton_solver_h

#include <deal.II/base/parameter_handler.h>

#include <functional>
#include <ostream>
#include <string>
#include <vector>

namespace bsmpm
{
  using namespace dealii;

  /**
   * Newton-Raphson iterations of one load step, and the rules for cutting a
   * step that does not converge (section "Nonlinear solver"). The problem is
   * given as two functions, so that this class knows nothing of how the
   * system is made (doc/newton.md):
   *
   * - residual(): assembles the tangent and the residual R at the current
   *   increment and returns |R|;
   * - correct(): solves K_T dx = R, adds dx to the increment and returns
   *   (|dx| / |x|, linear iterations);
   * - step_back(alpha): moves the increment by -alpha dx, dx the last
   *   correction (alpha may be negative);
   * - slope() (optional): dx . R at the current increment, R as the last
   *   residual() assembled it.
   *
   * Where many points change between elastic and plastic within one
   * iteration, the full Newton step can overshoot: it is shortened by a
   * line search of at most 'Line search steps' evaluations. With slope()
   * the search is on the potential whose gradient is -R (small strain,
   * associated flow: the incremental problem minimises a convex potential):
   * g(a) = dx . R(x + a dx) is minus the derivative of the potential along
   * dx and falls with a, and a step is accepted where |g(a)| <= g(0) / 2
   * (the full step where g(1) > 0); its zero is found by regula falsi. A
   * decrease of |R| is no test of a step: near a limit load |R| along dx
   * can fall where the potential has long risen again, and such steps
   * stall the iterations (doc/newton.md). Without slope(), or where
   * g(0) <= 0 (an unsymmetric or indefinite tangent), a correction that
   * does not lower |R| is halved.
   */
  class NewtonSolver
  {
  public:
    struct Iteration
    {
      /** |R| / |R(0)|. */
      double relative_residual = 0;
      /** |dx| / |x| of the correction that followed (0 for the last). */
      double       relative_correction = 0;
      unsigned int linear_iterations   = 0;
      /** Length of the correction taken (1 unless the line search
       * shortened it). */
      double step_length = 1;
    };

    struct Result
    {
      bool                   converged = false;
      std::vector<Iteration> iterations;
      /** Why it did not converge. */
      std::string failure;
      /** Whether it stopped at a residual that is not finite (a singular
       * system, not a mechanism). */
      bool not_finite = false;
    };

    static void
    declare_parameters(ParameterHandler &prm);
    void
    parse_parameters(ParameterHandler &prm);

    /**
     * Iterates from the increment the caller has set. @p reference: the
     * residual of a zero increment, |R(0)|, the scale of the tolerance (a
     * good starting increment must not make it stricter).
     *
     * @p positive_tangent: the tangent is symmetric positive
     * (semi-)definite (small strain, associated flow), so every exact
     * correction descends, slope() > 0. A correction that does not is the
     * linear solve's round-off in the tangent's nearly free modes (a
     * perfectly plastic mechanism); once |R| is within a hundred times the
     * tolerance such a correction is undone and the increment counts as
     * converged, instead of halving noise (doc/newton.md).
     *
     * @p looser_tolerance: converged already at this fraction of
     * @p reference if it is above 'Residual tolerance' (the solves between
     * two updates of contact multipliers, whose result the update moves
     * anyway).
     */
    Result
    solve(const double                                            reference,
          const std::function<double()>                          &residual,
          const std::function<std::pair<double, unsigned int>()> &correct,
          const std::function<void(const double)>                &step_back,
          const std::function<double()>                          &slope = {},
          const double initial_norm                                     = -1,
          const bool   positive_tangent                                 = false,
          const double looser_tolerance = 0) const;

    /**
     * After the iterations @p result of the load increment @p delta from
     * load factor @p lambda in load step @p step failed, with @p cuts
     * halvings of the increment so far: writes why and the residuals of
     * the iterations to @p log (if not null), and throws if the increment
     * may not be halved again.
     */
    void
    report_failure(const Result      &result,
                   const unsigned int step,
                   const double       lambda,
                   const double       delta,
                   const unsigned int cuts,
                   std::ostream      *log,
                   const std::string &hint = "") const;

    /** Writes why the iterations @p result of the load increment @p delta
     * from @p lambda failed, with their residuals, to @p log (if not
     * null). */
    void
    log_failure(const Result &result,
                const double  lambda,
                const double  delta,
                std::ostream *log) const;

    /** Where the iterations of a load increment start (after the first
     * converged one; the first starts from zero). */
    enum class Predictor
    {
      /** tangent in small strain, last_increment in finite strain. */
      automatic,
      /** The last converged increment scaled to this one. */
      last_increment,
      /** Zero, with the tangent of the last converged state: the points
       * that yielded in the last increment load plastically (a forward
       * Euler step along the tangent). */
      tangent
    };

    Predictor
    predictor() const
    {
      return start;
    }

    /** Converged when |R| is below this fraction of the increment's
     * scale (Nonlinear solver/Residual tolerance). */
    double
    residual_tolerance() const
    {
      return tolerance;
    }

    /** How many times a load increment may be halved. */
    unsigned int
    max_step_cuts() const
    {
      return max_cuts;
    }

    /** The residual, relative to the largest internal force of the run,
     * below which the best iterate of a last cut that did not converge is
     * accepted (Nonlinear solver/Stall tolerance; 0: never). */
    double
    stall_tolerance() const
    {
      return accepted_stall;
    }

    /** 'Nonlinear solver/Check tangent'. */
    bool
    checks_tangent() const
    {
      return check_tangent;
    }

  private:
    bool         check_tangent  = false;
    unsigned int max_iterations = 20;
    double       tolerance      = 1e-9;
    unsigned int max_cuts       = 6;
    double       accepted_stall = 1e-2;
    unsigned int line_search    = 5;
    Predictor    start          = Predictor::automatic;
  };
} // namespace bsmpm

#endif
