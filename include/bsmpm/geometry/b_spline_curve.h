#ifndef bsmpm_b_spline_curve_h
#define bsmpm_b_spline_curve_h

#include <deal.II/base/bounding_box.h>
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

namespace bsmpm
{
  using namespace dealii;

  /**
   * A planar cubic B-spline through given points, built by local cubic
   * interpolation (NURBS book Sec. 9.3.4; paper Secs. 3.1-3.2;
   * method-notes Sec. 2). It is C1 where the data are smooth and C0 at
   * corners, which are either marked by the user or detected where the data
   * are straight on both sides of a point.
   *
   * The curve is stored as a cubic B-spline with an open knot vector on
   * [0, 1] whose interior knots u_1, ..., u_{N-1} have multiplicity 3, so
   * knot span k is a Bezier segment from point Q_k to Q_{k+1}. Everything is
   * evaluated on those Bezier segments.
   *
   * Orientation: the body lies to the left of the direction of increasing
   * u, so outward_normal() is the unit tangent turned clockwise (paper eq.
   * 29). A closed chain must therefore run counter-clockwise around the
   * body.
   */
  class BSplineCurve
  {
  public:
    /** Result of closest_point(). */
    struct ClosestPoint
    {
      double   u;
      Point<2> point;
      double   distance;
    };

    /**
     * Interpolates @p points in the given order. If @p closed, the last point
     * joins the first (do not repeat it). @p marked_corners are indices into
     * @p points where the curve must keep a sharp corner.
     */
    BSplineCurve(const std::vector<Point<2>>     &points,
                 const bool                       closed,
                 const std::vector<unsigned int> &marked_corners = {});

    bool
    is_closed() const
    {
      return closed;
    }

    /** The points the curve was built through. */
    const std::vector<Point<2>> &
    interpolation_points() const
    {
      return points;
    }

    /** Number of Bezier segments (knot spans). */
    unsigned int
    n_segments() const
    {
      return segments.size();
    }

    /** The full knot vector: 0 and 1 four times, interior knots three times. */
    std::vector<double>
    knots() const;

    /**
     * The 3 N + 1 control points Q_0, P_{0,1}, P_{0,2}, Q_1, ..., Q_N (for a
     * closed curve Q_N = Q_0).
     */
    std::vector<Point<2>>
    control_points() const;

    /** [u_k, u_{k+1}]: the parameter interval of segment @p k. */
    std::array<double, 2>
    segment_parameters(const unsigned int k) const
    {
      return {{breaks[k], breaks[k + 1]}};
    }

    /** The Bezier control points of segment @p k. */
    const std::array<Point<2>, 4> &
    bezier_control_points(const unsigned int k) const
    {
      return segments[k];
    }

    /**
     * The segment k with u_k <= u < u_{k+1}; u = 1 belongs to the last one.
     * At an interior knot, value and derivatives are those of the segment
     * that starts there.
     */
    unsigned int
    segment_of(const double u) const;

    Point<2>
    value(const double u) const;

    /** dC/du. */
    Tensor<1, 2>
    derivative(const double u) const;

    /** d^2C/du^2. */
    Tensor<1, 2>
    second_derivative(const double u) const;

    Tensor<1, 2>
    unit_tangent(const double u) const;

    /** The unit normal pointing away from the body (to the right). */
    Tensor<1, 2>
    outward_normal(const double u) const;

    /** Length of the whole curve. */
    double
    length() const;

    /** Length of the part between parameters @p u0 <= @p u1. */
    double
    length(const double u0, const double u1) const;

    /** The point of segment @p k at its local parameter @p t in [0, 1], and
     * its first and second derivatives by t. Unlike value() and
     * derivative(), t = 1 is the end of segment @p k, where a corner's
     * incoming tangent is. */
    Point<2>
    segment_value(const unsigned int k, const double t) const;

    Tensor<1, 2>
    segment_derivative(const unsigned int k, const double t) const;

    Tensor<1, 2>
    segment_second_derivative(const unsigned int k, const double t) const;

    /** The point of the curve nearest to @p p. */
    ClosestPoint
    closest_point(const Point<2> &p) const;

    /** The point of segment @p k nearest to @p p (its ends included; u
     * is exactly the segment's end parameter there). */
    ClosestPoint
    closest_point(const Point<2> &p, const unsigned int k) const;

    /** The smallest axis-aligned box holding the curve. */
    BoundingBox<2>
    bounding_box() const;

    /**
     * Whether two segments that are not neighbours cross or touch, judged on
     * fine polylines through each segment (so near-misses closer than the
     * polyline error may count as crossings).
     */
    bool
    is_self_intersecting() const;

  private:
    std::vector<Point<2>>                points;
    bool                                 closed;
    std::vector<std::array<Point<2>, 4>> segments;

    /** u_0 = 0, ..., u_N = 1: the distinct knots. */
    std::vector<double> breaks;

    /** Length of each segment. */
    std::vector<double> segment_lengths;

    /** Length of segment @p k between local parameters t0 <= t1 in [0, 1]. */
    double
    segment_length(const unsigned int k,
                   const double       t0,
                   const double       t1) const;

    /** Local parameter in [0, 1] of @p u within segment @p k. */
    double
    local_parameter(const unsigned int k, const double u) const
    {
      return (u - breaks[k]) / (breaks[k + 1] - breaks[k]);
    }
  };



  namespace internal
  {
    /**
     * The local parameters t in (0, 1) where the cubic with Bernstein
     * coefficients @p c has zero derivative, in increasing order. Between
     * them the cubic is monotone.
     */
    std::vector<double>
    bezier_turning_points(const std::array<double, 4> &c);

    /**
     * The root in [lo, hi] of a function that changes sign there (or is zero
     * at an end), to machine precision for t of order one: Newton steps,
     * replaced by bisection whenever they would leave the bracket or do not
     * halve the step (Numerical Recipes' rtsafe). @p f returns
     * {f(t), f'(t)}. Of several roots in the bracket it finds one where f
     * goes from the sign of f(lo) to that of f(hi).
     */
    template <typename Function>
    double
    safeguarded_newton(const Function &f, double lo, double hi)
    {
      const double f_lo = f(lo)[0], f_hi = f(hi)[0];
      if (f_lo == 0)
        return lo;
      if (f_hi == 0)
        return hi;
      Assert(f_lo * f_hi < 0, ExcMessage("The root is not bracketed."));
      if (f_lo > 0)
        std::swap(lo, hi); // from here on f(lo) < 0 < f(hi)

      const double eps  = std::numeric_limits<double>::epsilon();
      double       t    = 0.5 * (lo + hi);
      double       step = hi - lo;
      for (unsigned int i = 0; i < 200; ++i)
        {
          const std::array<double, 2> ft = f(t);
          if (ft[0] == 0)
            return t;
          (ft[0] < 0 ? lo : hi) = t;

          const double last_step = step;
          step                   = ft[0] / ft[1];
          double next            = t - step;
          if (!((next - lo) * (next - hi) < 0) ||
              std::abs(2 * step) > std::abs(last_step))
            {
              next = 0.5 * (lo + hi);
              step = t - next;
            }
          if (std::abs(next - t) <= eps * std::max(1., std::abs(t)) ||
              std::abs(hi - lo) <= 2 * eps * std::max(1., std::abs(t)))
            return next;
          t = next;
        }
      return t;
    }
  } // namespace internal
} // namespace bsmpm

#endif
