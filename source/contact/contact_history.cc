#include <bsmpm/contact/contact_history.h>

namespace bsmpm
{
  void
  ContactHistory::reinit(const BoundaryCurves &curves)
  {
    const auto &all_curves = curves.get_curves();
    point_tractions.resize(all_curves.size());
    for (unsigned int c = 0; c < all_curves.size(); ++c)
      // A curve whose points changed in number starts without history.
      if (point_tractions[c].size() != all_curves[c].positions.size())
        point_tractions[c].assign(all_curves[c].positions.size(),
                                  Tensor<1, 2>());
  }



  Tensor<1, 2>
  ContactHistory::at(const unsigned int   c,
                     const BoundaryCurve &curve,
                     const unsigned int   segment,
                     const double         u) const
  {
    const auto   range = curve.spline->segment_parameters(segment);
    const double f     = (u - range[0]) / (range[1] - range[0]);
    return (1 - f) * point_tractions[c][segment] +
           f * point_tractions[c][(segment + 1) % curve.positions.size()];
  }



  void
  ContactHistory::store(const BoundaryCurves                 &curves,
                        const std::vector<ContactPiece>      &pieces,
                        const std::vector<ContactPieceState> &states,
                        const MPI_Comm                        communicator)
  {
    const auto                      &all_curves = curves.get_curves();
    std::vector<std::vector<double>> tractions(all_curves.size());
    for (unsigned int c = 0; c < all_curves.size(); ++c)
      tractions[c].assign(2 * all_curves[c].positions.size(), 0.);
    for (unsigned int p = 0; p < pieces.size(); ++p)
      {
        const ContactPiece      &piece = pieces[p];
        const ContactPieceState &state = states[p];
        if (!state.active)
          continue;
        const BoundaryCurve &curve = all_curves[piece.curve];
        // The knot of point k: the start of its segment (u = 1 for an
        // open curve's last point).
        const auto knot = [&](const unsigned int k) {
          return k < curve.spline->n_segments() ?
                   curve.spline->segment_parameters(k)[0] :
                   1.;
        };
        if (piece.between_crossings)
          {
            // Interpolated between the crossings' tractions.
            for (unsigned int k = 0; k < curve.positions.size(); ++k)
              {
                const double u_k = knot(k);
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
        const Tensor<1, 2> n = state.normal;
        const Tensor<1, 2> traction =
          state.pressure * n + state.tangential * Tensor<1, 2>({-n[1], n[0]});
        for (unsigned int k = 0; k < curve.positions.size(); ++k)
          {
            const double u_k = knot(k);
            if ((u_k >= piece.u_begin && u_k < piece.u_end) ||
                (u_k == 1. && piece.u_end == 1.))
              {
                tractions[piece.curve][2 * k] += traction[0];
                tractions[piece.curve][2 * k + 1] += traction[1];
              }
          }
      }
    for (unsigned int c = 0; c < all_curves.size(); ++c)
      {
        Utilities::MPI::sum(tractions[c], communicator, tractions[c]);
        for (unsigned int k = 0; k < all_curves[c].positions.size(); ++k)
          point_tractions[c][k] =
            Tensor<1, 2>({tractions[c][2 * k], tractions[c][2 * k + 1]});
      }
  }



  void
  ContactHistory::follow_point_changes(
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
  ContactHistory::store(const BoundaryCurves             &curves,
                        const std::vector<PointTraction> &tractions,
                        const MPI_Comm                    communicator)
  {
    const auto                      &all_curves = curves.get_curves();
    std::vector<std::vector<double>> sums(all_curves.size());
    for (unsigned int c = 0; c < all_curves.size(); ++c)
      sums[c].assign(2 * all_curves[c].positions.size(), 0.);
    for (const PointTraction &point : tractions)
      for (unsigned int d = 0; d < 2; ++d)
        sums[point.curve][2 * point.index + d] += point.traction[d];
    for (unsigned int c = 0; c < all_curves.size(); ++c)
      {
        Utilities::MPI::sum(sums[c], communicator, sums[c]);
        for (unsigned int k = 0; k < all_curves[c].positions.size(); ++k)
          point_tractions[c][k] =
            Tensor<1, 2>({sums[c][2 * k], sums[c][2 * k + 1]});
      }
  }
} // namespace bsmpm
