// The closed curves of the geometry tests' parts: n points on a circle.
#ifndef bsmpm_tests_circle_points_h
#define bsmpm_tests_circle_points_h

#include <deal.II/base/numbers.h>
#include <deal.II/base/point.h>

#include <cmath>
#include <vector>

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
