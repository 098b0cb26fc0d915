#include <deal.II/base/quadrature_lib.h>

#include <bsmpm/geometry/b_spline_curve.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <string>

namespace bsmpm
{
  namespace
  {
    using Bezier = std::array<Point<2>, 4>;

    Point<2>
    bezier_value(const Bezier &P, const double t)
    {
      const double s = 1 - t;
      return Point<2>(s * s * s * P[0] + 3 * s * s * t * P[1] +
                      3 * s * t * t * P[2] + t * t * t * P[3]);
    }

    /** dB/dt. */
    Tensor<1, 2>
    bezier_derivative(const Bezier &P, const double t)
    {
      const double s = 1 - t;
      return 3 * (s * s * (P[1] - P[0]) + 2 * s * t * (P[2] - P[1]) +
                  t * t * (P[3] - P[2]));
    }

    /** d^2B/dt^2. */
    Tensor<1, 2>
    bezier_second_derivative(const Bezier &P, const double t)
    {
      return 6 * ((1 - t) * ((P[2] - P[1]) - (P[1] - P[0])) +
                  t * ((P[3] - P[2]) - (P[2] - P[1])));
    }

    double
    cross(const Tensor<1, 2> &a, const Tensor<1, 2> &b)
    {
      return a[0] * b[1] - a[1] * b[0];
    }

    /**
     * Whether |a x b| is round-off against |a| |b|: the test for vanishing
     * cross products in the Akima weights and for parallel chords.
     */
    bool
    is_flat(const Tensor<1, 2> &a, const Tensor<1, 2> &b)
    {
      return std::abs(cross(a, b)) <= 1e-12 * a.norm() * b.norm();
    }

    /** Whether the closed line segments [a, b] and [c, d] meet. */
    bool
    segments_meet(const Point<2> &a,
                  const Point<2> &b,
                  const Point<2> &c,
                  const Point<2> &d)
    {
      const auto side =
        [](const Point<2> &p, const Point<2> &q, const Point<2> &r) {
          const double o = cross(q - p, r - p);
          return (o > 0) - (o < 0);
        };
      // r on [p, q], given that p, q, r are collinear.
      const auto on =
        [](const Point<2> &p, const Point<2> &q, const Point<2> &r) {
          return std::min(p[0], q[0]) <= r[0] && r[0] <= std::max(p[0], q[0]) &&
                 std::min(p[1], q[1]) <= r[1] && r[1] <= std::max(p[1], q[1]);
        };
      const int s1 = side(a, b, c), s2 = side(a, b, d), s3 = side(c, d, a),
                s4 = side(c, d, b);
      if (s1 * s2 < 0 && s3 * s4 < 0)
        return true;
      return (s1 == 0 && on(a, b, c)) || (s2 == 0 && on(a, b, d)) ||
             (s3 == 0 && on(c, d, a)) || (s4 == 0 && on(c, d, b));
    }
  } // namespace



  namespace internal
  {
    std::vector<double>
    bezier_turning_points(const std::array<double, 4> &c)
    {
      // The derivative is 3 (d0 (1-t)^2 + 2 d1 t (1-t) + d2 t^2) with
      // d_i = c_{i+1} - c_i, i.e. A t^2 + B t + C below.
      const double d0 = c[1] - c[0], d1 = c[2] - c[1], d2 = c[3] - c[2];
      const double A = d0 - 2 * d1 + d2, B = 2 * (d1 - d0), C = d0;
      const double discriminant = B * B - 4 * A * C;

      std::vector<double> roots;
      if (discriminant < 0)
        return roots;
      // The cancellation-free pair of roots q/A and C/q.
      const double q = -0.5 * (B + std::copysign(std::sqrt(discriminant), B));
      for (const double t : {(q != 0 ? C / q : -1.), (A != 0 ? q / A : -1.)})
        if (t > 0 && t < 1)
          roots.push_back(t);
      std::sort(roots.begin(), roots.end());
      return roots;
    }
  } // namespace internal



