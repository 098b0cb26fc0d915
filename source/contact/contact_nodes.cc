#include <bsmpm/contact/contact_nodes.h>

#include <algorithm>
#include <map>
#include <tuple>

namespace bsmpm
{
  void
  ContactNodes::reinit(const std::vector<ContactPiece> &pieces,
                       const BoundaryCurves            &curves,
                       const std::vector<RigidBody>    &bodies,
                       const RigidBodyMotion           &motion,
                       const BackgroundGrid            &grid)
  {
    const MPI_Comm     communicator = grid.mpi_communicator();
    const unsigned int n_x          = grid.n_cells(0);
    cells_per_row                   = n_x;

    // W_a per node and cell on this process (a cell's points are all on
    // its owner, summed in the order of the curves), then over all
    // processes by node and cell: the same sums on every process, bit for
    // bit, whatever the partition. Only the places that face the body or
    // already penetrate it (see the class's documentation).
    using Key = std::tuple<unsigned int, unsigned int, double, unsigned int>;
    std::map<Key, double>     partial;
    std::vector<unsigned int> taken_pieces;
    std::vector<unsigned int> taken_points;
    for (unsigned int p = 0; p < pieces.size(); ++p)
      {
        const ContactPiece &piece = pieces[p];
        Assert(piece.between_crossings, ExcInternalError());
        for (unsigned int q = 0; q < piece.positions.size(); ++q)
          {
            const SurfacePoint surface =
              bodies[piece.body].to_feature(piece.positions[q],
                                            motion.start(piece.body),
                                            piece.features[q]);
            if (!(piece.curve_normals[q] * surface.normal < 0 ||
                  surface.gap < 0))
              continue;
            taken_pieces.push_back(p);
            taken_points.push_back(q);
            const unsigned int cell = piece.cell[1] * n_x + piece.cell[0];
            for (unsigned int e = 0; e < 2; ++e)
              {
                const double phi = e == 0 ? 1 - piece.phi[q] : piece.phi[q];
                if (phi != 0)
                  partial[{piece.body, piece.curve, piece.end_keys[e], cell}] +=
                    phi * piece.weights[q];
              }
          }
      }
    std::vector<double> local;
    for (const auto &[key, weight] : partial)
      local.insert(local.end(),
                   {double(std::get<0>(key)),
                    double(std::get<1>(key)),
                    std::get<2>(key),
                    double(std::get<3>(key)),
                    weight});
    std::map<Key, double> all;
    for (const auto &part : Utilities::MPI::all_gather(communicator, local))
      for (unsigned int i = 0; i + 5 <= part.size(); i += 5)
        all[{static_cast<unsigned int>(part[i]),
             static_cast<unsigned int>(part[i + 1]),
             part[i + 2],
             static_cast<unsigned int>(part[i + 3])}] = part[i + 4];
    all_nodes.clear();
    std::vector<bool> holds(n_x * grid.n_cells(1), false);
    for (const auto &[key, weight] : all)
      {
        holds[std::get<3>(key)] = true;
        if (all_nodes.empty() || all_nodes.back().body != std::get<0>(key) ||
            all_nodes.back().curve != std::get<1>(key) ||
            all_nodes.back().key != std::get<2>(key))
          {
            Node node;
            node.body  = std::get<0>(key);
            node.curve = std::get<1>(key);
            node.key   = std::get<2>(key);
            all_nodes.push_back(node);
          }
        all_nodes.back().weight += weight;
      }
    all_cells.clear();
    for (unsigned int c = 0; c < holds.size(); ++c)
      if (holds[c])
        all_cells.push_back({{c % n_x, c / n_x}});

    gauss_points.clear();
    for (unsigned int i = 0; i < taken_pieces.size(); ++i)
      {
        const ContactPiece &piece = pieces[taken_pieces[i]];
        const unsigned int  q     = taken_points[i];
        GaussPoint          point;
        point.body     = piece.body;
        point.curve    = piece.curve;
        point.feature  = piece.features[q];
        point.cell     = piece.cell;
        point.position = piece.positions[q];
        point.weight   = piece.weights[q];
        point.previous = piece.previous[q];
        locate(piece, piece.phi[q], point.nodes, point.shape);
        gauss_points.push_back(point);
      }

    // The curves' points in the pieces (u_begin <= u_k < u_end, past u = 1
    // on a closed curve, and u = 1 in the last piece of an open curve):
    // where the tractions are kept.
    const auto &all_curves = curves.get_curves();
    knots.clear();
    for (const ContactPiece &piece : pieces)
      {
        const BoundaryCurve &curve = all_curves[piece.curve];
        for (unsigned int k = 0; k < curve.positions.size(); ++k)
          {
            const double u_k = k < curve.spline->n_segments() ?
                                 curve.spline->segment_parameters(k)[0] :
                                 1.;
            for (const double u : {u_k, u_k + 1})
              if ((u >= piece.u_begin && u < piece.u_end) ||
                  (u == 1. && piece.u_end == 1.))
                {
                  CurvePoint knot;
                  knot.body     = piece.body;
                  knot.curve    = piece.curve;
                  knot.index    = k;
                  knot.cell     = piece.cell;
                  knot.position = curve.spline->value(u_k);
                  knot.feature =
                    bodies[piece.body]
                      .nearest(knot.position, motion.start(piece.body))
                      .feature;
                  locate(piece,
                         (u - piece.u_begin) / (piece.u_end - piece.u_begin),
                         knot.nodes,
                         knot.shape);
                  knots.push_back(knot);
                  break;
                }
          }
      }
  }



