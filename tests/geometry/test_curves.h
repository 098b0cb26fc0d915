// The curves of the geometry tests' parts: the points of the paper's
// Sec. 4.4 boundary, and n points on a circle.
#ifndef bsmpm_tests_test_curves_h
#define bsmpm_tests_test_curves_h

#include <deal.II/base/numbers.h>
#include <deal.II/base/point.h>

#include <cmath>
#include <vector>

inline std::vector<dealii::Point<2>>
paper_points()
{
  const double x[] = {0, 0.1, 0.35, 0.6, 0.73, 1, 1.5, 1.75, 2, 1.78, 1.5};
  const double y[] = {
    1.5, 1.75, 1.95, 1.8, 1.31, 1.15, 1.35, 1.3, 0.75, 0.21, 0};
  std::vector<dealii::Point<2>> points;
  for (unsigned int i = 0; i < 11; ++i)
    points.emplace_back(x[i], y[i]);
  return points;
}

inline std::vector<dealii::Point<2>>
circle_points(const unsigned int      n,
              const dealii::Point<2> &center,
              const double            r)
{
  std::vector<dealii::Point<2>> points;
  for (unsigned int i = 0; i < n; ++i)
    {
      const double phi = 2 * dealii::numbers::PI * i / n;
      points.emplace_back(center[0] + r * std::cos(phi),
                          center[1] + r * std::sin(phi));
    }
  return points;
}

#endif
