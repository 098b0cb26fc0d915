#include <bsmpm/boundary/boundary_curves.h>

#include <algorithm>
#include <cmath>
#include <sstream>

// BoundaryCurves, part 4: the face that an excavation leaves becomes part
// of the closed curves round the body (doc/stages.md, "Excavation").

namespace bsmpm
{
  namespace
  {
    /** Distance from @p x to the boundary of the closed polygon @p p. */
    double
    distance_to_edges(const std::vector<Point<2>> &p, const Point<2> &x)
    {
      return nearest_on_polygon(p, x).distance;
    }

    /** The path along the boundary of polygon @p p from @p x to @p y (both
     * on it): its vertices, @p x and @p y included; forward runs through
     * vertices 1, 2, ..., backward the other way. */
    std::vector<Point<2>>
    polygon_path(const std::vector<Point<2>> &p,
                 const Point<2>              &x,
                 const Point<2>              &y,
                 const bool                   forward,
                 const double                 tolerance)
    {
      const unsigned int  m = p.size();
      std::vector<double> vertex_position(m + 1, 0.);
      for (unsigned int i = 0; i < m; ++i)
        vertex_position[i + 1] =
          vertex_position[i] + p[i].distance(p[(i + 1) % m]);
      const double perimeter = vertex_position[m];
      const double sx        = nearest_on_polygon(p, x).arc_length,
                   sy        = nearest_on_polygon(p, y).arc_length;
      // Arc lengths from x in the direction of travel.
      const auto ahead = [&](const double s) {
        const double d = forward ? s - sx : sx - s;
        return d - perimeter * std::floor(d / perimeter);
      };
      const double                             end = ahead(sy);
      std::vector<std::pair<double, Point<2>>> vertices;
      for (unsigned int i = 0; i < m; ++i)
        {
          const double a = ahead(vertex_position[i]);
          if (a > tolerance && a < end - tolerance)
            vertices.emplace_back(a, p[i]);
        }
      std::sort(vertices.begin(),
                vertices.end(),
                [](const auto &u, const auto &v) { return u.first < v.first; });
      std::vector<Point<2>> path = {x};
      for (const auto &v : vertices)
        path.push_back(v.second);
      path.push_back(y);
      return path;
    }

    /** Twice the signed area of the closed chain @p p: positive where it
     * runs counter-clockwise (round a body), negative clockwise (round a
     * hole of it). */
    double
    signed_area(const std::vector<Point<2>> &p)
    {
      double area = 0;
      for (unsigned int i = 0; i < p.size(); ++i)
        {
          const Point<2> &a = p[i], &b = p[(i + 1) % p.size()];
          area += a[0] * b[1] - b[0] * a[1];
        }
      return area;
    }

    /**
     * Points along @p path about @p spacing apart, its vertices among them
     * and marked in @p corners; with @p smooth (a sampled B-spline) evenly
     * along its whole length, its ends the only corners. Without its first
     * point if @p skip_first, without its last if @p skip_last.
     */
    void
    sample_path(const std::vector<Point<2>> &path,
                const bool                   smooth,
                const double                 spacing,
                const bool                   skip_first,
                const bool                   skip_last,
                std::vector<Point<2>>       &samples,
                std::vector<unsigned int>   &corners)
    {
      // Where the legs start along the path.
      std::vector<double> start(1, 0.);
      for (unsigned int leg = 0; leg + 1 < path.size(); ++leg)
        start.push_back(start.back() + path[leg].distance(path[leg + 1]));
      const auto along = [&](const double s) {
        const unsigned int leg = std::min<unsigned int>(
          std::upper_bound(start.begin(), start.end(), s) - start.begin() - 1,
          path.size() - 2);
        const double length = start[leg + 1] - start[leg];
        return length > 0 ? path[leg] + ((s - start[leg]) / length) *
                                          (path[leg + 1] - path[leg]) :
                            path[leg];
      };
      // The stretches between corners: the legs, or the whole path.
      std::vector<unsigned int> ends;
      for (unsigned int i = 0; i < path.size(); ++i)
        if (!smooth || i == 0 || i + 1 == path.size())
          ends.push_back(i);
      for (unsigned int c = 0; c + 1 < ends.size(); ++c)
        {
          const double from = start[ends[c]], to = start[ends[c + 1]];
          if (c > 0 || !skip_first)
            {
              corners.push_back(samples.size());
              samples.push_back(path[ends[c]]);
            }
          const unsigned int pieces = std::max(
            1u, static_cast<unsigned int>(std::round((to - from) / spacing)));
          for (unsigned int i = 1; i < pieces; ++i)
            samples.push_back(along(from + (to - from) * i / pieces));
        }
      if (!skip_last)
        {
          corners.push_back(samples.size());
          samples.push_back(path.back());
        }
    }

