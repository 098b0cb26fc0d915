#include <deal.II/base/quadrature_lib.h>

#include <bsmpm/boundary/curve_piece_values.h>
#include <bsmpm/contact/contact_history.h>
#include <bsmpm/contact/contact_pieces.h>

namespace bsmpm
{
  namespace
  {
    /** Whether a piece whose middle is @p middle can reach body @p b in
     * the increment: within two cells of the body where the increment
     * ends, or of its path (a piece cannot move further in one
     * increment). */
    bool
    contact_piece_within_reach(const std::vector<RigidBody> &bodies,
                               const RigidBodyMotion        &motion,
                               const unsigned int            b,
                               const Point<2>               &middle,
                               const double                  h)
    {
      const Tensor<1, 2> &start = motion.start(b);
      const Tensor<1, 2> &end   = motion.end(b);
      const double        reach = 2 * h + (end - start).norm();
      return !bodies[b].surely_further_than(middle, end, reach) &&
             !(bodies[b].nearest(middle, end).gap > reach);
    }
  } // namespace



  std::vector<ContactPiece>
  collect_pieces_per_cell(const BoundaryCurves         &curves,
                          const BackgroundGrid         &grid,
                          const std::vector<RigidBody> &bodies,
                          const RigidBodyMotion        &motion,
                          const ContactHistory         &history,
                          const unsigned int            n_gauss_points)
  {
    const double              h = grid.min_cell_size();
    CurvePieceValues          values(grid, QGauss<1>(n_gauss_points));
    std::vector<ContactPiece> pieces;
    for (const auto &piece :
         values.pieces(curves, CurvePieceValues::free_pieces()))
      {
        const Point<2> middle =
          piece.curve->spline->value((piece.u_begin + piece.u_end) / 2);
        // The Gauss points are evaluated only for a piece that some body
        // can reach: most free pieces are far from every body.
        bool evaluated = false;
        for (unsigned int b = 0; b < bodies.size(); ++b)
          {
            if (!contact_piece_within_reach(bodies, motion, b, middle, h))
              continue;
            if (!evaluated)
              values.reinit(piece);
            evaluated                 = true;
            const Tensor<1, 2> &start = motion.start(b);
            const Tensor<1, 2> &end   = motion.end(b);
            // The part of the outline the piece faces: that nearest to it
            // before the increment moves anything.
            const SurfacePoint nearest = bodies[b].nearest(middle, start);
            // The pieces of a curve in one cell (one per segment there)
            // that face one part of the rigid outline act as one: one
            // pressure per cell, curve and part.
            const bool joins = !pieces.empty() && pieces.back().body == b &&
                               pieces.back().curve == piece.curve_index &&
                               pieces.back().cell == piece.cell &&
                               pieces.back().feature == nearest.feature &&
                               pieces.back().u_end == piece.u_begin;
            if (!joins)
              pieces.push_back(ContactPiece::make(b,
                                                  piece.curve_index,
                                                  piece.cell,
                                                  nearest.feature,
                                                  piece.u_begin,
                                                  piece.u_end));
            ContactPiece &contact_piece = pieces.back();
            contact_piece.u_end         = piece.u_end;
            for (unsigned int q = 0; q < values.n_quadrature_points(); ++q)
              {
                const Point<2> &x = values.position(q);
                contact_piece.positions.push_back(x);
                contact_piece.features.push_back(
                  bodies[b].nearest(x, start).feature);
                // The first guess of the part that touches: where the
                // rigid body, moved to the increment's end, overlaps the
                // curve that has not moved yet.
                contact_piece.touching.push_back(
                  bodies[b]
                    .to_feature(x, end, contact_piece.features.back())
                    .gap <= 1e-12 * h);
                contact_piece.weights.push_back(values.JxW(q));
                contact_piece.curve_normals.push_back(values.normal(q));
                contact_piece.previous.push_back(
                  history.at(piece.curve_index,
                             *piece.curve,
                             piece.segment,
                             values.parameter(q)));
                contact_piece.length += contact_piece.weights.back();
              }
          }
      }
    return pieces;
  }



