#include <bsmpm/boundary/boundary_curves.h>

// BoundaryCurves, part 3: the tracking points inserted and removed where
// the body has stretched or crowded them (the plan is BoundaryPointSpacing's),
// in the points and in the curves' chains.

namespace bsmpm
{
  std::vector<BoundaryCurves::PointOrigins>
  BoundaryCurves::adapt_point_spacing(MaterialPoints       &points,
                                      const BackgroundGrid &grid)
  {
    std::vector<PointOrigins> origins(curves.size());
    n_inserted.resize(curves.size(), 0);
    n_removed.resize(curves.size(), 0);
    if (!point_spacing.enabled())
      return origins;
    const double       h       = grid.min_cell_size();
    const unsigned int invalid = numbers::invalid_unsigned_int;
    for (unsigned int c = 0; c < curves.size(); ++c)
      {
        // Points of the outer layer of material points carry volume:
        // they cannot be made or dropped here.
        if (sources[c].through_material_points())
          continue;
        BoundaryCurve                   &curve = curves[c];
        const BoundaryPointSpacing::Plan plan  = point_spacing.plan(curve, h);
        if (plan.empty())
          continue;
        const unsigned int n = curve.positions.size();
        std::vector<bool>  removed(n, false), split(n, false);
        for (const unsigned int k : plan.removed_points)
          removed[k] = true;
        for (const unsigned int s : plan.split_segments)
          split[s] = true;

        // The new chain, its new points at the middle of their segments'
        // parameter ranges on the spline through the moved points.
        PointOrigins             &origin = origins[c];
        std::vector<unsigned int> new_index(n, invalid);
        std::vector<Point<2>>     new_positions;
        std::vector<unsigned int> neighbour_slots;
        for (unsigned int k = 0; k < n; ++k)
          {
            if (!removed[k])
              {
                new_index[k] = origin.size();
                origin.push_back({{k, k}});
              }
            if (split[k])
              {
                const unsigned int k1    = (k + 1) % n;
                const auto         range = curve.spline->segment_parameters(k);
                origin.push_back({{k, k1}});
                // A segment whose ends lie on a face of the grid (a body
                // against a roller face, its corner there) may bulge
                // past the face between them, the spline being cubic and
                // the face straight: the new point goes back onto the
                // face, where the material is. Farther out than a tenth
                // of a cell is an error (add_tracked_points()).
                new_positions.push_back(grid.pulled_onto(
                  curve.spline->value((range[0] + range[1]) / 2), 0.1));
                neighbour_slots.push_back(curve.tracked_slots[k]);
                neighbour_slots.push_back(curve.tracked_slots[k1]);
              }
          }

        // The state of a new point: the mean of its neighbours'; its total
        // displacement takes it from the mean of their starting places to
        // where it is.
        const auto neighbours = points.tracked_properties(neighbour_slots);
        std::vector<std::vector<double>> new_properties;
        std::vector<Point<2>>            new_initial_positions;
        for (unsigned int i = 0; i < new_positions.size(); ++i)
          {
            std::vector<double> props = neighbours[2 * i];
            for (unsigned int j = 0; j < props.size(); ++j)
              props[j] = (props[j] + neighbours[2 * i + 1][j]) / 2;
            using P = MaterialPoints::Property;
            const Point<2> X(props[P::initial_position],
                             props[P::initial_position + 1]);
            props[P::displacement]     = new_positions[i][0] - X[0];
            props[P::displacement + 1] = new_positions[i][1] - X[1];
            new_properties.push_back(props);
            new_initial_positions.push_back(X);
          }
        const std::vector<unsigned int> new_slots =
          points.add_tracked_points(new_positions, new_properties);
        std::vector<unsigned int> removed_slots;
        for (const unsigned int k : plan.removed_points)
          removed_slots.push_back(curve.tracked_slots[k]);
        points.remove_tracked_points(removed_slots);

        // The chain's own records, in the new order.
        std::vector<Point<2>>     positions, initial_positions;
        std::vector<Voigt>        stresses;
        std::vector<unsigned int> slots;
        unsigned int              next_new = 0;
        for (const auto &[a, b] : origin)
          if (a == b)
            {
              positions.push_back(curve.positions[a]);
              initial_positions.push_back(curve.initial_positions[a]);
              stresses.push_back(curve.stresses[a]);
              slots.push_back(curve.tracked_slots[a]);
            }
          else
            {
              positions.push_back(new_positions[next_new]);
              initial_positions.push_back(new_initial_positions[next_new]);
              stresses.push_back(0.5 * (curve.stresses[a] + curve.stresses[b]));
              slots.push_back(new_slots[next_new]);
              ++next_new;
            }
        // Corners and the ends of ranges are never removed: renumbered,
        // they bound the same stretch of material as before.
        const unsigned int n_new    = origin.size();
        const auto         renumber = [&](const unsigned int k) {
          AssertThrow(k == n || new_index[k % n] != invalid,
                      ExcInternalError());
          return k == n ? n_new : new_index[k];
        };
        for (auto &corner : curve.corners)
          corner = renumber(corner);
        for (auto &condition : curve.conditions)
          if (condition.has_range())
            {
              condition.first_segment = renumber(condition.first_segment);
              condition.end_segment   = renumber(condition.end_segment);
            }
        curve.positions         = std::move(positions);
        curve.initial_positions = std::move(initial_positions);
        curve.stresses          = std::move(stresses);
        curve.tracked_slots     = std::move(slots);
        n_inserted[c] += new_positions.size();
        n_removed[c] += removed_slots.size();
        any_points_changed = true;
      }
    return origins;
  }



  void
  BoundaryCurves::record_point_changes(
    std::map<std::string, double> &quantities)
  {
    if (!any_points_changed)
      return;
    for (unsigned int c = 0; c < curves.size(); ++c)
      {
        const std::string name                = "curve" + std::to_string(c + 1);
        quantities[name + "_points_inserted"] = n_inserted[c];
        quantities[name + "_points_removed"]  = n_removed[c];
        quantities[name + "_points"]          = curves[c].positions.size();
        n_inserted[c] = n_removed[c] = 0;
      }
  }
} // namespace bsmpm
