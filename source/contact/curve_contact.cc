#include <deal.II/base/mpi.h>

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include <bsmpm/contact/curve_contact.h>
#include <bsmpm/points/material_points.h>

#include <cmath>
#include <iomanip>
#include <limits>
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
      "at grid lines",
      Patterns::Selection("at grid lines|per cell|mortar|automatic"),
      "Where the contact pressure is taken (doc/contact.md). 'at grid lines' "
      "(the default): the curve's displacement taken where it crosses the "
      "grid lines and linear between them, a pressure at every Gauss point "
      "of that gap and multipliers at the crossings; it holds the grid nodes "
      "under a flat rigid base. 'per cell': one pressure for the mean gap of "
      "the touching part of each cell's piece of curve; it holds a body's "
      "edge in the middle of a cell more firmly, but leaves the nodes under a "
      "flat base free to move in and out in turn, which plastic soil in flow "
      "hardly resists: with one or three points per cell, or many small load "
      "steps, a footing's force and contact length can collapse part way. "
      "'mortar': one pressure per crossing of a curve with a grid line, for "
      "the gap weighted by the crossing's hat function along the curve, and "
      "linear between the crossings: a continuous pressure, an exact tangent "
      "and no touching parts to update; it holds a body's edge in the middle "
      "of a cell weakly. 'automatic': the same as 'at grid lines' (kept for "
      "older parameter files).");
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
      "slides round a body's corner, and with mortar pressures (whose "
      "augmented pressures hold the edge of a rigid footing better but "
      "follow a curved outline less well, doc/contact.md). Choose 'penalty' for a cheaper run whose "
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
    gamma                        = prm.get_double("Penalty");
    check_tangent                = prm.get_bool("Check tangent");
    n_gauss_points               = prm.get_integer("Gauss points per piece");
    const std::string  method    = prm.get("Method");
    const double       tolerance = prm.get_double("Augmentation tolerance");
    const unsigned int max_augmentations =
      prm.get_integer("Maximum augmentations");
    gamma_tilt              = prm.get_double("Tilt penalty");
    const std::string where = prm.get("Pressure");
    prm.leave_subsection();
    prm.enter_subsection("Material");
    const bool finite_strain = prm.get("Kinematics") == "finite strain";
    prm.leave_subsection();
    pressure_at_nodes     = where == "mortar";
    pressure_at_crossings = where != "per cell";
    augmented             = method == "augmented Lagrangian" ||
                (method == "automatic" && !finite_strain && !pressure_at_nodes);
    augmentation.initialize(tolerance,
                            max_augmentations,
                            pressure_at_crossings);
    bodies = RigidBody::create_all(prm);
    AssertThrow(bodies.empty() || gamma > 0,
                ExcMessage("Contact/Penalty must be positive."));
    results.reinit(bodies.size());
    body_motion.initialize(bodies);
  }



  void
  CurveContact::begin_increment(const BoundaryCurves &curves,
                                const BackgroundGrid &grid,
                                const double          stiffness,
                                const double          load_from,
                                const double          load_to)
  {
    const double h       = grid.min_cell_size();
    const double penalty = gamma * stiffness / h;
    terms.reinit(augmented ? ContactLaw::Method::augmented_lagrangian :
                             ContactLaw::Method::penalty,
                 penalty,
                 gamma_tilt * penalty,
                 1e-12 * h);
    from = load_from;
    to   = load_to;
    body_motion.begin_increment(bodies, from, to);
    touching_updates = 0;
    augmentation.begin_increment(bodies.size(), penalty);
    history.reinit(curves);
    pieces = pressure_at_crossings ?
               collect_pieces_between_crossings(
                 curves, grid, bodies, body_motion, history, n_gauss_points) :
               collect_pieces_per_cell(
                 curves, grid, bodies, body_motion, history, n_gauss_points);
    for (unsigned int b = 0; b < bodies.size(); ++b)
      if (bodies[b].has_free_motion())
        touch_if_free(b, grid);
    if (pressure_at_nodes)
      {
        contact_nodes.reinit(pieces, curves, bodies, body_motion, grid);
        if (augmented)
          contact_nodes.initialize_multipliers(bodies,
                                               body_motion,
                                               grid.mpi_communicator());
      }
    else if (augmented)
      augmentation.initialize_multipliers(pieces, bodies, body_motion);
  }



  void
  CurveContact::touch_if_free(const unsigned int b, const BackgroundGrid &grid)
  {
    const MPI_Comm communicator = grid.mpi_communicator();
    const double   h            = grid.min_cell_size();
    const double   touching     = 1e-12 * h;
    // Where the Gauss points, which carry the pressure, meet the body's
    // outline. (Between crossings not the crossings: a crossing that
    // touches, such as the lowest point of a disc on a grid line, gives
    // no stiffness while the Gauss points beside it are open.)
    const auto surfaces = [&](const ContactPiece &piece) {
      std::vector<SurfacePoint> points;
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
                      bodies[b].name() + " (" + bodies[b].section() +
                      "): its Force at load factor " + std::to_string(to) +
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



  NodalContactTerms::State
  CurveContact::evaluate_nodes(
    const BackgroundGrid                             &grid,
    const Q1CellKernel                               &kernel,
    const LinearAlgebra::distributed::Vector<double> &increment,
    const LinearAlgebra::distributed::Vector<double> *prescribed) const
  {
    return NodalContactTerms::evaluate(terms,
                                       contact_nodes,
                                       bodies,
                                       body_motion,
                                       grid,
                                       kernel,
                                       increment,
                                       prescribed);
  }



  std::vector<ContactPieceState>
  CurveContact::evaluate_all(
    const BackgroundGrid                             &grid,
    const Q1CellKernel                               &kernel,
    const LinearAlgebra::distributed::Vector<double> &increment,
    const LinearAlgebra::distributed::Vector<double> *prescribed) const
  {
    std::vector<types::global_dof_index> dof_indices(
      Q1CellKernel::dofs_per_cell);
    std::vector<ContactPieceState> states;
    states.reserve(pieces.size());
    for (const ContactPiece &piece : pieces)
      states.push_back(terms.evaluate(
        piece,
        bodies,
        body_motion,
        grid,
        kernel,
        MaterialPoints::cell_increment(grid.locally_owned_cell(piece.cell),
                                       increment,
                                       prescribed,
                                       dof_indices)));
    return states;
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
                                       terms.penalty() * grid.min_cell_size());
    if (pressure_at_nodes)
      {
        const NodalContactTerms::State state =
          evaluate_nodes(grid, kernel, increment, prescribed);
        NodalContactTerms::add_newton_terms(
          state, contact_nodes, grid, constraints, body_motion, tangent, force);
        if (check_tangent)
          tangent_check.add(NodalContactTerms::relative_error(terms,
                                                              contact_nodes,
                                                              bodies,
                                                              body_motion,
                                                              grid,
                                                              kernel,
                                                              increment,
                                                              prescribed,
                                                              state),
                            !state.symmetric);
        if (bordered)
          body_motion.finish_bordered_terms(bodies, to);
        return state.symmetric;
      }
    bool               symmetric = true;
    FullMatrix<double> stiffness(n, n);
    Vector<double>     cell_force(n), column(n), row(n);
    for (const ContactPiece &piece : pieces)
      {
        const Q1CellKernel::LocalVector d =
          MaterialPoints::cell_increment(grid.locally_owned_cell(piece.cell),
                                         increment,
                                         prescribed,
                                         dof_indices);
        const ContactPieceState state =
          terms.evaluate(piece, bodies, body_motion, grid, kernel, d);
        if (!state.active)
          continue;
        symmetric = symmetric && state.symmetric;
        for (unsigned int i = 0; i < n; ++i)
          {
            cell_force[i] = state.force[i];
            for (unsigned int j = 0; j < n; ++j)
              stiffness(i, j) = state.stiffness(i, j);
          }
        constraints.distribute_local_to_global(
          stiffness, cell_force, dof_indices, tangent, force);
        if (check_tangent)
          tangent_check.add(
            ContactTangentCheck::relative_error(
              terms, piece, bodies, body_motion, grid, kernel, state, d),
            state.sliding);
        if (!bordered)
          continue;
        // A force-controlled component k of the body's translation: the
        // column -d(grid force)/dc_k, the row -d(force on the body)_k/du,
        // the block -d(force on the body)/dc and the force on the body
        // (the extended entries n + d of ContactTerms::evaluate()).
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



  bool
  CurveContact::after_convergence(
    const BackgroundGrid                             &grid,
    const Q1CellKernel                               &kernel,
    const LinearAlgebra::distributed::Vector<double> &increment,
    const LinearAlgebra::distributed::Vector<double> *prescribed)
  {
    if (!pressure_at_nodes && touching_updates < max_touching_updates &&
        update_touching_parts(grid, kernel, increment, prescribed))
      {
        // The touching parts first: the multipliers are updated only at a
        // solve whose parts stand (changing both at once, the parts and
        // the pressures fed each other).
        ++touching_updates;
        return true;
      }
    if (!augmented)
      return false;
    const bool again =
      pressure_at_nodes ?
        augmentation.augment_nodes(
          contact_nodes,
          evaluate_nodes(grid, kernel, increment, prescribed),
          bodies,
          body_motion,
          grid.mpi_communicator()) :
        augmentation.augment(pieces,
                             evaluate_all(grid, kernel, increment, prescribed),
                             bodies,
                             body_motion,
                             grid.mpi_communicator());
    if (augmentation.stopped_unconverged())
      {
        // Said in the step's log: the increment stands with pressures that
        // do not balance the last update (a wrong answer if the change is
        // large; more updates, smaller load steps or another Pressure may
        // help).
        std::ostringstream text;
        text << "the contact pressures did not converge: the force on a "
                "rigid body still changed by "
             << std::setprecision(2) << augmentation.last_force_change()
             << " after " << augmentation.n_augmentations()
             << " updates (Contact/Maximum augmentations)";
        body_motion.note(text.str());
      }
    return again;
  }



  bool
  CurveContact::update_touching_parts(
    const BackgroundGrid                             &grid,
    const Q1CellKernel                               &kernel,
    const LinearAlgebra::distributed::Vector<double> &increment,
    const LinearAlgebra::distributed::Vector<double> *prescribed)
  {
    // Between crossings a Gauss point acts where its gap says so: there are
    // no touching parts to update.
    const double touching = 1e-12 * grid.min_cell_size();
    bool         changed  = false;
    const std::vector<ContactPieceState> states =
      pressure_at_crossings ? std::vector<ContactPieceState>() :
                              evaluate_all(grid, kernel, increment, prescribed);
    for (unsigned int p = 0; p < states.size(); ++p)
      {
        ContactPiece            &piece = pieces[p];
        const ContactPieceState &state = states[p];
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
    const MPI_Comm communicator = grid.mpi_communicator();
    if (pressure_at_nodes)
      finish_nodal_increment(
        curves, grid, evaluate_nodes(grid, kernel, increment, prescribed));
    else
      {
        const std::vector<ContactPieceState> states =
          evaluate_all(grid, kernel, increment, prescribed);
        results.collect(pieces, states, communicator);
        history.store(curves, pieces, states, communicator);
      }
    if (check_tangent)
      tangent_check.gather(communicator);
    body_motion.accept();
  }



  void
  CurveContact::finish_nodal_increment(const BoundaryCurves           &curves,
                                       const BackgroundGrid           &grid,
                                       const NodalContactTerms::State &state)
  {
    // The places that carry a pressure (p(x) > 0) touch: the curve's arc
    // in contact, the traction p n + tau t on it.
    const auto                        &points = contact_nodes.points();
    std::vector<ContactResults::Touch> touches;
    std::vector<double>                penetration(bodies.size(), 0.);
    for (unsigned int q = 0; q < points.size(); ++q)
      {
        const NodalContactTerms::PointState &here = state.points[q];
        if (!here.active || !(here.pressure > 0 || here.tangential != 0))
          continue;
        const Tensor<1, 2>   &n = here.surface.normal;
        ContactResults::Touch touch;
        touch.body           = points[q].body;
        touch.curve          = points[q].curve;
        touch.x              = here.x;
        touch.normal         = n;
        touch.gap            = here.surface.gap;
        touch.pressure       = here.pressure;
        touch.tangential     = here.tangential;
        touch.length         = points[q].weight;
        touch.contact_length = points[q].weight;
        touch.sliding        = here.sliding;
        touch.sliding_length = here.sliding ? points[q].weight : 0.;
        touch.resultant      = points[q].weight * here.traction();
        touch.moment         = moment_about_origin(here.x, touch.resultant);
        touches.push_back(touch);
      }
    // The largest mean penetration of a node (the same on all processes).
    for (unsigned int a = 0; a < state.nodes.size(); ++a)
      if (state.nodes[a].traction.active)
        {
          const ContactNodes::Node &node = contact_nodes.nodes()[a];
          penetration[node.body] =
            std::max(penetration[node.body], -state.nodes[a].gap / node.weight);
        }
    results.collect(touches, penetration, grid.mpi_communicator());

    // The tractions at the curves' points in the pieces, interpolated from
    // the nodes as along the curve, for the next increment's friction.
    std::vector<ContactHistory::PointTraction> tractions;
    for (const ContactNodes::CurvePoint &knot : contact_nodes.curve_points())
      {
        double p = 0, tau = 0;
        for (unsigned int v = 0; v < 4; ++v)
          if (knot.nodes[v] != numbers::invalid_unsigned_int &&
              state.nodes[knot.nodes[v]].traction.active)
            {
              p += knot.shape[v] * state.nodes[knot.nodes[v]].traction.pressure;
              tau +=
                knot.shape[v] * state.nodes[knot.nodes[v]].traction.tangential;
            }
        const Tensor<1, 2> n =
          bodies[knot.body]
            .to_feature(knot.position, body_motion.end(knot.body), knot.feature)
            .normal;
        tractions.push_back(
          {knot.curve, knot.index, p * n + tau * Tensor<1, 2>({-n[1], n[0]})});
      }
    history.store(curves, tractions, grid.mpi_communicator());
  }



  void
  CurveContact::check_initial_places(const BoundaryCurves &curves,
                                     const MaterialPoints &points,
                                     const BackgroundGrid &grid,
                                     const double last_load_factor) const
  {
    std::vector<Tensor<1, 2>> places;
    for (unsigned int b = 0; b < bodies.size(); ++b)
      places.push_back(body_motion.start(b));
    RigidBodyPlacement::check(bodies,
                              places,
                              curves,
                              points,
                              grid.min_cell_size(),
                              grid.mpi_communicator());
    RigidBodyPlacement::check_motion_along_faces(bodies,
                                                 grid,
                                                 points,
                                                 last_load_factor);
  }



  std::vector<std::vector<Point<2>>>
  CurveContact::outlines() const
  {
    std::vector<std::vector<Point<2>>> lines;
    for (unsigned int b = 0; b < bodies.size(); ++b)
      lines.push_back(bodies[b].outline(body_motion.end(b)));
    return lines;
  }



  std::string
  CurveContact::friction_hint(const BackgroundGrid &grid,
                              const Tensor<1, 2>   *body_load) const
  {
    // The rigid outlines' normals where the curves (at the increment's
    // start) touch the bodies (where the iterations left them), or come
    // within a hundredth of a cell, on all processes.
    const double                     near = 1e-2 * grid.min_cell_size();
    std::vector<std::vector<double>> local(bodies.size());
    const auto                       consider =
      [&](const unsigned int b, const Point<2> &x, const unsigned int feature) {
        const SurfacePoint s =
          bodies[b].to_feature(x, body_motion.end(b), feature);
        if (s.gap <= near)
          local[b].insert(local[b].end(), {s.normal[0], s.normal[1]});
      };
    for (const ContactPiece &piece : pieces)
      {
        for (unsigned int q = 0; q < piece.positions.size(); ++q)
          consider(piece.body, piece.positions[q], piece.features[q]);
        if (piece.between_crossings)
          for (unsigned int e = 0; e < 2; ++e)
            consider(piece.body, piece.ends[e], piece.end_features[e]);
      }
    std::vector<std::vector<Tensor<1, 2>>> normals(bodies.size());
    std::vector<Tensor<1, 2>>              all_normals;
    for (unsigned int b = 0; b < bodies.size(); ++b)
      for (const auto &part :
           Utilities::MPI::all_gather(grid.mpi_communicator(), local[b]))
        for (unsigned int i = 0; i + 1 < part.size(); i += 2)
          {
            normals[b].push_back(Tensor<1, 2>({part[i], part[i + 1]}));
            all_normals.push_back(normals[b].back());
          }

    // A rigid body under a force is in equilibrium when the force equals
    // the sum of the pressures p n on it (n its outward normal); the body
    // when its loads and the pressures p n on it sum to zero.
    bool only_friction = false;
    for (unsigned int b = 0; b < bodies.size(); ++b)
      if (bodies[b].friction() == RigidBody::Friction::frictional &&
          !normals[b].empty())
        {
          if (bodies[b].has_free_motion() &&
              !pressures_can_balance(bodies[b].applied_force(to),
                                     normals[b],
                                     {{bodies[b].force_controlled(0),
                                       bodies[b].force_controlled(1)}}))
            only_friction = true;
          if (body_load != nullptr &&
              !pressures_can_balance(-*body_load, all_normals))
            only_friction = true;
        }
    return only_friction ?
             " With rigid bodies: a body that only friction holds has no "
             "quasi-static equilibrium once it slides (on an incline steeper "
             "than its friction angle); hold it, or move the rigid body "
             "instead." :
             "";
  }



  void
  CurveContact::follow_point_changes(
    const std::vector<BoundaryCurves::PointOrigins> &origins)
  {
    history.follow_point_changes(origins);
  }



  void
  CurveContact::record(std::map<std::string, double> &quantities) const
  {
    results.record(bodies, body_motion, quantities);
    if (augmented && enabled())
      {
        // Of the last increment: the Uzawa updates it took. (Not the
        // relative change of the force, a difference of nearly equal
        // forces whose round-off differs from np = 1 to np = 3.)
        quantities["contact_augmentations"] = augmentation.n_augmentations();
        quantities["contact_augmentations_unconverged"] =
          augmentation.stopped_unconverged() ? 1 : 0;
      }
    body_motion.record(bodies, to, quantities);
    if (check_tangent)
      tangent_check.record(quantities);
  }



  void
  CurveContact::write_tractions(std::ostream  &out,
                                const MPI_Comm communicator) const
  {
    results.write_tractions(out, communicator);
  }
} // namespace bsmpm
