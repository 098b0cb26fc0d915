#ifndef bsmpm_input_checks_h
#define bsmpm_input_checks_h

#include <deal.II/base/point.h>

#include <bsmpm/boundary/boundary_curves.h>
#include <bsmpm/geometry/background_grid.h>
#include <bsmpm/geometry/body_region.h>
#include <bsmpm/points/material_point_layout.h>

#include <string>
#include <utility>
#include <vector>

namespace bsmpm
{
  using namespace dealii;

  /**
   * Checks of a scene made before anything is built, so that a run that
   * cannot work stops at once with a message that names the cause, instead
   * of clipping the body, hanging on an absurd grid or failing late:
   *
   * - the body region, the given points of every curve and every named
   *   point (the probe) lie inside the grid; the message names what sticks
   *   out and by how much;
   * - the number of cells and points and the memory they need, estimated
   *   from the parameters, fit the machine: the estimate is compared with
   *   the memory available (/proc/meminfo) and the run refused with the
   *   figures if it does not fit.
   */
  class InputChecks
  {
  public:
    /** What a run will hold, estimated from its parameters. */
    struct Estimate
    {
      double n_cells  = 0;
      double n_points = 0;
      /** Bytes, all processes together. */
      double memory = 0;
    };

    /** Bytes per cell and per point, and the fixed part of a process, as
     * measured with CG + AMG (doc/benchmarks.md): the peak of a run grows by
     * about this much. A direct solver needs more. */
    static constexpr double bytes_per_cell  = 2000;
    static constexpr double bytes_per_point = 300;
    static constexpr double bytes_fixed     = 150e6;

    static Estimate
    estimate(const BackgroundGrid      &grid,
             const BodyRegion          &region,
             const MaterialPointLayout &layout);

    /** Runs all checks; throws an error with a message if one fails.
     * @p named_points: points that must lie in the grid, with their
     * parameter names. */
    static void
    check(const BackgroundGrid                                &grid,
          const BodyRegion                                    &region,
          const MaterialPointLayout                           &layout,
          const BoundaryCurves                                &curves,
          const std::vector<std::pair<std::string, Point<2>>> &named_points);

    /** Throws if nothing holds the body against rigid motion: no face
     * condition of @p grid, no support on @p curves and no
     * @p rigid_bodies (contact may hold it; if it does not, the first
     * linear solve says so). */
    static void
    check_supports(const BackgroundGrid &grid,
                   const BoundaryCurves &curves,
                   const bool            rigid_bodies);

    /** MemAvailable of /proc/meminfo in bytes, or 0 if unknown. */
    static double
    available_memory();
  };
} // namespace bsmpm

#endif
