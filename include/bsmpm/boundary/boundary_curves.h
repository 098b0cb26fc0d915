#ifndef bsmpm_boundary_curves_h
#define bsmpm_boundary_curves_h

#include <deal.II/base/parameter_handler.h>

#include <bsmpm/boundary/boundary_curve.h>
#include <bsmpm/boundary/boundary_point_spacing.h>
#include <bsmpm/boundary/curve_condition.h>
#include <bsmpm/boundary/curve_touch_check.h>
#include <bsmpm/geometry/b_spline_curve.h>
#include <bsmpm/geometry/background_grid.h>
#include <bsmpm/geometry/body_region.h>
#include <bsmpm/geometry/curve_cell_intersection.h>
#include <bsmpm/points/material_points.h>
#include <bsmpm/verification/exact_solution.h>

#include <array>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace bsmpm
{
  using namespace dealii;

  /**
   * The boundary of the body as B-spline curves (paper Sec. 3.2): where their
   * points come from, how they move, and their rebuilding and cutting by the
   * grid at every load step (paper Sec. 3.3). Curves are global: their few
   * points are gathered on every process, which builds the same splines.
   *
   * A curve is declared in a subsection "Curve 1" ... "Curve 8" of "Boundary
   * curves"; see declare_parameters() for its entries.
   */
  class BoundaryCurves
  {
  public:
    static constexpr unsigned int max_curves = 8;
    /** Most tracking points per region edge ("Number of points"): far
     * more than any grid resolves, few enough to build in a moment. */
    static constexpr int max_points_per_edge = 100000;

    static void
    declare_parameters(ParameterHandler &prm);
    /** Reads the curves; also reads "Exact solution/Name" (declared by the
     * Scene) to refuse conditions that need an exact solution without one. */
    void
    parse_parameters(ParameterHandler &prm);

    /** Where @p prm defines no curve: sets Curve 1 to a free closed curve
     * round the boundary of @p region, with tracking points about
     * @p cell_size apart on its longest part (finite strain: the cut-cell
     * quadrature then follows the moving body). Call before
     * parse_parameters(). */
    static void
    enclose_body_region(ParameterHandler &prm,
                        const BodyRegion &region,
                        const double      cell_size);

    bool
    empty() const
    {
      return curves.empty();
    }

    /**
     * Whether a material point at @p p (in the grid) is cut away by a
     * trimming curve: it lies on the outer side of it. Only points in cells
     * that a trimming curve cuts need a closest-point search; every other
     * cell lies wholly on one side, decided once by its centre.
     */
    bool
    trims(const Point<2> &p) const;

    /**
     * Builds the initial splines of the curves whose points are given
     * directly (coordinates, a file, the edges of the body region): they
     * must exist before the material points, to trim them. With
     * @p complete, free curves close the region's boundary where the
     * given ones leave it open (complete_region_boundary()).
     */
    void
    create_initial_curves(const BodyRegion     &region,
                          const BackgroundGrid &grid,
                          const bool            complete = true);

    /**
     * Inserts the tracking points of the curves, or finds the material
     * points that form them. Returns the ids to track, without repetitions:
     * MaterialPoints::track() must be given them (possibly followed by
     * others), then read_initial_positions() called.
     */
    std::vector<types::particle_index>
    create_points(MaterialPoints &points, const BodyRegion &region);

    /** Reads the starting positions of the curves' points. */
    void
    read_initial_positions(const MaterialPoints &points);

    /** Rebuilds the splines from the current point positions and cuts them
     * by @p grid. */
    void
    update(const MaterialPoints &points, const BackgroundGrid &grid);

    /**
     * The increment of every curve point that belongs to a rigid body
     * (BoundaryCurve::rigid_support()) over the load increment
     * @p increment: the change of u_n n over it, with n the outward normal
     * at the point and u_n the condition's normal displacement there (from
     * @p exact for 'normal displacement exact'), by the point's slot in
     * the tracked list of
     * @p n_slots points; the flag is false for every other slot.
     */
    std::vector<std::pair<bool, Tensor<1, 2>>>
    rigid_support_increments(const unsigned int   n_slots,
                             const ExactSolution *exact,
                             const LoadIncrement &increment) const;

    const std::vector<BoundaryCurve> &
    get_curves() const
    {
      return curves;
    }

    /** Whether any curve carries a load. */
    bool
    has_loads() const;

    /** Whether every load is its value times the load factor (none is
     * given as an expression of t): what displacement control needs. */
    bool
    loads_proportional() const;

    /** Whether any curve prescribes a displacement (a displacement-
     * controlled run: the load factor scales that displacement). */
    bool
    prescribe_displacement() const;

    /**
     * Sets @p cells[c] for every locally owned cell c (by
     * active_cell_index()) that a support imposed by @p method crosses;
     * with @p both_components_only, only supports that hold both components
     * (not rollers) count.
     */
    void
    mark_support_cells(const BackgroundGrid &grid,
                       const std::string    &method,
                       const bool            both_components_only,
                       std::vector<bool>    &cells) const;

    /** Whether any curve carries a support imposed by the support method
     * registered as @p method; by any method if @p method is empty. */
    bool
    has_supports(const std::string &method = "") const;

    /**
     * Whether the curves together are the whole boundary of the body, so
     * that the region they enclose is the body (CutCellGeometry): they form
     * closed loops (a closed curve, or open curves each ending where another
     * starts), and every curve lies on the body's boundary: its points are
     * tracking points, or material points whose volumes are halved (without
     * that, the points' volumes reach beyond the curve). If not, @p reason
     * says why; otherwise it is left empty.
     */
    bool
    encloses_body(std::string &reason) const;

    /** The points given directly (coordinates or a file) of every curve
     * that has them, with the curve's name. */
    std::vector<std::pair<std::string, std::vector<Point<2>>>>
    given_points() const;

    /** Total number of boundary points. */
    unsigned int
    n_points() const;

    /** Where each point of a changed chain comes from: the two points of
     * the chain before the change whose mean it is (the same one twice for
     * a point that stays). */
    using PointOrigins = std::vector<std::array<unsigned int, 2>>;

    /**
     * Inserts and removes tracking points where the curves' points have
     * drifted apart or crowded (BoundaryPointSpacing), in @p points and in
     * the curves' chains: corners and the ranges of conditions are
     * renumbered so that they keep their stretch of material. Call after
     * update() (the splines through the moved points place the new ones),
     * then update() again if anything changed. Decides from the curves,
     * which every process holds alike (collective). Returns, per curve,
     * where its new points come from; empty for a curve that did not
     * change.
     */
    std::vector<PointOrigins>
    adapt_point_spacing(MaterialPoints &points, const BackgroundGrid &grid);

    /**
     * Once any curve's points have changed in the run: sets
     * curve<N>_points_inserted, curve<N>_points_removed (since the last
     * call) and curve<N>_points (now) of every curve in @p quantities.
     * Before that, sets nothing, so that runs whose curves keep their
     * points report what they always did.
     */
    void
    record_point_changes(std::map<std::string, double> &quantities);

    /** Throws, naming the curves, their points and the place, where a
     * curve touches itself or another one (CurveTouchCheck) on a grid of
     * cell size @p h. */
    void
    check_touching(const double h) const;

    /**
     * The face that the excavation of the region inside @p polygon leaves
     * (doc/stages.md, "Excavation"): in every closed curve of tracking
     * points that the region reaches (follows_excavation()), the stretch
     * of points inside it gives way to the region's edge from where the
     * spline leaves it to where it enters it again, through the body:
     * free, with points about as far apart as the curve's, its corners
     * (not with @p smooth_edge, a sampled B-spline) and the crossings as
     * corners of the spline, each point with the state and total
     * displacement of the material within a cell of it. Conditions keep
     * their stretch outside the region. A curve round a hole (clockwise)
     * follows the same way, the body outside it. A region wholly in the
     * body and away from the curves (a cavity, a tunnel) gets a new free
     * closed curve round the hole; one that holds a whole hole's curve
     * replaces it. Refuses (naming @p where) a region that reaches into
     * the body between two points of a curve, that crosses a curve more
     * than once in and out, or whose face a condition would cover. Call
     * after the material points inside the region are removed, then
     * update(). Returns whether a curve changed or was added. Collective.
     */
    bool
    excavate(const std::vector<Point<2>> &polygon,
             const bool                   smooth_edge,
             MaterialPoints              &points,
             const BackgroundGrid        &grid,
             const std::string           &where);

    /** Whether curve @p c follows an excavation (excavate()): a closed
     * curve of tracking points. */
    bool
    follows_excavation(const unsigned int c) const;

    /** The curves' chains (their points' slots, starting places and
     * corners, the ranges of their conditions) and the counts of points
     * inserted and removed, as a string of bytes: what a checkpoint keeps
     * of curves whose points changed (adapt_point_spacing(), excavate()),
     * with MaterialPoints::tracking_state(). */
    std::string
    chain_state() const;

    /** Takes back a chain_state() into the curves as the parameters made
     * them; update() then rebuilds their splines. */
    void
    restore_chains(const std::string &state);

    /** Whether any curve's points have changed in the run. */
    bool
    points_changed() const
    {
      return any_points_changed;
    }

  private:
    /**
     * If every curve lies on a named part of the body region's boundary
     * (Points = region edge) and together they leave parts uncovered, adds
     * a free curve of tracking points along each of those, so that the
     * curves enclose the body (encloses_body()).
     */
    void
    complete_region_boundary(const BodyRegion     &region,
                             const BackgroundGrid &grid);

    /** Where a curve of material points runs (Points = material points):
     * along the body region's edge beside the outer layer of points, through
     * the points, or through the points with their volumes halved. */
    enum class OuterLayer
    {
      region_edge,
      through_points,
      through_halved_points
    };

    /** How the points of a curve are given. */
    struct Source
    {
      std::string kind; // region edge | coordinates | file |
                        // material points
      std::string           edge;
      unsigned int          n_points = 0;
      std::vector<Point<2>> positions; // for the first three
      OuterLayer            outer_layer = OuterLayer::region_edge;

      /** Whether the curve's points are material points, which carry
       * volume (and cannot be inserted or removed). */
      bool
      through_material_points() const
      {
        return kind == "material points" &&
               outer_layer != OuterLayer::region_edge;
      }

      /** Whether the curve runs along an edge of the body region. */
      bool
      along_region_edge() const
      {
        return kind == "region edge" ||
               (kind == "material points" &&
                outer_layer == OuterLayer::region_edge);
      }
    };

    void
    rebuild(BoundaryCurve &curve) const;

    /** Whether @p p lies on the outer side of a trimming curve (search). */
    bool
    outside_trimming_curve(const Point<2> &p) const;

    std::vector<BoundaryCurve> curves;
    std::vector<Source>        sources;

    BoundaryPointSpacing point_spacing;
    CurveTouchCheck      touch_check;

    /** Points inserted and removed per curve since the last
     * record_point_changes(). */
    std::vector<unsigned int> n_inserted, n_removed;
    bool                      any_points_changed = false;

    /** Per grid cell (row-major): 0 unknown, 1 kept, 2 trimmed, 3 cut by a
     * trimming curve; filled lazily by trims(). */
    const BackgroundGrid              *trimming_grid = nullptr;
    mutable std::vector<unsigned char> trimming_state;
  };
} // namespace bsmpm

#endif
