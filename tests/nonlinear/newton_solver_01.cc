// NewtonSolver (doc/newton.md) on small problems with a known root, given
// as the functions the solver takes: residual R = f - N(x), the correction
// J dx = R, the step back and the slope dx . R.
//
// 1. Three unknowns, N(x) = K x + x^3 (componentwise cube, K symmetric
//    positive definite), f = N(x*): from x = 0 the relative residuals fall
//    quadratically (each about the square of the one before) to x*; the
//    line search shortens the first step only.
// 2. Two unknowns, N(x) = atan(x) + k (x_1 - x_2) (1, -1), the gradient of
//    a convex potential, from x = (3, -2.5), where a full Newton step
//    overshoots to the other side of the root and further (plain Newton
//    diverges from |x| > 1.39 for atan): without a line search the
//    iterations do not converge; the line search on the potential
//    (with slope()) shortens the first steps and ends with full steps and
//    quadratic convergence; without slope() halving the corrections that
//    do not lower |R| converges too.
// 3. A load increment that failed may be halved 'Maximum step cuts' times:
//    report_failure() throws only after that many, and logs the residuals.

#include <deal.II/base/parameter_handler.h>

#include <bsmpm/nonlinear/newton_solver.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <sstream>
#include <string>

// tests.h uses deallog unqualified: the using directive must come first.
using namespace dealii;

#include "../tests.h"

#include "../unit_test.h"

using namespace bsmpm;

namespace
{
  template <int n>
  using SmallVector = std::array<double, n>;
  template <int n>
  using SmallMatrix = std::array<std::array<double, n>, n>;

  template <int n>
  double
  norm(const SmallVector<n> &v)
  {
    double sum = 0;
    for (const double x : v)
      sum += x * x;
    return std::sqrt(sum);
  }

  /** The solution of A x = b by Gaussian elimination without pivoting (A
   * symmetric positive definite here). */
  template <int n>
  SmallVector<n>
  solve(SmallMatrix<n> A, SmallVector<n> b)
  {
    for (int k = 0; k < n; ++k)
      for (int i = k + 1; i < n; ++i)
        {
          const double factor = A[i][k] / A[k][k];
          for (int j = k; j < n; ++j)
            A[i][j] -= factor * A[k][j];
          b[i] -= factor * b[k];
        }
    SmallVector<n> x;
    for (int i = n - 1; i >= 0; --i)
      {
        double sum = b[i];
        for (int j = i + 1; j < n; ++j)
          sum -= A[i][j] * x[j];
        x[i] = sum / A[i][i];
      }
    return x;
  }

  /**
   * A problem R(x) = f - N(x) = 0 with the tangent J = dN/dx, held as
   * NewtonSolver's functions hold the Newton system of a load step: the
   * iterate x, the residual and tangent of the last residual(), the last
   * correction.
   */
  template <int n>
  struct Problem
  {
    std::function<SmallVector<n>(const SmallVector<n> &)> internal_force;
    std::function<SmallMatrix<n>(const SmallVector<n> &)> tangent;
    SmallVector<n>                                        f, x, R, dx;
    SmallMatrix<n>                                        J;

    double
    residual()
    {
      const SmallVector<n> N = internal_force(x);
      for (int i = 0; i < n; ++i)
        R[i] = f[i] - N[i];
      J = tangent(x);
      return norm<n>(R);
    }

    std::pair<double, unsigned int>
    correct()
    {
      dx = solve<n>(J, R);
      for (int i = 0; i < n; ++i)
        x[i] += dx[i];
      return {norm<n>(dx) / norm<n>(x), 0};
    }

    void
    step_back(const double alpha)
    {
      for (int i = 0; i < n; ++i)
        x[i] -= alpha * dx[i];
    }

    double
    slope() const
    {
      double sum = 0;
      for (int i = 0; i < n; ++i)
        sum += dx[i] * R[i];
      return sum;
    }

    /** Newton from @p start: |R(start)| is the scale of the tolerance. */
    NewtonSolver::Result
    solve_from(const NewtonSolver   &newton,
               const SmallVector<n> &start,
               const bool            with_slope)
    {
      x                      = start;
      const double reference = residual();
      return newton.solve(
        reference,
        [this]() { return residual(); },
        [this]() { return correct(); },
        [this](const double alpha) { step_back(alpha); },
        with_slope ? std::function<double()>([this]() { return slope(); }) :
                     std::function<double()>(),
        reference);
    }
  };

  NewtonSolver
  make_newton(const std::string &settings)
  {
    ParameterHandler prm;
    NewtonSolver::declare_parameters(prm);
    prm.parse_input_from_string("subsection Nonlinear solver\n" + settings +
                                "end\n");
    NewtonSolver newton;
    newton.parse_parameters(prm);
    return newton;
  }

  /** The relative residuals and step lengths of @p result; residuals below
   * 1e-13, round-off of the last iteration, printed as 0. */
  std::string
  history(const NewtonSolver::Result &result)
  {
    std::ostringstream text;
    text << std::scientific << std::setprecision(1);
    for (const auto &iteration : result.iterations)
      text << ' ' << filter_roundoff(iteration.relative_residual, 1e-13);
    text << ", step lengths" << std::defaultfloat << std::setprecision(3);
    for (unsigned int k = 0; k + 1 < result.iterations.size(); ++k)
      text << ' ' << result.iterations[k].step_length;
    return text.str();
  }

