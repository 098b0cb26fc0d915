#ifndef bsmpm_cut_cell_quadrature_h
#define bsmpm_cut_cell_quadrature_h

#include <deal.II/base/parameter_handler.h>

#include <bsmpm/boundary/boundary_curves.h>
#include <bsmpm/geometry/background_grid.h>
#include <bsmpm/geometry/cut_cell_geometry.h>
#include <bsmpm/points/material_points.h>
#include <bsmpm/points/q1_cell_kernel.h>

#include <map>
#include <string>
#include <vector>

namespace bsmpm
{
  using namespace dealii;

  /**
   * Material-point quadrature in the cells that the body's boundary cuts
   * (beyond the paper; method-notes Sec. 9, doc/cut-cells.md).
   *
   * Plain MPM integrates a cell by its points with their physical volumes.
   * In a cut cell these volumes and their moments are not those of the part
   * of the cell inside the body, so the discrete equations are inconsistent
   * there: a constant-stress patch is not reproduced. When the boundary
   * curves enclose the body, this class takes the exact part K ∩ Ω of every
   * cut cell from the curves (CutCellGeometry) and
   *
   * - sets the cell's volume moments (stiffness, body force) to the exact
   *   ones;
   * - integrates the stress of the points with weights fitted to the exact
   *   moments (MomentFitting), so that the internal force of a linear stress
   *   field is exact; where the points can only carry the area and centroid
   *   (or the area), the missing first moments are completed with the
   *   cell's mean stress, so a constant stress stays exact;
   * - gives a cut cell that holds no point the exact moments and the
   *   stress of its neighbours, interpolated from the grid (a lumped
   *   projection of the points' stresses).
   *
   * The physical volumes (and masses) of the points do not change. Cells
   * that are full or empty keep the plain quadrature.
   */
  class CutCellQuadrature
  {
  public:
    static void
    declare_parameters(ParameterHandler &prm);
    void
    parse_parameters(ParameterHandler &prm);

    /**
     * Decides whether the cut-cell quadrature applies to @p curves: it is
     * selected and the curves enclose the body
     * (BoundaryCurves::encloses_body()).
     */
    void
    initialize(const BoundaryCurves &curves);

    /** Turns the cut-cell quadrature off for the @p reason (reason_off()). */
    void
    switch_off(const std::string &reason)
    {
      is_active = false;
      why_off   = reason;
    }

    /** Whether the cut cells are integrated by fitted weights. */
    bool
    active() const
    {
      return is_active;
    }

    /** Why the cut-cell quadrature is off (empty if it is on). */
    const std::string &
    reason_off() const
    {
      return why_off;
    }

    /** Recomputes the geometry from the current curves. */
    void
    update_geometry(const BoundaryCurves &curves, const BackgroundGrid &grid);

    const CutCellGeometry &
    geometry() const
    {
      return cut_geometry;
    }

    /**
     * Replaces the moments (from MaterialPoints::compute_cell_moments()) of
     * the locally owned cut cells in @p moments by the consistent ones.
     * Points that store an inelastic state (a nonlinear constitutive model
     * integrates with them point by point) receive their quadrature weight,
     * MaterialPoints::Property::weight: the fitted one, or their volume.
     */
    void
    correct_cell_moments(MaterialPoints           &points,
                         const BackgroundGrid     &grid,
                         std::vector<CellMoments> &moments);

    /**
     * The fraction of every locally owned cell (by active_cell_index()) that
     * the body fills: from the geometry where the cut cells are integrated
     * by fitted weights, else the points' volume in @p moments over the
     * cell's area (0 for every cell while @p moments is empty).
     */
    std::vector<double>
    fill_fractions(const BackgroundGrid           &grid,
                   const std::vector<CellMoments> &moments) const;

    /** Counts of the last correct_cell_moments() over all processes: cut
     * cells, cells fitted with 6, 3, 1 moments, cut cells without points,
     * cells with points that the geometry finds empty. */
    std::map<std::string, double>
    statistics() const
    {
      return counts;
    }

  private:
    /** What correct_cell_moments() did on this process. */
    struct FitCounts
    {
      unsigned int n_cut = 0;
      /** Cut cells by the number of moments their points' weights fit. */
      unsigned int n_fitted[7] = {0, 0, 0, 0, 0, 0, 0};
      /** Cells with points that the geometry finds empty. */
      unsigned int n_outside = 0;
      /** Full cells whose points' weights had to be fitted. */
      unsigned int n_full_fit = 0;
    };

    /**
     * The consistent moments @p m of the locally owned @p cell (on entry
     * the points' own) and its points' weights; false, @p m holding the
     * exact volume moments alone, for a cell of the body without points
     * (fill_cells_without_points()).
     */
    bool
    fit_cell(MaterialPoints                            &points,
             const BackgroundGrid                      &grid,
             const DoFHandler<2>::active_cell_iterator &cell,
             CellMoments                               &m,
             FitCounts                                 &n) const;

    /** The stress moments of the cells @p cells of the body without
     * points (collective): the stress of the neighbourhood at the
     * centroid of K ∩ Ω, from a lumped projection of the points' stresses
     * onto the grid's vertices. */
    void
    fill_cells_without_points(
      const MaterialPoints                            &points,
      const BackgroundGrid                            &grid,
      const std::vector<DoFHandler<2>::cell_iterator> &cells,
      std::vector<CellMoments>                        &moments) const;

    bool                          use_moment_fitting = true;
    bool                          is_active          = false;
    std::string                   why_off;
    CutCellGeometry               cut_geometry;
    std::map<std::string, double> counts;
  };
} // namespace bsmpm

#endif
