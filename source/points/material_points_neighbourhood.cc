#include <deal.II/base/mpi.h>

#include <bsmpm/points/material_points.h>

#include <algorithm>
#include <cmath>

// MaterialPoints, part 4: what a cell learns from its neighbours, across
// processes too. The field a boundary point in a cell without material
// takes (boundary_strain(), boundary_gradient()), and the mean state of
// the neighbourhood of a cell of the body without points.

namespace bsmpm
{
  std::vector<double>
  MaterialPoints::neighbourhood_mean_properties(
    const DoFHandler<2>::active_cell_iterator &cell) const
  {
    AssertThrow(neighbourhood_current,
                ExcMessage("MaterialPoints::exchange_neighbourhood_state() "
                           "after the points changed"));
    const unsigned int  W = n_point_properties + 1;
    std::vector<double> mean;
    double              volume     = 0;
    const auto          add_points = [&](const auto &neighbour) {
      if (!neighbour->is_active() || neighbour->is_artificial())
        return;
      const types::global_dof_index first =
        neighbour->global_active_cell_index() * W;
      const double V = neighbourhood_sums[first + W - 1];
      if (!(V > 0))
        return;
      if (mean.empty())
        mean.assign(W - 1, 0.);
      for (unsigned int k = 0; k + 1 < W; ++k)
        mean[k] += neighbourhood_sums[first + k];
      volume += V;
    };
    // The face neighbours; where none holds material (a corner cell whose
    // face neighbours are slivers without points), the diagonal ones.
    for (const unsigned int f : cell->face_indices())
      if (!cell->at_boundary(f))
        add_points(cell->neighbor(f));
    if (mean.empty())
      for (const unsigned int f : {0u, 1u})
        if (!cell->at_boundary(f) && cell->neighbor(f)->is_active() &&
            !cell->neighbor(f)->is_artificial())
          for (const unsigned int g : {2u, 3u})
            if (!cell->neighbor(f)->at_boundary(g))
              add_points(cell->neighbor(f)->neighbor(g));
    for (double &value : mean)
      value /= volume;
    // Several bodies: the state is that of the body most of the volume
    // belongs to (of two, the nearer to the mean index).
    if (mean.size() > Property::body)
      mean[Property::body] = std::round(mean[Property::body]);
    return mean;
  }



  void
  MaterialPoints::exchange_neighbourhood_state()
  {
    // The cells' sums in blocks of W entries: the cells' own partition
    // (owned and ghost cells) with every index widened to W.
    const auto &tria  = grid.triangulation();
    const auto  cells = tria.global_active_cell_index_partitioner().lock();
    const types::global_dof_index W = n_point_properties + 1;
    if (neighbourhood_sums.size() != cells->size() * W)
      {
        IndexSet owned(cells->size() * W), ghost(cells->size() * W);
        for (const auto i : cells->locally_owned_range())
          owned.add_range(i * W, (i + 1) * W);
        for (const auto i : cells->ghost_indices())
          ghost.add_range(i * W, (i + 1) * W);
        neighbourhood_sums.reinit(std::make_shared<Utilities::MPI::Partitioner>(
          owned, ghost, cells->get_mpi_communicator()));
      }
    neighbourhood_sums = 0;
    std::vector<std::pair<types::particle_index, ArrayView<const double>>>
      ordered;
    for (const auto &cell : grid.dof_handler().active_cell_iterators())
      {
        if (!cell->is_locally_owned())
          continue;
        const types::global_dof_index first =
          cell->global_active_cell_index() * W;
        // Summed in the order of the points' ids: the order of the points
        // in a cell follows the order in which messages arrived when points
        // changed process, and a sum in that order makes one run differ
        // from the next in the last bits.
        ordered.clear();
        for (const auto &particle : particles.particles_in_cell(cell))
          if (particle.get_properties()[Property::volume] > 0)
            ordered.emplace_back(particle.get_id(), particle.get_properties());
        std::sort(ordered.begin(),
                  ordered.end(),
                  [](const auto &a, const auto &b) {
                    return a.first < b.first;
                  });
        for (const auto &[id, props] : ordered)
          {
            const double V = props[Property::volume];
            for (unsigned int k = 0; k + 1 < W; ++k)
              neighbourhood_sums[first + k] += V * props[k];
            neighbourhood_sums[first + W - 1] += V;
          }
      }
    neighbourhood_sums.update_ghost_values();
    neighbourhood_current = true;
  }



  void
  MaterialPoints::find_material_cells()
  {
    // Only a zero-volume point can lie in a cell without material: without
    // any, boundary_source() is never asked (7 ms a step on a grid of 128^2
    // cells).
    material_cells.clear();
    if (particles.n_global_particles() == n_material_points)
      return;
    const auto                                &tria = grid.triangulation();
    LinearAlgebra::distributed::Vector<double> flags(
      tria.global_active_cell_index_partitioner().lock());
    for (const auto &cell : grid.dof_handler().active_cell_iterators())
      if (cell->is_locally_owned() && holds_material(cell))
        flags[cell->global_active_cell_index()] = 1;
    flags.update_ghost_values();
    material_cells.assign(tria.n_active_cells(), false);
    for (const auto &cell : tria.active_cell_iterators())
      if (!cell->is_artificial())
        material_cells[cell->active_cell_index()] =
          flags[cell->global_active_cell_index()] > 0;
  }



