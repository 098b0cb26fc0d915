#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include <bsmpm/contact/curve_contact.h>
#include <bsmpm/points/material_points.h>

#include <array>
#include <cmath>
#include <iomanip>
#include <limits>
#include <map>
#include <sstream>

namespace bsmpm
{
  void
  CurveContact::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Contact");
    prm.declare_entry(
      "Check tangent",
      "false",
      Patterns::Bool(),
      "A check for developers: compares the contact's tangent on every "
      "touching piece, with the terms of a force-controlled rigid body's "
      "translation, with central differences of its forces at every Newton "
      "iteration; summary.json records the largest relative difference as "
      "contact_tangent_error. Costs ten force evaluations per piece.");
    prm.declare_entry(
      "Penalty",
      "10",
      Patterns::Double(0.),
      "gamma in the contact penalty eps = gamma max(E, kappa) / h: the "
      "pressure per unit penetration, and the tangential traction per unit "
      "slip while sticking. With Method = penalty the penetration is about p "
      "h / (gamma E); with the augmented Lagrangian the mean penetration goes "
      "to zero and gamma sets how fast the updates converge. Keep it at most "
      "about 20: larger values over-constrain one pressure per cell under a "
      "flat rigid base, whose pressures then alternate from cell to cell "
      "(doc/contact.md).");
    prm.declare_entry(
      "Pressure",
      "automatic",
      Patterns::Selection("automatic|per cell|at grid lines"),
      "Where the contact pressure is taken (doc/contact.md). 'per cell': one "
      "pressure for the mean gap of the touching part of each cell's piece of "
      "curve. 'at grid lines': the curve's displacement taken where it "
      "crosses the grid lines and linear between them, a pressure at every "
      "Gauss point of that gap and multipliers at the crossings; it holds the "
      "grid nodes under a flat rigid base, which one pressure per cell leaves "
      "free to move in and out in turn (plastic soil in flow hardly resists "
      "that), but holds a body's edge in the middle of a cell more weakly. "
      "'automatic' (the default): per cell in small strain, at grid lines in "
      "finite strain.");
    prm.declare_entry(
      "Tilt penalty",
      "0",
      Patterns::Double(0.),
      "Experimental; leave it at 0 (off). A penalty on the tilt of the gap "
      "along the touching part of a piece, as a factor of 'Penalty' (1: the "
      "gap's projection on linear functions along the piece as a whole), "
      "aimed at the alternating mode that 'Pressure = at grid lines' holds; "
      "its force jumps where a piece's mean gap passes zero (doc/contact.md).");
    prm.declare_entry(
      "Method",
      "automatic",
      Patterns::Selection("automatic|augmented Lagrangian|penalty"),
      "How contact is imposed on the curves' pieces (doc/contact.md). "
      "'penalty': a pressure eps times the penetration (eps = Penalty max(E, "
      "kappa) / h): the body penetrates by about p h / (Penalty E). "
      "'augmented Lagrangian': the same penalty with multipliers, updated "
      "after each converged Newton solve of the load step until the force on "
      "every rigid body changes by less than the Augmentation tolerance: the "
      "mean penetration goes to zero, at the cost of a few more solves per "
      "step. Both hold sticking friction by the penalty. 'automatic' (the "
      "default): the augmented Lagrangian in small strain, the penalty in "
      "finite strain, where the augmentations may not converge as a curve "
      "slides round a body's corner. Choose 'penalty' for a cheaper run whose "
      "small penetration does not matter.");
    prm.declare_entry(
      "Augmentation tolerance",
      "1e-4",
      Patterns::Double(0., 1.),
      "The augmented Lagrangian stops updating the multipliers of a load step "
      "when the force on every rigid body (for a body under a Force: its "
      "motion in the step) has changed by less than this fraction of it in "
      "the last update. Lower it for forces closer to the exact mean gaps at "
      "the cost of more solves; much lower values may not be reached (the "
      "updates stop at 'Maximum augmentations').");
    prm.declare_entry(
      "Maximum augmentations",
      "30",
      Patterns::Integer(0, 1000),
      "Multiplier updates (each one more Newton solve) per load step at "
      "most; then the step goes on with the last multipliers, and "
      "summary.json's contact_augmentations shows when the limit was "
      "reached.");
    prm.declare_entry("Gauss points per piece",
                      "4",
                      Patterns::Integer(1, 100),
                      "Gauss points on each piece of a free curve that can "
                      "touch a rigid body; more for strongly curved outlines "
                      "or pieces.");
    prm.leave_subsection();
    RigidBody::declare_parameters(prm);
  }



  void
  CurveContact::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Contact");
    gamma                    = prm.get_double("Penalty");
    check_tangent            = prm.get_bool("Check tangent");
    n_gauss_points           = prm.get_integer("Gauss points per piece");
    const std::string method = prm.get("Method");
    augmentation_tolerance   = prm.get_double("Augmentation tolerance");
    max_augmentations        = prm.get_integer("Maximum augmentations");
    gamma_tilt               = prm.get_double("Tilt penalty");
    const std::string where  = prm.get("Pressure");
    prm.leave_subsection();
    prm.enter_subsection("Material");
    const bool finite_strain = prm.get("Kinematics") == "finite strain";
    prm.leave_subsection();
    augmented = method == "augmented Lagrangian" ||
                (method == "automatic" && !finite_strain);
    pressure_at_crossings =
      where == "at grid lines" || (where == "automatic" && finite_strain);
    bodies = RigidBody::create_all(prm);
    AssertThrow(bodies.empty() || gamma > 0,
                ExcMessage("Contact/Penalty must be positive."));
    resultants.assign(bodies.size(), Resultant());
    body_motion.initialize(bodies);
  }



  void
  CurveContact::begin_increment(const BoundaryCurves &curves,
                                const BackgroundGrid &grid,
                                const double          stiffness,
                                const double          load_from,
                                const double          load_to)
  {
    const double h = grid.min_cell_size();
    penalty        = gamma * stiffness / h;
    tilt_penalty   = gamma_tilt * penalty;
    from           = load_from;
    to             = load_to;
    body_motion.begin_increment(bodies, from, to);
    pieces.clear();
    touching_updates = 0;
    augmentations    = 0;
    force_change     = 0;
    // No force yet: the first update always asks for one more solve.
    last_places.assign(bodies.size(),
                       Tensor<1, 2>(
                         {std::numeric_limits<double>::infinity(), 0.}));
    last_forces.assign(bodies.size(),
                       Tensor<1, 2>(
                         {std::numeric_limits<double>::infinity(), 0.}));
    const QGauss<1> gauss(n_gauss_points);
    const auto     &all_curves = curves.get_curves();
    point_tractions.resize(all_curves.size());
    for (unsigned int c = 0; c < all_curves.size(); ++c)
      // A curve whose points changed in number starts without history.
      if (point_tractions[c].size() != all_curves[c].positions.size())
        point_tractions[c].assign(all_curves[c].positions.size(),
                                  Tensor<1, 2>());
    if (pressure_at_crossings)
      collect_crossings(curves, grid);
    for (unsigned int c = 0; c < all_curves.size() && !pressure_at_crossings;
         ++c)
      {
        const BoundaryCurve &curve  = all_curves[c];
        const BSplineCurve  &spline = *curve.spline;
        for (const auto &piece : curve.pieces)
          {
            if (curve.condition_of_segment(piece.segment) != nullptr ||
                grid.locally_owned_cell(piece.cell) == grid.dof_handler().end())
              continue;
            const Point<2> middle =
              spline.value((piece.u_begin + piece.u_end) / 2);
            for (unsigned int b = 0; b < bodies.size(); ++b)
              {
                // Within two cells of the body where the increment ends,
                // or of its path: a piece cannot move further in one
                // increment.
                const Tensor<1, 2> &start = body_motion.start(b);
                const Tensor<1, 2> &end   = body_motion.end(b);
                const double        reach = 2 * h + (end - start).norm();
                if (bodies[b].surely_further_than(middle, end, reach))
                  continue;
                if (bodies[b].nearest(middle, end).gap > reach)
                  continue;
                // The part of the outline the piece faces: that nearest to
                // it before the increment moves anything.
                const SurfacePoint nearest = bodies[b].nearest(middle, start);
                // The pieces of a curve in one cell (one per segment there)
                // that face one part of the rigid outline act as one: one
                // pressure per cell, curve and part.
                const bool joins = !pieces.empty() && pieces.back().body == b &&
                                   pieces.back().curve == c &&
                                   pieces.back().cell == piece.cell &&
                                   pieces.back().feature == nearest.feature &&
                                   pieces.back().u_end == piece.u_begin;
                if (!joins)
                  pieces.push_back(ContactPiece::make(b,
                                                      c,
                                                      piece.cell,
                                                      nearest.feature,
                                                      piece.u_begin,
                                                      piece.u_end));
                ContactPiece &contact_piece = pieces.back();
                contact_piece.u_end         = piece.u_end;
                const auto range = spline.segment_parameters(piece.segment);
                const unsigned int k1 =
                  (piece.segment + 1) % curve.positions.size();
                const double du = piece.u_end - piece.u_begin;
                for (unsigned int q = 0; q < gauss.size(); ++q)
                  {
                    const double u = piece.u_begin + gauss.point(q)[0] * du;
                    const double f = (u - range[0]) / (range[1] - range[0]);
                    contact_piece.positions.push_back(spline.value(u));
                    contact_piece.features.push_back(
                      bodies[b]
                        .nearest(contact_piece.positions.back(), start)
                        .feature);
                    // The first guess of the part that touches: where the
                    // rigid body, moved to the increment's end, overlaps
                    // the curve that has not moved yet.
                    contact_piece.touching.push_back(
                      bodies[b]
                        .to_feature(contact_piece.positions.back(),
                                    end,
                                    contact_piece.features.back())
                        .gap <= 1e-12 * h);
                    contact_piece.weights.push_back(
                      spline.derivative(u).norm() * du * gauss.weight(q));
                    contact_piece.previous.push_back(
                      (1 - f) * point_tractions[c][piece.segment] +
                      f * point_tractions[c][k1]);
                    contact_piece.length += contact_piece.weights.back();
                  }
              }
          }
      }
    for (unsigned int b = 0; b < bodies.size(); ++b)
      if (bodies[b].has_free_motion())
        touch_if_free(b, grid);
    if (augmented)
      initialize_multipliers();
  }



  void
  CurveContact::collect_crossings(const BoundaryCurves &curves,
                                  const BackgroundGrid &grid)
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
    const double    h = grid.min_cell_size();
    const QGauss<1> gauss(n_gauss_points);
    const auto     &all_curves = curves.get_curves();
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
          const auto   range = spline.segment_parameters(piece.segment);
          const double f     = (u - range[0]) / (range[1] - range[0]);
          return (1 - f) * point_tractions[c][piece.segment] +
                 f * point_tractions[c][(piece.segment + 1) %
                                        curve.positions.size()];
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
                const Tensor<1, 2> &start = body_motion.start(b);
                const Tensor<1, 2> &end   = body_motion.end(b);
                const double        reach = 2 * h + (end - start).norm();
                if (bodies[b].surely_further_than(middle, end, reach) ||
                    bodies[b].nearest(middle, end).gap > reach)
                  continue;
                // The parts of the outline the crossings and the Gauss
                // points face: those nearest before the increment.
                ContactPiece candidate = piece;
                candidate.body         = b;
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
  }



  void
  CurveContact::initialize_multipliers()
  {
    // The multipliers carry the traction of the last increment into this
    // one, as the friction history does: the first Newton solve then
    // penetrates only by what the increment adds, and fewer updates
    // follow. They are kept at the curves' points (which every process
    // holds alike, and which follow the points added and removed), so a
    // piece takes the mean over the Gauss points of its first guess of the
    // touching part (of all its Gauss points if none touches).
    for (ContactPiece &piece : pieces)
      {
        const RigidBody &body = bodies[piece.body];
        if (piece.between_crossings)
          {
            for (unsigned int e = 0; e < 2; ++e)
              piece.end_multipliers[e] =
                std::max(piece.end_previous[e] *
                           body
                             .to_feature(piece.ends[e],
                                         body_motion.end(piece.body),
                                         piece.end_features[e])
                             .normal,
                         0.);
            continue;
          }
        double normal = 0, length = 0;
        bool   any = false;
        for (const bool t : piece.touching)
          any = any || t;
        for (unsigned int q = 0; q < piece.positions.size(); ++q)
          if (piece.touching[q] || !any)
            {
              const Tensor<1, 2> n = body
                                       .to_feature(piece.positions[q],
                                                   body_motion.end(piece.body),
                                                   piece.features[q])
                                       .normal;
              normal += piece.weights[q] * (piece.previous[q] * n);
              length += piece.weights[q];
            }
        piece.multiplier_pressure =
          length > 0 ? std::max(normal / length, 0.) : 0.;
      }
  }



  void
  CurveContact::touch_if_free(const unsigned int b, const BackgroundGrid &grid)
  {
    const MPI_Comm communicator = grid.mpi_communicator();
    const double   h            = grid.min_cell_size();
    const double   touching     = 1e-12 * h;
    // Where the points that measure a piece's gap meet the body's outline:
    // the Gauss points, or between crossings the crossings.
    const auto surfaces = [&](const ContactPiece &piece) {
      std::vector<SurfacePoint> points;
      if (piece.between_crossings)
        for (unsigned int e = 0; e < 2; ++e)
          points.push_back(bodies[b].to_feature(piece.ends[e],
                                                body_motion.end(b),
                                                piece.end_features[e]));
      else
        for (unsigned int q = 0; q < piece.positions.size(); ++q)
          points.push_back(bodies[b].to_feature(piece.positions[q],
                                                body_motion.end(b),
                                                piece.features[q]));
      return points;
    };
    const auto touches = [&]() {
      bool any = false;
      for (const ContactPiece &piece : pieces)
        if (piece.body == b)
          {
            for (const bool t : piece.touching)
              any = any || t;
            if (piece.between_crossings)
              for (const SurfacePoint &point : surfaces(piece))
                any = any || point.gap <= touching;
          }
      return Utilities::MPI::logical_or(any, communicator);
    };
    if (touches())
      return;
    // A body under a force that touches nothing has no stiffness against
    // its free motion (H - G Y = 0): move it along its force until it
    // touches the first Gauss point of a curve. The gap of a point falls
    // by s n . e as the body moves by s e (exactly for an edge, to first
    // order for a circle: a few rounds).
    Tensor<1, 2> direction = bodies[b].applied_force(to);
    if (direction.norm() == 0)
      return;
    direction /= direction.norm();
    double moved = 0;
    for (unsigned int round = 0; round < 4 && !touches(); ++round)
      {
        double shift = std::numeric_limits<double>::infinity();
        for (const ContactPiece &piece : pieces)
          if (piece.body == b)
            for (const SurfacePoint &surface : surfaces(piece))
              {
                const double approach = surface.normal * direction;
                if (approach > 0)
                  shift = std::min(shift, surface.gap / approach);
              }
        shift = Utilities::MPI::min(shift, communicator);
        AssertThrow(std::isfinite(shift),
                    ExcMessage(
                      bodies[b].name() + " (Rigid body " +
                      std::to_string(b + 1) + "): its Force at load factor " +
                      std::to_string(to) +
                      " pushes it where no boundary curve is within two "
                      "cells: nothing supports it. Place it touching the "
                      "body (or within two cells in the direction of its "
                      "Force)."));
        // Just past touching, so that the nearest point presses with a
        // pressure of round-off and the body has a stiffness.
        shift += 1e-10 * h;
        body_motion.approach(b, shift * direction);
        moved += shift;
        for (ContactPiece &piece : pieces)
          if (piece.body == b && !piece.between_crossings)
            for (unsigned int q = 0; q < piece.positions.size(); ++q)
              piece.touching[q] = bodies[b]
                                    .to_feature(piece.positions[q],
                                                body_motion.end(b),
                                                piece.features[q])
                                    .gap <= touching;
      }
    std::ostringstream text;
    text << bodies[b].name() << " touched nothing: moved by " << moved
         << " m along its force to touch";
    body_motion.note(text.str());
  }



  CurveContact::PieceState
  CurveContact::evaluate(const ContactPiece              &piece,
                         const BackgroundGrid            &grid,
                         const Q1CellKernel              &kernel,
                         const Q1CellKernel::LocalVector &d,
                         const Tensor<1, 2>              &body_shift) const
  {
    if (piece.between_crossings)
      return evaluate_between_crossings(piece, grid, kernel, d, body_shift);
    // The cell's DoFs and, as two more, the body's translation at the
    // increment's end: moving the body by c moves every gap as moving the
    // point by -c does, so c enters as a DoF with the shape -e_k at every
    // Gauss point. The extended force and stiffness give the bordered
    // terms of a force-controlled body (RigidBodyMotion) with no other
    // formula than the grid's.
    constexpr unsigned int n_grid = Q1CellKernel::dofs_per_cell;
    constexpr unsigned int n      = n_grid + 2;
    const RigidBody       &body   = bodies[piece.body];
    const unsigned int     n_q    = piece.positions.size();
    // Where the Gauss points are after the increment, and their gaps to
    // the part of the outline each faces.
    std::vector<std::array<Tensor<1, 2>, n>> N(n_q);
    std::vector<Tensor<1, 2>>                u(n_q);
    PieceState                               state;
    std::vector<SurfacePoint>               &surface = state.surface;
    surface.resize(n_q);
    double length = 0;
    for (unsigned int q = 0; q < n_q; ++q)
      {
        const Point<2> st =
          grid.local_coordinates(piece.positions[q], piece.cell);
        for (unsigned int i = 0; i < n_grid; ++i)
          {
            N[q][i] = kernel.shape_value(i, st);
            u[q] += d[i] * N[q][i];
          }
        N[q][n_grid]     = Tensor<1, 2>({-1., 0.});
        N[q][n_grid + 1] = Tensor<1, 2>({0., -1.});
        surface[q]       = body.to_feature(piece.positions[q] + u[q],
                                     body_motion.end(piece.body) + body_shift,
                                     piece.features[q]);
        if (!piece.touching[q])
          continue;
        state.gap += piece.weights[q] * surface[q].gap;
        length += piece.weights[q];
        state.normal += piece.weights[q] * surface[q].normal;
        state.midpoint += piece.weights[q] * (piece.positions[q] + u[q]);
      }
    state.force.reinit(n);
    state.stiffness.reinit(n, n);
    if (length == 0)
      return state;
    state.gap /= length;
    // The augmented Lagrangian's pressure max(0, lambda - eps g) acts
    // while the gap is below lambda / eps (zero for the plain penalty).
    const double lambda = augmented ? piece.multiplier_pressure : 0.;
    // Touching within round-off counts, with zero pressure: a body that
    // rests on a rigid one (and on nothing else) is held from the first
    // iteration on, which starts from the touching place.
    if (!(state.gap <= lambda / penalty + 1e-12 * grid.min_cell_size()))
      return state;
    state.active = true;
    state.normal /= state.normal.norm();
    state.midpoint /= length;
    state.contact_length = length;
    const double L       = length;

    // The potential eps L g^2 / 2 of the mean gap g over the part of the
    // piece that touches: one pressure p = -eps g for the part. One
    // pressure per cell does not over-constrain the bilinear displacement,
    // as one per Gauss point did (its pressure alternated between zero and
    // twice Hertz's); which Gauss points touch is fixed within the Newton
    // iterations (update_touching_parts()), so that the force stays a
    // smooth function of the increment. G_i = -d(L g)/du_i = int n . N_i.
    state.pressure = std::max(lambda - penalty * state.gap, 0.);
    Vector<double> G(n), T(n);
    for (unsigned int q = 0; q < n_q; ++q)
      {
        if (!piece.touching[q])
          continue;
        const Tensor<1, 2> &nq = surface[q].normal;
        const Tensor<1, 2>  tq({-nq[1], nq[0]});
        for (unsigned int i = 0; i < n; ++i)
          {
            G[i] += piece.weights[q] * (nq * N[q][i]);
            T[i] += piece.weights[q] * (tq * N[q][i]);
          }
        state.resultant += piece.weights[q] * state.pressure * nq;
        // p dn/dx with dn/dx = (I - n n) / rho where the surface turns.
        const double rho = surface[q].turning_radius;
        if (std::isfinite(rho) && rho > 0)
          for (unsigned int i = 0; i < n; ++i)
            for (unsigned int j = 0; j < n; ++j)
              state.stiffness(i, j) -=
                piece.weights[q] * state.pressure / rho *
                (N[q][i] * N[q][j] - (nq * N[q][i]) * (nq * N[q][j]));
      }
    for (unsigned int i = 0; i < n; ++i)
      {
        state.force[i] = state.pressure * G[i];
        for (unsigned int j = 0; j < n; ++j)
          state.stiffness(i, j) += penalty / L * G[i] * G[j];
      }
    add_tilt_terms(piece, N, surface, state);
    if (body.friction() == RigidBody::Friction::smooth)
      return state;

    // Coulomb's return map on the mean slip, relative to the rigid body,
    // of the part that touches, from the mean tangential traction of the
    // last increment there.
    const Tensor<1, 2> rigid =
      body_motion.end(piece.body) + body_shift - body_motion.start(piece.body);
    double slip = 0, previous = 0;
    for (unsigned int q = 0; q < n_q; ++q)
      if (piece.touching[q])
        {
          const Tensor<1, 2> &nq = surface[q].normal;
          const Tensor<1, 2>  tq({-nq[1], nq[0]});
          slip += piece.weights[q] * ((u[q] - rigid) * tq) / length;
          previous += piece.weights[q] * (piece.previous[q] * tq) / length;
        }
    // Sticking stays regularized by the penalty (eps per unit slip, from
    // the traction of the last increment) also with the augmented
    // Lagrangian: augmenting the tangential traction per piece drifted
    // without end along the alternating mode (doc/contact.md).
    const double trial   = previous - penalty * slip;
    const double limit   = body.friction() == RigidBody::Friction::rough ?
                             std::numeric_limits<double>::infinity() :
                             body.friction_coefficient() * state.pressure;
    const double sign    = trial > 0 ? 1. : -1.;
    state.sliding        = std::abs(trial) > limit;
    state.tangential     = state.sliding ? sign * limit : trial;
    state.sliding_length = state.sliding ? length : 0.;
    for (unsigned int i = 0; i < n; ++i)
      {
        state.force[i] += state.tangential * T[i];
        for (unsigned int j = 0; j < n; ++j)
          state.stiffness(i, j) +=
            state.sliding ?
              // t_T = mu p sign: its derivative is p's.
              sign * body.friction_coefficient() * penalty / L * T[i] * G[j] :
              penalty / L * T[i] * T[j];
      }
    // Where the outline turns, t_q turns with n_q (dn/dx = t t^T / rho,
    // dt/dx = -n t^T / rho): T_i and, while sticking, the trial traction
    // (the mean of (t_previous - eps (u - u_rigid)) . t) feel it.
    for (unsigned int q = 0; q < n_q; ++q)
      {
        const double rho = surface[q].turning_radius;
        if (!piece.touching[q] || !std::isfinite(rho) || !(rho > 0))
          continue;
        const Tensor<1, 2> &nq = surface[q].normal;
        const Tensor<1, 2>  tq({-nq[1], nq[0]});
        const double        w = piece.weights[q] / rho;
        const double        c =
          state.sliding ?
                   0. :
                   (piece.previous[q] * nq - penalty * ((u[q] - rigid) * nq)) / L;
        for (unsigned int i = 0; i < n; ++i)
          for (unsigned int j = 0; j < n; ++j)
            state.stiffness(i, j) +=
              w * (c * T[i] + state.tangential * (nq * N[q][i])) *
              (tq * N[q][j]);
      }
    for (unsigned int q = 0; q < n_q; ++q)
      if (piece.touching[q])
        {
          const Tensor<1, 2> &nq = surface[q].normal;
          state.resultant +=
            piece.weights[q] * state.tangential * Tensor<1, 2>({-nq[1], nq[0]});
        }
    return state;
  }



  CurveContact::PieceState
  CurveContact::evaluate_between_crossings(const ContactPiece   &piece,
                                           const BackgroundGrid &grid,
                                           const Q1CellKernel   &kernel,
                                           const Q1CellKernel::LocalVector &d,
                                           const Tensor<1, 2> &body_shift) const
  {
    // The curve's displacement is taken at the two crossings and linear
    // between them, u = (1 - phi) u_0 + phi u_1 (on a straight curve the
    // bilinear field's own trace): a Gauss point X moves to X + u, its gap
    // g to the outline is measured there, and its pressure is
    // p = max(0, lambda - eps g), lambda interpolated as u from the
    // crossings' multipliers. The potential int (max(0, lambda - eps g)^2
    // - lambda^2) / (2 eps) ds then has the force int p n . N and the
    // tangent eps int (n . N)(n . N)^T ds (with N = (1 - phi) N(x_0) +
    // phi N(x_1)), plus the turning of n where the outline turns. The
    // gap has only the two crossings' freedom per piece, so a pressure
    // per Gauss point does not over-constrain it, and it is held at the
    // grid lines, where alternating up and down would hide from a mean
    // per cell. As in evaluate(), the body's translation enters as two
    // more DoFs.
    constexpr unsigned int n_grid = Q1CellKernel::dofs_per_cell;
    constexpr unsigned int n      = n_grid + 2;
    const RigidBody       &body   = bodies[piece.body];
    const Tensor<1, 2>     place  = body_motion.end(piece.body) + body_shift;
    const Tensor<1, 2>     rigid  = place - body_motion.start(piece.body);
    PieceState             state;
    state.force.reinit(n);
    state.stiffness.reinit(n, n);
    std::array<std::array<Tensor<1, 2>, n>, 2> N_end;
    std::array<Tensor<1, 2>, 2>                u_end;
    for (unsigned int e = 0; e < 2; ++e)
      {
        const Point<2> st = grid.local_coordinates(piece.ends[e], piece.cell);
        for (unsigned int i = 0; i < n_grid; ++i)
          {
            N_end[e][i] = kernel.shape_value(i, st);
            u_end[e] += d[i] * N_end[e][i];
          }
        N_end[e][n_grid]     = Tensor<1, 2>({-1., 0.});
        N_end[e][n_grid + 1] = Tensor<1, 2>({0., -1.});
      }
    const double tolerance = 1e-12 * grid.min_cell_size();
    const bool   smooth    = body.friction() == RigidBody::Friction::smooth;
    const bool   rough     = body.friction() == RigidBody::Friction::rough;
    std::array<Tensor<1, 2>, n> N;
    Vector<double>              G(n), T(n);
    double                      length = 0;
    for (unsigned int q = 0; q < piece.positions.size(); ++q)
      {
        const double w      = piece.weights[q];
        const double phi[2] = {1 - piece.phi[q], piece.phi[q]};
        for (unsigned int e = 0; e < 2; ++e)
          state.end_weights[e] += w * phi[e];
        for (unsigned int i = 0; i < n; ++i)
          N[i] = phi[0] * N_end[0][i] + phi[1] * N_end[1][i];
        const Tensor<1, 2> u = phi[0] * u_end[0] + phi[1] * u_end[1];
        const SurfacePoint surface =
          body.to_feature(piece.positions[q] + u, place, piece.features[q]);
        const double lambda = augmented ? phi[0] * piece.end_multipliers[0] +
                                            phi[1] * piece.end_multipliers[1] :
                                          0.;
        // Touching within round-off counts, with zero pressure (as in
        // evaluate()).
        if (!(surface.gap <= lambda / penalty + tolerance))
          continue;
        state.active           = true;
        const double        p  = std::max(lambda - penalty * surface.gap, 0.);
        const Tensor<1, 2> &nq = surface.normal;
        const Tensor<1, 2>  tq({-nq[1], nq[0]});
        length += w;
        state.gap += w * surface.gap;
        state.pressure += w * p;
        state.normal += w * nq;
        state.midpoint += w * (piece.positions[q] + u);
        for (unsigned int i = 0; i < n; ++i)
          {
            G[i] = nq * N[i];
            T[i] = tq * N[i];
          }
        double traction = 0;
        if (!smooth)
          {
            // Coulomb's return map at the Gauss point, on its slip
            // relative to the body and the traction of the last increment
            // there.
            const double trial =
              piece.previous[q] * tq - penalty * ((u - rigid) * tq);
            const double limit   = rough ?
                                     std::numeric_limits<double>::infinity() :
                                     body.friction_coefficient() * p;
            const double sign    = trial > 0 ? 1. : -1.;
            const bool   sliding = std::abs(trial) > limit;
            traction             = sliding ? sign * limit : trial;
            state.sliding        = state.sliding || sliding;
            state.sliding_length += sliding ? w : 0.;
            state.tangential += w * traction;
            for (unsigned int i = 0; i < n; ++i)
              for (unsigned int j = 0; j < n; ++j)
                state.stiffness(i, j) +=
                  sliding ?
                    // t_T = mu p sign: its derivative is p's.
                    w * sign * body.friction_coefficient() * penalty * T[i] *
                      G[j] :
                    w * penalty * T[i] * T[j];
            // Where the outline turns, the tangent t turns with n:
            // dn/dx = t t^T / rho and dt/dx = -n t^T / rho, which the force
            // t_T t . N_i and, while sticking, the trial traction
            // (t_previous - eps (u - u_rigid)) . t feel.
            const double rho = surface.turning_radius;
            if (std::isfinite(rho) && rho > 0)
              {
                const double trial_turning =
                  sliding ?
                    0. :
                    piece.previous[q] * nq - penalty * ((u - rigid) * nq);
                for (unsigned int i = 0; i < n; ++i)
                  for (unsigned int j = 0; j < n; ++j)
                    state.stiffness(i, j) +=
                      w / rho * (trial_turning * T[i] + traction * G[i]) * T[j];
              }
          }
        for (unsigned int i = 0; i < n; ++i)
          {
            state.force[i] += w * (p * G[i] + traction * T[i]);
            for (unsigned int j = 0; j < n; ++j)
              state.stiffness(i, j) += w * penalty * G[i] * G[j];
          }
        // p dn/dx with dn/dx = (I - n n) / rho where the outline turns.
        const double rho = surface.turning_radius;
        if (p > 0 && std::isfinite(rho) && rho > 0)
          for (unsigned int i = 0; i < n; ++i)
            for (unsigned int j = 0; j < n; ++j)
              state.stiffness(i, j) -=
                w * p / rho * (N[i] * N[j] - (nq * N[i]) * (nq * N[j]));
        const Tensor<1, 2> t = p * nq + traction * tq;
        state.resultant += w * t;
        for (unsigned int e = 0; e < 2; ++e)
          {
            state.end_pressures[e] += w * phi[e] * p;
            state.end_tractions[e] += w * phi[e] * t;
          }
      }
    for (unsigned int e = 0; e < 2; ++e)
      if (state.end_weights[e] > 0)
        state.end_tractions[e] /= state.end_weights[e];
    if (!state.active)
      return state;
    state.contact_length = length;
    state.gap /= length;
    state.pressure /= length;
    state.tangential /= length;
    state.normal /= state.normal.norm();
    state.midpoint /= length;
    return state;
  }



  template <typename ShapeValues>
  void
  CurveContact::add_tilt_terms(const ContactPiece              &piece,
                               const ShapeValues               &N,
                               const std::vector<SurfacePoint> &surface,
                               PieceState                      &state) const
  {
    // The gap's tilt along the touching part: with xi the distance along
    // the part from its centre (arc length of the Gauss points at the
    // increment's start), m = int_A xi g ds and I = int_A xi^2 ds, the
    // potential eps_t m^2 / (2 I) holds the linear part m / I of the gap.
    // One pressure per cell leaves it free: the nodes of the cells under a
    // flat rigid base may move up and down in turn with every cell's mean
    // gap zero, and plastic soil does not resist that (doc/contact.md,
    // "Deep penetration"). dm/du_i = int xi n . N_i = H_i; force -eps_t m /
    // I H_i, stiffness eps_t / I (H H^T + m int xi (N_i . N_j - (n . N_i)
    // (n . N_j)) / rho) where the outline turns.
    if (tilt_penalty == 0)
      return;
    const unsigned int  n_q = piece.positions.size();
    std::vector<double> xi(n_q, 0.);
    double              s = 0, centre = 0, L = 0;
    // The Gauss points lie in order along the curve: xi counts the arc
    // length of those that do not touch too.
    for (unsigned int q = 0; q < n_q; ++q)
      {
        xi[q] = s + piece.weights[q] / 2;
        s += piece.weights[q];
        if (!piece.touching[q])
          continue;
        centre += piece.weights[q] * xi[q];
        L += piece.weights[q];
      }
    centre /= L;
    double m = 0, I = 0;
    for (unsigned int q = 0; q < n_q; ++q)
      if (piece.touching[q])
        {
          xi[q] -= centre;
          m += piece.weights[q] * xi[q] * surface[q].gap;
          I += piece.weights[q] * xi[q] * xi[q];
        }
    if (!(I > 0))
      return;
    const unsigned int n = state.force.size();
    Vector<double>     H(n);
    for (unsigned int q = 0; q < n_q; ++q)
      if (piece.touching[q])
        {
          const Tensor<1, 2> &nq = surface[q].normal;
          for (unsigned int i = 0; i < n; ++i)
            H[i] += piece.weights[q] * xi[q] * (nq * N[q][i]);
          // The traction -eps_t m / I xi n on the curve.
          state.resultant +=
            piece.weights[q] * (-tilt_penalty * m / I * xi[q]) * nq;
          const double rho = surface[q].turning_radius;
          if (std::isfinite(rho) && rho > 0)
            for (unsigned int i = 0; i < n; ++i)
              for (unsigned int j = 0; j < n; ++j)
                state.stiffness(i, j) +=
                  tilt_penalty * m / I * piece.weights[q] * xi[q] / rho *
                  (N[q][i] * N[q][j] - (nq * N[q][i]) * (nq * N[q][j]));
        }
    for (unsigned int i = 0; i < n; ++i)
      {
        state.force[i] -= tilt_penalty * m / I * H[i];
        for (unsigned int j = 0; j < n; ++j)
          state.stiffness(i, j) += tilt_penalty / I * H[i] * H[j];
      }
  }



  CurveContact::PieceState
  CurveContact::evaluate(
    const ContactPiece                               &piece,
    const BackgroundGrid                             &grid,
    const Q1CellKernel                               &kernel,
    const LinearAlgebra::distributed::Vector<double> &increment,
    const LinearAlgebra::distributed::Vector<double> *prescribed,
    std::vector<types::global_dof_index>             &dof_indices) const
  {
    return evaluate(piece,
                    grid,
                    kernel,
                    MaterialPoints::cell_increment(grid.locally_owned_cell(
                                                     piece.cell),
                                                   increment,
                                                   prescribed,
                                                   dof_indices));
  }



  bool
  CurveContact::add_newton_terms(
    const BackgroundGrid                             &grid,
    const Q1CellKernel                               &kernel,
    const LinearAlgebra::distributed::Vector<double> &increment,
    const LinearAlgebra::distributed::Vector<double> *prescribed,
    const AffineConstraints<double>                  &constraints,
    TrilinosWrappers::SparseMatrix                   &tangent,
    TrilinosWrappers::MPI::Vector                    &force)
  {
    constexpr unsigned int               n = Q1CellKernel::dofs_per_cell;
    std::vector<types::global_dof_index> dof_indices(n);
    const bool                           bordered = body_motion.has_unknowns();
    if (bordered)
      body_motion.reset_bordered_terms(grid.locally_owned_dofs(),
                                       grid.mpi_communicator(),
                                       penalty * grid.min_cell_size());
    bool               symmetric = true;
    FullMatrix<double> stiffness(n, n);
    Vector<double>     cell_force(n), column(n), row(n);
    for (const ContactPiece &piece : pieces)
      {
        const PieceState state =
          evaluate(piece, grid, kernel, increment, prescribed, dof_indices);
        if (!state.active)
          continue;
        symmetric = symmetric && !state.sliding;
        for (unsigned int i = 0; i < n; ++i)
          {
            cell_force[i] = state.force[i];
            for (unsigned int j = 0; j < n; ++j)
              stiffness(i, j) = state.stiffness(i, j);
          }
        constraints.distribute_local_to_global(
          stiffness, cell_force, dof_indices, tangent, force);
        if (check_tangent)
          largest_tangent_error = std::max(
            largest_tangent_error,
            tangent_error(piece, grid, kernel, state, increment, prescribed));
        if (!bordered)
          continue;
        // A force-controlled component k of the body's translation: the
        // column -d(grid force)/dc_k, the row -d(force on the body)_k/du,
        // the block -d(force on the body)/dc and the force on the body
        // (the extended entries n + d of evaluate()).
        for (unsigned int d = 0; d < 2; ++d)
          {
            const int k = body_motion.unknown_of(piece.body, d);
            if (k < 0)
              continue;
            for (unsigned int i = 0; i < n; ++i)
              {
                column[i] = state.stiffness(i, n + d);
                row[i]    = state.stiffness(n + d, i);
              }
            constraints.distribute_local_to_global(column,
                                                   dof_indices,
                                                   body_motion.column(k));
            constraints.distribute_local_to_global(row,
                                                   dof_indices,
                                                   body_motion.row(k));
            body_motion.contact_force()[k] += state.force[n + d];
            for (unsigned int e = 0; e < 2; ++e)
              {
                const int l = body_motion.unknown_of(piece.body, e);
                if (l >= 0)
                  body_motion.block()(k, l) += state.stiffness(n + d, n + e);
              }
          }
      }
    if (bordered)
      body_motion.finish_bordered_terms(bodies, to);
    return Utilities::MPI::min(symmetric ? 1 : 0, grid.mpi_communicator()) == 1;
  }



  double
  CurveContact::tangent_error(
    const ContactPiece                               &piece,
    const BackgroundGrid                             &grid,
    const Q1CellKernel                               &kernel,
    const PieceState                                 &state,
    const LinearAlgebra::distributed::Vector<double> &increment,
    const LinearAlgebra::distributed::Vector<double> *prescribed) const
  {
    constexpr unsigned int               n = Q1CellKernel::dofs_per_cell;
    std::vector<types::global_dof_index> dof_indices(n);
    const Q1CellKernel::LocalVector      d = MaterialPoints::cell_increment(
      grid.locally_owned_cell(piece.cell), increment, prescribed, dof_indices);
    // Central differences of the force on the cell's DoFs and the body's
    // translation by each of them, against minus the stiffness.
    const double step = 1e-6 * grid.min_cell_size();
    // A piece that touches by less than the differences move it has the
    // kink where it opens between them: no derivative to compare.
    // (p / eps is the distance to the kink: -g for the penalty, lambda / eps
    // - g for the augmented Lagrangian.)
    if (state.pressure / penalty < 10 * step)
      return 0.;
    double largest = 0, difference = 0;
    for (unsigned int j = 0; j < n + 2; ++j)
      {
        std::array<PieceState, 2> sides;
        for (unsigned int side = 0; side < 2; ++side)
          {
            const double              sign = side == 0 ? 1. : -1.;
            Q1CellKernel::LocalVector dj   = d;
            Tensor<1, 2>              shift;
            if (j < n)
              dj[j] += sign * step;
            else
              shift[j - n] = sign * step;
            sides[side] = evaluate(piece, grid, kernel, dj, shift);
          }
        const auto force = [&](const unsigned int side, const unsigned int i) {
          return sides[side].active ? sides[side].force[i] : 0.;
        };
        for (unsigned int i = 0; i < n + 2; ++i)
          {
            const double fi = force(0, i) - force(1, i);
            largest = std::max(largest, std::abs(state.stiffness(i, j)));
            difference =
              std::max(difference,
                       std::abs(state.stiffness(i, j) + fi / (2 * step)));
          }
      }
    return largest > 0 ? difference / largest : 0.;
  }



  bool
  CurveContact::after_convergence(
    const BackgroundGrid                             &grid,
    const Q1CellKernel                               &kernel,
    const LinearAlgebra::distributed::Vector<double> &increment,
    const LinearAlgebra::distributed::Vector<double> *prescribed)
  {
    // The touching parts first: the multipliers are updated only at a
    // solve whose parts stand (changing both at once, the parts and the
    // pressures fed each other).
    if (touching_updates < max_touching_updates &&
        update_touching_parts(grid, kernel, increment, prescribed))
      {
        ++touching_updates;
        return true;
      }
    if (augmented && augmentations < max_augmentations &&
        augment(grid, kernel, increment, prescribed))
      {
        ++augmentations;
        return true;
      }
    return false;
  }



  bool
  CurveContact::augment(
    const BackgroundGrid                             &grid,
    const Q1CellKernel                               &kernel,
    const LinearAlgebra::distributed::Vector<double> &increment,
    const LinearAlgebra::distributed::Vector<double> *prescribed)
  {
    // Uzawa's update of a piece would be lambda <- max(0, lambda - eps g),
    // the pressure of the converged increment. One multiplier per piece
    // (constant per cell) against the bilinear displacement has a null
    // mode: pressures that alternate from piece to piece give next to no
    // nodal force, and the plain update drifted along it (doc/contact.md).
    // So a touching piece takes the mean of its own update and its
    // touching neighbours' along the curve, weighted 1 2 1 by length,
    // which is blind to that mode: at the fixed point the mean gaps vanish
    // but for an alternating part, which the penalty holds.
    std::vector<types::global_dof_index> dof_indices(
      Q1CellKernel::dofs_per_cell);
    // Per piece: body, curve, u_begin, u_end, length, whether it touches,
    // the raw update of lambda.
    constexpr unsigned int width = 7;
    std::vector<double>    local;
    std::vector<double>    forces(2 * bodies.size(), 0.);
    // Between crossings, per crossing of a piece: body, curve, crossing,
    // int phi p ds, int phi ds. A crossing's multiplier becomes the
    // pressure's lumped projection there, summed over the pieces on either
    // side (which may be on two processes). Continuous pressures have no
    // alternating mode: no filter.
    std::vector<double> at_crossings;
    for (const ContactPiece &piece : pieces)
      {
        const PieceState state =
          evaluate(piece, grid, kernel, increment, prescribed, dof_indices);
        if (state.active)
          for (unsigned int d = 0; d < 2; ++d)
            forces[2 * piece.body + d] += state.resultant[d];
        if (piece.between_crossings)
          {
            for (unsigned int e = 0; e < 2; ++e)
              at_crossings.insert(at_crossings.end(),
                                  {double(piece.body),
                                   double(piece.curve),
                                   piece.end_keys[e],
                                   state.end_pressures[e],
                                   state.end_weights[e]});
            continue;
          }
        local.insert(local.end(),
                     {double(piece.body),
                      double(piece.curve),
                      piece.u_begin,
                      piece.u_end,
                      state.active ? state.contact_length : piece.length,
                      state.active ? 1. : 0.,
                      (state.active ? state.pressure : 0.) -
                        piece.multiplier_pressure});
      }
    // Every process gathers all pieces (a few per cell along the contact),
    // so that a piece's neighbour on another process counts and every
    // process forms the same sums.
    const MPI_Comm      communicator = grid.mpi_communicator();
    const auto          parts = Utilities::MPI::all_gather(communicator, local);
    std::vector<double> all;
    unsigned int        offset = 0;
    for (unsigned int p = 0; p < parts.size(); ++p)
      {
        if (p == Utilities::MPI::this_mpi_process(communicator))
          offset = all.size() / width;
        all.insert(all.end(), parts[p].begin(), parts[p].end());
      }
    const unsigned int n_all = all.size() / width;
    // The neighbours along the curve: the pieces of the same body and
    // curve that end where a piece begins and begin where it ends.
    std::map<std::array<double, 3>, unsigned int> by_begin, by_end;
    for (unsigned int k = 0; k < n_all; ++k)
      {
        const double *r                = &all[width * k];
        by_begin[{{r[0], r[1], r[2]}}] = k;
        by_end[{{r[0], r[1], r[3]}}]   = k;
      }
    std::vector<double> updates(n_all);
    for (unsigned int k = 0; k < n_all; ++k)
      {
        const double *r      = &all[width * k];
        double        update = r[6];
        // Pressures at the crossings have no such mode: no filter.
        if (r[5] == 1. && !pressure_at_crossings)
          {
            double weight = 2 * r[4];
            update *= 2 * r[4];
            const auto before = by_end.find({{r[0], r[1], r[2]}});
            const auto after  = by_begin.find({{r[0], r[1], r[3]}});
            for (const int n :
                 {before == by_end.end() ? -1 : int(before->second),
                  after == by_begin.end() ? -1 : int(after->second)})
              if (n >= 0 && all[width * n + 5] == 1.)
                {
                  weight += all[width * n + 4];
                  update += all[width * n + 4] * all[width * n + 6];
                }
            update /= weight;
          }
        updates[k] = update;
      }
    // The force on each body at this solve against the last decides when
    // to stop: it is what the updates are for, and the multipliers
    // converge more slowly in the modes that hardly change it.
    Utilities::MPI::sum(forces, communicator, forces);
    force_change = 0;
    for (unsigned int b = 0; b < bodies.size(); ++b)
      {
        const Tensor<1, 2> force({forces[2 * b], forces[2 * b + 1]});
        const double       difference = (force - last_forces[b]).norm();
        if (difference > 0)
          force_change =
            std::max(force_change,
                     force.norm() > 0 ? difference / force.norm() : 1.);
        last_forces[b] = force;
        // A force-controlled body balances its Force whatever the
        // multipliers: its motion in the increment is what they change.
        if (bodies[b].has_free_motion())
          {
            const Tensor<1, 2> place = body_motion.end(b);
            const double       moved = (place - body_motion.start(b)).norm();
            const double       shift = (place - last_places[b]).norm();
            if (shift > 0)
              force_change =
                std::max(force_change, moved > 0 ? shift / moved : 1.);
            last_places[b] = place;
          }
      }
    // Converged: the increment stands with the multipliers it was solved
    // with, so that the forces reported balance the body (an update now
    // would leave them unbalanced by the last change).
    if (force_change <= augmentation_tolerance)
      return false;
    if (pressure_at_crossings)
      {
        std::map<std::array<double, 3>, std::array<double, 2>> sums;
        for (const auto &part :
             Utilities::MPI::all_gather(communicator, at_crossings))
          for (unsigned int i = 0; i + 5 <= part.size(); i += 5)
            {
              auto &sum = sums[{{part[i], part[i + 1], part[i + 2]}}];
              sum[0] += part[i + 3];
              sum[1] += part[i + 4];
            }
        for (ContactPiece &piece : pieces)
          for (unsigned int e = 0; e < 2; ++e)
            {
              const auto &sum          = sums[{
                         {double(piece.body), double(piece.curve), piece.end_keys[e]}}];
              piece.end_multipliers[e] = sum[1] > 0 ? sum[0] / sum[1] : 0.;
            }
        return true;
      }
    for (unsigned int k = 0; k < pieces.size(); ++k)
      pieces[k].multiplier_pressure =
        std::max(pieces[k].multiplier_pressure + updates[offset + k], 0.);
    return true;
  }



  bool
  CurveContact::update_touching_parts(
    const BackgroundGrid                             &grid,
    const Q1CellKernel                               &kernel,
    const LinearAlgebra::distributed::Vector<double> &increment,
    const LinearAlgebra::distributed::Vector<double> *prescribed)
  {
    const double touching = 1e-12 * grid.min_cell_size();
    bool         changed  = false;
    std::vector<types::global_dof_index> dof_indices(
      Q1CellKernel::dofs_per_cell);
    for (ContactPiece &piece : pieces)
      {
        if (piece.between_crossings)
          continue;
        const PieceState state =
          evaluate(piece, grid, kernel, increment, prescribed, dof_indices);
        // A Gauss point that penetrates joins the part; one leaves it only
        // where it stands clearly open: further than the part is closed on
        // average and than a hundredth of a cell. The pressure of the part
        // holds its mean gap, not each point's, and within a cell of
        // plastic soil the gaps scatter by about the penetration; letting
        // every point with a gap above zero go shrank the contact under a
        // footing to a few pieces of cells, with pressures ten times the
        // mean. A part open on average (the edge of a contact that the
        // first guess overestimated) keeps only the points that penetrate.
        const double open =
          state.active ? -state.gap + 1e-2 * grid.min_cell_size() : touching;
        for (unsigned int q = 0; q < piece.positions.size(); ++q)
          {
            const double gap = state.surface[q].gap;
            const bool   touches =
              piece.touching[q] ? gap <= open : gap <= touching;
            if (touches != piece.touching[q])
              {
                piece.touching[q] = touches;
                changed           = true;
              }
          }
      }
    return Utilities::MPI::logical_or(changed, grid.mpi_communicator());
  }



  void
  CurveContact::finish_increment(
    const BoundaryCurves                             &curves,
    const BackgroundGrid                             &grid,
    const Q1CellKernel                               &kernel,
    const LinearAlgebra::distributed::Vector<double> &increment,
    const LinearAlgebra::distributed::Vector<double> *prescribed)
  {
    const MPI_Comm      communicator = grid.mpi_communicator();
    const auto         &all_curves   = curves.get_curves();
    std::vector<double> sums(4 * bodies.size(), 0.);
    std::vector<double> penetration(bodies.size(), 0.);
    // The history of friction: the traction of a piece at the curve points
    // whose knots lie in it (u_begin <= u_k < u_end, and u = 1 in the
    // last), so that each point has one piece and one process.
    std::vector<std::vector<double>> tractions(all_curves.size());
    for (unsigned int c = 0; c < all_curves.size(); ++c)
      tractions[c].assign(2 * all_curves[c].positions.size(), 0.);
    last_tractions.clear();
    std::vector<types::global_dof_index> dof_indices(
      Q1CellKernel::dofs_per_cell);
    for (const ContactPiece &piece : pieces)
      {
        const PieceState state =
          evaluate(piece, grid, kernel, increment, prescribed, dof_indices);
        if (!state.active)
          continue;
        // The rigid body feels the opposite of what the curve feels.
        sums[4 * piece.body + 0] -= state.resultant[0];
        sums[4 * piece.body + 1] -= state.resultant[1];
        sums[4 * piece.body + 2] += state.contact_length;
        sums[4 * piece.body + 3] += state.sliding_length;
        penetration[piece.body] = std::max(penetration[piece.body], -state.gap);
        last_tractions.insert(last_tractions.end(),
                              {double(piece.body + 1),
                               state.midpoint[0],
                               state.midpoint[1],
                               state.gap,
                               state.pressure,
                               state.tangential,
                               state.contact_length,
                               state.sliding ? 1. : 0.});

        const BoundaryCurve &curve = all_curves[piece.curve];
        const Tensor<1, 2>   n     = state.normal;
        const Tensor<1, 2>   traction =
          state.pressure * n + state.tangential * Tensor<1, 2>({-n[1], n[0]});
        if (piece.between_crossings)
          {
            // Interpolated between the crossings' tractions.
            for (unsigned int k = 0; k < curve.positions.size(); ++k)
              {
                const double u_k = k < curve.spline->n_segments() ?
                                     curve.spline->segment_parameters(k)[0] :
                                     1.;
                for (const double u : {u_k, u_k + 1})
                  if ((u >= piece.u_begin && u < piece.u_end) ||
                      (u == 1. && piece.u_end == 1.))
                    {
                      const double f =
                        (u - piece.u_begin) / (piece.u_end - piece.u_begin);
                      const Tensor<1, 2> t = (1 - f) * state.end_tractions[0] +
                                             f * state.end_tractions[1];
                      tractions[piece.curve][2 * k] += t[0];
                      tractions[piece.curve][2 * k + 1] += t[1];
                      break;
                    }
              }
            continue;
          }
        for (unsigned int k = 0; k < curve.positions.size(); ++k)
          {
            const double u_k = k < curve.spline->n_segments() ?
                                 curve.spline->segment_parameters(k)[0] :
                                 1.;
            if ((u_k >= piece.u_begin && u_k < piece.u_end) ||
                (u_k == 1. && piece.u_end == 1.))
              {
                tractions[piece.curve][2 * k] += traction[0];
                tractions[piece.curve][2 * k + 1] += traction[1];
              }
          }
      }
    Utilities::MPI::sum(sums, communicator, sums);
    Utilities::MPI::max(penetration, communicator, penetration);
    if (check_tangent)
      largest_tangent_error =
        Utilities::MPI::max(largest_tangent_error, communicator);
    for (unsigned int b = 0; b < bodies.size(); ++b)
      {
        resultants[b].force = Tensor<1, 2>({sums[4 * b + 0], sums[4 * b + 1]});
        resultants[b].contact_length = sums[4 * b + 2];
        resultants[b].sliding_length = sums[4 * b + 3];
        resultants[b].penetration    = penetration[b];
      }
    for (unsigned int c = 0; c < all_curves.size(); ++c)
      {
        Utilities::MPI::sum(tractions[c], communicator, tractions[c]);
        for (unsigned int k = 0; k < all_curves[c].positions.size(); ++k)
          point_tractions[c][k] =
            Tensor<1, 2>({tractions[c][2 * k], tractions[c][2 * k + 1]});
      }
    body_motion.accept();
  }



  std::vector<std::vector<Point<2>>>
  CurveContact::outlines() const
  {
    std::vector<std::vector<Point<2>>> lines;
    for (unsigned int b = 0; b < bodies.size(); ++b)
      lines.push_back(bodies[b].outline(body_motion.end(b)));
    return lines;
  }



  void
  CurveContact::follow_point_changes(
    const std::vector<BoundaryCurves::PointOrigins> &origins)
  {
    for (unsigned int c = 0; c < origins.size() && c < point_tractions.size();
         ++c)
      if (!origins[c].empty())
        {
          const auto               &old = point_tractions[c];
          std::vector<Tensor<1, 2>> tractions;
          for (const auto &[a, b] : origins[c])
            tractions.push_back(a < old.size() && b < old.size() ?
                                  0.5 * (old[a] + old[b]) :
                                  Tensor<1, 2>());
          point_tractions[c] = std::move(tractions);
        }
  }



  void
  CurveContact::record(std::map<std::string, double> &quantities) const
  {
    for (unsigned int b = 0; b < bodies.size(); ++b)
      {
        const std::string &name              = bodies[b].name();
        const Tensor<1, 2> u                 = body_motion.end(b);
        quantities[name + "_force_x"]        = resultants[b].force[0];
        quantities[name + "_force_y"]        = resultants[b].force[1];
        quantities[name + "_displacement_x"] = u[0];
        quantities[name + "_displacement_y"] = u[1];
        quantities[name + "_contact_length"] = resultants[b].contact_length;
        quantities[name + "_sliding_length"] = resultants[b].sliding_length;
        quantities[name + "_penetration"]    = resultants[b].penetration;
      }
    if (augmented && enabled())
      {
        // Of the last increment: the Uzawa updates it took. (Not the
        // relative change of the force, a difference of nearly equal
        // forces whose round-off differs from np = 1 to np = 3.)
        quantities["contact_augmentations"] = augmentations;
      }
    body_motion.record(bodies, to, quantities);
    if (check_tangent)
      quantities["contact_tangent_error"] = largest_tangent_error;
  }



  void
  CurveContact::write_tractions(std::ostream  &out,
                                const MPI_Comm communicator) const
  {
    const auto all = Utilities::MPI::gather(communicator, last_tractions, 0);
    if (Utilities::MPI::this_mpi_process(communicator) != 0)
      return;
    out << "body,x,y,gap,pressure,tangential_traction,length,sliding\n"
        << std::setprecision(10);
    for (const auto &part : all)
      for (unsigned int i = 0; i + 8 <= part.size(); i += 8)
        {
          out << static_cast<unsigned int>(part[i]);
          for (unsigned int j = 1; j < 8; ++j)
            out << ',' << part[i + j];
          out << '\n';
        }
  }
} // namespace bsmpm