  BSplineCurve::BSplineCurve(const std::vector<Point<2>>     &points,
                             const bool                       closed,
                             const std::vector<unsigned int> &marked_corners)
    : points(points)
    , closed(closed)
  {
    const unsigned int n_points = points.size();
    AssertThrow(n_points >= (closed ? 3u : 2u),
                ExcMessage(std::string(closed ? "A closed" : "An open") +
                           " boundary curve needs at least " +
                           (closed ? "3" : "2") + " points, but " +
                           std::to_string(n_points) + " were given."));
    for (const Point<2> &p : points)
      AssertThrow(std::isfinite(p[0]) && std::isfinite(p[1]),
                  ExcMessage("A point of a boundary curve has a coordinate "
                             "that is not a finite number."));

    Point<2> lower = points[0], upper = points[0];
    for (const Point<2> &p : points)
      for (unsigned int d = 0; d < 2; ++d)
        {
          lower[d] = std::min(lower[d], p[d]);
          upper[d] = std::max(upper[d], p[d]);
        }
    const double       size       = lower.distance(upper);
    const unsigned int n_segments = closed ? n_points : n_points - 1;
    for (unsigned int k = 0; k < n_segments; ++k)
      AssertThrow(points[k].distance(points[(k + 1) % n_points]) > 1e-12 * size,
                  ExcMessage(
                    "Points " + std::to_string(k) + " and " +
                    std::to_string((k + 1) % n_points) +
                    " of a boundary curve coincide" +
                    (k + 1 == n_points ?
                       " (a closed chain joins its last point to the first by "
                       "itself: do not repeat the first point)." :
                       ".")));

    std::vector<bool> is_corner(n_points, false);
    for (const unsigned int c : marked_corners)
      {
        AssertThrow(c < n_points,
                    ExcMessage("Corner " + std::to_string(c) +
                               " is marked, but the curve has only " +
                               std::to_string(n_points) + " points."));
        is_corner[c] = true;
      }

    // Chords q_k = Q_k - Q_{k-1} for k = -1, ..., n + 2 (n = n_points - 1),
    // stored at k + 1. Closed chains wrap; open ones get two ghost chords at
    // each end by linear extrapolation.
    const int                 n = n_points - 1;
    std::vector<Tensor<1, 2>> chords(n + 4);

    const auto q = [&chords](const int k) -> Tensor<1, 2> & {
      return chords[k + 1];
    };
    if (closed)
      for (int k = -1; k <= n + 2; ++k)
        q(k) = points[(k + n_points) % n_points] -
               points[(k - 1 + 2 * n_points) % n_points];
    else
      {
        for (int k = 1; k <= n; ++k)
          q(k) = points[k] - points[k - 1];
        // A single chord extrapolates to itself.
        q(0)     = (n > 1 ? 2 * q(1) - q(2) : q(1));
        q(-1)    = 2 * q(0) - q(1);
        q(n + 1) = (n > 1 ? 2 * q(n) - q(n - 1) : q(n));
        q(n + 2) = 2 * q(n + 1) - q(n);
      }

    // Unit tangents at each Q_k: the one ending the segment into Q_k and the
    // one starting the segment out of it; they differ only at corners.
    std::vector<Tensor<1, 2>> tangent_in(n_points), tangent_out(n_points);
    for (int k = 0; k <= n; ++k)
      {
        const Tensor<1, 2> &q0 = q(k - 1), &q1 = q(k), &q2 = q(k + 1),
                           &q3 = q(k + 2);
        bool   corner          = is_corner[k];
        double a               = 0.5;
        if (!corner)
          {
            if (is_flat(q0, q1) && is_flat(q2, q3))
              // Straight on both sides: collinear points keep a = 1/2, a
              // change of direction between the straight parts is a corner.
              corner = !(is_flat(q1, q2) && q1 * q2 > 0);
            else
              {
                const double c01 = std::abs(cross(q0, q1)),
                             c23 = std::abs(cross(q2, q3));
                a                = c01 / (c01 + c23);
              }
          }
        const Tensor<1, 2> V = (1 - a) * q1 + a * q2;
        // A vanishing V means the chain turns back on itself: a cusp.
        if (corner || V.norm() <= 1e-12 * (q1.norm() + q2.norm()))
          {
            tangent_in[k]  = q1 / q1.norm();
            tangent_out[k] = q2 / q2.norm();
          }
        else
          tangent_in[k] = tangent_out[k] = V / V.norm();
      }

    // Segment k from Q_k to Q_{k+1}: alpha is the positive root of the
    // quadratic of method-notes Sec. 2, step 3, taken in the form that
    // does not cancel.
    segments.resize(n_segments);
    std::vector<double> alpha(n_segments);
    for (unsigned int k = 0; k < n_segments; ++k)
      {
        const unsigned int  k1 = (k + 1) % n_points;
        const Tensor<1, 2> &T0 = tangent_out[k], &T1 = tangent_in[k1];
        const Tensor<1, 2>  d    = points[k1] - points[k];
        const double        A    = 16 - (T0 + T1).norm_square();
        const double        B    = 12 * (d * (T0 + T1));
        const double        C    = -36 * d.norm_square();
        const double        root = std::sqrt(B * B - 4 * A * C);
        alpha[k]    = (B >= 0 ? -2 * C / (B + root) : (root - B) / (2 * A));
        segments[k] = {{points[k],
                        points[k] + alpha[k] / 3 * T0,
                        points[k1] - alpha[k] / 3 * T1,
                        points[k1]}};
      }

    // Knots u_{k+1} = u_k + alpha_k, normalised to [0, 1].
    breaks.resize(n_segments + 1, 0.);
    for (unsigned int k = 0; k < n_segments; ++k)
      breaks[k + 1] = breaks[k] + alpha[k];
    const double total = breaks.back();
    for (double &u : breaks)
      u /= total;
    breaks.back() = 1.;

    segment_lengths.resize(n_segments);
    for (unsigned int k = 0; k < n_segments; ++k)
      segment_lengths[k] = segment_length(k, 0., 1.);
  }



