#include <deal.II/base/exceptions.h>

#include <bsmpm/quadrature/moment_fitting.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace bsmpm
{
  namespace
  {
    using Vector6 = std::array<double, 6>;
    using Matrix6 = std::array<std::array<double, 6>, 6>;

    /** Solves the SPD system J x = f of size n by Cholesky; false if J is
     * not numerically positive definite (pivot below @p threshold times the
     * largest diagonal entry). */
    bool
    cholesky_solve(Matrix6            J,
                   const Vector6     &f,
                   Vector6           &x,
                   const unsigned int n,
                   const double       threshold)
    {
      double largest = 0;
      for (unsigned int i = 0; i < n; ++i)
        largest = std::max(largest, J[i][i]);
      if (!(largest > 0))
        return false;
      for (unsigned int j = 0; j < n; ++j)
        {
          double d = J[j][j];
          for (unsigned int k = 0; k < j; ++k)
            d -= J[j][k] * J[j][k];
          if (!(d > threshold * largest))
            return false;
          J[j][j] = std::sqrt(d);
          for (unsigned int i = j + 1; i < n; ++i)
            {
              double v = J[i][j];
              for (unsigned int k = 0; k < j; ++k)
                v -= J[i][k] * J[j][k];
              J[i][j] = v / J[j][j];
            }
        }
      Vector6 y{};
      for (unsigned int i = 0; i < n; ++i)
        {
          double v = f[i];
          for (unsigned int k = 0; k < i; ++k)
            v -= J[i][k] * y[k];
          y[i] = v / J[i][i];
        }
      for (unsigned int i = n; i-- > 0;)
        {
          double v = y[i];
          for (unsigned int k = i + 1; k < n; ++k)
            v -= J[k][i] * x[k];
          x[i] = v / J[i][i];
        }
      return true;
    }

    Vector6
    basis(const double s, const double t)
    {
      return {{1., s, t, s * s, s * t, t * t}};
    }
  } // namespace



  std::vector<double>
  MomentFitting::fit_exactly(const std::vector<Point<2>> &points,
                             const std::vector<double>   &volumes,
                             const std::array<double, 6> &target,
                             const unsigned int           n)
  {
    Assert(n == 1 || n == 3 || n == 6, ExcInternalError());
    AssertDimension(points.size(), volumes.size());
    const std::size_t n_points = points.size();
    const double      m0       = target[0];
    if (n_points == 0)
      return {};
    if (!(m0 > 0))
      return std::vector<double>(n_points, 0.);

    double total = 0;
    for (const double v : volumes)
      total += v;
    AssertThrow(total > 0, ExcInternalError());

    // Centred and scaled basis: s^ = (s - c_s) / L, t^ = (t - c_t) / L.
    const double cs = target[1] / m0, ct = target[2] / m0;
    double       L = 0;
    for (const auto &p : points)
      L = std::max({L, std::abs(p[0] - cs), std::abs(p[1] - ct)});
    if (!(L > 0))
      L = 1;
    // Targets of the scaled basis, per unit area.
    const Vector6 m = {{1.,
                        0.,
                        0.,
                        (target[3] / m0 - cs * cs) / (L * L),
                        (target[4] / m0 - cs * ct) / (L * L),
                        (target[5] / m0 - ct * ct) / (L * L)}};

    std::vector<Vector6> a(n_points);
    std::vector<double>  v(n_points);
    for (std::size_t p = 0; p < n_points; ++p)
      {
        a[p] = basis((points[p][0] - cs) / L, (points[p][1] - ct) / L);
        v[p] = volumes[p] / total;
      }

    const auto weight = [&](const Vector6 &lambda, const std::size_t p) {
      double z = 1;
      for (unsigned int k = 0; k < n; ++k)
        z += a[p][k] * lambda[k];
      return v[p] * std::max(z, 0.);
    };
    const auto dual = [&](const Vector6 &lambda) {
      double g = 0;
      for (unsigned int k = 0; k < n; ++k)
        g += lambda[k] * m[k];
      for (std::size_t p = 0; p < n_points; ++p)
        {
          const double w = weight(lambda, p);
          g -= w * w / (2 * v[p]);
        }
      return g;
    };

    Vector6      lambda{};
    bool         converged = false;
    const double tolerance = 1e-13;
    for (unsigned int iteration = 0; iteration < 100; ++iteration)
      {
        // Residual F = m - A w and Jacobian J = sum over the points with
        // positive weight of v_p a_p a_p^T.
        Vector6 F = m;
        Matrix6 J{};
        for (std::size_t p = 0; p < n_points; ++p)
          {
            const double w = weight(lambda, p);
            for (unsigned int k = 0; k < n; ++k)
              F[k] -= w * a[p][k];
            if (w > 0)
              for (unsigned int k = 0; k < n; ++k)
                for (unsigned int l = 0; l <= k; ++l)
                  J[k][l] += v[p] * a[p][k] * a[p][l];
          }
        double size = 0;
        for (unsigned int k = 0; k < n; ++k)
          size = std::max(size, std::abs(F[k]));
        if (size < tolerance)
          {
            converged = true;
            break;
          }
        for (unsigned int k = 0; k < n; ++k)
          for (unsigned int l = k + 1; l < n; ++l)
            J[k][l] = J[l][k];

        Vector6 step{};
        if (!cholesky_solve(J, F, step, n, 1e-12))
          return {}; // the points with weight cannot carry n moments

        // Backtracking on the concave dual g; F is its gradient.
        double slope = 0;
        for (unsigned int k = 0; k < n; ++k)
          slope += F[k] * step[k];
        const double g0    = dual(lambda);
        double       alpha = 1;
        Vector6      trial;
        bool         accepted = false;
        for (unsigned int halving = 0; halving < 60; ++halving, alpha /= 2)
          {
            for (unsigned int k = 0; k < 6; ++k)
              trial[k] = lambda[k] + alpha * step[k];
            if (dual(trial) >= g0 + 1e-4 * alpha * slope)
              {
                accepted = true;
                break;
              }
          }
        if (!accepted)
          break;
        lambda      = trial;
        double norm = 0;
        for (unsigned int k = 0; k < n; ++k)
          norm = std::max(norm, std::abs(lambda[k]));
        if (norm > 1e10) // the dual is unbounded: no solution w >= 0
          return {};
      }
    if (!converged)
      return {};

    std::vector<double> w(n_points);
    for (std::size_t p = 0; p < n_points; ++p)
      w[p] = m0 * weight(lambda, p);

    // The moments in the original basis, against the target.
    Vector6 moments{};
    for (std::size_t p = 0; p < n_points; ++p)
      {
        const Vector6 phi = basis(points[p][0], points[p][1]);
        for (unsigned int k = 0; k < n; ++k)
          moments[k] += w[p] * phi[k];
      }
    for (unsigned int k = 0; k < n; ++k)
      if (std::abs(moments[k] - target[k]) > 1e-10 * m0)
        return {};
    return w;
  }



  MomentFitting::Result
  MomentFitting::fit(const std::vector<Point<2>> &points,
                     const std::vector<double>   &volumes,
                     const std::array<double, 6> &target,
                     const unsigned int           max_moments)
  {
    Result result;
    if (points.empty())
      return result;
    for (const unsigned int n : {6u, 3u, 1u})
      if (n <= max_moments)
        {
          result.weights = fit_exactly(points, volumes, target, n);
          if (!result.weights.empty())
            {
              result.n_moments = n;
              return result;
            }
        }
    return result;
  }
} // namespace bsmpm