  std::pair<DoFHandler<2>::active_cell_iterator, Point<2>>
  MaterialPoints::boundary_source(
    const DoFHandler<2>::active_cell_iterator &cell,
    const Point<2>                            &st) const
  {
    // A zero-volume point in a cell without material: a boundary point on a
    // grid line is sorted into the cell above or to the right of it, and a
    // boundary that has just crossed into a cell leaves only a sliver of
    // body there, whose outer vertices hold nothing. The strain of the body
    // is that of the nearest neighbour across a face that holds material,
    // its affine field extended to the point. Faces are numbered left,
    // right, bottom, top.
    const std::array<double, 4> distance = {
      {st[0], 1 - st[0], st[1], 1 - st[1]}};
    std::array<unsigned int, 4> faces = {{0, 1, 2, 3}};
    std::sort(faces.begin(), faces.end(), [&](unsigned int a, unsigned int b) {
      return distance[a] < distance[b];
    });
    AssertThrow(material_cells.size() == grid.triangulation().n_active_cells(),
                ExcMessage("MaterialPoints::find_material_cells() first"));
    auto     source = cell;
    Point<2> where  = st;
    for (const unsigned int face : faces)
      {
        if (cell->at_boundary(face) || cell->neighbor(face)->is_artificial())
          continue;
        const auto neighbour = cell->neighbor(face);
        if (!material_cells[neighbour->active_cell_index()])
          continue;
        source = neighbour;
        where[face / 2] += (face % 2 == 0) ? 1. : -1.;
        break;
      }
    return {source, where};
  }



  std::pair<Q1CellKernel::LocalVector, Point<2>>
  MaterialPoints::boundary_increment(
    const DoFHandler<2>::active_cell_iterator        &cell,
    const Point<2>                                   &st,
    const LinearAlgebra::distributed::Vector<double> &increment,
    const LinearAlgebra::distributed::Vector<double> *prescribed) const
  {
    const auto [source, where] = boundary_source(cell, st);
    std::vector<types::global_dof_index> dof_indices(
      Q1CellKernel::dofs_per_cell);
    return {cell_increment(source, increment, prescribed, dof_indices), where};
  }



  Voigt
  MaterialPoints::boundary_strain(
    const Q1CellKernel                               &kernel,
    const DoFHandler<2>::active_cell_iterator        &cell,
    const Point<2>                                   &st,
    const LinearAlgebra::distributed::Vector<double> &increment,
    const LinearAlgebra::distributed::Vector<double> *prescribed) const
  {
    const auto [d, where] = boundary_increment(cell, st, increment, prescribed);
    const auto e          = kernel.strain_coefficients(d);
    return e[0] + where[0] * e[1] + where[1] * e[2];
  }



  Tensor<2, 2>
  MaterialPoints::boundary_gradient(
    const Q1CellKernel                               &kernel,
    const DoFHandler<2>::active_cell_iterator        &cell,
    const Point<2>                                   &st,
    const LinearAlgebra::distributed::Vector<double> &increment,
    const LinearAlgebra::distributed::Vector<double> *prescribed) const
  {
    const auto [d, where] = boundary_increment(cell, st, increment, prescribed);
    return kernel.gradient(d, where);
  }
} // namespace bsmpm



namespace bsmpm
{
  std::vector<std::vector<double>>
  MaterialPoints::mean_properties_near(const std::vector<Point<2>> &positions,
                                       const double radius) const
  {
    // Per position: the volume-weighted sums of the properties of the
    // nearby points this process owns, then their volume; summed over the
    // processes, each in the order of the points' ids (as
    // exchange_neighbourhood_state()), so that the result does not depend
    // on the order in which points arrived in their cells.
    const unsigned int  W = n_point_properties + 1;
    std::vector<double> sums(positions.size() * W, 0.);
    std::vector<std::pair<types::particle_index, ArrayView<const double>>> near;
    // The cells that the square of half-width radius round x overlaps.
    const auto cells_round = [&](const Point<2> &x, const double sign) {
      Point<2> corner = x + sign * radius * Tensor<1, 2>({1., 1.});
      for (unsigned int d = 0; d < 2; ++d)
        corner[d] =
          std::clamp(corner[d], grid.lower_left()[d], grid.upper_right()[d]);
      return grid.cell_index(corner);
    };
    for (unsigned int i = 0; i < positions.size(); ++i)
      {
        const Point<2> &x = positions[i];
        near.clear();
        const auto first = cells_round(x, -1.), last = cells_round(x, 1.);
        for (unsigned int j = first[1]; j <= last[1]; ++j)
          for (unsigned int k = first[0]; k <= last[0]; ++k)
            {
              const auto cell = grid.locally_owned_cell({{k, j}});
              if (cell == grid.dof_handler().end())
                continue;
              for (const auto &particle : particles.particles_in_cell(cell))
                if (particle.get_properties()[Property::volume] > 0 &&
                    particle.get_location().distance(x) <= radius)
                  near.emplace_back(particle.get_id(),
                                    particle.get_properties());
            }
        std::sort(near.begin(), near.end(), [](const auto &a, const auto &b) {
          return a.first < b.first;
        });
        for (const auto &[id, props] : near)
          {
            const double V = props[Property::volume];
            for (unsigned int p = 0; p + 1 < W; ++p)
              sums[i * W + p] += V * props[p];
            sums[i * W + W - 1] += V;
          }
      }
    Utilities::MPI::sum(sums, grid.mpi_communicator(), sums);
    std::vector<std::vector<double>> means(positions.size());
    for (unsigned int i = 0; i < positions.size(); ++i)
      {
        const double V = sums[i * W + W - 1];
        if (!(V > 0))
          continue;
        means[i].resize(W - 1);
        for (unsigned int p = 0; p + 1 < W; ++p)
          means[i][p] = sums[i * W + p] / V;
        if (means[i].size() > Property::body)
          means[i][Property::body] = std::round(means[i][Property::body]);
      }
    return means;
  }
} // namespace bsmpm
