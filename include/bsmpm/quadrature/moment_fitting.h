#ifndef bsmpm_moment_fitting_h
#define bsmpm_moment_fitting_h

#include <deal.II/base/point.h>

#include <array>
#include <vector>

namespace bsmpm
{
  using namespace dealii;

  /**
   * Quadrature weights for the material points of a cut cell whose moments
   * equal the exact moments of the cell's part inside the body (moment
   * fitting; Mueller, Kummer and Oberlack, IJNME 2013, for cut cells;
   * doc/cut-cells.md for the derivation).
   *
   * Given points x_p with physical volumes V_p and target moments m_k of the
   * basis phi = (1, s, t, s^2, s t, t^2) (the first n of them), the weights
   * solve
   *
   *   min sum_p (w_p - v_p)^2 / v_p   s.t.   sum_p w_p phi_k(x_p) = m_k,
   *                                          w_p >= 0,
   *
   * with v_p the volumes scaled to the target area: the weights closest to
   * the physical volumes among all non-negative ones that integrate the
   * basis exactly. The Lagrange conditions give
   *
   *   w_p = v_p max(0, 1 + phi(x_p) . lambda),
   *
   * so the weights are the volumes tilted by a quadratic polynomial and cut
   * at zero. lambda maximises the concave, piecewise quadratic dual
   *
   *   g(lambda) = lambda . m - sum_p v_p max(0, 1 + phi_p . lambda)^2 / 2,
   *
   * found by Newton's method with a backtracking line search on g (n
   * unknowns, n <= 6, however many points). The basis is centred at the
   * target centroid and scaled to the points' spread, so that slivers are
   * as well conditioned as full cells. If no non-negative solution exists
   * (the dual is unbounded) or the points cannot carry the n moments (too
   * few, or on a line), fewer moments are fitted: 6, then 3 (area and
   * centroid), then 1 (area).
   */
  class MomentFitting
  {
  public:
    struct Result
    {
      std::vector<double> weights;
      /** How many moments the weights match: 6, 3 or 1 (0 if there are no
       * points). */
      unsigned int n_moments = 0;
    };

    /**
     * Fits weights for points at local coordinates @p points with volumes
     * @p volumes (all positive) to @p target (moments of 1, s, t, s^2, s t,
     * t^2 in the same units as the volumes), trying at most
     * @p max_moments (6, 3 or 1) moments.
     */
    static Result
    fit(const std::vector<Point<2>> &points,
        const std::vector<double>   &volumes,
        const std::array<double, 6> &target,
        const unsigned int           max_moments = 6);

    /**
     * Weights matching exactly @p n_moments (6, 3 or 1) moments, or an empty
     * vector if that is impossible with non-negative weights.
     */
    static std::vector<double>
    fit_exactly(const std::vector<Point<2>> &points,
                const std::vector<double>   &volumes,
                const std::array<double, 6> &target,
                const unsigned int           n_moments);
  };
} // namespace bsmpm

#endif
