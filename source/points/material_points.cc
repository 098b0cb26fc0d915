#include <deal.II/base/mpi.h>

#include <bsmpm/points/material_points.h>
#include <bsmpm/points/point_sorting.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>

// MaterialPoints, part 1: the points as stored, made and sorted into cells.
// The class spans four files by concern (the ASPECT way): this one; the
// move by a load increment (material_points_move.cc); the tracked points
// (material_points_tracking.cc); what a cell learns from its neighbours
// (material_points_neighbourhood.cc).

namespace bsmpm
{
  std::string
  MaterialPoints::format_point(const Point<2> &p)
  {
    std::ostringstream s;
    s << '(' << p[0] << ", " << p[1] << ')';
    return s.str();
  }



  MaterialPoints::MaterialPoints(const BackgroundGrid &grid,
                                 const bool            inelastic_state)
    : grid(grid)
    , n_point_properties(inelastic_state ? Property::n_properties_inelastic :
                                           Property::n_properties)
  {}



  bool
  MaterialPoints::insert(const Point<2>             &position,
                         const double                volume,
                         const types::particle_index id,
                         const unsigned int          body)
  {
    AssertThrow(grid.contains(position),
                ExcMessage("Material point " + std::to_string(id) + " at " +
                           format_point(position) +
                           " lies outside the background grid " +
                           format_point(grid.lower_left()) + " - " +
                           format_point(grid.upper_right()) + "."));
    const auto ij   = grid.cell_index(position);
    const auto cell = grid.locally_owned_cell(ij);
    if (cell == grid.dof_handler().end())
      return false;

    std::array<double, Property::n_properties_inelastic> properties{};
    properties[Property::volume]               = volume;
    properties[Property::d_function]           = 1.;
    properties[Property::initial_position]     = position[0];
    properties[Property::initial_position + 1] = position[1];
    if (n_point_properties == Property::n_properties_inelastic)
      {
        properties[Property::deformation_gradient]     = 1.;
        properties[Property::deformation_gradient + 3] = 1.;
        properties[Property::det_F]                    = 1.;
        properties[Property::body]                     = body;
      }
    else
      AssertThrow(body == 0,
                  ExcMessage("Points of several bodies need the "
                             "point-by-point state (Property::body)."));
    particles.insert_particle(position,
                              grid.local_coordinates(position, ij),
                              id,
                              cell,
                              ArrayView<const double>(properties.data(),
                                                      n_point_properties));
    return true;
  }



  void
  MaterialPoints::generate(
    const MaterialPointLayout                   &layout,
    const BodyRegion                            &region,
    const std::function<bool(const Point<2> &)> &excluded)
  {
    particles.initialize(grid.triangulation(),
                         grid.mapping(),
                         n_point_properties);
    // Room for this process' share at once: growing the storage point by
    // point costs more than the insertion itself.
    const unsigned int n_cells = grid.n_cells(0) * grid.n_cells(1);
    particles.reserve(layout.n_candidates(grid) / n_cells *
                      grid.triangulation().n_locally_owned_active_cells());
    next_id = 0;
    n_material_points =
      insert_body(layout, region, 0, excluded, reserve_ids(layout));
    AssertThrow(n_material_points > 0,
                ExcMessage("Material points: the body region holds no "
                           "material point of the chosen layout."));
  }



  types::particle_index
  MaterialPoints::add_body(
    const MaterialPointLayout                   &layout,
    const BodyRegion                            &region,
    const unsigned int                           body,
    const std::string                           &section,
    const std::function<bool(const Point<2> &)> &excluded,
    const std::optional<types::particle_index>  &first_id)
  {
    const types::particle_index n =
      insert_body(layout,
                  region,
                  body,
                  excluded,
                  first_id ? *first_id : reserve_ids(layout));
    AssertThrow(n > 0,
                ExcMessage(section +
                           ": the body region holds no material point of "
                           "the chosen layout."));
    n_material_points += n;
    neighbourhood_current = false;
    find_material_cells();
    return n;
  }



