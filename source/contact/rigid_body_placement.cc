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
} // namespace bsmpm
