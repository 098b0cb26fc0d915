#ifndef bsmpm_point_moments_h
#define bsmpm_point_moments_h

#include <deal.II/base/point.h>

#include <bsmpm/points/q1_cell_kernel.h>

#include <algorithm>
#include <array>
#include <cmath>

namespace bsmpm
{
  using namespace dealii;

  /**
   * The moments m = (1, s, t) in which ConstitutiveUpdate integrates the
   * points of a cell: the strain columns of Q1 are affine in the cell, so
   * the points enter its system only through sums of w_p m_a m_b times
   * their tangents and of w_p m_a times their stresses (see
   * ConstitutiveUpdate::cell_system()).
   */
  namespace PointMoments
  {
    /**
     * The weighted moments w m_a m_b of a point at @p st, in the order of
     * the sums H_ab and M_ab of ConstitutiveUpdate::cell_system(): (1, 1),
     * (1, s), (1, t), (s, s), (s, t), (t, t); the first three are also
     * w m_a.
     */
    inline std::array<double, 6>
    weighted(const double w, const Point<2> &st)
    {
      const double ws = w * st[0], wt = w * st[1];
      return {{w, ws, wt, ws * st[0], ws * st[1], wt * st[1]}};
    }

    /** Where H_ab and M_ab (a, b in 1, s, t) are stored, by a and b. */
    constexpr unsigned int index[3][3] = {{0, 1, 2}, {1, 3, 4}, {2, 4, 5}};

    /**
     * Four points, a quarter of the area v each, at (c_s +- r_s, c_t +-
     * r_t), c the centroid of @p m and r_s^2 = vss / v - c_s^2,
     * r_t^2 = vtt / v - c_t^2 the variances of s and t over it: they
     * integrate 1, s, t, s^2 and t^2 exactly, so a constant tangent gives
     * the cell a stiffness that holds every deformation mode (the exact
     * moments of the linear path do the same).
     */
    inline std::array<Point<2>, 4>
    exact_four_point_rule(const CellMoments &m)
    {
      const Point<2> c(m.vs / m.v, m.vt / m.v);
      const double   r_s = std::sqrt(std::max(0., m.vss / m.v - c[0] * c[0]));
      const double   r_t = std::sqrt(std::max(0., m.vtt / m.v - c[1] * c[1]));
      std::array<Point<2>, 4> rule;
      unsigned int            q = 0;
      for (const double a : {-1., 1.})
        for (const double b : {-1., 1.})
          rule[q++] = Point<2>(c[0] + a * r_s, c[1] + b * r_t);
      return rule;
    }
  } // namespace PointMoments
} // namespace bsmpm

#endif
