#include <deal.II/base/numbers.h>

#include <bsmpm/contact/rigid_shapes.h>
#include <bsmpm/geometry/b_spline_curve.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace bsmpm
{
  namespace
  {
    /**
     * A polygon grown by a radius r >= 0 (the set of points within r of
     * it): r = 0 is the polygon itself, r > 0 rounds its convex corners by
     * arcs of radius r about them. The gap of x is its distance from the
     * polygon less r, signed by the side.
     */
    class PolygonShape : public RigidShape
    {
    public:
      PolygonShape(const std::vector<Point<2>> &vertices, const double radius)
        : vertices(vertices)
        , radius(radius)
      {}

      SurfacePoint
      nearest(const Point<2> &x) const override
      {
        const unsigned int n         = vertices.size();
        double             best      = std::numeric_limits<double>::max();
        Point<2>           closest   = vertices[0];
        bool               at_corner = false;
        unsigned int       feature   = 0;
        Tensor<1, 2>       edge_normal;
        unsigned int       edge   = 0;
        bool               inside = false;
        for (unsigned int k = 0; k < n; ++k)
          {
            const Point<2>    &a = vertices[k];
            const Point<2>    &b = vertices[(k + 1) % n];
            const Tensor<1, 2> e = b - a;
            const double       f =
              std::clamp(((x - a) * e) / e.norm_square(), 0., 1.);
            const Point<2> q = a + f * e;
            const double   d = (x - q).norm();
            if (d < best)
              {
                best        = d;
                closest     = q;
                at_corner   = (f == 0. || f == 1.);
                feature     = f == 0. ? 2 * k + 1 :
                              f == 1. ? 2 * ((k + 1) % n) + 1 :
                                        2 * k;
                edge        = k;
                edge_normal = Tensor<1, 2>({e[1], -e[0]}) / e.norm();
              }
            // Crossing number: the edges that a ray from x in +x crosses.
            if ((a[1] > x[1]) != (b[1] > x[1]) &&
                x[0] < a[0] + (x[1] - a[1]) / (b[1] - a[1]) * e[0])
              inside = !inside;
          }
        SurfacePoint s;
        if (inside || best == 0.)
          {
            s.gap     = -best - radius;
            s.normal  = edge_normal;
            s.feature = 2 * edge;
            return s;
          }
        s.gap     = best - radius;
        s.normal  = (x - closest) / best;
        s.feature = feature;
        // Round a corner, or the polygon grown by r anywhere: n turns about
        // the nearest point of the polygon.
        if (at_corner)
          s.turning_radius = best;
        return s;
      }

      SurfacePoint
      to_feature(const Point<2> &x, const unsigned int feature) const override
      {
        const unsigned int k = feature / 2;
        SurfacePoint       s;
        s.feature = feature;
        if (feature % 2 == 0)
          {
            // The line of edge k, its outward normal n: gap (x - a) . n - r.
            const Point<2>    &a = vertices[k];
            const Tensor<1, 2> e = vertices[(k + 1) % vertices.size()] - a;
            s.normal             = Tensor<1, 2>({e[1], -e[0]}) / e.norm();
            s.gap                = (x - a) * s.normal - radius;
            return s;
          }
        // The circle of radius r round vertex k.
        const double d = (x - vertices[k]).norm();
        s.gap          = d - radius;
        s.normal =
          d > 0 ? Tensor<1, 2>((x - vertices[k]) / d) : Tensor<1, 2>({0., 1.});
        s.turning_radius = d;
        return s;
      }

      std::vector<Point<2>>
      outline() const override
      {
        if (radius == 0.)
          {
            std::vector<Point<2>> line = vertices;
            line.push_back(vertices[0]);
            return line;
          }
        // Each edge shifted out by r, joined by arcs about the corners.
        std::vector<Point<2>> line;
        const unsigned int    n = vertices.size();
        for (unsigned int k = 0; k < n; ++k)
          {
            const Point<2> &a  = vertices[(k + n - 1) % n];
            const Point<2> &b  = vertices[k];
            const Point<2> &c  = vertices[(k + 1) % n];
            const double    a0 = std::atan2(a[0] - b[0], b[1] - a[1]);
            double          a1 = std::atan2(b[0] - c[0], c[1] - b[1]);
            if (a1 - a0 > numbers::PI)
              a1 -= 2 * numbers::PI;
            if (a1 - a0 <= -numbers::PI)
              a1 += 2 * numbers::PI;
            // A concave corner (a1 < a0) has no arc: the two shifted edges
            // cross; its two ends suffice for a picture.
            const unsigned int samples = a1 > a0 ? 8 : 1;
            for (unsigned int i = 0; i <= samples; ++i)
              {
                const double phi = a0 + (a1 - a0) * i / samples;
                line.push_back(
                  b + radius * Tensor<1, 2>({std::cos(phi), std::sin(phi)}));
              }
          }
        line.push_back(line.front());
        return line;
      }

      double
      size() const override
      {
        double largest = 0;
        for (const auto &v : vertices)
          largest = std::max(largest, (v - vertices[0]).norm());
        return largest + radius;
      }

      Point<2>
      reference_point() const override
      {
        return vertices[0];
      }

    private:
      std::vector<Point<2>> vertices;
      double                radius;
    };



    class CircleShape : public RigidShape
    {
    public:
      CircleShape(const Point<2> &center, const double radius)
        : center(center)
        , radius(radius)
      {}

      SurfacePoint
      nearest(const Point<2> &x) const override
      {
        const double d = (x - center).norm();
        SurfacePoint s;
        s.gap = d - radius;
        s.normal =
          d > 0 ? Tensor<1, 2>((x - center) / d) : Tensor<1, 2>({0., 1.});
        s.turning_radius = d;
        return s;
      }

      SurfacePoint
      to_feature(const Point<2> &x, const unsigned int) const override
      {
        return nearest(x);
      }

      std::vector<Point<2>>
      outline() const override
      {
        std::vector<Point<2>>  line;
        constexpr unsigned int samples = 128;
        for (unsigned int i = 0; i <= samples; ++i)
          {
            const double phi = 2 * numbers::PI * i / samples;
            line.push_back(
              center + radius * Tensor<1, 2>({std::cos(phi), std::sin(phi)}));
          }
        return line;
      }

      double
      size() const override
      {
        return radius;
      }

      Point<2>
      reference_point() const override
      {
        return center;
      }

    private:
      Point<2> center;
      double   radius;
    };



    /**
     * A closed cubic B-spline (BSplineCurve) as a rigid outline. Its
     * smooth stretches (between sharp corners; the whole curve if it has
     * none) and its corners are the parts that contact tells apart
     * (SurfacePoint::feature): 2 s for stretch s, 2 j + 1 for the corner
     * at point j. Like a polygon's edge, a stretch is extended beyond its
     * ends by the lines of its end tangents, and a corner is a circle of
     * radius zero about it.
     */
    class SplineShape : public RigidShape
    {
    public:
      SplineShape(const std::vector<Point<2>>     &points,
                  const std::vector<unsigned int> &corners)
        : curve(points, true, corners)
        , n_points(points.size())
        , corner(points.size(), false)
        , stretch_of(points.size(), 0)
      {
        // Point j is a corner where the segments before and after it leave
        // in different directions (marked, or detected by BSplineCurve).
        for (unsigned int j = 0; j < n_points; ++j)
          {
            const Tensor<1, 2> a = tangent(previous(j), 1.), b = tangent(j, 0.);
            corner[j] =
              std::abs(a[0] * b[1] - a[1] * b[0]) > 1e-10 || a * b < 0;
          }
        const auto first =
          std::find(corner.begin(), corner.end(), true) - corner.begin();
        if (first == n_points)
          {
            stretches.push_back({{0, n_points}});
            closed_stretch = true;
            return;
          }
        // Stretch s: segments start, start + 1, ..., start + length - 1
        // (mod n), from one corner to the next.
        for (unsigned int i = 0; i < n_points; ++i)
          {
            const unsigned int k = (first + i) % n_points;
            if (corner[k])
              stretches.push_back({{k, 0}});
            ++stretches.back()[1];
            stretch_of[k] = stretches.size() - 1;
          }
      }

      SurfacePoint
      nearest(const Point<2> &x) const override
      {
        Closest best;
        for (unsigned int k = 0; k < n_points; ++k)
          consider_segment(k, x, best);
        const unsigned int j = best.t == 0. ? best.k :
                               best.t == 1. ? next(best.k) :
                                              n_points;
        if (j < n_points && corner[j])
          {
            // The nearest point is a corner: outside where x lies on the
            // outer side of the two edges' mean normal.
            const Tensor<1, 2> r = x - best.point;
            const Tensor<1, 2> m = normal(previous(j), 1.) + normal(j, 0.);
            SurfacePoint       s;
            const bool         outside = r * m >= 0;
            s.gap     = outside ? best.distance : -best.distance;
            s.normal  = best.distance > 0 ?
                          Tensor<1, 2>((outside ? r : -r) / best.distance) :
                          normal(j, 0.);
            s.feature = outside ? 2 * j + 1 : 2 * stretch_of[j];
            if (outside)
              s.turning_radius = best.distance;
            return s;
          }
        return smooth_point(x, best, 2 * stretch_of[best.k]);
      }

      SurfacePoint
      to_feature(const Point<2> &x, const unsigned int feature) const override
      {
        if (feature % 2 == 1)
          {
            // The corner at point j as a circle of radius zero.
            const Point<2> c = curve.interpolation_points()[feature / 2];
            const double   d = (x - c).norm();
            SurfacePoint   s;
            s.feature = feature;
            s.gap     = d;
            s.normal =
              d > 0 ? Tensor<1, 2>((x - c) / d) : normal(feature / 2, 0.);
            s.turning_radius = d;
            return s;
          }
        const auto &stretch = stretches[feature / 2];
        Closest     best;
        for (unsigned int i = 0; i < stretch[1]; ++i)
          consider_segment((stretch[0] + i) % n_points, x, best);
        if (!closed_stretch)
          {
            // Beyond an end of the stretch: the line of its end tangent.
            const unsigned int last = (stretch[0] + stretch[1] - 1) % n_points;
            const bool         at_start = best.k == stretch[0] && best.t == 0.;
            const bool         at_end   = best.k == last && best.t == 1.;
            if (at_start || at_end)
              {
                const Tensor<1, 2> t =
                  at_start ? tangent(best.k, 0.) : tangent(best.k, 1.);
                if ((x - best.point) * t * (at_start ? -1. : 1.) > 0)
                  {
                    SurfacePoint s;
                    s.feature = feature;
                    s.normal  = Tensor<1, 2>({t[1], -t[0]});
                    s.gap     = (x - best.point) * s.normal;
                    return s;
                  }
              }
          }
        return smooth_point(x, best, feature);
      }

      std::vector<Point<2>>
      outline() const override
      {
        std::vector<Point<2>>  line;
        constexpr unsigned int samples = 8;
        for (unsigned int k = 0; k < n_points; ++k)
          for (unsigned int i = 0; i < samples; ++i)
            line.push_back(curve.segment_value(k, double(i) / samples));
        line.push_back(line.front());
        return line;
      }

      double
      size() const override
      {
        // A Bezier segment lies in the hull of its control points.
        double largest = 0;
        for (const auto &q : curve.control_points())
          largest = std::max(largest, (q - reference_point()).norm());
        return largest;
      }

      Point<2>
      reference_point() const override
      {
        return curve.interpolation_points()[0];
      }

    private:
      /** The nearest point found so far: segment k at local parameter t. */
      struct Closest
      {
        unsigned int k = 0;
        double       t = 0;
        Point<2>     point;
        double       distance = std::numeric_limits<double>::max();
      };

      BSplineCurve                             curve;
      unsigned int                             n_points;
      std::vector<bool>                        corner;
      std::vector<unsigned int>                stretch_of;
      std::vector<std::array<unsigned int, 2>> stretches;
      bool                                     closed_stretch = false;

      unsigned int
      next(const unsigned int k) const
      {
        return (k + 1) % n_points;
      }

      unsigned int
      previous(const unsigned int k) const
      {
        return (k + n_points - 1) % n_points;
      }

      Tensor<1, 2>
      tangent(const unsigned int k, const double t) const
      {
        Tensor<1, 2> d = curve.segment_derivative(k, t);
        if (d.norm() == 0.)
          {
            const auto &P = curve.bezier_control_points(k);
            d             = P[3] - P[0];
          }
        return d / d.norm();
      }

      /** Away from the body: the tangent turned clockwise. */
      Tensor<1, 2>
      normal(const unsigned int k, const double t) const
      {
        const Tensor<1, 2> d = tangent(k, t);
        return Tensor<1, 2>({d[1], -d[0]});
      }

      /** Updates @p best with the nearest point of segment @p k to x. */
      void
      consider_segment(const unsigned int k,
                       const Point<2>    &x,
                       Closest           &best) const
      {
        const BSplineCurve::ClosestPoint c = curve.closest_point(x, k);
        if (c.distance < best.distance)
          {
            // The segment's ends are its parameters exactly: t is 0 or 1
            // there.
            const auto u = curve.segment_parameters(k);
            best = {k, (c.u - u[0]) / (u[1] - u[0]), c.point, c.distance};
          }
      }

      /** The gap and normal at a nearest point where the outline is smooth;
       * the normal turns about the centre of curvature where the outline
       * is convex, at 1 / kappa + gap from x. */
      SurfacePoint
      smooth_point(const Point<2>    &x,
                   const Closest     &best,
                   const unsigned int feature) const
      {
        SurfacePoint s;
        s.feature            = feature;
        s.normal             = normal(best.k, best.t);
        s.gap                = (x - best.point) * s.normal;
        const Tensor<1, 2> d = curve.segment_derivative(best.k, best.t),
                           e = curve.segment_second_derivative(best.k, best.t);
        const double kappa =
          (d[0] * e[1] - d[1] * e[0]) / std::pow(d.norm(), 3);
        if (kappa > 0 && 1 / kappa + s.gap > 0)
          s.turning_radius = 1 / kappa + s.gap;
        return s;
      }
    };
  } // namespace



  namespace RigidShapes
  {
    std::shared_ptr<const RigidShape>
    polygon(const std::vector<Point<2>> &vertices, const double corner_radius)
    {
      return std::make_shared<PolygonShape>(vertices, corner_radius);
    }



    std::shared_ptr<const RigidShape>
    circle(const Point<2> &center, const double radius)
    {
      return std::make_shared<CircleShape>(center, radius);
    }



    std::shared_ptr<const RigidShape>
    spline(const std::vector<Point<2>>     &points,
           const std::vector<unsigned int> &corners)
    {
      return std::make_shared<SplineShape>(points, corners);
    }
  } // namespace RigidShapes
} // namespace bsmpm