  types::particle_index
  MaterialPoints::reserve_ids(const MaterialPointLayout &layout)
  {
    const types::particle_index first = next_id;
    next_id += layout.n_candidates(grid);
    return first;
  }



  void
  MaterialPoints::count_material_points()
  {
    types::particle_index n = 0;
    for (const auto &particle : particles)
      if (particle.get_properties()[Property::volume] > 0)
        ++n;
    n_material_points     = Utilities::MPI::sum(n, grid.mpi_communicator());
    neighbourhood_current = false;
    find_material_cells();
  }



  types::particle_index
  MaterialPoints::insert_body(
    const MaterialPointLayout                   &layout,
    const BodyRegion                            &region,
    const unsigned int                           body,
    const std::function<bool(const Point<2> &)> &excluded,
    const types::particle_index                  first)
  {
    // Each process creates the points of its own cells, with the index of
    // the layout's enumeration (after the earlier bodies' candidates) as
    // id: unique and partition-independent.
    types::particle_index n_here = 0;
    layout.for_each_point(
      grid,
      region,
      [this](const MaterialPointLayout::CellIndex &ij) {
        return grid.locally_owned_cell(ij) != grid.dof_handler().end();
      },
      [&](const Point<2> &p, const double volume, const unsigned long id) {
        if (!excluded || !excluded(p))
          n_here += insert(p, volume, first + id, body);
      });
    particles.update_cached_numbers();
    return Utilities::MPI::sum(n_here, grid.mpi_communicator());
  }



  std::vector<types::particle_index>
  MaterialPoints::add_tracking_points(const std::vector<Point<2>> &positions)
  {
    std::vector<types::particle_index> ids;
    for (const auto &p : positions)
      {
        ids.push_back(next_id);
        insert(p, 0., next_id++);
      }
    particles.update_cached_numbers();
    return ids;
  }



  double
  MaterialPoints::global_volume() const
  {
    double volume = 0;
    for (const auto &particle : particles)
      volume += particle.get_properties()[Property::volume];
    return Utilities::MPI::sum(volume, grid.mpi_communicator());
  }



  namespace
  {
    /** Resets @p moments to one entry per active cell and lets @p add put
     * every point with volume of a locally owned cell into its cell's:
     * add(moments of the cell, reference location, properties, volume). */
    template <typename Add>
    void
    sum_into_cells(const Particles::ParticleHandler<2> &particles,
                   const BackgroundGrid                &grid,
                   std::vector<CellMoments>            &moments,
                   const Add                           &add)
    {
      moments.assign(grid.triangulation().n_active_cells(), CellMoments());
      for (const auto &cell : grid.triangulation().active_cell_iterators())
        if (cell->is_locally_owned())
          {
            CellMoments &m = moments[cell->active_cell_index()];
            for (const auto &particle : particles.particles_in_cell(cell))
              {
                const auto   props  = particle.get_properties();
                const double volume = props[MaterialPoints::Property::volume];
                if (volume != 0.)
                  add(m, particle.get_reference_location(), props, volume);
              }
          }
    }
  } // namespace



  void
  MaterialPoints::compute_cell_moments(std::vector<CellMoments> &moments) const
  {
    sum_into_cells(particles,
                   grid,
                   moments,
                   [](CellMoments    &m,
                      const Point<2> &st,
                      const auto     &props,
                      const double    volume) {
                     m.add(st,
                           volume,
                           Voigt({props[Property::stress],
                                  props[Property::stress + 1],
                                  props[Property::stress + 2]}));
                   });
  }



  void
  MaterialPoints::compute_mass_moments(std::vector<CellMoments> &moments) const
  {
    sum_into_cells(particles,
                   grid,
                   moments,
                   [this](CellMoments    &m,
                          const Point<2> &st,
                          const auto     &props,
                          const double    volume) {
                     m.add(st, density(props) * volume, Voigt());
                   });
  }



