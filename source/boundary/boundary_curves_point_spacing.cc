#include <bsmpm/boundary/boundary_curves.h>

#include <boost/archive/binary_iarchive.hpp>
#include <boost/archive/binary_oarchive.hpp>
#include <boost/serialization/string.hpp>
#include <boost/serialization/vector.hpp>

#include <sstream>

// BoundaryCurves, part 3: the tracking points inserted and removed where
// the body has stretched or crowded them (the plan is BoundaryPointSpacing's),
// in the points and in the curves' chains, and what a checkpoint keeps of
// changed chains.

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


  std::string
  BoundaryCurves::chain_state() const
  {
    std::ostringstream out;
    {
      boost::archive::binary_oarchive archive(out);
      archive << n_inserted << n_removed << any_points_changed;
      // The curves that excavations added (round holes) come after those
      // of the parameters.
      const unsigned int n_curves = curves.size();
      archive << n_curves;
      for (const BoundaryCurve &curve : curves)
        {
          archive << curve.name;
          // A condition by its parameter (CurveCondition::where), which
          // names it among those the curve was given.
          std::vector<std::string>  where;
          std::vector<unsigned int> first, end;
          for (const auto &condition : curve.conditions)
            {
              where.push_back(condition.where);
              first.push_back(condition.first_segment);
              end.push_back(condition.end_segment);
            }
          archive << curve.tracked_slots << curve.initial_positions
                  << curve.corners << where << first << end;
        }
    }
    return out.str();
  }



  void
  BoundaryCurves::restore_chains(const std::string &state)
  {
    std::istringstream              in(state);
    boost::archive::binary_iarchive archive(in);
    archive >> n_inserted >> n_removed >> any_points_changed;
    unsigned int n_curves = 0;
    archive >> n_curves;
    AssertThrow(n_curves >= curves.size(),
                ExcMessage("The checkpoint has fewer boundary curves than the "
                           "parameters give."));
    while (curves.size() < n_curves)
      {
        // A free closed curve round a hole that an excavation made.
        BoundaryCurve hole;
        hole.closed = true;
        hole.conditions.push_back(CurveCondition());
        curves.push_back(std::move(hole));
        Source source;
        source.kind = "excavation";
        sources.push_back(source);
      }
    for (BoundaryCurve &curve : curves)
      {
        archive >> curve.name;
        std::vector<std::string>  where;
        std::vector<unsigned int> first, end;
        archive >> curve.tracked_slots >> curve.initial_positions >>
          curve.corners >> where >> first >> end;
        std::vector<CurveCondition> conditions;
        for (unsigned int i = 0; i < where.size(); ++i)
          {
            const auto given =
              std::find_if(curve.conditions.begin(),
                           curve.conditions.end(),
                           [&](const auto &c) { return c.where == where[i]; });
            AssertThrow(given != curve.conditions.end(),
                        ExcMessage("The checkpoint's " + curve.name +
                                   " has a condition '" + where[i] +
                                   "' that the parameters do not give."));
            conditions.push_back(*given);
            conditions.back().first_segment = first[i];
            conditions.back().end_segment   = end[i];
          }
        curve.conditions = std::move(conditions);
        curve.positions.assign(curve.tracked_slots.size(), Point<2>());
      }
  }
} // namespace bsmpm
