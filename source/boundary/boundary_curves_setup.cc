#include <bsmpm/boundary/boundary_curves.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

// BoundaryCurves, part 2: building the curves before the first step. Where
// their points come from (the body region's edges, given points, the outer
// layer of material points), the curves that complete the region's
// boundary, and which material points a trimming curve cuts away.

namespace bsmpm
{
  namespace
  {
    /**
     * The chain along a straight-sided part @p edge of the region's boundary
     * beside the outer layer of material points at @p layer (ordered along
     * it): each point's nearest point on the edge, and the edge's corners in
     * place of the nearest of them (an open edge: its two ends in place of
     * the layer's first and last), so that the curve bounds exactly the
     * region that the points' volumes fill.
     */
    std::vector<Point<2>>
    beside_outer_layer(const std::vector<Point<2>>      &layer,
                       const BodyRegion::BoundaryPoints &edge)
    {
      const std::vector<Point<2>> &corners = edge.points;
      const unsigned int           n_sides =
        edge.closed ? corners.size() : corners.size() - 1;
      std::vector<Point<2>> chain;
      for (const auto &q : layer)
        {
          Point<2> nearest;
          double   distance = std::numeric_limits<double>::max();
          for (unsigned int k = 0; k < n_sides; ++k)
            {
              const Point<2> p0    = corners[k],
                             p1    = corners[(k + 1) % corners.size()];
              const Tensor<1, 2> d = p1 - p0;
              const Point<2>     x =
                p0 + std::clamp((q - p0) * d / (d * d), 0., 1.) * d;
              if (x.distance(q) < distance)
                {
                  distance = x.distance(q);
                  nearest  = x;
                }
            }
          chain.push_back(nearest);
        }
      if (!edge.closed)
        {
          if (chain.size() < 2)
            return corners;
          chain.front() = corners.front();
          chain.back()  = corners.back();
          return chain;
        }
      std::vector<bool> is_corner(chain.size(), false);
      for (const auto &corner : corners)
        {
          unsigned int nearest = numbers::invalid_unsigned_int;
          for (unsigned int k = 0; k < chain.size(); ++k)
            if (!is_corner[k] &&
                (nearest == numbers::invalid_unsigned_int ||
                 chain[k].distance(corner) < chain[nearest].distance(corner)))
              nearest = k;
          AssertThrow(nearest != numbers::invalid_unsigned_int,
                      ExcMessage("Boundary curves: the outer layer of "
                                 "material points has fewer points than the "
                                 "edge has corners."));
          chain[nearest]     = corner;
          is_corner[nearest] = true;
        }
      return chain;
    }
  } // namespace



  void
  BoundaryCurves::enclose_body_region(ParameterHandler &prm,
                                      const BodyRegion &region,
                                      const double      cell_size)
  {
    // Points that move across cells leave full cells with uneven point
    // sets and partly filled cells at the surface: integrated by the points
    // alone, the stress of a column compressed by 38 % did not converge
    // under refinement (L2_u 8.3e-2, 7.5e-2, 8.0e-2 for h = 0.5 .. 0.125).
    // A closed curve round the body lets the cut-cell quadrature integrate
    // those cells consistently (1.2e-3, 2.3e-4, 9.1e-5; doc/finite-strain.md).
    prm.enter_subsection("Boundary curves");
    for (unsigned int c = 1; c <= max_curves; ++c)
      {
        prm.enter_subsection("Curve " + std::to_string(c));
        const bool used = prm.get("Points") != "none";
        prm.leave_subsection();
        if (used)
          {
            prm.leave_subsection();
            return;
          }
      }
    // Tracking points about a cell apart on the longest side.
    double longest = 0;
    for (const auto &name : region.boundary_part_names())
      {
        const auto points = region.boundary_points(name, 129).points;
        double     length = 0;
        for (unsigned int i = 1; i < points.size(); ++i)
          length += points[i].distance(points[i - 1]);
        longest = std::max(longest, length);
      }
    const unsigned int n =
      std::max<unsigned int>(2, std::ceil(longest / cell_size - 1e-9) + 1);
    prm.enter_subsection("Curve 1");
    prm.set("Points", "region edge");
    prm.set("Edge", "boundary");
    prm.set("Number of points", std::to_string(n));
    prm.leave_subsection();
    prm.leave_subsection();
  }



  void
  BoundaryCurves::complete_region_boundary(const BodyRegion     &region,
                                           const BackgroundGrid &grid)
  {
    std::set<std::string> used;
    for (const auto &source : sources)
      {
        if (!source.along_region_edge())
          return;
        used.insert(source.edge);
      }
    if (used.empty() || used.count("boundary") > 0)
      return;
    const auto names = region.boundary_part_names();
    for (const auto &name : names)
      if (used.count(name) == 0 &&
          std::count(names.begin(), names.end(), name) > 1)
        return; // a part the region cannot name on its own

    for (const auto &name : names)
      if (used.count(name) == 0)
        {
          // Tracking points about one cell apart, so that the curve follows
          // the body as it deforms.
          const auto fine   = region.boundary_points(name, 129).points;
          double     length = 0;
          for (unsigned int i = 1; i < fine.size(); ++i)
            length += fine[i].distance(fine[i - 1]);
          Source source;
          source.kind     = "region edge";
          source.edge     = name;
          source.n_points = std::max<unsigned int>(
            2, std::ceil(length / grid.min_cell_size() - 1e-9) + 1);
          BoundaryCurve curve;
          curve.name = "free " + name + " (completes the boundary)";
          curve.conditions.push_back(CurveCondition());
          curves.push_back(std::move(curve));
          sources.push_back(source);
          used.insert(name);
        }
  }