  std::vector<double>
  BSplineCurve::knots() const
  {
    std::vector<double> knots(4, 0.);
    for (unsigned int k = 1; k < n_segments(); ++k)
      knots.insert(knots.end(), 3, breaks[k]);
    knots.insert(knots.end(), 4, 1.);
    return knots;
  }



  std::vector<Point<2>>
  BSplineCurve::control_points() const
  {
    std::vector<Point<2>> P;
    for (const Bezier &segment : segments)
      P.insert(P.end(), segment.begin(), segment.begin() + 3);
    P.push_back(segments.back()[3]);
    return P;
  }



  unsigned int
  BSplineCurve::segment_of(const double u) const
  {
    Assert(u >= 0 && u <= 1,
           ExcMessage("The curve parameter " + std::to_string(u) +
                      " is not in [0, 1]."));
    const unsigned int k =
      std::upper_bound(breaks.begin(), breaks.end(), u) - breaks.begin();
    return std::min(std::max(k, 1u), n_segments()) - 1;
  }



  Point<2>
  BSplineCurve::value(const double u) const
  {
    const unsigned int k = segment_of(u);
    return bezier_value(segments[k], local_parameter(k, u));
  }



  Tensor<1, 2>
  BSplineCurve::derivative(const double u) const
  {
    const unsigned int k = segment_of(u);
    return bezier_derivative(segments[k], local_parameter(k, u)) /
           (breaks[k + 1] - breaks[k]);
  }



  Tensor<1, 2>
  BSplineCurve::second_derivative(const double u) const
  {
    const unsigned int k  = segment_of(u);
    const double       du = breaks[k + 1] - breaks[k];
    return bezier_second_derivative(segments[k], local_parameter(k, u)) /
           (du * du);
  }



  Tensor<1, 2>
  BSplineCurve::unit_tangent(const double u) const
  {
    const Tensor<1, 2> d = derivative(u);
    return d / d.norm();
  }



  Tensor<1, 2>
  BSplineCurve::outward_normal(const double u) const
  {
    const Tensor<1, 2> t = unit_tangent(u);
    return Tensor<1, 2>({t[1], -t[0]});
  }