  double
  MaterialPoints::global_mass() const
  {
    double mass = 0;
    for (const auto &particle : particles)
      mass += density(particle.get_properties()) *
              particle.get_properties()[Property::volume];
    return Utilities::MPI::sum(mass, grid.mpi_communicator());
  }



  void
  MaterialPoints::sort_into_cells()
  {
    const auto before = particles.n_global_particles();
    // By arithmetic on the uniform grid, not deal.II's search
    // (sort_particles_into_subdomains_and_cells): doc/benchmarks.md.
    bsmpm::sort_into_cells(particles, grid);
    AssertThrow(particles.n_global_particles() == before,
                ExcMessage(
                  "Material points were lost while sorting them into "
                  "cells: " +
                  std::to_string(before - particles.n_global_particles()) +
                  " of them left the grid."));
  }



  std::vector<types::particle_index>
  MaterialPoints::outer_layer(const std::vector<Point<2>> &corners,
                              const bool                   closed) const
  {
    std::vector<types::particle_index> layer;
    const unsigned int n_sides = closed ? corners.size() : corners.size() - 1;
    for (unsigned int k = 0; k < n_sides; ++k)
      {
        const Point<2> p0 = corners[k], p1 = corners[(k + 1) % corners.size()];
        const double   length    = p0.distance(p1);
        const Tensor<1, 2> along = (p1 - p0) / length;
        const Tensor<1, 2> inward({-along[1], along[0]});
        const double       tolerance = 1e-9 * length;

        // Distance to the side of the nearest points beside it, then those.
        double nearest = std::numeric_limits<double>::max();
        for (const auto &particle : particles)
          {
            const Tensor<1, 2> d = particle.get_location() - p0;
            if (particle.get_properties()[Property::volume] > 0 &&
                d * along >= -tolerance && d * along <= length + tolerance &&
                d * inward >= -tolerance)
              nearest = std::min(nearest, d * inward);
          }
        nearest = Utilities::MPI::min(nearest, grid.mpi_communicator());

        std::vector<std::pair<double, types::particle_index>> side;
        for (const auto &particle : particles)
          {
            const Tensor<1, 2> d = particle.get_location() - p0;
            if (particle.get_properties()[Property::volume] > 0 &&
                d * along >= -tolerance && d * along <= length + tolerance &&
                std::abs(d * inward - nearest) <= tolerance)
              side.emplace_back(d * along, particle.get_id());
          }
        std::vector<std::pair<double, types::particle_index>> all;
        for (const auto &part :
             Utilities::MPI::all_gather(grid.mpi_communicator(), side))
          all.insert(all.end(), part.begin(), part.end());
        AssertThrow(!all.empty(),
                    ExcMessage("Boundary curves: no material point lies "
                               "along side " +
                               std::to_string(k) + " of the region."));
        std::sort(all.begin(), all.end());
        for (const auto &[position, id] : all)
          if (layer.empty() || layer.back() != id)
            layer.push_back(id);
      }
    if (closed && layer.size() > 1 && layer.front() == layer.back())
      layer.pop_back();
    return layer;
  }



  void
  MaterialPoints::scale_volumes(const std::vector<types::particle_index> &ids,
                                const double factor)
  {
    std::map<types::particle_index, unsigned int> count;
    for (const auto id : ids)
      ++count[id];
    for (auto &particle : particles)
      {
        const auto it = count.find(particle.get_id());
        if (it != count.end())
          particle.get_properties()[Property::volume] *=
            std::pow(factor, it->second);
      }
  }



