// BSplineCurve: local cubic interpolation (method-notes Sec. 2), checked
// against what the construction promises and against an independent
// Cox-de Boor evaluation of the knot vector (paper eqs. 10-12).
#ifndef bsmpm_tests_b_spline_curve_01_h
#define bsmpm_tests_b_spline_curve_01_h

#include <deal.II/base/quadrature_lib.h>

#include <bsmpm/geometry/b_spline_curve.h>

#include <random>
#include <sstream>

// tests.h uses deallog unqualified: the using directive must come first.
using namespace dealii;

#include "../tests.h"

#include "test_curves.h"

using namespace bsmpm;

namespace b_spline_curve_01
{
  namespace
  {
    // N_{i,p}(u) by the recursion of eqs. (11)-(12), with 0/0 = 0.
    double
    basis(const std::vector<double> &knots,
          const unsigned int         i,
          const unsigned int         p,
          const double               u)
    {
      if (p == 0)
        return (knots[i] <= u && u < knots[i + 1]) ? 1. : 0.;
      double value = 0;
      if (knots[i + p] > knots[i])
        value += (u - knots[i]) / (knots[i + p] - knots[i]) *
                 basis(knots, i, p - 1, u);
      if (knots[i + p + 1] > knots[i + 1])
        value += (knots[i + p + 1] - u) / (knots[i + p + 1] - knots[i + 1]) *
                 basis(knots, i + 1, p - 1, u);
      return value;
    }

    Point<2>
    cox_de_boor(const BSplineCurve &curve, const double u)
    {
      const std::vector<double>   knots = curve.knots();
      const std::vector<Point<2>> P     = curve.control_points();
      Point<2>                    x;
      for (unsigned int i = 0; i < P.size(); ++i)
        x += basis(knots, i, 3, u) * P[i];
      return x;
    }

    // Rounded to two decimals for printing.
    double
    round2(const double x)
    {
      return std::round(100 * x) / 100;
    }

    // Largest distance between the tangent directions on the two sides of the
    // joints between segments (the wrap included for closed curves).
    double
    tangent_jump(const BSplineCurve &curve)
    {
      double             jump = 0;
      const unsigned int n    = curve.n_segments();
      for (unsigned int k = (curve.is_closed() ? 0 : 1); k < n; ++k)
        {
          const auto &before    = curve.bezier_control_points((k + n - 1) % n);
          const auto &after     = curve.bezier_control_points(k);
          const Tensor<1, 2> t0 = (before[3] - before[2]) /
                                  (before[3] - before[2]).norm(),
                             t1 = (after[1] - after[0]) /
                                  (after[1] - after[0]).norm();
          jump = std::max(jump, (t1 - t0).norm());
        }
      return jump;
    }

    template <typename Function>
    void
    expect_throw(const std::string &what, const Function &f)
    {
      try
        {
          f();
          deallog << what << ": not thrown" << std::endl;
        }
      catch (const ExceptionBase &e)
        {
          std::ostringstream message;
          e.print_info(message);
          std::string text = message.str();
          text             = text.substr(text.find_first_not_of(' '));
          text.erase(text.find_last_not_of("\n ") + 1);
          deallog << what << ": thrown: " << text << std::endl;
        }
    }
  } // namespace