  std::vector<ContactPiece>
  collect_pieces_between_crossings(const BoundaryCurves         &curves,
                                   const BackgroundGrid         &grid,
                                   const std::vector<RigidBody> &bodies,
                                   const RigidBodyMotion        &motion,
                                   const ContactHistory         &history,
                                   const unsigned int            n_gauss_points)
  {
    // A piece runs from one point where a free stretch of curve passes
    // from one cell to the next (or ends) to the next such point: the
    // curve's displacement is taken at these crossings and interpolated
    // linearly between them, with the multipliers, so the gap is held
    // where the bilinear displacement has its values on the curve. One
    // pressure per cell held only the mean gap per cell and left the
    // crossings free to move in and out in turn (doc/contact.md,
    // "Pressures at the grid lines"). Both crossings lie on the piece's
    // cell: no coupling beyond the cell pattern.
    const double              h = grid.min_cell_size();
    const QGauss<1>           gauss(n_gauss_points);
    const auto               &all_curves = curves.get_curves();
    std::vector<ContactPiece> pieces;
    for (unsigned int c = 0; c < all_curves.size(); ++c)
      {
        const BoundaryCurve &curve  = all_curves[c];
        const BSplineCurve  &spline = *curve.spline;
        const auto          &P      = curve.pieces;
        const unsigned int   n      = P.size();
        std::vector<bool>    free(n);
        for (unsigned int i = 0; i < n; ++i)
          free[i] = curve.condition_of_segment(P[i].segment) == nullptr;
        // The crossings: boundary i lies before piece i (i = n: an open
        // curve's end).
        std::vector<unsigned int> crossings;
        const unsigned int        n_boundaries = curve.closed ? n : n + 1;
        for (unsigned int i = 0; i < n_boundaries; ++i)
          {
            const int  before      = i > 0        ? int(i) - 1 :
                                     curve.closed ? int(n) - 1 :
                                                    -1;
            const bool free_before = before >= 0 && free[before];
            const bool free_after  = i < n && free[i];
            if ((free_before || free_after) &&
                !(free_before && free_after && P[before].cell == P[i].cell))
              crossings.push_back(i);
          }
        const auto traction_at = [&](const CurvePiece &piece, const double u) {
          return history.at(c, curve, piece.segment, u);
        };
        for (unsigned int j = 0; j < crossings.size(); ++j)
          {
            const unsigned int first = crossings[j];
            if (first == n || !free[first] ||
                grid.locally_owned_cell(P[first].cell) ==
                  grid.dof_handler().end())
              continue;
            const unsigned int next = (j + 1) % crossings.size();
            // The spline's pieces up to the next crossing (past u = 1 on a
            // closed curve): all in the cell of the first.
            std::vector<unsigned int> parts;
            for (unsigned int k = first;
                 parts.empty() || (curve.closed ? k % n : k) != crossings[next];
                 ++k)
              {
                parts.push_back(k % n);
                if (parts.size() > n)
                  break;
              }
            // The parameter ranges of the spline's pieces, counted on past
            // u = 1 (shift) where a closed curve's stretch runs past its
            // start.
            std::vector<std::array<double, 2>> ranges;
            std::vector<double>                shifts;
            for (const unsigned int k : parts)
              {
                shifts.push_back(k < first ? 1. : 0.);
                ranges.push_back(
                  {{P[k].u_begin + shifts.back(), P[k].u_end + shifts.back()}});
              }
            const double u_first = ranges.front()[0];
            const double u_last  = ranges.back()[1];
            if (!(u_last > u_first))
              continue;
            // The piece's geometry, the same for every body.
            ContactPiece piece =
              ContactPiece::make(0, c, P[first].cell, 0, u_first, u_last);
            piece.between_crossings = true;
            piece.end_keys     = {{P[first].u_begin, P[parts.back()].u_end}};
            piece.ends         = {{spline.value(P[first].u_begin),
                                   spline.value(P[parts.back()].u_end)}};
            piece.end_previous = {
              {traction_at(P[first], P[first].u_begin),
               traction_at(P[parts.back()], P[parts.back()].u_end)}};
            for (unsigned int r = 0; r < ranges.size(); ++r)
              {
                const double lo = ranges[r][0], hi = ranges[r][1];
                for (unsigned int q = 0; q < gauss.size(); ++q)
                  {
                    const double u = lo + gauss.point(q)[0] * (hi - lo);
                    piece.positions.push_back(spline.value(u - shifts[r]));
                    piece.weights.push_back(
                      spline.derivative(u - shifts[r]).norm() * (hi - lo) *
                      gauss.weight(q));
                    piece.curve_normals.push_back(
                      spline.outward_normal(u - shifts[r]));
                    piece.phi.push_back((u - u_first) / (u_last - u_first));
                    piece.previous.push_back(
                      traction_at(P[parts[r]], u - shifts[r]));
                    piece.length += piece.weights.back();
                  }
              }
            unsigned int middle_range = 0;
            const double u_middle     = (u_first + u_last) / 2;
            while (middle_range + 1 < ranges.size() &&
                   u_middle > ranges[middle_range][1])
              ++middle_range;
            const Point<2> middle =
              spline.value(u_middle - shifts[middle_range]);
            for (unsigned int b = 0; b < bodies.size(); ++b)
              {
                if (!contact_piece_within_reach(bodies, motion, b, middle, h))
                  continue;
                // The parts of the outline the crossings and the Gauss
                // points face: those nearest before the increment.
                const Tensor<1, 2> &start     = motion.start(b);
                ContactPiece        candidate = piece;
                candidate.body                = b;
                for (unsigned int e = 0; e < 2; ++e)
                  candidate.end_features[e] =
                    bodies[b].nearest(piece.ends[e], start).feature;
                candidate.feature = candidate.end_features[0];
                for (const Point<2> &x : piece.positions)
                  candidate.features.push_back(
                    bodies[b].nearest(x, start).feature);
                pieces.push_back(std::move(candidate));
              }
          }
      }
    return pieces;
  }
} // namespace bsmpm
