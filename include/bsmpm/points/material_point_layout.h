#ifndef bsmpm_material_point_layout_h
#define bsmpm_material_point_layout_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>

#include <bsmpm/geometry/background_grid.h>
#include <bsmpm/geometry/body_region.h>

#include <functional>

namespace bsmpm
{
  using namespace dealii;

  /**
   * Where the material points start and what volume each one carries.
   *
   * - per cell: n x n points at the centres of the n x n sub-squares of every
   *   grid cell, each with volume (cell area)/n^2, kept where inside the body.
   * - lattice: nx x ny points at the centres of the sub-rectangles of a
   *   rectangle (by default the body's bounding box), each with its
   *   sub-rectangle's area, kept where inside the body.
   * - polar: n_r x n_theta points at the centres (mid radius, mid angle) of
   *   the polar sub-cells of an annulus-sector body, each with its sub-cell's
   *   exact area.
   * - cell centroid: one point per cell at the centroid of the part of the
   *   cell inside a (rotated) rectangular body, with that part's area: the
   *   points then integrate functions linear in each cell exactly, so a
   *   constant-stress state is in equilibrium to round-off even in partly
   *   filled cells.
   *
   * Every candidate point has an index in the layout's enumeration (whether
   * the body holds it or not): a partition-independent particle id.
   */
  class MaterialPointLayout
  {
  public:
    enum class Kind
    {
      per_cell,
      lattice,
      polar,
      cell_centroid
    };

    static void
    declare_parameters(ParameterHandler &prm);
    void
    parse_parameters(ParameterHandler &prm);

    /** Cell index (i, j) of the grid. */
    using CellIndex = std::array<unsigned int, 2>;

    /**
     * Calls @p f(position, volume, index) for every point of the layout that
     * lies in @p region, except points in grid cells for which @p wanted_cell
     * is false (points outside the grid are always passed on, so that the
     * caller can reject them).
     */
    void
    for_each_point(
      const BackgroundGrid                         &grid,
      const BodyRegion                             &region,
      const std::function<bool(const CellIndex &)> &wanted_cell,
      const std::function<void(const Point<2> &, double, unsigned long)> &f)
      const;

    /** One more than the largest index for_each_point() can give. */
    unsigned long
    n_candidates(const BackgroundGrid &grid) const;


    Kind
    kind() const
    {
      return layout;
    }

  private:
    using WantedCell = std::function<bool(const CellIndex &)>;
    using PointVisitor =
      std::function<void(const Point<2> &, double, unsigned long)>;

    /** for_each_point() of the layout "per cell": n x n points at the
     * centres of equal sub-cells of each wanted cell, each with its
     * sub-cell's volume. */
    void
    for_each_point_per_cell(const BackgroundGrid &grid,
                            const BodyRegion     &region,
                            const WantedCell     &wanted_cell,
                            const PointVisitor   &f) const;

    /** "lattice": the centres of a regular lattice over the body's
     * bounding box or the given rectangle, each with its lattice cell's
     * volume. */
    void
    for_each_lattice_point(const BackgroundGrid &grid,
                           const BodyRegion     &region,
                           const WantedCell     &wanted_cell,
                           const PointVisitor   &f) const;

    /** "cell centroid": one point per wanted cell at the centroid of the
     * cell's part of a (rotated) rectangle, with that part's area. */
    void
    for_each_cell_centroid(const BackgroundGrid &grid,
                           const BodyRegion     &region,
                           const WantedCell     &wanted_cell,
                           const PointVisitor   &f) const;

    /** "polar": the centres of a polar grid over an annulus sector, each
     * with its polar cell's exact area. */
    void
    for_each_polar_point(const BackgroundGrid &grid,
                         const BodyRegion     &region,
                         const WantedCell     &wanted_cell,
                         const PointVisitor   &f) const;

    Kind                        layout          = Kind::per_cell;
    unsigned int                points_per_cell = 2;
    std::array<unsigned int, 2> lattice_points  = {{1, 1}};
    std::string                 lattice_lower_left, lattice_upper_right;
    std::array<unsigned int, 2> polar_points = {{1, 1}};
  };
} // namespace bsmpm

#endif