  double
  BSplineCurve::segment_length(const unsigned int k,
                               const double       t0,
                               const double       t1) const
  {
    // Adaptive Gauss-Legendre: accept the 16-point rule on an interval when
    // the 8-point rule agrees with it to 1e-14 of the control polygon's
    // length (an upper bound of the segment's length) per unit of t, else
    // halve. The speed is analytic unless the segment nearly has a cusp, so
    // the 16-point rule is then far more accurate than this test demands;
    // near a cusp, halving takes over.
    static const QGauss<1> low(8), high(16);
    const Bezier          &P = segments[k];
    const double           tolerance =
      1e-14 * (P[0].distance(P[1]) + P[1].distance(P[2]) + P[2].distance(P[3]));
    const auto integrate =
      [&P](const Quadrature<1> &quadrature, const double a, const double b) {
        double sum = 0;
        for (unsigned int q = 0; q < quadrature.size(); ++q)
          sum +=
            quadrature.weight(q) *
            bezier_derivative(P, a + (b - a) * quadrature.point(q)[0]).norm();
        return sum * (b - a);
      };
    const std::function<double(double, double, unsigned int)> adapt =
      [&](const double a, const double b, const unsigned int depth) {
        const double accurate = integrate(high, a, b);
        if (std::abs(accurate - integrate(low, a, b)) <= tolerance * (b - a) ||
            depth == 30)
          return accurate;
        const double m = 0.5 * (a + b);
        return adapt(a, m, depth + 1) + adapt(m, b, depth + 1);
      };
    return adapt(t0, t1, 0);
  }



  double
  BSplineCurve::length() const
  {
    double sum = 0;
    for (const double l : segment_lengths)
      sum += l;
    return sum;
  }



  double
  BSplineCurve::length(const double u0, const double u1) const
  {
    Assert(u0 <= u1, ExcMessage("The parameters must be in increasing order."));
    const unsigned int k0 = segment_of(u0);
    unsigned int       k1 = segment_of(u1);
    if (k1 > k0 && u1 == breaks[k1])
      --k1;
    double sum = 0;
    for (unsigned int k = k0; k <= k1; ++k)
      {
        const double t0 = (k == k0 ? local_parameter(k, u0) : 0.);
        const double t1 = (k == k1 ? std::min(local_parameter(k, u1), 1.) : 1.);
        sum +=
          (t0 == 0 && t1 == 1 ? segment_lengths[k] : segment_length(k, t0, t1));
      }
    return sum;
  }



  Point<2>
  BSplineCurve::segment_value(const unsigned int k, const double t) const
  {
    return bezier_value(segments[k], t);
  }



  Tensor<1, 2>
  BSplineCurve::segment_derivative(const unsigned int k, const double t) const
  {
    return bezier_derivative(segments[k], t);
  }



  Tensor<1, 2>
  BSplineCurve::segment_second_derivative(const unsigned int k,
                                          const double       t) const
  {
    return bezier_second_derivative(segments[k], t);
  }



  namespace
  {
    /**
     * A lower bound of the distance from @p p to the Bezier segment @p P:
     * the distance to the box of its control points, which holds the
     * segment (convex hull property), less a margin for the round-off of
     * the points computed on the segment (a few ulps of the coordinates;
     * the margin is 1e-12 of them).
     */
    double
    distance_bound(const Bezier &P, const Point<2> &p)
    {
      double square = 0, scale = 1 + std::abs(p[0]) + std::abs(p[1]);
      for (unsigned int d = 0; d < 2; ++d)
        {
          const double lower =
            std::min(std::min(P[0][d], P[1][d]), std::min(P[2][d], P[3][d]));
          const double upper =
            std::max(std::max(P[0][d], P[1][d]), std::max(P[2][d], P[3][d]));
          const double gap = std::max(std::max(lower - p[d], p[d] - upper), 0.);
          square += gap * gap;
          scale += std::abs(lower) + std::abs(upper);
        }
      return std::sqrt(square) - 1e-12 * scale;
    }
  } // namespace



