#include <deal.II/base/mpi.h>

#include <bsmpm/contact/contact_results.h>

#include <algorithm>
#include <array>
#include <iomanip>
#include <map>

namespace bsmpm
{
  void
  ContactResults::reinit(const unsigned int n_bodies)
  {
    resultants.assign(n_bodies, Resultant());
  }



  void
  ContactResults::collect(const std::vector<ContactPiece>      &pieces,
                          const std::vector<ContactPieceState> &states,
                          const MPI_Comm                        communicator)
  {
    std::vector<double> penetration(resultants.size(), 0.);
    for (unsigned int p = 0; p < pieces.size(); ++p)
      if (states[p].active)
        penetration[pieces[p].body] =
          std::max(penetration[pieces[p].body], -states[p].gap);
    const bool between_crossings =
      Utilities::MPI::logical_or(std::any_of(pieces.begin(),
                                             pieces.end(),
                                             [](const ContactPiece &piece) {
                                               return piece.between_crossings;
                                             }),
                                 communicator);
    collect(between_crossings ?
              touches_at_crossings(pieces, states, communicator) :
              touches_of_pieces(pieces, states),
            penetration,
            communicator);
  }



  std::vector<ContactResults::Touch>
  ContactResults::touches_of_pieces(
    const std::vector<ContactPiece>      &pieces,
    const std::vector<ContactPieceState> &states)
  {
    std::vector<Touch> touches;
    for (unsigned int p = 0; p < pieces.size(); ++p)
      {
        const ContactPiece      &piece = pieces[p];
        const ContactPieceState &state = states[p];
        if (!state.active)
          continue;
        Touch touch;
        touch.body           = piece.body;
        touch.curve          = piece.curve;
        touch.normal         = state.normal;
        touch.x              = state.midpoint;
        touch.gap            = state.gap;
        touch.pressure       = state.pressure;
        touch.tangential     = state.tangential;
        touch.length         = state.contact_length;
        touch.contact_length = state.contact_length;
        touch.sliding_length = state.sliding_length;
        touch.sliding        = state.sliding;
        touch.resultant      = state.resultant;
        touch.moment         = state.moment;
        touches.push_back(touch);
      }
    return touches;
  }



  std::vector<ContactResults::Touch>
  ContactResults::touches_at_crossings(
    const std::vector<ContactPiece>      &pieces,
    const std::vector<ContactPieceState> &states,
    const MPI_Comm                        communicator)
  {
    // The traction at a crossing k is its lumped projection
    // T_k = int phi_k t ds / W_k, W_k = int phi_k ds, over the pieces on
    // either side (on any process): the force the crossing's hat function
    // carries per unit length. Its penalty pressures at the Gauss points
    // sit where a straight trace cuts a curved outline; T_k is the
    // pressure the discretisation holds. sum_k T_k W_k = int t ds, the
    // force. Per crossing of a piece: body, curve, key, W, int phi t ds
    // (x, y), int phi ds where it slides, int phi g ds, the crossing's
    // place (x, y), the outline's normal there (x, y) and int phi x x t
    // ds (the crossings' moments sum to the force's).
    constexpr unsigned int width = 13;
    std::vector<double>    local;
    for (unsigned int p = 0; p < pieces.size(); ++p)
      for (unsigned int e = 0; e < 2; ++e)
        {
          const ContactPieceState &state = states[p];
          const Tensor<1, 2>       force =
            state.end_weights[e] * state.end_tractions[e];
          local.insert(local.end(),
                       {double(pieces[p].body),
                        double(pieces[p].curve),
                        pieces[p].end_keys[e],
                        state.end_weights[e],
                        force[0],
                        force[1],
                        state.end_sliding[e],
                        state.end_weighted_gaps[e],
                        state.end_places[e][0],
                        state.end_places[e][1],
                        state.end_normals[e][0],
                        state.end_normals[e][1],
                        state.end_moments[e]});
        }
    // The length in contact: a touching piece between two crossings that
    // touching pieces share on both sides (inside a touching stretch)
    // counts whole, one at a stretch's end the part that touches. A
    // straight trace against a curved outline touches in the middle of
    // its pieces only (a wrapped pipe), and the crossing beyond a
    // footing's edge carries a pressure from the part of its piece that
    // touches: neither the touching Gauss points nor the crossings' W
    // alone measure the arc. Per touching piece: body, curve, both keys,
    // its length and the length that touches.
    std::vector<double> touching;
    for (unsigned int p = 0; p < pieces.size(); ++p)
      if (states[p].active)
        touching.insert(touching.end(),
                        {double(pieces[p].body),
                         double(pieces[p].curve),
                         pieces[p].end_keys[0],
                         pieces[p].end_keys[1],
                         pieces[p].length,
                         states[p].contact_length});
    const auto all          = Utilities::MPI::gather(communicator, local, 0);
    const auto all_touching = Utilities::MPI::gather(communicator, touching, 0);
    if (Utilities::MPI::this_mpi_process(communicator) != 0)
      return {};
    using Key = std::array<double, 3>;
    std::map<Key, unsigned int> n_touching;
    for (const auto &part : all_touching)
      for (unsigned int i = 0; i + 6 <= part.size(); i += 6)
        for (const unsigned int e : {2u, 3u})
          ++n_touching[{{part[i], part[i + 1], part[i + e]}}];
    std::map<Key, double> contact_length;
    for (const auto &part : all_touching)
      for (unsigned int i = 0; i + 6 <= part.size(); i += 6)
        {
          const Key  ends[2] = {{{part[i], part[i + 1], part[i + 2]}},
                                {{part[i], part[i + 1], part[i + 3]}}};
          const bool inside =
            n_touching[ends[0]] == 2 && n_touching[ends[1]] == 2;
          for (const Key &end : ends)
            contact_length[end] += (inside ? part[i + 4] : part[i + 5]) / 2;
        }
    // Summed by crossing in the order of the keys (the same on any number
    // of processes); the place, normal and gap are the crossing's own.
    std::map<Key, std::array<double, width>> crossings;
    for (const auto &part : all)
      for (unsigned int i = 0; i + width <= part.size(); i += width)
        {
          auto [at, added] =
            crossings.try_emplace({{part[i], part[i + 1], part[i + 2]}},
                                  std::array<double, width>());
          auto &sum = at->second;
          for (unsigned int j = 3; j < 8; ++j)
            sum[j] += part[i + j];
          sum[12] += part[i + 12];
          if (added)
            for (unsigned int j = 8; j < 12; ++j)
              sum[j] = part[i + j];
        }
    std::vector<Touch> touches;
    for (const auto &[key, sum] : crossings)
      {
        const double       W = sum[3];
        const Tensor<1, 2> force({sum[4], sum[5]});
        if (!(W > 0) || force.norm() == 0.)
          continue;
        const Tensor<1, 2> n({sum[10], sum[11]});
        const Tensor<1, 2> traction = force / W;
        Touch              touch;
        touch.body           = static_cast<unsigned int>(key[0]);
        touch.curve          = static_cast<unsigned int>(key[1]);
        touch.x              = Point<2>(sum[8], sum[9]);
        touch.normal         = n;
        touch.gap            = sum[7] / W;
        touch.pressure       = traction * n;
        touch.tangential     = traction * Tensor<1, 2>({-n[1], n[0]});
        touch.length         = W;
        touch.contact_length = contact_length[key];
        touch.sliding_length = sum[6];
        touch.sliding        = sum[6] > 0;
        touch.resultant      = force;
        touch.moment         = sum[12];
        touches.push_back(touch);
      }
    return touches;
  }



