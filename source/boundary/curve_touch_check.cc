#include <bsmpm/boundary/boundary_curves.h>
#include <bsmpm/boundary/curve_touch_check.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>

namespace bsmpm
{
  namespace
  {
    /** A straight piece of a curve: half a spline segment. */
    struct Chord
    {
      unsigned int curve;
      unsigned int segment;
      Point<2>     a, b;
      /** Length of the boundary from the curve's first point to a. */
      double arc;
    };

    /** The point of segment [a, b] nearest to p. */
    Point<2>
    nearest_on(const Point<2> &p, const Point<2> &a, const Point<2> &b)
    {
      const Tensor<1, 2> d  = b - a;
      const double       dd = d.norm_square();
      const double       t = dd > 0 ? std::clamp((p - a) * d / dd, 0., 1.) : 0.;
      return a + t * d;
    }

    /** Distance of two chords and the middle of their nearest points. */
    std::pair<double, Point<2>>
    chord_distance(const Chord &p, const Chord &q)
    {
      // Crossing: the ends of each lie on both sides of the other.
      const auto side =
        [](const Point<2> &o, const Point<2> &e, const Point<2> &x) {
          const Tensor<1, 2> u = e - o, v = x - o;
          return u[0] * v[1] - u[1] * v[0];
        };
      const double s1 = side(p.a, p.b, q.a), s2 = side(p.a, p.b, q.b);
      const double s3 = side(q.a, q.b, p.a), s4 = side(q.a, q.b, p.b);
      if (((s1 > 0 && s2 < 0) || (s1 < 0 && s2 > 0)) &&
          ((s3 > 0 && s4 < 0) || (s3 < 0 && s4 > 0)))
        {
          const double t = s3 / (s3 - s4);
          return {0., p.a + t * (p.b - p.a)};
        }
      std::pair<double, Point<2>> best{std::numeric_limits<double>::max(),
                                       Point<2>()};
      const auto consider = [&](const Point<2> &x, const Point<2> &y) {
        const double d = x.distance(y);
        if (d < best.first)
          best = {d, Point<2>((x[0] + y[0]) / 2, (x[1] + y[1]) / 2)};
      };
      consider(p.a, nearest_on(p.a, q.a, q.b));
      consider(p.b, nearest_on(p.b, q.a, q.b));
      consider(q.a, nearest_on(q.a, p.a, p.b));
      consider(q.b, nearest_on(q.b, p.a, p.b));
      return best;
    }
  } // namespace



