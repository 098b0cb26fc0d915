#include <bsmpm/contact/rigid_body_placement.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

namespace bsmpm
{
  namespace
  {
    std::string
    placement_figure(const double value)
    {
      std::ostringstream s;
      s << std::setprecision(3) << value;
      return s.str();
    }



    std::string
    placement_point(const Point<2> &p)
    {
      return "(" + placement_figure(p[0]) + ", " + placement_figure(p[1]) + ")";
    }



    /** The deepest of the overlaps found on the processes. Collective. */
    RigidBodyPlacement::Overlap
    deepest_on_all(const RigidBodyPlacement::Overlap &local,
                   const MPI_Comm                     communicator)
    {
      RigidBodyPlacement::Overlap deepest;
      for (const auto &part : Utilities::MPI::all_gather(
             communicator,
             std::vector<double>{local.depth, local.where[0], local.where[1]}))
        if (part[0] > deepest.depth)
          {
            deepest.depth = part[0];
            deepest.where = Point<2>(part[1], part[2]);
          }
      return deepest;
    }
  } // namespace



  RigidBodyPlacement::Overlap
  RigidBodyPlacement::deepest(const RigidBody             &body,
                              const Tensor<1, 2>          &translation,
                              const std::vector<Point<2>> &points)
  {
    Overlap overlap;
    for (const Point<2> &x : points)
      if (!body.surely_further_than(x, translation, 0.))
        {
          const double depth = -body.nearest(x, translation).gap;
          if (depth > overlap.depth)
            overlap = {depth, x};
        }
    return overlap;
  }



  std::vector<Point<2>>
  RigidBodyPlacement::densified(const std::vector<Point<2>> &outline,
                                const double                 spacing)
  {
    std::vector<Point<2>> dense;
    for (unsigned int k = 0; k + 1 < outline.size(); ++k)
      {
        const Tensor<1, 2> edge = outline[k + 1] - outline[k];
        const unsigned int n = std::max(1., std::ceil(edge.norm() / spacing));
        for (unsigned int i = 0; i < n; ++i)
          dense.push_back(outline[k] + (double(i) / n) * edge);
      }
    return dense;
  }



  void
  RigidBodyPlacement::check(const std::vector<RigidBody>    &bodies,
                            const std::vector<Tensor<1, 2>> &places,
                            const BoundaryCurves            &curves,
                            const MaterialPoints            &points,
                            const double                     cell_size,
                            const MPI_Comm                   communicator)
  {
    // An overlap of up to a twentieth of a cell is what one load increment
    // of a footing typically moves it into the soil (2 to 9 % of a cell in
    // prm/strip-footing-rigid.prm): contact resolves it in the first
    // increment as it does every increment's motion.
    const double tolerance = 0.05 * cell_size;
    // The body's material: its points (distributed) and its curves (the
    // same on every process), with the splines' segment midpoints, so that
    // a corner of a rigid body between two curve points is found too.
    std::vector<Point<2>> material;
    for (const auto &particle : points.particle_handler())
      if (particle.get_properties()[MaterialPoints::Property::volume] > 0)
        material.push_back(particle.get_location());
    std::vector<Point<2>> boundary;
    for (const BoundaryCurve &curve : curves.get_curves())
      {
        boundary.insert(boundary.end(),
                        curve.positions.begin(),
                        curve.positions.end());
        if (curve.spline)
          for (unsigned int k = 0; k < curve.spline->n_segments(); ++k)
            boundary.push_back(curve.spline->segment_value(k, 0.5));
      }

    std::string problems;
    for (unsigned int b = 0; b < bodies.size(); ++b)
      {
        Overlap inside =
          deepest_on_all(deepest(bodies[b], places[b], material), communicator);
        const Overlap on_curves = deepest(bodies[b], places[b], boundary);
        if (on_curves.depth > inside.depth)
          inside = on_curves;
        if (inside.depth > tolerance)
          problems += " " + bodies[b].section() +
                      " starts inside the body: the body's material lies "
                      "up to " +
                      placement_figure(inside.depth) +
                      " m inside its outline (the deepest at " +
                      placement_point(inside.where) + ").";
      }
    // Each outline tested against the other body at points a quarter of a
    // cell apart at most (a circle's outline has 128 points, a polygon's
    // only its corners).
    const double spacing = cell_size / 4;
    for (unsigned int a = 0; a < bodies.size(); ++a)
      for (unsigned int b = a + 1; b < bodies.size(); ++b)
        {
          Overlap overlap =
            deepest(bodies[b],
                    places[b],
                    densified(bodies[a].outline(places[a]), spacing));
          const Overlap reverse =
            deepest(bodies[a],
                    places[a],
                    densified(bodies[b].outline(places[b]), spacing));
          if (reverse.depth > overlap.depth)
            overlap = reverse;
          if (overlap.depth > tolerance)
            problems += " " + bodies[a].section() + " and " +
                        bodies[b].section() + " overlap by " +
                        placement_figure(overlap.depth) + " m (at " +
                        placement_point(overlap.where) + ").";
        }
    AssertThrow(problems.empty(),
                ExcMessage(
                  "Rigid bodies placed where they cannot be:" + problems +
                  " A rigid body must start outside the body and the other "
                  "rigid bodies, touching them at most (an overlap of up to "
                  "a twentieth of a cell, " +
                  placement_figure(tolerance) +
                  " m, counts as touching): move it (its Vertices or Center, "
                  "or its Displacement at t = 0) or make it smaller."));
  }