  void
  ContactResults::collect(const std::vector<Touch>  &touches,
                          const std::vector<double> &local_penetration,
                          const MPI_Comm             communicator)
  {
    const unsigned int     n_bodies = resultants.size();
    constexpr unsigned int per_body = 5;
    std::vector<double>    sums(per_body * n_bodies, 0.);
    std::vector<double>    penetration = local_penetration;
    piece_rows.clear();
    for (const Touch &touch : touches)
      {
        // The rigid body feels the opposite of what the curve feels.
        double *sum = &sums[per_body * touch.body];
        sum[0] -= touch.resultant[0];
        sum[1] -= touch.resultant[1];
        sum[2] += touch.contact_length;
        sum[3] += touch.sliding_length;
        sum[4] -= touch.moment;
        piece_rows.insert(piece_rows.end(),
                          {double(touch.body + 1),
                           double(touch.curve + 1),
                           touch.x[0],
                           touch.x[1],
                           touch.normal[0],
                           touch.normal[1],
                           touch.gap,
                           touch.pressure,
                           touch.tangential,
                           touch.length,
                           touch.sliding ? 1. : 0.,
                           touch.sliding_length});
      }
    Utilities::MPI::sum(sums, communicator, sums);
    Utilities::MPI::max(penetration, communicator, penetration);
    for (unsigned int b = 0; b < n_bodies; ++b)
      {
        const double *sum            = &sums[per_body * b];
        resultants[b].force          = Tensor<1, 2>({sum[0], sum[1]});
        resultants[b].contact_length = sum[2];
        resultants[b].sliding_length = sum[3];
        resultants[b].moment         = sum[4];
        resultants[b].penetration    = penetration[b];
      }
  }



  void
  ContactResults::record(const std::vector<RigidBody>  &bodies,
                         const RigidBodyMotion         &motion,
                         std::map<std::string, double> &quantities) const
  {
    for (unsigned int b = 0; b < bodies.size(); ++b)
      {
        const std::string &name       = bodies[b].name();
        const Tensor<1, 2> u          = motion.end(b);
        quantities[name + "_force_x"] = resultants[b].force[0];
        quantities[name + "_force_y"] = resultants[b].force[1];
        quantities[name + "_moment"] =
          resultants[b].moment -
          moment_about_origin(bodies[b].centroid(u), resultants[b].force);
        quantities[name + "_displacement_x"] = u[0];
        quantities[name + "_displacement_y"] = u[1];
        quantities[name + "_contact_length"] = resultants[b].contact_length;
        quantities[name + "_sliding_length"] = resultants[b].sliding_length;
        quantities[name + "_penetration"]    = resultants[b].penetration;
      }
  }



  void
  ContactResults::write_tractions(std::ostream  &out,
                                  const MPI_Comm communicator) const
  {
    const auto all = Utilities::MPI::gather(communicator, piece_rows, 0);
    if (Utilities::MPI::this_mpi_process(communicator) != 0)
      return;
    out << "body,curve,x,y,normal_x,normal_y,gap,pressure,"
           "tangential_traction,length,sliding,sliding_length\n"
        << std::setprecision(10);
    for (const auto &part : all)
      for (unsigned int i = 0; i + row_size <= part.size(); i += row_size)
        {
          out << static_cast<unsigned int>(part[i]) << ','
              << static_cast<unsigned int>(part[i + 1]);
          for (unsigned int j = 2; j < row_size; ++j)
            out << ',' << part[i + j];
          out << '\n';
        }
  }
} // namespace bsmpm