    /** The state of the material at the points @p face of a new face
     * (MaterialPoints' properties: the mean of the points within a cell,
     * or two), their starting places into @p initial_positions. */
    std::vector<std::vector<double>>
    face_states(const std::vector<Point<2>> &face,
                const MaterialPoints        &points,
                const double                 h,
                const std::string           &where,
                std::vector<Point<2>>       &initial_positions)
    {
      auto means = points.mean_properties_near(face, h);
      // Where the face runs along a stretch the points have left (one point
      // per cell, a corner that bulged), the material two cells away.
      std::vector<Point<2>>     far;
      std::vector<unsigned int> far_index;
      for (unsigned int i = 0; i < face.size(); ++i)
        if (means[i].empty())
          {
            far.push_back(face[i]);
            far_index.push_back(i);
          }
      if (!far.empty())
        {
          const auto far_means = points.mean_properties_near(far, 2 * h);
          for (unsigned int j = 0; j < far.size(); ++j)
            means[far_index[j]] = far_means[j];
        }
      using P = MaterialPoints::Property;
      initial_positions.clear();
      for (unsigned int i = 0; i < face.size(); ++i)
        {
          std::ostringstream at;
          at << "(" << face[i] << ")";
          AssertThrow(!means[i].empty(),
                      ExcMessage(where +
                                 ": no material lies within two cells "
                                 "of the excavation's face at " +
                                 at.str() + "."));
          std::vector<double> &props = means[i];
          const Point<2>       X(face[i][0] - props[P::displacement],
                           face[i][1] - props[P::displacement + 1]);
          props[P::initial_position]     = X[0];
          props[P::initial_position + 1] = X[1];
          initial_positions.push_back(X);
        }
      return means;
    }
  } // namespace



  bool
  BoundaryCurves::follows_excavation(const unsigned int c) const
  {
    return curves[c].closed && !sources[c].through_material_points();
  }