  /** Whether each relative residual from the second on, down to 1e-13, is
   * at most @p C times the square of the one before (once below 1e-2). */
  bool
  quadratic(const NewtonSolver::Result &result, const double C)
  {
    const auto &it = result.iterations;
    for (unsigned int k = 1; k < it.size(); ++k)
      if (it[k - 1].relative_residual < 1e-2 &&
          it[k].relative_residual > 1e-13 &&
          it[k].relative_residual >
            C * it[k - 1].relative_residual * it[k - 1].relative_residual)
        return false;
    return true;
  }



  void
  test_cubic()
  {
    deallog.push("cubic");
    Problem<3>           p;
    const SmallMatrix<3> K = {
      {{{4., -1., 0.}}, {{-1., 4., -1.}}, {{0., -1., 4.}}}};
    p.internal_force = [&K](const SmallVector<3> &x) {
      SmallVector<3> N;
      for (int i = 0; i < 3; ++i)
        {
          N[i] = x[i] * x[i] * x[i];
          for (int j = 0; j < 3; ++j)
            N[i] += K[i][j] * x[j];
        }
      return N;
    };
    p.tangent = [&K](const SmallVector<3> &x) {
      SmallMatrix<3> J = K;
      for (int i = 0; i < 3; ++i)
        J[i][i] += 3. * x[i] * x[i];
      return J;
    };
    const SmallVector<3> root = {{1., -0.5, 2.}};
    p.f                       = p.internal_force(root);

    const NewtonSolver         newton = make_newton("");
    const NewtonSolver::Result result =
      p.solve_from(newton, {{0., 0., 0.}}, true);
    SmallVector<3> error;
    for (int i = 0; i < 3; ++i)
      error[i] = p.x[i] - root[i];
    deallog << "converged: " << yes_no(result.converged) << " in "
            << result.iterations.size() - 1
            << " iterations, |R|/|R_0|:" << history(result) << std::endl;
    deallog << "quadratic (|R_k+1| <= 10 |R_k|^2 below 1e-2): "
            << yes_no(quadratic(result, 10.)) << ", |x - x*| / |x*| < 1e-12: "
            << yes_no(norm<3>(error) < 1e-12 * norm<3>(root)) << std::endl;
    deallog.pop();
  }



  void
  test_arctangent()
  {
    deallog.push("arctangent");
    const double k = 0.1;
    Problem<2>   p;
    p.internal_force = [k](const SmallVector<2> &x) {
      return SmallVector<2>{{std::atan(x[0]) + k * (x[0] - x[1]),
                             std::atan(x[1]) + k * (x[1] - x[0])}};
    };
    p.tangent = [k](const SmallVector<2> &x) {
      return SmallMatrix<2>{{{{1. / (1. + x[0] * x[0]) + k, -k}},
                             {{-k, 1. / (1. + x[1] * x[1]) + k}}}};
    };
    const SmallVector<2> root = {{0.2, -0.1}}, start = {{3., -2.5}};
    p.f = p.internal_force(root);

    {
      const NewtonSolver newton = make_newton("set Line search steps = 0\n"
                                              "set Maximum iterations = 8\n");
      const NewtonSolver::Result result = p.solve_from(newton, start, true);
      deallog << "full steps: converged: " << yes_no(result.converged) << " ("
              << result.failure << "), |R| above |R_0| at some iteration: "
              << yes_no(std::any_of(result.iterations.begin(),
                                    result.iterations.end(),
                                    [](const auto &i) {
                                      return !(i.relative_residual <= 1.);
                                    }))
              << std::endl;
    }
    for (const bool with_slope : {true, false})
      {
        const NewtonSolver         newton = make_newton("");
        const NewtonSolver::Result result =
          p.solve_from(newton, start, with_slope);
        SmallVector<2> error = {{p.x[0] - root[0], p.x[1] - root[1]}};
        deallog << (with_slope ? "line search on the potential" :
                                 "halving without slope()")
                << ": converged: " << yes_no(result.converged) << " in "
                << result.iterations.size() - 1
                << " iterations, |R|/|R_0|:" << history(result) << std::endl;
        deallog << "  the first step shortened: "
                << yes_no(result.iterations[0].step_length < 1.)
                << ", the last full: "
                << yes_no(result.iterations[result.iterations.size() - 2]
                            .step_length == 1.)
                << ", quadratic at the end: " << yes_no(quadratic(result, 10.))
                << ", |x - x*| / |x*| < 1e-8: "
                << yes_no(norm<2>(error) < 1e-8 * norm<2>(root)) << std::endl;
      }
    deallog.pop();
  }



  void
  test_step_cuts()
  {
    deallog.push("step cuts");
    const NewtonSolver   newton = make_newton("set Maximum step cuts = 3\n");
    NewtonSolver::Result failed;
    failed.failure = "no convergence in 2 iterations";
    failed.iterations.resize(3);
    failed.iterations[0].relative_residual = 1.;
    failed.iterations[1].relative_residual = 0.5;
    failed.iterations[2].relative_residual = 0.25;
    for (const unsigned int cuts : {2u, 3u})
      {
        std::ostringstream log;
        bool               thrown = false;
        try
          {
            newton.report_failure(failed, 4, 0.5, 0.125, cuts, &log);
          }
        catch (const ExceptionBase &)
          {
            thrown = true;
          }
        // The log line without its indentation and newline.
        std::string line = log.str();
        line.erase(line.find_last_not_of(" \n") + 1);
        line.erase(0, line.find_first_not_of(' '));
        deallog << "after " << cuts << " of 3 cuts: throws: " << yes_no(thrown)
                << ", log: " << line << std::endl;
      }
    deallog.pop();
  }
} // namespace



BSMPM_UNIT_TEST("nonlinear/newton_solver_01")
{
  initlog();
  test_cubic();
  test_arctangent();
  test_step_cuts();
}