  void
  MaterialPoints::set_stress(
    const std::function<SymmetricTensor<2, 3>(const Point<2> &,
                                              const unsigned int)> &stress,
    const std::vector<SymmetricTensor<4, 3>>                       &compliances)
  {
    for (auto &particle : particles)
      {
        const ArrayView<double> properties = particle.get_properties();
        const unsigned int      body =
          n_point_properties == Property::n_properties_inelastic ?
                 static_cast<unsigned int>(properties[Property::body]) :
                 0;
        const SymmetricTensor<4, 3> &compliance = compliances[body];
        const SymmetricTensor<2, 3>  sigma =
          stress(particle.get_location(), body);
        properties[Property::stress]     = sigma[0][0];
        properties[Property::stress + 1] = sigma[1][1];
        properties[Property::stress + 2] = sigma[0][1];
        if (n_point_properties == Property::n_properties_inelastic)
          {
            const SymmetricTensor<2, 3> eps          = compliance * sigma;
            properties[Property::stress_zz]          = sigma[2][2];
            properties[Property::elastic_strain]     = eps[0][0];
            properties[Property::elastic_strain + 1] = eps[1][1];
            properties[Property::elastic_strain + 2] = eps[2][2];
            properties[Property::elastic_strain + 3] = eps[0][1];
          }
      }
  }



  types::particle_index
  MaterialPoints::remove_points(
    const std::function<bool(const Point<2> &)> &inside)
  {
    std::vector<Particles::ParticleHandler<2>::particle_iterator> removed;
    for (auto particle = particles.begin(); particle != particles.end();
         ++particle)
      if (particle->get_properties()[Property::volume] > 0 &&
          inside(particle->get_location()))
        removed.push_back(particle);
    const types::particle_index n =
      Utilities::MPI::sum<types::particle_index>(removed.size(),
                                                 grid.mpi_communicator());
    particles.remove_particles(removed);
    particles.update_cached_numbers();
    n_material_points -= n;
    neighbourhood_current = false;
    find_material_cells();
    return n;
  }



  void
  MaterialPoints::reset_displacements()
  {
    for (auto &particle : particles)
      {
        const ArrayView<double> properties     = particle.get_properties();
        properties[Property::displacement]     = 0;
        properties[Property::displacement + 1] = 0;
      }
    record_tracked_points();
  }



  bool
  MaterialPoints::holds_material(
    const DoFHandler<2>::active_cell_iterator &cell) const
  {
    for (const auto &particle : particles.particles_in_cell(cell))
      if (particle.get_properties()[Property::volume] > 0)
        return true;
    return false;
  }



  Q1CellKernel::LocalVector
  MaterialPoints::cell_increment(
    const DoFHandler<2>::active_cell_iterator        &cell,
    const LinearAlgebra::distributed::Vector<double> &increment,
    const LinearAlgebra::distributed::Vector<double> *prescribed,
    std::vector<types::global_dof_index>             &dof_indices)
  {
    cell->get_dof_indices(dof_indices);
    Q1CellKernel::LocalVector d;
    for (unsigned int i = 0; i < Q1CellKernel::dofs_per_cell; ++i)
      d[i] = increment(dof_indices[i]) +
             (prescribed ? (*prescribed)(dof_indices[i]) : 0.);
    return d;
  }



  std::vector<std::string>
  MaterialPoints::property_names(const unsigned int n_properties)
  {
    std::vector<std::string> names{"volume",
                                   "stress_xx",
                                   "stress_yy",
                                   "stress_xy",
                                   "strain_xx",
                                   "strain_yy",
                                   "strain_xy",
                                   "displacement",
                                   "displacement",
                                   "initial_position",
                                   "initial_position",
                                   "d_function"};
    if (n_properties == Property::n_properties_inelastic)
      for (const char *name : {"elastic_strain_xx",
                               "elastic_strain_yy",
                               "elastic_strain_zz",
                               "elastic_strain_xy",
                               "equivalent_plastic_strain",
                               "stress_zz",
                               "yielded",
                               "quadrature_weight",
                               "F_xx",
                               "F_xy",
                               "F_yx",
                               "F_yy",
                               "det_F",
                               "body"})
        names.emplace_back(name);
    return names;
  }
} // namespace bsmpm