  void
  CurveTouchCheck::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Self contact");
    prm.declare_entry("Check",
                      "true",
                      Patterns::Bool(),
                      "Stop the run, naming the load step, the curves, "
                      "their points and the place, when after a load "
                      "increment a boundary curve crosses itself or "
                      "another curve, or comes closer to it than "
                      "'Distance' where the two parts are not neighbours "
                      "along the boundary: bsmpm has no contact of a body "
                      "with itself.");
    prm.declare_entry("Distance",
                      "0.01",
                      Patterns::Double(0.),
                      "How close (as a fraction of the cell size h) two "
                      "parts of the boundary may come: parts closer than "
                      "this whose boundary between them is longer than "
                      "three times it touch.");
    prm.leave_subsection();
  }



  void
  CurveTouchCheck::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Self contact");
    check    = prm.get_bool("Check");
    distance = prm.get_double("Distance");
    prm.leave_subsection();
  }



  std::string
  CurveTouchCheck::find_touch(const std::vector<BoundaryCurve> &curves,
                              const double                      h) const
  {
    if (!check)
      return "";
    const double touch = distance * h;
    const double apart = 3 * touch;

    std::vector<Chord>  chords;
    std::vector<double> length(curves.size(), 0.);
    for (unsigned int c = 0; c < curves.size(); ++c)
      {
        const BoundaryCurve &curve = curves[c];
        if (!curve.spline)
          continue;
        for (unsigned int s = 0; s < curve.spline->n_segments(); ++s)
          {
            const auto     range = curve.spline->segment_parameters(s);
            const Point<2> x0    = curve.spline->value(range[0]);
            const Point<2> x1 = curve.spline->value((range[0] + range[1]) / 2);
            const Point<2> x2 = curve.spline->value(range[1]);
            chords.push_back({c, s, x0, x1, length[c]});
            length[c] += x0.distance(x1);
            chords.push_back({c, s, x1, x2, length[c]});
            length[c] += x1.distance(x2);
          }
      }

    // Where two curves meet: an end of each at the same place.
    const auto meet = [&](const unsigned int c,
                          const bool         c_end,
                          const unsigned int d,
                          const bool         d_end) {
      const auto &p = curves[c].positions, &q = curves[d].positions;
      if (curves[c].closed || curves[d].closed || p.empty() || q.empty())
        return false;
      return (c_end ? p.back() : p.front())
               .distance(d_end ? q.back() : q.front()) <= 1e-9 * h;
    };
    const auto chord_length = [](const Chord &k) { return k.a.distance(k.b); };
    // Whether the boundary between chords p and q is shorter than 'apart'.
    const auto neighbours = [&](const Chord &p, const Chord &q) {
      if (p.curve == q.curve)
        {
          const Chord &first   = p.arc <= q.arc ? p : q;
          const Chord &second  = p.arc <= q.arc ? q : p;
          double       between = second.arc - first.arc - chord_length(first);
          if (curves[p.curve].closed)
            between = std::min(between,
                               length[p.curve] - second.arc -
                                 chord_length(second) + first.arc);
          return between < apart;
        }
      // Through a point where the two curves meet.
      for (const bool p_end : {false, true})
        for (const bool q_end : {false, true})
          if (meet(p.curve, p_end, q.curve, q_end))
            {
              const double to_p =
                p_end ? length[p.curve] - p.arc - chord_length(p) : p.arc;
              const double to_q =
                q_end ? length[q.curve] - q.arc - chord_length(q) : q.arc;
              if (to_p + to_q < apart)
                return true;
            }
      return false;
    };

    // Chords into buckets of size h (a chord in every bucket its box,
    // grown by the touching distance, overlaps); each pair compared once.
    std::map<std::pair<long, long>, std::vector<unsigned int>> buckets;
    std::vector<unsigned int> seen(chords.size(), chords.size());
    for (unsigned int i = 0; i < chords.size(); ++i)
      {
        const Chord &p      = chords[i];
        const auto   bucket = [&](const double v) {
          return static_cast<long>(std::floor(v / h));
        };
        const long x0 = bucket(std::min(p.a[0], p.b[0]) - touch);
        const long x1 = bucket(std::max(p.a[0], p.b[0]) + touch);
        const long y0 = bucket(std::min(p.a[1], p.b[1]) - touch);
        const long y1 = bucket(std::max(p.a[1], p.b[1]) + touch);
        for (long bx = x0; bx <= x1; ++bx)
          for (long by = y0; by <= y1; ++by)
            {
              auto &list = buckets[{bx, by}];
              for (const unsigned int j : list)
                {
                  if (seen[j] == i)
                    continue;
                  seen[j]               = i;
                  const Chord &q        = chords[j];
                  const auto [d, where] = chord_distance(q, p);
                  if (d >= touch || neighbours(q, p))
                    continue;
                  const auto points = [&](const Chord &k) {
                    const unsigned int n = curves[k.curve].positions.size();
                    return std::to_string(k.segment) + " and " +
                           std::to_string((k.segment + 1) % n);
                  };
                  std::ostringstream message;
                  message
                    << "Boundary curves/" << curves[q.curve].name
                    << (q.curve == p.curve ? " touches itself" :
                                             " touches " + curves[p.curve].name)
                    << ": its segment between points " << points(q)
                    << " and the segment between points " << points(p)
                    << (q.curve == p.curve ? "" : " of " + curves[p.curve].name)
                    << (d == 0 ? " cross" : " come within ");
                  if (d > 0)
                    message << d;
                  message << " at (" << where[0] << ", " << where[1]
                          << "). bsmpm has no contact of a body with "
                             "itself: the body folds onto itself there (a "
                             "deep penetration that closes the soil over "
                             "the footing, a corner turned inside out). "
                             "Use more load steps or a finer grid if the "
                             "fold is spurious, or stop the load before "
                             "it; 'Boundary curves/Self contact/Distance' "
                             "sets how close parts may come ("
                          << distance << " h).";
                  return message.str();
                }
              list.push_back(i);
            }
      }
    return "";
  }
} // namespace bsmpm