  void
  RigidBodyPlacement::check_motion_along_faces(
    const std::vector<RigidBody> &bodies,
    const BackgroundGrid         &grid,
    const MaterialPoints         &points,
    const double                  last_load_factor)
  {
    const double                      h          = grid.min_cell_size();
    const std::array<const char *, 4> face_names = {
      {"Left", "Right", "Bottom", "Top"}};
    std::string problems;
    for (unsigned int f = 0; f < 4; ++f)
      {
        if (grid.face_condition(f) != BackgroundGrid::FaceCondition::fixed)
          continue;
        // The face's line n = at, and the direction t along it.
        const unsigned int n = f / 2, t = 1 - n;
        const double       at =
          f % 2 == 0 ? grid.lower_left()[n] : grid.upper_right()[n];
        for (const RigidBody &body : bodies)
          {
            // Where the body's outline crosses the face's line: the
            // stretch [a, b] of the line inside the body.
            const std::vector<Point<2>> outline =
              body.outline(body.displacement(0));
            double a = std::numeric_limits<double>::infinity(), b = -a;
            for (unsigned int k = 0; k + 1 < outline.size(); ++k)
              {
                const Point<2> &p = outline[k], &q = outline[k + 1];
                if ((p[n] - at) * (q[n] - at) > 0 || p[n] == q[n])
                  continue;
                const double s = (at - p[n]) / (q[n] - p[n]);
                const double c = p[t] + s * (q[t] - p[t]);
                a              = std::min(a, c);
                b              = std::max(b, c);
              }
            if (!(a < b))
              continue;
            // The farthest the body moves along the face either way.
            double ahead = 0, back = 0;
            for (unsigned int i = 1; i <= 64; ++i)
              {
                const double along =
                  body.displacement(i * last_load_factor / 64)[t] -
                  body.displacement(0)[t];
                ahead = std::max(ahead, along);
                back  = std::min(back, along);
              }
            // Material held by the face next to the body, on the side it
            // moves to.
            double met = std::numeric_limits<double>::quiet_NaN();
            for (const auto &particle : points.particle_handler())
              {
                const Point<2> &x = particle.get_location();
                if (particle
                        .get_properties()[MaterialPoints::Property::volume] <=
                      0 ||
                    std::abs(x[n] - at) > h)
                  continue;
                if ((ahead > 0 && x[t] >= b && x[t] - b < h) ||
                    (back < 0 && x[t] <= a && a - x[t] < h))
                  met = x[t];
              }
            met = Utilities::MPI::max(std::isnan(met) ? -1e300 : met,
                                      grid.mpi_communicator());
            if (met > -1e300)
              problems += " " + body.section() +
                          " reaches through the grid's fixed " + face_names[f] +
                          " face, and its Displacement moves it along "
                          "that face towards the material the face holds "
                          "(at " +
                          (t == 0 ? "x = " : "y = ") + placement_figure(met) +
                          "): that material can neither move nor make room, "
                          "so the body would have to pass through it. Make "
                          "the face a roller (Background grid/Face "
                          "conditions/" +
                          face_names[f] +
                          ") or let the body end inside the grid.";
          }
      }
    AssertThrow(problems.empty(), ExcMessage(Utilities::trim(problems)));
  }
} // namespace bsmpm
