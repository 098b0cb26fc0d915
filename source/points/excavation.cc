#include <bsmpm/geometry/b_spline_curve.h>
#include <bsmpm/geometry/body_region.h>
#include <bsmpm/points/excavation.h>
#include <bsmpm/points/material_points.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <sstream>

namespace bsmpm
{
  types::particle_index
  Excavation::remove(const std::vector<Point<2>> &polygon,
                     MaterialPoints              &points,
                     const BackgroundGrid        &grid,
                     const std::vector<Point<2>> &kept_points,
                     const std::string           &where)
  {
    AssertThrow(polygon.size() >= 3,
                ExcMessage(where + ": an excavation is a region of at "
                                   "least 3 points 'x0, y0; x1, y1; ...'."));
    // Within a cell of the polygon: inside it, or nearer than h to an edge.
    const double h = grid.min_cell_size();
    for (const Point<2> &x : kept_points)
      if (polygon_contains(polygon, x) ||
          nearest_on_polygon(polygon, x).distance < h)
        {
          std::ostringstream message;
          message << where << ": the excavated region reaches the "
                  << "tracked point (" << x
                  << ") of a boundary curve or the probe. Only a closed "
                     "curve of tracking points without rigid bodies in the "
                     "scene follows the cut's face: keep other curves and "
                     "the probe more than a cell away from the region.";
          AssertThrow(false, ExcMessage(message.str()));
        }
    forces.clear();
    return points.remove_points(
      [&](const Point<2> &x) { return polygon_contains(polygon, x); });
  }



  std::vector<Point<2>>
  Excavation::region_outline(const std::vector<Point<2>> &points,
                             const bool                   spline,
                             const double                 spacing,
                             const std::string           &where)
  {
    AssertThrow(points.size() >= 3,
                ExcMessage(where + ": an excavation is a region of at "
                                   "least 3 points 'x0, y0; x1, y1; ...'."));
    if (!spline)
      return points;
    std::unique_ptr<BSplineCurve> curve;
    try
      {
        curve = std::make_unique<BSplineCurve>(points, true);
      }
    catch (const ExceptionBase &e)
      {
        std::ostringstream message;
        e.print_info(message);
        AssertThrow(false, ExcMessage(where + ": " + message.str()));
      }
    std::vector<Point<2>> outline;
    for (unsigned int k = 0; k < curve->n_segments(); ++k)
      {
        const auto         range = curve->segment_parameters(k);
        const unsigned int n     = std::max(
          4u,
          static_cast<unsigned int>(std::ceil(
            points[k].distance(points[(k + 1) % points.size()]) / spacing)));
        for (unsigned int i = 0; i < n; ++i)
          outline.push_back(
            curve->value(range[0] + (range[1] - range[0]) * i / n));
      }
    return outline;
  }



  void
  Excavation::release(const TrilinosWrappers::MPI::Vector &out_of_balance)
  {
    forces = out_of_balance;
    forces *= -1.;
  }



  void
  Excavation::add_released_forces(const double                     factor,
                                  const AffineConstraints<double> &constraints,
                                  TrilinosWrappers::MPI::Vector   &rhs) const
  {
    if (factor == 0 || forces.size() == 0)
      return;
    TrilinosWrappers::MPI::Vector released(forces);
    released *= factor;
    constraints.set_zero(released);
    rhs.add(1., released);
  }
} // namespace bsmpm
