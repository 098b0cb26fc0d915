#include <deal.II/base/mpi.h>

#include <bsmpm/support_reaction.h>

#include <set>

namespace bsmpm
{
  std::vector<Tensor<1, 2>>
  SupportReaction::compute(const BoundaryCurves &curves,
                           const BackgroundGrid &grid,
                           const MaterialPoints &points,
                           const Q1CellKernel   &kernel,
                           const Tensor<1, 2>   &body_force)
  {
    using Vertex         = std::array<unsigned int, 2>;
    using Property       = MaterialPoints::Property;
    const auto &all      = curves.get_curves();
    const auto  n_curves = all.size();

    // The grid vertices of the cells crossed by each curve's supports
    // (pieces are known on every process).
    std::vector<std::set<Vertex>> vertices(n_curves);
    bool                          any = false;
    for (unsigned int c = 0; c < n_curves; ++c)
      for (const auto &piece : all[c].pieces)
        {
          const CurveCondition *condition =
            all[c].condition_of_segment(piece.segment);
          if (!condition || !condition->is_support())
            continue;
          any = true;
          for (unsigned int v = 0; v < 4; ++v)
            vertices[c].insert(
              {{piece.cell[0] + v % 2, piece.cell[1] + v / 2}});
        }

    std::vector<Tensor<1, 2>> force(n_curves);
    if (any)
      {
        const auto &particles = points.particle_handler();
        for (const auto &cell : grid.triangulation().active_cell_iterators())
          {
            if (!cell->is_locally_owned() ||
                particles.n_particles_in_cell(cell) == 0)
              continue;
            const auto ij = grid.cell_index(cell->center());
            // Which curves' test fields are nonzero in this cell, by vertex.
            std::vector<std::array<bool, 4>> on(n_curves);
            bool                             needed = false;
            for (unsigned int c = 0; c < n_curves; ++c)
              for (unsigned int v = 0; v < 4; ++v)
                {
                  on[c][v] =
                    vertices[c].count({{ij[0] + v % 2, ij[1] + v / 2}}) > 0;
                  needed |= on[c][v];
                }
            if (!needed)
              continue;
            for (const auto &particle : particles.particles_in_cell(cell))
              {
                const auto   props  = particle.get_properties();
                const double volume = props[Property::volume];
                if (volume == 0.)
                  continue;
                const Point<2> st = particle.get_reference_location();
                const Voigt    sigma({props[Property::stress],
                                      props[Property::stress + 1],
                                      props[Property::stress + 2]});
                const auto     N = Q1CellKernel::vertex_shape_values(st);
                for (unsigned int i = 0; i < Q1CellKernel::dofs_per_cell; ++i)
                  {
                    const unsigned int v = kernel.vertex(i);
                    const unsigned int k = kernel.component(i);
                    const double       f =
                      volume * (kernel.strain_column(i, st) * sigma -
                                N[v] * body_force[k]);
                    for (unsigned int c = 0; c < n_curves; ++c)
                      if (on[c][v])
                        force[c][k] += f;
                  }
              }
          }
      }
    for (auto &f : force)
      f = Utilities::MPI::sum(f, grid.mpi_communicator());
    return force;
  }
} // namespace bsmpm