  unsigned int
  ContactNodes::find(const unsigned int body,
                     const unsigned int curve,
                     const double       key) const
  {
    const auto less =
      [](const Node                                           &node,
         const std::tuple<unsigned int, unsigned int, double> &k) {
        return std::make_tuple(node.body, node.curve, node.key) < k;
      };
    const auto it = std::lower_bound(all_nodes.begin(),
                                     all_nodes.end(),
                                     std::make_tuple(body, curve, key),
                                     less);
    if (it == all_nodes.end() || it->body != body || it->curve != curve ||
        it->key != key)
      return numbers::invalid_unsigned_int;
    return it - all_nodes.begin();
  }



  void
  ContactNodes::locate(const ContactPiece          &piece,
                       const double                 phi,
                       std::array<unsigned int, 4> &nodes,
                       std::array<double, 4>       &shape) const
  {
    nodes.fill(numbers::invalid_unsigned_int);
    shape.fill(0.);
    for (unsigned int e = 0; e < 2; ++e)
      {
        shape[e] = e == 0 ? 1 - phi : phi;
        nodes[e] = shape[e] != 0 ?
                     find(piece.body, piece.curve, piece.end_keys[e]) :
                     numbers::invalid_unsigned_int;
        if (nodes[e] == numbers::invalid_unsigned_int)
          shape[e] = 0;
      }
  }



  void
  ContactNodes::initialize_multipliers(const std::vector<RigidBody> &bodies,
                                       const RigidBodyMotion        &motion,
                                       const MPI_Comm communicator)
  {
    // The normal traction of the last increment, as the friction history
    // keeps it at the curves' points, projected on the nodes: lambda_a =
    // sum_q w_q phi_a t_prev . n_q / W_a, summed by node and cell as W_a.
    std::map<std::array<unsigned int, 2>, double> partial;
    for (const GaussPoint &point : gauss_points)
      {
        const double normal =
          point.previous *
          bodies[point.body]
            .to_feature(point.position, motion.end(point.body), point.feature)
            .normal;
        for (unsigned int v = 0; v < 4; ++v)
          if (point.nodes[v] != numbers::invalid_unsigned_int)
            partial[{{point.nodes[v],
                      point.cell[1] * cells_per_row + point.cell[0]}}] +=
              point.shape[v] * point.weight * normal;
      }
    std::vector<double> local;
    for (const auto &[key, value] : partial)
      local.insert(local.end(), {double(key[0]), double(key[1]), value});
    std::map<std::array<unsigned int, 2>, double> all;
    for (const auto &part : Utilities::MPI::all_gather(communicator, local))
      for (unsigned int i = 0; i + 3 <= part.size(); i += 3)
        all[{{static_cast<unsigned int>(part[i]),
              static_cast<unsigned int>(part[i + 1])}}] = part[i + 2];
    std::vector<double> sums(all_nodes.size(), 0.);
    for (const auto &[key, value] : all)
      sums[key[0]] += value;
    for (unsigned int a = 0; a < all_nodes.size(); ++a)
      all_nodes[a].multiplier = std::max(sums[a] / all_nodes[a].weight, 0.);
  }
} // namespace bsmpm