  bool
  BoundaryCurves::excavate(const std::vector<Point<2>> &polygon,
                           const bool                   smooth_edge,
                           MaterialPoints              &points,
                           const BackgroundGrid        &grid,
                           const std::string           &where)
  {
    const double h         = grid.min_cell_size();
    const double tolerance = 1e-9 * h;
    // A point of a curve within a tenth of a cell of the region's edge
    // counts as inside: where a lift's region ends on the face that the
    // lift before left, that face's points, moved a little either way
    // since, give way to the new face.
    const double band   = 0.1 * h;
    const auto   inside = [&](const Point<2> &x) {
      return polygon_contains(polygon, x) ||
             distance_to_edges(polygon, x) < band;
    };
    bool changed = false;
    n_inserted.resize(curves.size(), 0);
    n_removed.resize(curves.size(), 0);
    // A region wholly in the body and away from its curves (a cavity, a
    // tunnel) becomes a closed curve of its own, round the hole; so does a
    // region that holds a whole hole's curve (the hole widened all round),
    // in that curve's place.
    bool         cavity          = false;
    bool         in_a_hole       = false;
    double       cavity_spacing  = h;
    unsigned int widened         = numbers::invalid_unsigned_int;
    double       widened_spacing = h;
    for (unsigned int c = 0; c < curves.size(); ++c)
      {
        if (!follows_excavation(c))
          continue;
        BoundaryCurve     &curve = curves[c];
        const std::string  name  = "Boundary curves/" + curve.name;
        const unsigned int n     = curve.positions.size();
        std::vector<bool>  in(n);
        unsigned int       n_in = 0;
        for (unsigned int k = 0; k < n; ++k)
          n_in += (in[k] = inside(curve.positions[k]));
        const auto refuse = [&](const std::string &why) {
          AssertThrow(false,
                      ExcMessage(where + ": the excavated region " + why +
                                 " (" + name + ")."));
        };
        // A curve round a hole runs clockwise, the body outside it.
        const bool hole      = signed_area(curve.positions) < 0;
        double     perimeter = 0;
        for (unsigned int k = 0; k < n; ++k)
          perimeter +=
            curve.positions[k].distance(curve.positions[(k + 1) % n]);
        const double spacing = std::min(perimeter / n, h);
        if (n_in == 0)
          {
            // The region's corners: in the body beyond the band round the
            // curve, or near the curve. All in the body: a cavity; none in
            // the body nor near: the region lies beyond the curve (in the
            // hole it bounds, or outside the body). Otherwise the region
            // reaches into the body between two points of the curve.
            unsigned int n_body = 0, n_near = 0;
            for (const Point<2> &v : polygon)
              if (distance_to_edges(curve.positions, v) <= band)
                ++n_near;
              else if (polygon_contains(curve.positions, v) != hole)
                ++n_body;
            if (n_body == polygon.size())
              {
                if (!hole)
                  {
                    cavity         = true;
                    cavity_spacing = spacing;
                  }
              }
            else if (n_body == 0 && n_near == 0)
              in_a_hole = in_a_hole || hole;
            else
              refuse("reaches into the body between two points of the "
                     "curve round it, a notch narrower than the curve's "
                     "points are apart; let it take in a stretch of the "
                     "body's boundary");
            continue;
          }
        if (n_in == n)
          {
            if (!hole)
              refuse("holds the whole curve round the body");
            widened         = c;
            widened_spacing = spacing;
            continue;
          }
        // The stretch of the chain inside the region: r0 .. r1 (cyclic),
        // between the points a and b outside it.
        unsigned int r0 = 0;
        while (!(in[r0] && !in[(r0 + n - 1) % n]))
          ++r0;
        unsigned int length = 0;
        while (in[(r0 + length) % n])
          ++length;
        if (length != n_in)
          refuse("crosses the curve round the body more than once in and "
                 "out; an excavation takes one stretch of its boundary");
        const unsigned int a = (r0 + n - 1) % n, b = (r0 + length) % n;

        // Where the spline crosses the region's edge, by bisection on the
        // segments a -> a + 1 and b - 1 -> b (onto the edge from the band
        // round it).
        const auto crossing = [&](const unsigned int segment,
                                  const bool         leaving_at_start) {
          auto range = curve.spline->segment_parameters(segment);
          for (unsigned int i = 0; i < 60; ++i)
            {
              const double u = (range[0] + range[1]) / 2;
              (inside(curve.spline->value(u)) == leaving_at_start ? range[0] :
                                                                    range[1]) =
                u;
            }
          return nearest_on_polygon(polygon,
                                    curve.spline->value((range[0] + range[1]) /
                                                        2))
            .point;
        };
        const Point<2> x1 = crossing(a, false);
        const Point<2> x2 = crossing((b + n - 1) % n, true);

        // The face: the region's edge from x1 to x2 through the body, the
        // way round whose legs run inside it: none of their middles
        // outside the body, one at least inside it (beyond the band round
        // its boundary, where an edge of the region may run along it).
        const auto runs_inside = [&](const std::vector<Point<2>> &path) {
          bool some_inside = false;
          for (unsigned int i = 0; i + 1 < path.size(); ++i)
            {
              const Point<2> middle = path[i] + 0.5 * (path[i + 1] - path[i]);
              if (distance_to_edges(curve.positions, middle) <= band)
                continue;
              if (polygon_contains(curve.positions, middle) == hole)
                return false;
              some_inside = true;
            }
          return some_inside;
        };
        const std::vector<Point<2>>
          forward  = polygon_path(polygon, x1, x2, true, tolerance),
          backward = polygon_path(polygon, x1, x2, false, tolerance);
        const bool forward_inside  = runs_inside(forward),
                   backward_inside = runs_inside(backward);
        if (forward_inside == backward_inside)
          refuse("has an edge that leaves and enters the body again between "
                 "its crossings of the curve round it");
        const std::vector<Point<2>> &path = forward_inside ? forward : backward;

        // The face's points, its corners among them, about as far apart as
        // the curve's points are (at most a cell); an end next to the
        // chain's point outside is that point. A smooth edge (a sampled
        // B-spline) has corners at its ends only, its points evenly along
        // its length.
        const bool first_is_a = x1.distance(curve.positions[a]) < 0.2 * spacing;
        const bool last_is_b  = x2.distance(curve.positions[b]) < 0.2 * spacing;
        std::vector<Point<2>>     face;
        std::vector<unsigned int> face_corners; // in face
        sample_path(path,
                    smooth_edge,
                    spacing,
                    first_is_a,
                    last_is_b,
                    face,
                    face_corners);
        // A crossing on a face of the grid (a body held by it) may lie
        // beyond it by round-off.
        for (Point<2> &x : face)
          x = grid.pulled_onto(x, 0.1);

        // The material's state along the face: that of the points within a
        // cell of it; its total displacement, that of the material there.
        std::vector<Point<2>>                  initial_positions;
        const std::vector<std::vector<double>> properties =
          face_states(face, points, h, where, initial_positions);

        // The new chain: the points outside the region in their order, the
        // face where the stretch inside was.
        const unsigned int        invalid = numbers::invalid_unsigned_int;
        std::vector<unsigned int> new_index(n, invalid);
        std::vector<int>          origin; // old index, or -1 - face index
        for (unsigned int k = 0; k < n; ++k)
          {
            if (k == r0)
              for (unsigned int i = 0; i < face.size(); ++i)
                origin.push_back(-1 - static_cast<int>(i));
            if (!in[k])
              {
                new_index[k] = origin.size();
                origin.push_back(k);
              }
          }
        const unsigned int n_new = origin.size();
        // The face's first and last points in the new chain (a or b where
        // the face starts or ends there).
        const unsigned int face_start =
          first_is_a ? new_index[a] : (new_index[a] + 1) % n_new;
        const unsigned int face_end =
          last_is_b ? new_index[b] :
                      (face_start + face.size() - (first_is_a ? 0 : 1)) % n_new;

        // Conditions keep their stretch of the outside; one that ended in
        // the stretch now ends at the face's start, one that began there
        // begins at the face's end, one wholly inside it is gone.
        std::vector<CurveCondition> conditions;
        for (CurveCondition condition : curve.conditions)
          {
            if (condition.has_range())
              {
                const unsigned int i = condition.first_segment,
                                   j = condition.end_segment % n;
                if (in[i] && in[j] && !condition.covers(b, n))
                  continue;
                condition.first_segment = in[i] ? face_end : new_index[i];
                condition.end_segment =
                  in[j] ? face_start :
                          (condition.end_segment == n && new_index[0] == 0 ?
                             n_new :
                             new_index[j]);
                // A range that kept no segment outside is gone too.
                if (condition.first_segment % n_new ==
                    condition.end_segment % n_new)
                  continue;
              }
            conditions.push_back(condition);
          }
        std::vector<unsigned int> corners;
        for (const unsigned int k : curve.corners)
          if (!in[k])
            corners.push_back(new_index[k]);
        const unsigned int first_face_point = (new_index[a] + 1) % n_new;
        for (const unsigned int i : face_corners)
          corners.push_back((first_face_point + i) % n_new);
        if (first_is_a)
          corners.push_back(new_index[a]);
        if (last_is_b)
          corners.push_back(new_index[b]);
        std::sort(corners.begin(), corners.end());
        corners.erase(std::unique(corners.begin(), corners.end()),
                      corners.end());

        // The points themselves.
        const std::vector<unsigned int> face_slots =
          points.add_tracked_points(face, properties);
        std::vector<unsigned int> removed_slots;
        for (unsigned int k = 0; k < n; ++k)
          if (in[k])
            removed_slots.push_back(curve.tracked_slots[k]);
        points.remove_tracked_points(removed_slots);

        std::vector<Point<2>>     positions, initial;
        std::vector<unsigned int> slots;
        for (const int o : origin)
          if (o >= 0)
            {
              positions.push_back(curve.positions[o]);
              initial.push_back(curve.initial_positions[o]);
              slots.push_back(curve.tracked_slots[o]);
            }
          else
            {
              positions.push_back(face[-1 - o]);
              initial.push_back(initial_positions[-1 - o]);
              slots.push_back(face_slots[-1 - o]);
            }
        curve.positions         = std::move(positions);
        curve.initial_positions = std::move(initial);
        curve.tracked_slots     = std::move(slots);
        curve.corners           = std::move(corners);
        curve.conditions        = std::move(conditions);
        // The face is free: a condition that would now cover it is refused.
        rebuild(curve);
        for (unsigned int s = face_start; s != face_end; s = (s + 1) % n_new)
          if (curve.condition_of_segment(s) != nullptr)
            refuse("takes a stretch of the curve round the body whose "
                   "condition would then hold on the excavation's face: "
                   "give that condition a range of points outside the "
                   "region");
        n_inserted[c] += face.size();
        n_removed[c] += removed_slots.size();
        any_points_changed = true;
        changed            = true;
      }
    if (widened != numbers::invalid_unsigned_int)
      AssertThrow(!changed,
                  ExcMessage(where + ": the excavated region holds the whole "
                                     "curve round a hole and reaches another "
                                     "curve too: excavate the two apart."));
    if ((cavity && !changed && !in_a_hole) ||
        widened != numbers::invalid_unsigned_int)
      {
        // The hole's curve: the region's edge, clockwise (the body on its
        // left), free, its points about as far apart as the curves'.
        std::vector<Point<2>> loop = polygon;
        if (signed_area(loop) > 0)
          std::reverse(loop.begin(), loop.end());
        loop.push_back(loop.front());
        std::vector<Point<2>>     face;
        std::vector<unsigned int> corners;
        sample_path(loop,
                    smooth_edge,
                    widened != numbers::invalid_unsigned_int ? widened_spacing :
                                                               cavity_spacing,
                    false,
                    true,
                    face,
                    corners);
        if (smooth_edge)
          corners.clear();
        for (Point<2> &x : face)
          x = grid.pulled_onto(x, 0.1);
        BoundaryCurve hole;
        hole.closed = true;
        hole.conditions.push_back(CurveCondition());
        hole.corners   = corners;
        hole.positions = face;
        const std::vector<std::vector<double>> properties =
          face_states(face, points, h, where, hole.initial_positions);
        hole.tracked_slots = points.add_tracked_points(face, properties);
        rebuild(hole);
        if (widened != numbers::invalid_unsigned_int)
          {
            points.remove_tracked_points(curves[widened].tracked_slots);
            n_removed[widened] += curves[widened].tracked_slots.size();
            n_inserted[widened] += face.size();
            hole.name       = curves[widened].name;
            curves[widened] = std::move(hole);
          }
        else
          {
            hole.name = "the face of " + where;
            curves.push_back(std::move(hole));
            Source source;
            source.kind = "excavation";
            sources.push_back(source);
            n_inserted.push_back(face.size());
            n_removed.push_back(0);
          }
        any_points_changed = true;
        changed            = true;
      }
    return changed;
  }
} // namespace bsmpm