  void
  run()
  {
    // Interpolation: the curve passes through every point at the knots.
    {
      deallog.push("interpolation");
      for (const bool closed : {false, true})
        {
          const std::vector<Point<2>> points =
            closed ? circle_points(7, Point<2>(0.5, -0.25), 2) : paper_points();
          const BSplineCurve curve(points, closed);
          double             error = 0;
          for (unsigned int k = 0; k < curve.n_segments(); ++k)
            error = std::max(
              error,
              curve.value(curve.segment_parameters(k)[0]).distance(points[k]));
          error = std::max(error,
                           curve.value(1.).distance(closed ? points[0] :
                                                             points.back()));
          deallog << (closed ? "closed" : "open") << ": segments "
                  << curve.n_segments() << ", knots " << curve.knots().size()
                  << ", control points " << curve.control_points().size()
                  << ", through every point: " << yes_no(error == 0)
                  << std::endl;
        }
      deallog.pop();
    }

    // Collinear points (unevenly spaced) give a straight curve parametrised by
    // arc length, whose length is the sum of the chords.
    {
      deallog.push("straight");
      const Point<2>            A(0.1, -0.3);
      const Tensor<1, 2>        e({0.6, 0.8});
      const std::vector<double> s = {0, 0.37, 0.5, 1.3, 1.4, 2.9};
      std::vector<Point<2>>     points;
      for (const double si : s)
        points.push_back(A + si * e);
      const BSplineCurve curve(points, false);
      double             error = 0, tangent_error = 0;
      for (unsigned int i = 0; i <= 1000; ++i)
        {
          const double u = i / 1000.;
          error =
            std::max(error, curve.value(u).distance(A + u * s.back() * e));
          tangent_error = std::max(tangent_error,
                                   (curve.derivative(u) - s.back() * e).norm());
        }
      deallog << "value(u) = A + u L e to 1e-14 L: "
              << yes_no(error < 1e-14 * 2.9) << std::endl;
      deallog << "dC/du = L e to 1e-14 L: "
              << yes_no(tangent_error < 1e-14 * 2.9) << std::endl;
      deallog << "length equals the chord sum to 1e-14: "
              << yes_no(std::abs(curve.length() - 2.9) < 1e-14 * 2.9)
              << std::endl;
      deallog << "length(0.2, 0.7) = 0.5 L to 1e-14: "
              << yes_no(std::abs(curve.length(0.2, 0.7) - 1.45) < 1e-14 * 2.9)
              << std::endl;
      const auto box = curve.bounding_box().get_boundary_points();
      deallog << "bounding box: " << box.first << " to " << box.second
              << std::endl;

      // Two points only: a straight segment.
      const BSplineCurve two({A, A + e}, false);
      deallog << "two points: midpoint " << two.value(0.5) << std::endl;
      deallog.pop();
    }

    // Circle: convergence of the largest distance to the circle and of the
    // length, smoothness at the joints, orientation of the normal.
    {
      deallog.push("circle");
      const Point<2> center(0.3, -0.2);
      double         last_distance = 0, last_length = 0;
      for (unsigned int n = 8; n <= 256; n *= 2)
        {
          const BSplineCurve curve(circle_points(n, center, 1), true);
          double             distance = 0;
          bool               outward  = true;
          for (unsigned int i = 0; i <= 100 * n; ++i)
            {
              const double u = double(i) / (100 * n);
              distance =
                std::max(distance,
                         std::abs(curve.value(u).distance(center) - 1));
              outward =
                outward &&
                curve.outward_normal(u) * (curve.value(u) - center) > 0.99;
            }
          const double length_error =
            std::abs(curve.length() - 2 * numbers::PI);
          deallog << "n " << n << ": distance " << std::setprecision(3)
                  << distance << ", length error " << length_error;
          if (n > 8)
            deallog << ", rates " << round2(std::log2(last_distance / distance))
                    << " " << round2(std::log2(last_length / length_error));
          deallog << std::setprecision(8) << std::endl;
          deallog << "n " << n << ": C1 at all joints to 1e-13: "
                  << yes_no(tangent_jump(curve) < 1e-13)
                  << ", outward normal points out: " << yes_no(outward)
                  << ", self-intersecting: "
                  << yes_no(curve.is_self_intersecting()) << std::endl;
          last_distance = distance;
          last_length   = length_error;
        }

      // The wrap: same point and same derivative at u = 0 and u = 1.
      const BSplineCurve curve(circle_points(16, center, 1), true);
      deallog << "wraps: value(1) = value(0): "
              << yes_no(curve.value(1.).distance(curve.value(0.)) == 0)
              << ", derivative(1) = derivative(0) to 1e-13: "
              << yes_no((curve.derivative(1.) - curve.derivative(0.)).norm() <
                        1e-13 * curve.derivative(0.).norm())
              << std::endl;
      const auto box = curve.bounding_box().get_boundary_points();
      deallog << "bounding box is the circle's to 1e-4: "
              << yes_no(box.first.distance(Point<2>(-0.7, -1.2)) < 1e-4 &&
                        box.second.distance(Point<2>(1.3, 0.8)) < 1e-4)
              << std::endl;
      deallog.pop();
    }

    // Length against a brute-force composite Gauss rule (64 x 20 points per
    // segment), on the paper's curve and on a hairpin whose tip is close to a
    // cusp.
    {
      deallog.push("length");
      const QGauss<1> gauss(20);
      for (const bool hairpin : {false, true})
        {
          const BSplineCurve curve(hairpin ?
                                     std::vector<Point<2>>{Point<2>(0, 0),
                                                           Point<2>(1, 0),
                                                           Point<2>(1.02, 0.01),
                                                           Point<2>(0, 0.02)} :
                                     paper_points(),
                                   false);
          double brute = 0;
          for (unsigned int k = 0; k < curve.n_segments(); ++k)
            {
              const auto u = curve.segment_parameters(k);
              for (unsigned int i = 0; i < 64; ++i)
                for (unsigned int q = 0; q < gauss.size(); ++q)
                  brute += gauss.weight(q) * (u[1] - u[0]) / 64 *
                           curve
                             .derivative(u[0] + (u[1] - u[0]) *
                                                  (i + gauss.point(q)[0]) / 64)
                             .norm();
            }
          double pieces = 0;
          for (unsigned int i = 0; i < 10; ++i)
            pieces += curve.length(i / 10., (i + 1) / 10.);
          deallog << (hairpin ? "hairpin" : "paper's curve") << ": length "
                  << curve.length()
                  << ", equals the brute-force rule to 1e-14: "
                  << yes_no(std::abs(curve.length() - brute) < 1e-14 * brute)
                  << ", sum over ten parts to 1e-14: "
                  << yes_no(std::abs(curve.length() - pieces) < 1e-14 * brute)
                  << std::endl;
        }
      deallog.pop();
    }

    // Corners: a square keeps them when they are marked or when the data are
    // straight on both sides; with its four corner points only and no marks
    // it is rounded.
    {
      deallog.push("square");
      const std::vector<Point<2>> corners        = {Point<2>(0, 0),
                                                    Point<2>(2, 0),
                                                    Point<2>(2, 2),
                                                    Point<2>(0, 2)};
      const std::vector<Point<2>> with_midpoints = {Point<2>(0, 0),
                                                    Point<2>(1, 0),
                                                    Point<2>(2, 0),
                                                    Point<2>(2, 1),
                                                    Point<2>(2, 2),
                                                    Point<2>(1, 2),
                                                    Point<2>(0, 2),
                                                    Point<2>(0, 1)};
      const auto                  report         = [](const std::string  &name,
                             const BSplineCurve &curve) {
        // On the square's boundary: distance to the nearest side.
        double off = 0;
        for (unsigned int i = 0; i <= 1000; ++i)
          {
            const Point<2> x = curve.value(i / 1000.);
            off =
              std::max(off,
                       std::min(std::min(std::abs(x[0]), std::abs(x[0] - 2)),
                                std::min(std::abs(x[1]), std::abs(x[1] - 2))));
          }
        deallog << name << ": on the square: " << yes_no(off < 1e-15)
                << ", length " << filter_roundoff(curve.length() - 8) + 8
                << ", tangent jump at corners " << std::setprecision(3)
                << filter_roundoff(tangent_jump(curve)) << std::setprecision(8)
                << std::endl;
      };
      report("marked", BSplineCurve(corners, true, {0, 1, 2, 3}));
      report("detected", BSplineCurve(with_midpoints, true));
      report("unmarked", BSplineCurve(corners, true));
      report("one marked", BSplineCurve(corners, true, {2}));
      deallog.pop();
    }

    // The knot vector and control points are a true B-spline: Cox-de Boor
    // gives the same curve.
    {
      deallog.push("cox-de boor");
      std::mt19937                           generator(42);
      std::uniform_real_distribution<double> uniform(0, 1);
      for (const bool closed : {false, true})
        {
          const BSplineCurve curve(closed ? circle_points(9, Point<2>(), 1) :
                                            paper_points(),
                                   closed,
                                   closed ? std::vector<unsigned int>{3} :
                                            std::vector<unsigned int>{});
          const std::vector<double> knots = curve.knots();
          bool valid = knots.size() == 3 * curve.n_segments() + 5;
          for (unsigned int i = 0; i + 1 < knots.size(); ++i)
            valid = valid && knots[i] <= knots[i + 1];
          std::vector<double> u = {0.};
          for (unsigned int k = 1; k < curve.n_segments(); ++k)
            u.push_back(curve.segment_parameters(k)[0]);
          for (unsigned int i = 0; i < 500; ++i)
            u.push_back(uniform(generator));
          double error = 0;
          for (const double ui : u)
            error =
              std::max(error, cox_de_boor(curve, ui).distance(curve.value(ui)));
          deallog << (closed ? "closed" : "open")
                  << ": knot vector valid: " << yes_no(valid)
                  << ", same points to 1e-14: " << yes_no(error < 1e-14)
                  << std::endl;
        }
      deallog.pop();
    }

    // Closest points: on a circle they lie towards the centre, the distance
    // is stationary there, and no dense sample is closer.
    {
      deallog.push("closest point");
      const Point<2>     center(0.3, -0.2);
      const BSplineCurve curve(circle_points(64, center, 1), true);
      std::mt19937       generator(7);
      std::uniform_real_distribution<double> uniform(-2.5, 2.5);
      // The curve is within 2.5e-7 of the circle (see above), so the distance
      // must be that far from the circle's; the foot may move further along
      // the circle since the curve's slope deviates by ~64 times more.
      double max_distance = 0, max_foot = 0, max_stationary = 0, max_worse = 0;
      for (unsigned int i = 0; i < 100; ++i)
        {
          const Point<2> p =
            center + Tensor<1, 2>({uniform(generator), uniform(generator)});
          if (p.distance(center) < 0.1)
            continue;
          const auto         c      = curve.closest_point(p);
          const Tensor<1, 2> radial = (p - center) / p.distance(center);
          max_distance =
            std::max(max_distance,
                     std::abs(c.distance - std::abs(p.distance(center) - 1)));
          max_foot = std::max(max_foot, (c.point - (center + radial)).norm());
          if (c.distance > 0)
            max_stationary =
              std::max(max_stationary,
                       std::abs((c.point - p) * curve.unit_tangent(c.u)) /
                         c.distance);
          double brute = c.distance;
          for (unsigned int j = 0; j <= 20000; ++j)
            brute = std::min(brute, curve.value(j / 20000.).distance(p));
          max_worse = std::max(max_worse, c.distance - brute);
          AssertThrow(c.point.distance(curve.value(c.u)) < 1e-15,
                      ExcInternalError());
        }
      deallog << "distance is the circle's to 2.5e-7: "
              << yes_no(max_distance < 2.5e-7)
              << ", foot on the circle's radius to 1e-4: "
              << yes_no(max_foot < 1e-4)
              << ", stationary to 1e-12: " << yes_no(max_stationary < 1e-12)
              << ", no sample closer: " << yes_no(max_worse <= 0) << std::endl;

      // closest_point() skips the segments whose control boxes lie farther
      // than a distance already reached: the answer must be, to the bit, that
      // of searching every segment in order (the first of equally near ones),
      // for points far off, near and on the curve, and on an open curve.
      {
        const BSplineCurve open(paper_points(), false);
        unsigned int       n_checked = 0, n_different = 0;
        for (const BSplineCurve *c : {&curve, &open})
          for (unsigned int i = 0; i < 400; ++i)
            {
              const Point<2> p =
                i % 4 == 0 ?
                  c->value(i / 400.) :
                i % 4 == 1 ?
                  c->value(i / 400.) +
                    1e-3 *
                      Tensor<1, 2>({uniform(generator), uniform(generator)}) :
                  center +
                    Tensor<1, 2>({uniform(generator), uniform(generator)});
              auto all = c->closest_point(p, 0);
              for (unsigned int k = 1; k < c->n_segments(); ++k)
                {
                  const auto ck = c->closest_point(p, k);
                  if (ck.distance < all.distance)
                    all = ck;
                }
              const auto found = c->closest_point(p);
              n_different += found.u != all.u || found.point != all.point ||
                             found.distance != all.distance;
              ++n_checked;
            }
        deallog << "skipping far segments, " << n_checked
                << " points: answers differing from the full search "
                << n_different << std::endl;
      }

      // Beyond the ends of an open straight chain: the ends.
      const BSplineCurve line({Point<2>(0, 0), Point<2>(1, 0), Point<2>(2, 0)},
                              false);
      const auto         a = line.closest_point(Point<2>(-1, 1));
      const auto         b = line.closest_point(Point<2>(2.5, -1));
      const auto         m = line.closest_point(Point<2>(0.75, 3));
      deallog << "line: u " << a.u << " " << b.u << " " << m.u << ", distances "
              << a.distance << " " << b.distance << " " << m.distance
              << std::endl;
      deallog.pop();
    }

    // Self-intersection: a figure eight crosses itself.
    {
      deallog.push("self-intersection");
      std::vector<Point<2>> eight;
      for (unsigned int i = 0; i < 16; ++i)
        {
          const double phi = 2 * numbers::PI * i / 16;
          eight.emplace_back(std::sin(phi), std::sin(phi) * std::cos(phi));
        }
      deallog << "figure eight: "
              << yes_no(BSplineCurve(eight, true).is_self_intersecting())
              << ", paper's curve: "
              << yes_no(
                   BSplineCurve(paper_points(), false).is_self_intersecting())
              << std::endl;
      deallog.pop();
    }

    // Bad input.
    {
      deallog.push("bad input");
      const Point<2> a(0, 0), b(1, 0), c(1, 1);
      expect_throw("one point", [&]() { BSplineCurve({a}, false); });
      expect_throw("two points closed", [&]() { BSplineCurve({a, b}, true); });
      expect_throw("duplicate", [&]() { BSplineCurve({a, b, b, c}, false); });
      expect_throw("first repeated", [&]() {
        BSplineCurve({a, b, c, a}, true);
      });
      expect_throw("not finite", [&]() {
        BSplineCurve({a, Point<2>(std::nan(""), 0), c}, false);
      });
      expect_throw("corner index", [&]() {
        BSplineCurve({a, b, c}, true, {3});
      });
      deallog.pop();
    }
  }
} // namespace b_spline_curve_01

#endif