  BSplineCurve::ClosestPoint
  BSplineCurve::closest_point(const Point<2> &p) const
  {
    // Searching a segment takes 17 evaluations and a Newton iteration; its
    // box takes a few comparisons. The segment with the nearest box gives a
    // distance that the nearest point does not exceed; a segment whose box
    // is farther than that cannot hold it and is skipped. The others are
    // searched in their order as before, so the answer is the same to the
    // bit (among equally near points the first segment's), in a fraction of
    // the time where a curve has many segments (trimming material points:
    // doc/changes/2026-12-03-fixed-costs-of-a-linear-run.md).
    const unsigned int n           = n_segments();
    unsigned int       first       = 0;
    double             nearest_box = std::numeric_limits<double>::max();
    for (unsigned int k = 0; k < n; ++k)
      {
        const double bound = distance_bound(segments[k], p);
        if (bound < nearest_box)
          {
            nearest_box = bound;
            first       = k;
          }
      }
    const ClosestPoint first_result = closest_point(p, first);
    const double       reach        = first_result.distance;

    ClosestPoint best{};
    bool         found = false;
    for (unsigned int k = 0; k < n; ++k)
      {
        if (k != first && distance_bound(segments[k], p) > reach)
          continue;
        const ClosestPoint c =
          (k == first) ? first_result : closest_point(p, k);
        if (!found || c.distance < best.distance)
          best = c;
        found = true;
      }
    return best;
  }



  BSplineCurve::ClosestPoint
  BSplineCurve::closest_point(const Point<2> &p, const unsigned int k) const
  {
    const Bezier &P = segments[k];
    ClosestPoint  best{breaks[k], P[0], P[0].distance(p)};
    const auto    consider = [&](const double t) {
      const Point<2> x = bezier_value(P, t);
      if (x.distance(p) < best.distance)
        best = {t == 1 ? breaks[k + 1] :
                            breaks[k] + t * (breaks[k + 1] - breaks[k]),
                x,
                x.distance(p)};
    };
    // f = (B - p).B' is zero where the distance is stationary; where it
    // goes from negative to positive the distance has a local minimum.
    const auto f = [&](const double t) {
      const Tensor<1, 2> r = bezier_value(P, t) - p,
                         d = bezier_derivative(P, t);
      return std::array<double, 2>{
        {r * d, d * d + r * bezier_second_derivative(P, t)}};
    };
    consider(1.);
    const unsigned int n_samples = 16;
    double             f_last    = f(0.)[0];
    for (unsigned int j = 1; j <= n_samples; ++j)
      {
        const double t0 = double(j - 1) / n_samples, t1 = double(j) / n_samples,
                     f1 = f(t1)[0];
        if (f_last < 0 && f1 >= 0)
          consider(internal::safeguarded_newton(f, t0, t1));
        f_last = f1;
      }
    return best;
  }



  BoundingBox<2>
  BSplineCurve::bounding_box() const
  {
    Point<2> lower = points[0], upper = points[0];
    for (const Bezier &P : segments)
      for (unsigned int d = 0; d < 2; ++d)
        {
          std::vector<double> t = internal::bezier_turning_points(
            {{P[0][d], P[1][d], P[2][d], P[3][d]}});
          t.push_back(1.);
          for (const double s : t)
            {
              const double x = bezier_value(P, s)[d];
              lower[d]       = std::min(lower[d], x);
              upper[d]       = std::max(upper[d], x);
            }
        }
    return BoundingBox<2>(std::make_pair(lower, upper));
  }



  bool
  BSplineCurve::is_self_intersecting() const
  {
    const unsigned int                 n = n_segments(), n_pieces = 32;
    std::vector<std::vector<Point<2>>> polylines(n);
    std::vector<BoundingBox<2>>        boxes;
    for (unsigned int k = 0; k < n; ++k)
      {
        for (unsigned int j = 0; j <= n_pieces; ++j)
          polylines[k].push_back(
            bezier_value(segments[k], double(j) / n_pieces));
        // The control polygon holds the segment and so its polyline.
        boxes.emplace_back(segments[k]);
      }

    for (unsigned int i = 0; i < n; ++i)
      for (unsigned int j = i + 2; j < n; ++j)
        {
          if (closed && i == 0 && j == n - 1)
            continue; // neighbours across the closing point
          const auto &bi = boxes[i].get_boundary_points(),
                     &bj = boxes[j].get_boundary_points();
          if (bi.first[0] > bj.second[0] || bj.first[0] > bi.second[0] ||
              bi.first[1] > bj.second[1] || bj.first[1] > bi.second[1])
            continue;
          for (unsigned int a = 0; a < n_pieces; ++a)
            for (unsigned int b = 0; b < n_pieces; ++b)
              if (segments_meet(polylines[i][a],
                                polylines[i][a + 1],
                                polylines[j][b],
                                polylines[j][b + 1]))
                return true;
        }
    return false;
  }
} // namespace bsmpm
