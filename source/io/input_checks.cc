#include <deal.II/base/exceptions.h>

#include <bsmpm/io/input_checks.h>

#include <cmath>
#include <fstream>
#include <iomanip>
#include <sstream>

namespace bsmpm
{
  namespace
  {
    std::string
    format(const Point<2> &p)
    {
      std::ostringstream s;
      s << '(' << p[0] << ", " << p[1] << ')';
      return s.str();
    }

    std::string
    bytes(const double b)
    {
      std::ostringstream s;
      s << std::setprecision(3) << b / 1e9 << " GB";
      return s.str();
    }

    /** How far @p p lies outside the grid, per direction (0 inside). */
    Tensor<1, 2>
    outside(const BackgroundGrid &grid, const Point<2> &p)
    {
      Tensor<1, 2> d;
      for (unsigned int k = 0; k < 2; ++k)
        d[k] = std::max(
          {grid.lower_left()[k] - p[k], p[k] - grid.upper_right()[k], 0.});
      return d;
    }
  } // namespace



  double
  InputChecks::available_memory()
  {
    std::ifstream in("/proc/meminfo");
    std::string   key;
    double        value;
    std::string   unit;
    while (in >> key >> value >> unit)
      if (key == "MemAvailable:")
        return value * 1024;
    return 0;
  }



  InputChecks::Estimate
  InputChecks::estimate(const BackgroundGrid      &grid,
                        const BodyRegion          &region,
                        const MaterialPointLayout &layout)
  {
    Estimate e;
    e.n_cells = double(grid.n_cells(0)) * grid.n_cells(1);
    // Cells the body's bounding box covers, at most the grid's.
    const auto   box        = region.bounding_box().get_boundary_points();
    const double body_cells = std::min(
      e.n_cells,
      (std::ceil((box.second[0] - box.first[0]) / grid.cell_size()[0]) + 1) *
        (std::ceil((box.second[1] - box.first[1]) / grid.cell_size()[1]) + 1));
    switch (layout.kind())
      {
        case MaterialPointLayout::Kind::per_cell:
          e.n_points = body_cells * double(layout.n_candidates(grid)) /
                       std::max(e.n_cells, 1.);
          break;
        case MaterialPointLayout::Kind::cell_centroid:
          e.n_points = body_cells;
          break;
        default:
          e.n_points = double(layout.n_candidates(grid));
      }
    e.memory =
      bytes_fixed + e.n_cells * bytes_per_cell + e.n_points * bytes_per_point;
    return e;
  }



  void
  InputChecks::check(
    const BackgroundGrid                                &grid,
    const BodyRegion                                    &region,
    const MaterialPointLayout                           &layout,
    const BoundaryCurves                                &curves,
    const std::vector<std::pair<std::string, Point<2>>> &named_points)
  {
    const Estimate     e = estimate(grid, region, layout);
    std::ostringstream what;
    what << std::setprecision(3) << e.n_cells << " cells and about "
         << e.n_points << " material points";
    AssertThrow(e.n_cells < 2e9,
                ExcMessage("Background grid: " + what.str() +
                           " are beyond what bsmpm can index (2e9 cells). "
                           "Use a larger cell size."));
    const double available = available_memory();
    AssertThrow(available == 0 || e.memory <= available,
                ExcMessage("The run would need about " + bytes(e.memory) +
                           " of memory for " + what.str() +
                           ", but the machine has " + bytes(available) +
                           " available. Use a larger cell size or fewer "
                           "points per cell."));

    // The body and every given point inside the grid.
    const double tolerance =
      1e-12 * (grid.upper_right() - grid.lower_left()).norm();
    // The body's outer boundary, sampled (its bounding box may be rounded
    // outwards).
    for (const auto &corner : region.boundary_points("boundary", 721).points)
      {
        const Tensor<1, 2> d = outside(grid, corner);
        AssertThrow(
          d.norm() <= tolerance,
          ExcMessage("Body region: the body reaches " + format(corner) +
                     ", outside the background "
                     "grid " +
                     format(grid.lower_left()) + " - " +
                     format(grid.upper_right()) + " by " + format(Point<2>(d)) +
                     ". Enlarge the grid (Background grid/Lower "
                     "left corner, Upper right corner)."));
      }
    std::vector<std::pair<std::string, Point<2>>> points = named_points;
    for (const auto &[name, given] : curves.given_points())
      for (const auto &p : given)
        points.emplace_back("Boundary curves/" + name, p);
    for (const auto &[name, p] : points)
      {
        const Tensor<1, 2> d = outside(grid, p);
        AssertThrow(d.norm() <= tolerance,
                    ExcMessage(name + ": the point " + format(p) +
                               " lies outside the background grid " +
                               format(grid.lower_left()) + " - " +
                               format(grid.upper_right()) + " by " +
                               format(Point<2>(d)) + ". Enlarge the grid."));
      }
  }


  void
  InputChecks::check_supports(const BackgroundGrid &grid,
                              const BoundaryCurves &curves,
                              const bool            rigid_bodies)
  {
    const bool curve_supports = curves.has_supports();
    AssertThrow(grid.has_face_conditions() || curve_supports || rigid_bodies,
                ExcMessage("The body has no support at all: no grid face "
                           "condition, no fixed, roller or displacement "
                           "condition on a boundary curve and no rigid body "
                           "to rest on. Its stiffness cannot resist rigid "
                           "motion; add a support."));
  }
} // namespace bsmpm
