#ifndef bsmpm_polygon_area_h
#define bsmpm_polygon_area_h

#include <deal.II/base/point.h>

#include <utility>
#include <vector>

namespace bsmpm
{
  using namespace dealii;

  /**
   * The signed area of the closed polygon @p polygon (positive
   * counter-clockwise; the last point joins the first) and its first
   * moment about the origin, by the shoelace formulas: the centroid is the
   * second divided by the first.
   */
  inline std::pair<double, Tensor<1, 2>>
  polygon_area_and_moment(const std::vector<Point<2>> &polygon)
  {
    double       area = 0;
    Tensor<1, 2> moment;
    for (unsigned int m = 0; m < polygon.size(); ++m)
      {
        const Point<2> &p = polygon[m];
        const Point<2> &q = polygon[(m + 1) % polygon.size()];
        const double    a = p[0] * q[1] - q[0] * p[1];
        area += a / 2;
        moment += a / 6 * (p + q);
      }
    return {area, moment};
  }
} // namespace bsmpm

#endif
