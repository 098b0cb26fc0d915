#include <bsmpm/contact/contact_results.h>

#include <algorithm>
#include <iomanip>

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
    std::vector<Touch>  touches;
    std::vector<double> penetration(resultants.size(), 0.);
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
        touches.push_back(touch);
        penetration[piece.body] = std::max(penetration[piece.body], -state.gap);
      }
    collect(touches, penetration, communicator);
  }



  void
  ContactResults::collect(const std::vector<Touch>  &touches,
                          const std::vector<double> &local_penetration,
                          const MPI_Comm             communicator)
  {
    const unsigned int  n_bodies = resultants.size();
    std::vector<double> sums(4 * n_bodies, 0.);
    std::vector<double> penetration = local_penetration;
    piece_rows.clear();
    for (const Touch &touch : touches)
      {
        // The rigid body feels the opposite of what the curve feels.
        sums[4 * touch.body + 0] -= touch.resultant[0];
        sums[4 * touch.body + 1] -= touch.resultant[1];
        sums[4 * touch.body + 2] += touch.contact_length;
        sums[4 * touch.body + 3] += touch.sliding_length;
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
        resultants[b].force = Tensor<1, 2>({sums[4 * b + 0], sums[4 * b + 1]});
        resultants[b].contact_length = sums[4 * b + 2];
        resultants[b].sliding_length = sums[4 * b + 3];
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
        const std::string &name              = bodies[b].name();
        const Tensor<1, 2> u                 = motion.end(b);
        quantities[name + "_force_x"]        = resultants[b].force[0];
        quantities[name + "_force_y"]        = resultants[b].force[1];
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
