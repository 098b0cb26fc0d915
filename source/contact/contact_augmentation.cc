#include <bsmpm/contact/contact_augmentation.h>

#include <algorithm>
#include <array>
#include <limits>
#include <map>

namespace bsmpm
{
  void
  ContactAugmentation::initialize(const double       tolerance,
                                  const unsigned int max_augmentations,
                                  const bool         at_crossings)
  {
    this->tolerance         = tolerance;
    this->max_augmentations = max_augmentations;
    this->at_crossings      = at_crossings;
  }



  void
  ContactAugmentation::begin_increment(const unsigned int n_bodies,
                                       const double       penalty)
  {
    this->penalty      = penalty;
    augmentations      = 0;
    unconverged_change = 0;
    // No force yet: the first update always asks for one more solve.
    last_places.assign(
      n_bodies, Tensor<1, 2>({std::numeric_limits<double>::infinity(), 0.}));
    last_forces.assign(
      n_bodies, Tensor<1, 2>({std::numeric_limits<double>::infinity(), 0.}));
  }



  void
  ContactAugmentation::initialize_multipliers(
    std::vector<ContactPiece>    &pieces,
    const std::vector<RigidBody> &bodies,
    const RigidBodyMotion        &motion) const
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
                                         motion.end(piece.body),
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
                                                   motion.end(piece.body),
                                                   piece.features[q])
                                       .normal;
              normal += piece.weights[q] * (piece.previous[q] * n);
              length += piece.weights[q];
            }
        piece.multiplier_pressure =
          length > 0 ? std::max(normal / length, 0.) : 0.;
      }
  }



  bool
  ContactAugmentation::augment(std::vector<ContactPiece>            &pieces,
                               const std::vector<ContactPieceState> &states,
                               const std::vector<RigidBody>         &bodies,
                               const RigidBodyMotion                &motion,
                               const MPI_Comm communicator)
  {
    unsigned int              offset = 0;
    const std::vector<double> updates =
      at_crossings ? std::vector<double>() :
                     piece_updates(pieces, states, communicator, offset);
    // Converged: the increment stands with the multipliers it was solved
    // with, so that the forces reported balance the body (an update now
    // would leave them unbalanced by the last change).
    std::vector<double> forces(2 * bodies.size(), 0.);
    for (unsigned int p = 0; p < pieces.size(); ++p)
      if (states[p].active)
        for (unsigned int d = 0; d < 2; ++d)
          forces[2 * pieces[p].body + d] += states[p].resultant[d];
    if (!needs_update(force_change(forces, bodies, motion, communicator)))
      return false;
    if (at_crossings)
      project_at_crossings(pieces, states, communicator);
    else
      for (unsigned int k = 0; k < pieces.size(); ++k)
        pieces[k].multiplier_pressure =
          std::max(pieces[k].multiplier_pressure + updates[offset + k], 0.);
    ++augmentations;
    return true;
  }



  std::vector<double>
  ContactAugmentation::piece_updates(
    const std::vector<ContactPiece>      &pieces,
    const std::vector<ContactPieceState> &states,
    const MPI_Comm                        communicator,
    unsigned int                         &offset) const
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
    //
    // Per piece: body, curve, u_begin, u_end, length, whether it touches,
    // the raw update of lambda.
    constexpr unsigned int width = 7;
    std::vector<double>    local;
    for (unsigned int p = 0; p < pieces.size(); ++p)
      {
        const ContactPiece      &piece = pieces[p];
        const ContactPieceState &state = states[p];
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
    const auto          parts = Utilities::MPI::all_gather(communicator, local);
    std::vector<double> all;
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
        if (r[5] == 1.)
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
    return updates;
  }



  bool
  ContactAugmentation::augment_nodes(ContactNodes                   &nodes,
                                     const NodalContactTerms::State &state,
                                     const std::vector<RigidBody>   &bodies,
                                     const RigidBodyMotion          &motion,
                                     const MPI_Comm communicator)
  {
    // The force on the curves at this process's Gauss points.
    std::vector<double> forces(2 * bodies.size(), 0.);
    const auto         &points = nodes.points();
    for (unsigned int q = 0; q < points.size(); ++q)
      if (state.points[q].active)
        for (unsigned int d = 0; d < 2; ++d)
          forces[2 * points[q].body + d] +=
            points[q].weight * state.points[q].traction()[d];
    if (!needs_update(force_change(forces, bodies, motion, communicator)))
      return false;
    // Every process holds every node's state: the same update everywhere.
    for (unsigned int a = 0; a < state.nodes.size(); ++a)
      nodes.set_multiplier(a,
                           state.nodes[a].traction.active ?
                             state.nodes[a].traction.pressure :
                             0.);
    ++augmentations;
    return true;
  }



  bool
  ContactAugmentation::needs_update(const double change)
  {
    if (change <= tolerance)
      return false;
    if (augmentations < max_augmentations)
      return true;
    // The updates may creep at a fraction of the tolerance per update for
    // the last of them (the rigid footing's flow: the force's change
    // falling by a factor 0.96 per update, from 2.5e-4 to 1.1e-4 over the
    // last 20): said only where the force still moves by more than ten
    // times the tolerance.
    if (change > 10 * tolerance)
      unconverged_change = change;
    return false;
  }



  double
  ContactAugmentation::force_change(std::vector<double>           forces,
                                    const std::vector<RigidBody> &bodies,
                                    const RigidBodyMotion        &motion,
                                    const MPI_Comm                communicator)
  {
    // The force on each body at this solve against the last decides when
    // to stop: it is what the updates are for, and the multipliers
    // converge more slowly in the modes that hardly change it.
    Utilities::MPI::sum(forces, communicator, forces);
    double change = 0;
    for (unsigned int b = 0; b < bodies.size(); ++b)
      {
        const Tensor<1, 2> force({forces[2 * b], forces[2 * b + 1]});
        const double       difference = (force - last_forces[b]).norm();
        if (difference > 0)
          change =
            std::max(change, force.norm() > 0 ? difference / force.norm() : 1.);
        last_forces[b] = force;
        // A force-controlled body balances its Force whatever the
        // multipliers: its motion in the increment is what they change.
        if (bodies[b].has_free_motion())
          {
            const Tensor<1, 2> place = motion.end(b);
            const double       moved = (place - motion.start(b)).norm();
            const double       shift = (place - last_places[b]).norm();
            if (shift > 0)
              change = std::max(change, moved > 0 ? shift / moved : 1.);
            last_places[b] = place;
          }
      }
    return change;
  }



  void
  ContactAugmentation::project_at_crossings(
    std::vector<ContactPiece>            &pieces,
    const std::vector<ContactPieceState> &states,
    const MPI_Comm                        communicator) const
  {
    // Uzawa's update on the crossing's weighted gap, lambda_k <- max(0,
    // lambda_k - eps G_k / W_k), G_k = int phi_k g ds where the curve
    // presses, W_k = int phi_k ds: at its fixed point the weighted gaps
    // of the pressing crossings vanish. (The lumped projection of the
    // pressure, lambda_k <- int phi_k p ds / W_k, stops where eps G_k
    // equals the curvature of lambda along the curve: at a footing's
    // edge, where the pressure falls to zero within a cell, 2.5 mm of
    // penetration at h = 0.125 and the elastic footing 2.1 % soft.)
    // Per crossing of a piece: body, curve, crossing, int phi g ds
    // (pressing), int phi ds. Continuous pressures have no alternating
    // mode: no filter.
    std::vector<double> at_crossings;
    for (unsigned int p = 0; p < pieces.size(); ++p)
      for (unsigned int e = 0; e < 2; ++e)
        at_crossings.insert(at_crossings.end(),
                            {double(pieces[p].body),
                             double(pieces[p].curve),
                             pieces[p].end_keys[e],
                             states[p].end_gaps[e],
                             states[p].end_weights[e]});
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
          const std::array<double, 3> crossing = {
            {double(piece.body), double(piece.curve), piece.end_keys[e]}};
          const auto &sum = sums[crossing];
          if (sum[1] > 0)
            piece.end_multipliers[e] =
              std::max(piece.end_multipliers[e] - penalty * sum[0] / sum[1],
                       0.);
        }
  }
} // namespace bsmpm