  void
  BoundaryCurves::create_initial_curves(const BodyRegion     &region,
                                        const BackgroundGrid &grid,
                                        const bool            complete)
  {
    // An edge the region's shape does not have is refused here, naming the
    // parameter, before any curve is built.
    for (unsigned int c = 0; c < curves.size(); ++c)
      if (sources[c].kind == "region edge" ||
          sources[c].kind == "material points")
        region.check_edge(sources[c].edge,
                          "Boundary curves/" + curves[c].name + "/Edge");
    if (complete)
      complete_region_boundary(region, grid);
    for (unsigned int c = 0; c < curves.size(); ++c)
      {
        BoundaryCurve &curve  = curves[c];
        Source        &source = sources[c];
        if (source.kind == "region edge")
          {
            const auto edge =
              region.boundary_points(source.edge, source.n_points);
            source.positions = edge.points;
            curve.closed     = edge.closed;
            curve.corners.insert(curve.corners.end(),
                                 edge.corners.begin(),
                                 edge.corners.end());
          }
        if (source.kind != "material points")
          {
            curve.positions = source.positions;
            rebuild(curve);
            AssertThrow(!curve.closed || !curve.spline->is_self_intersecting(),
                        ExcMessage("Boundary curves/" + curve.name +
                                   ": the closed curve through the given "
                                   "points intersects itself."));
          }
      }

    // Curves that the input draws across each other, or closer than the
    // touching distance, are refused here, before the first step (a
    // touch that deformation makes is found after the step that makes it:
    // check_touching()).
    const std::string touch =
      touch_check.find_touch(curves, grid.min_cell_size());
    AssertThrow(touch.empty(), ExcMessage("In the input: " + touch));

    trimming_grid = &grid;
    trimming_state.assign(std::size_t(grid.n_cells(0)) * grid.n_cells(1), 0);
    const UniformGrid uniform{grid.lower_left(),
                              grid.cell_size(),
                              {{grid.n_cells(0), grid.n_cells(1)}}};
    for (const auto &curve : curves)
      if (curve.trims_material_points && curve.spline)
        for (const auto &piece :
             CurveCellIntersection::cut(*curve.spline, uniform))
          trimming_state[piece.cell[1] * grid.n_cells(0) + piece.cell[0]] = 3;
  }



  bool
  BoundaryCurves::trims(const Point<2> &p) const
  {
    if (trimming_grid == nullptr || !trimming_grid->contains(p))
      return outside_trimming_curve(p);
    const auto     ij = trimming_grid->cell_index(p);
    unsigned char &state =
      trimming_state[ij[1] * trimming_grid->n_cells(0) + ij[0]];
    if (state == 3)
      return outside_trimming_curve(p);
    if (state == 0)
      {
        const Point<2> center =
          trimming_grid->cell_origin(ij) + 0.5 * trimming_grid->cell_size();
        state = outside_trimming_curve(center) ? 2 : 1;
      }
    return state == 2;
  }



  bool
  BoundaryCurves::outside_trimming_curve(const Point<2> &p) const
  {
    for (const auto &curve : curves)
      if (curve.trims_material_points && curve.spline)
        {
          const auto closest = curve.spline->closest_point(p);
          if ((p - closest.point) * curve.spline->outward_normal(closest.u) > 0)
            return true;
        }
    return false;
  }



  std::vector<types::particle_index>
  BoundaryCurves::create_points(MaterialPoints   &points,
                                const BodyRegion &region)
  {
    // A point may belong to two curves (a corner of the outer layer): it is
    // tracked once.
    std::vector<types::particle_index>              tracked;
    std::map<types::particle_index, unsigned int>   slot_of;
    std::vector<std::vector<types::particle_index>> ids(curves.size());
    for (unsigned int c = 0; c < curves.size(); ++c)
      {
        BoundaryCurve &curve  = curves[c];
        Source        &source = sources[c];
        if (source.kind == "material points")
          {
            const auto edge = region.boundary_points(source.edge, 2);
            ids[c]          = points.outer_layer(edge.points, edge.closed);
            curve.closed    = edge.closed;
            if (source.outer_layer == OuterLayer::region_edge)
              {
                // The chain on the edge beside the layer: tracking points,
                // as along any region edge.
                curve.positions =
                  beside_outer_layer(points.locations(ids[c]), edge);
                for (unsigned int k = 0; k < curve.positions.size(); ++k)
                  for (const auto &corner : edge.points)
                    if (edge.closed && curve.positions[k] == corner)
                      curve.corners.push_back(k);
                ids[c] = points.add_tracking_points(curve.positions);
              }
          }
        else
          ids[c] = points.add_tracking_points(curve.positions);

        curve.tracked_slots.clear();
        for (const auto id : ids[c])
          {
            const auto [it, inserted] = slot_of.emplace(id, tracked.size());
            if (inserted)
              tracked.push_back(id);
            curve.tracked_slots.push_back(it->second);
          }
      }
    // The outer layer stands for the body up to its boundary: its points
    // keep half their volume on a side, a quarter at a corner (paper
    // Sec. 4.1.2).
    for (unsigned int c = 0; c < curves.size(); ++c)
      if (sources[c].kind == "material points" &&
          sources[c].outer_layer == OuterLayer::through_halved_points)
        points.scale_volumes(ids[c], 0.5);
    return tracked;
  }



  void
  BoundaryCurves::read_initial_positions(const MaterialPoints &points)
  {
    std::vector<Point<2>> positions;
    std::vector<Voigt>    stresses;
    points.tracked_states(positions, stresses);
    for (auto &curve : curves)
      {
        curve.initial_positions.clear();
        for (const unsigned int slot : curve.tracked_slots)
          curve.initial_positions.push_back(positions[slot]);
      }
  }
} // namespace bsmpm
