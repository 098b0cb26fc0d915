#include <deal.II/base/mpi.h>

#include <bsmpm/points/material_points.h>
#include <bsmpm/points/point_sorting.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <sstream>

namespace bsmpm
{
  namespace
  {
    std::string
    format_point(const Point<2> &p)
    {
      std::ostringstream s;
      s << '(' << p[0] << ", " << p[1] << ')';
      return s.str();
    }
  } // namespace



  MaterialPoints::MaterialPoints(const BackgroundGrid &grid,
                                 const bool            inelastic_state)
    : grid(grid)
    , n_point_properties(inelastic_state ? Property::n_properties_inelastic :
                                           Property::n_properties)
  {}



  bool
  MaterialPoints::insert(const Point<2>             &position,
                         const double                volume,
                         const types::particle_index id)
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
      }
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
    // Each process creates the points of its own cells, with the index of
    // the layout's enumeration as id: unique and partition-independent.
    next_id = layout.n_candidates(grid);
    // Room for this process' share at once: growing the storage point by
    // point costs more than the insertion itself.
    const unsigned int n_cells = grid.n_cells(0) * grid.n_cells(1);
    particles.reserve(next_id / n_cells *
                      grid.triangulation().n_locally_owned_active_cells());
    types::particle_index n_here = 0;
    layout.for_each_point(
      grid,
      region,
      [this](const MaterialPointLayout::CellIndex &ij) {
        return grid.locally_owned_cell(ij) != grid.dof_handler().end();
      },
      [&](const Point<2> &p, const double volume, const unsigned long id) {
        if (!excluded || !excluded(p))
          n_here += insert(p, volume, id);
      });
    n_material_points = Utilities::MPI::sum(n_here, grid.mpi_communicator());
    AssertThrow(n_material_points > 0,
                ExcMessage("Material points: the body region holds no "
                           "material point of the chosen layout."));
    particles.update_cached_numbers();
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



  void
  MaterialPoints::compute_cell_moments(std::vector<CellMoments> &moments) const
  {
    moments.assign(grid.triangulation().n_active_cells(), CellMoments());
    for (const auto &cell : grid.triangulation().active_cell_iterators())
      if (cell->is_locally_owned())
        {
          CellMoments &m = moments[cell->active_cell_index()];
          for (const auto &particle : particles.particles_in_cell(cell))
            {
              const auto   props  = particle.get_properties();
              const double volume = props[Property::volume];
              if (volume == 0.)
                continue;
              m.add(particle.get_reference_location(),
                    volume,
                    Voigt({props[Property::stress],
                           props[Property::stress + 1],
                           props[Property::stress + 2]}));
            }
        }
  }



  MaterialPoints::MoveReport
  MaterialPoints::move(
    const Q1CellKernel                               &kernel,
    const LinearElasticMaterial                      &material,
    const LinearAlgebra::distributed::Vector<double> &increment,
    const LinearAlgebra::distributed::Vector<double> *prescribed,
    const std::vector<bool>                          *support_cells,
    const SupportFunction                            &support,
    const std::vector<double>                        *cell_quality,
    const bool                                        update_stress,
    const bool                                        update_strain,
    const std::vector<CellMoments>                   *cell_moments)
  {
    const Tensor<2, 3> &C = material.stiffness();
    MoveReport          report;
    bool                found_example           = false;
    double              max_displacement_square = 0;
    double              max_stress_square       = 0;
    double              max_increment_square    = 0;
    tracked_local.clear();
    neighbourhood_current = false;
    find_material_cells();

    std::vector<types::global_dof_index> dof_indices(
      Q1CellKernel::dofs_per_cell);
    Q1CellKernel::LocalVector d, da{}, total;
    // The grid's faces and the tolerance on them, read once: in the loop
    // the compiler cannot keep them in registers across the writes to the
    // points' properties (the same values and comparisons as
    // BackgroundGrid::contains()).
    const Point<2>     lower = grid.lower_left();
    const Point<2>     upper = grid.upper_right();
    const Tensor<1, 2> face_tolerance(
      {1e-6 * grid.cell_size()[0], 1e-6 * grid.cell_size()[1]});
    const auto in_grid = [&lower, &upper](const Point<2> &p) {
      return p[0] >= lower[0] && p[0] <= upper[0] && p[1] >= lower[1] &&
             p[1] <= upper[1];
    };
    const bool any_rigid_increments = !rigid_increments.empty();
    const bool any_tracked          = !is_tracked.empty();
    for (const auto &cell : grid.dof_handler().active_cell_iterators())
      {
        if (!cell->is_locally_owned() ||
            particles.n_particles_in_cell(cell) == 0)
          continue;
        cell->get_dof_indices(dof_indices);
        for (unsigned int i = 0; i < Q1CellKernel::dofs_per_cell; ++i)
          {
            d[i] = increment(dof_indices[i]);
            if (prescribed)
              da[i] = (*prescribed)(dof_indices[i]);
            total[i] = d[i] + da[i];
          }
        const auto e = kernel.strain_coefficients(total);
        const bool near_support =
          support_cells && (*support_cells)[cell->active_cell_index()];
        const bool has_material = holds_material(cell);
        // B-bar: the volumetric strain of the stress is that at the
        // centroid of the moments the cell's stiffness was made of.
        const bool b_bar =
          kernel.uses_b_bar() && cell_moments != nullptr && has_material;
        const Point<2> centroid =
          b_bar ?
            Q1CellKernel::centroid((*cell_moments)[cell->active_cell_index()]) :
            Point<2>();

        for (auto &particle : particles.particles_in_cell(cell))
          {
            const Point<2> st = particle.get_reference_location();
            Voigt          de = e[0] + st[0] * e[1] + st[1] * e[2];
            if (!has_material)
              de = boundary_strain(kernel, cell, st, increment, prescribed);
            const Voigt ds = b_bar ? kernel.stress(e, st, centroid) : C * de;
            auto        du = kernel.displacement(d, st);
            double      D  = 1;
            if (near_support)
              D = support(
                particle.get_location(),
                [&](const Point<2> &y) {
                  return kernel.displacement(
                    d, grid.local_coordinates(y, grid.cell_index(cell)));
                },
                du);
            if (prescribed)
              du += kernel.displacement(da, st);
            // A tracking point of a rigid body pushed along its normal (a
            // smooth footing) moves with the body, not with the soil that
            // slides along it (BoundaryCurve::rigid_support()).
            if (any_rigid_increments &&
                particle.get_properties()[Property::volume] == 0.)
              {
                const unsigned int slot = tracked_slot(particle.get_id());
                if (slot < rigid_increments.size() &&
                    rigid_increments[slot].first)
                  du = rigid_increments[slot].second;
              }

            // A point on a face of the grid (a curve that ends on a face's
            // support, as the footing's base at the symmetry line) stays in
            // the grid when the increment carries it out by no more than
            // the implicit boundary's inexactness (1e-9 .. 1e-7 h seen
            // where a support lies on a grid line); a real departure is
            // reported below. The position itself is set to the face:
            // adding the overshoot to the increment is lost to rounding
            // when the increment is much larger than the overshoot.
            Point<2> x = particle.get_location() + du;
            for (unsigned int k = 0; k < 2; ++k)
              {
                const double tolerance = face_tolerance[k];
                const double face =
                  x[k] < lower[k] && x[k] >= lower[k] - tolerance ? lower[k] :
                  x[k] > upper[k] && x[k] <= upper[k] + tolerance ? upper[k] :
                                                                    x[k];
                if (face != x[k])
                  {
                    x[k]  = face;
                    du[k] = face - particle.get_location()[k];
                  }
              }
            auto props                  = particle.get_properties();
            props[Property::d_function] = D;
            for (unsigned int r = 0; r < 3; ++r)
              {
                if (update_stress)
                  props[Property::stress + r] += ds[r];
                // Stored strain is the tensor component: eps_xy = gamma/2.
                if (update_strain)
                  props[Property::strain + r] += (r == 2 ? de[r] / 2 : de[r]);
              }
            props[Property::displacement] += du[0];
            props[Property::displacement + 1] += du[1];
            // Squares here, one square root after the loop: a square root
            // (and hypot's care for overflow) per point was a tenth of the
            // loop.
            if (props[Property::volume] > 0)
              {
                max_displacement_square =
                  std::max(max_displacement_square,
                           props[Property::displacement] *
                               props[Property::displacement] +
                             props[Property::displacement + 1] *
                               props[Property::displacement + 1]);
                max_stress_square =
                  std::max(max_stress_square,
                           props[Property::stress] * props[Property::stress] +
                             props[Property::stress + 1] *
                               props[Property::stress + 1] +
                             2 * props[Property::stress + 2] *
                               props[Property::stress + 2]);
              }

            const bool finite = std::isfinite(du[0]) && std::isfinite(du[1]);
            report.n_non_finite += !finite;
            if (finite && props[Property::volume] > 0)
              max_increment_square =
                std::max(max_increment_square, du.norm_square());
            if (!finite || !in_grid(x))
              {
                ++report.n_left_grid;
                if (!found_example)
                  {
                    report.example = x;
                    if (cell_quality)
                      report.example_quality =
                        (*cell_quality)[cell->active_cell_index()];
                  }
                found_example = true;
              }
            particle.set_location(x);
            if (any_tracked)
              record_if_tracked(particle.get_id(), x, props);
          }
      }

    // Make the report the same on every process.
    report.max_displacement =
      Utilities::MPI::max(std::sqrt(max_displacement_square),
                          grid.mpi_communicator());
    report.max_stress = Utilities::MPI::max(std::sqrt(max_stress_square),
                                            grid.mpi_communicator());
    report.n_left_grid =
      Utilities::MPI::sum(report.n_left_grid, grid.mpi_communicator());
    report.n_non_finite =
      Utilities::MPI::sum(report.n_non_finite, grid.mpi_communicator());
    report.max_increment = Utilities::MPI::max(std::sqrt(max_increment_square),
                                               grid.mpi_communicator());
    const unsigned int rank =
      Utilities::MPI::this_mpi_process(grid.mpi_communicator());
    const unsigned int reporter =
      Utilities::MPI::min(found_example ? rank : numbers::invalid_unsigned_int,
                          grid.mpi_communicator());
    if (reporter != numbers::invalid_unsigned_int)
      {
        report.example = Utilities::MPI::broadcast(grid.mpi_communicator(),
                                                   report.example,
                                                   reporter);
        report.example_quality =
          Utilities::MPI::broadcast(grid.mpi_communicator(),
                                    report.example_quality,
                                    reporter);
      }
    return report;
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
  MaterialPoints::track(const std::vector<types::particle_index> &ids)
  {
    is_tracked.assign(next_id, false);
    tracked_slots.clear();
    n_tracked_slots = ids.size();
    // From the last slot to the first: an id listed twice keeps its last.
    for (unsigned int slot = ids.size(); slot-- > 0;)
      {
        AssertThrow(ids[slot] < next_id,
                    ExcMessage("Tracked point id " + std::to_string(ids[slot]) +
                               " does not exist."));
        if (!is_tracked[ids[slot]])
          {
            is_tracked[ids[slot]] = true;
            tracked_slots.emplace_back(ids[slot], slot);
          }
      }
    std::sort(tracked_slots.begin(), tracked_slots.end());
    record_tracked_points();
  }



  void
  MaterialPoints::record_tracked_points()
  {
    tracked_local.clear();
    for (const auto &particle : particles)
      record_if_tracked(particle.get_id(),
                        particle.get_location(),
                        particle.get_properties());
  }



  std::vector<std::vector<double>>
  MaterialPoints::tracked_properties(
    const std::vector<unsigned int> &slots) const
  {
    // Slot -> its places in the request (a slot may be asked for twice).
    std::map<unsigned int, std::vector<unsigned int>> wanted;
    for (unsigned int i = 0; i < slots.size(); ++i)
      wanted[slots[i]].push_back(i);
    // (slot, properties...) of the wanted points this process owns.
    std::vector<double> local;
    for (const auto &particle : particles)
      {
        const unsigned int slot = tracked_slot(particle.get_id());
        if (slot == numbers::invalid_unsigned_int || wanted.count(slot) == 0)
          continue;
        local.push_back(slot);
        const auto props = particle.get_properties();
        local.insert(local.end(), props.begin(), props.end());
      }
    const auto all = Utilities::MPI::all_gather(grid.mpi_communicator(), local);
    std::vector<std::vector<double>> result(slots.size());
    const unsigned int               stride = n_point_properties + 1;
    for (const auto &part : all)
      for (std::size_t start = 0; start + stride <= part.size();
           start += stride)
        for (const unsigned int i :
             wanted[static_cast<unsigned int>(part[start])])
          result[i].assign(part.begin() + start + 1,
                           part.begin() + start + stride);
    for (unsigned int i = 0; i < slots.size(); ++i)
      AssertThrow(result[i].size() == n_point_properties,
                  ExcMessage("The tracked boundary point in slot " +
                             std::to_string(slots[i]) + " was lost."));
    return result;
  }



  std::vector<unsigned int>
  MaterialPoints::add_tracked_points(
    const std::vector<Point<2>>            &positions,
    const std::vector<std::vector<double>> &properties)
  {
    AssertThrow(positions.size() == properties.size(), ExcInternalError());
    neighbourhood_current = false;
    std::vector<unsigned int> slots;
    for (unsigned int i = 0; i < positions.size(); ++i)
      {
        const Point<2> &p = positions[i];
        AssertThrow(grid.contains(p),
                    ExcMessage("A boundary point inserted at " +
                               format_point(p) +
                               " lies outside the background grid."));
        AssertThrow(properties[i].size() == n_point_properties,
                    ExcInternalError());
        const types::particle_index id   = next_id++;
        const unsigned int          slot = n_tracked_slots++;
        slots.push_back(slot);
        is_tracked.resize(next_id, false);
        is_tracked[id] = true;
        // Ids grow, so the list stays sorted by id.
        tracked_slots.emplace_back(id, slot);
        const auto ij   = grid.cell_index(p);
        const auto cell = grid.locally_owned_cell(ij);
        if (cell == grid.dof_handler().end())
          continue;
        std::vector<double> props = properties[i];
        props[Property::volume]   = 0.;
        particles.insert_particle(p,
                                  grid.local_coordinates(p, ij),
                                  id,
                                  cell,
                                  ArrayView<const double>(props.data(),
                                                          props.size()));
      }
    particles.update_cached_numbers();
    record_tracked_points();
    return slots;
  }



  void
  MaterialPoints::remove_tracked_points(const std::vector<unsigned int> &slots)
  {
    neighbourhood_current = false;
    std::set<unsigned int> removed(slots.begin(), slots.end());
    std::vector<Particles::ParticleHandler<2>::particle_iterator> doomed;
    for (auto particle = particles.begin(); particle != particles.end();
         ++particle)
      if (removed.count(tracked_slot(particle->get_id())) > 0)
        doomed.push_back(particle);
    particles.remove_particles(doomed);
    for (auto &[id, slot] : tracked_slots)
      if (removed.count(slot) > 0)
        is_tracked[id] = false;
    tracked_slots.erase(std::remove_if(tracked_slots.begin(),
                                       tracked_slots.end(),
                                       [&](const auto &entry) {
                                         return removed.count(entry.second) > 0;
                                       }),
                        tracked_slots.end());
    particles.update_cached_numbers();
    record_tracked_points();
  }



  void
  MaterialPoints::record_if_tracked(const types::particle_index   id,
                                    const Point<2>               &x,
                                    const ArrayView<const double> properties)
  {
    const unsigned int slot = tracked_slot(id);
    if (slot == numbers::invalid_unsigned_int)
      return;
    std::array<double, 12> state{{double(slot),
                                  x[0],
                                  x[1],
                                  properties[Property::stress],
                                  properties[Property::stress + 1],
                                  properties[Property::stress + 2]}};
    state[11] = 1.; // det F
    if (properties.size() >= Property::n_properties_inelastic)
      {
        for (unsigned int k = 0; k < 4; ++k)
          state[6 + k] = properties[Property::elastic_strain + k];
        state[10] = properties[Property::plastic_strain];
        state[11] = properties[Property::det_F];
      }
    tracked_local.push_back(state);
  }



  void
  MaterialPoints::tracked_states(std::vector<Point<2>>     &positions,
                                 std::vector<Voigt>        &stresses,
                                 std::vector<TrackedState> *states) const
  {
    const auto all =
      Utilities::MPI::all_gather(grid.mpi_communicator(), tracked_local);
    std::size_t n = 0;
    for (const auto &part : all)
      n += part.size();
    AssertThrow(n == tracked_slots.size(),
                ExcMessage("A tracked boundary point was lost."));
    positions.assign(n_tracked_slots, Point<2>());
    stresses.assign(n_tracked_slots, Voigt());
    if (states != nullptr)
      states->assign(n_tracked_slots, TrackedState{{0., 0., 0., 0., 0., 1.}});
    for (const auto &part : all)
      for (const auto &state : part)
        {
          const auto slot = static_cast<std::size_t>(state[0]);
          AssertThrow(slot < n_tracked_slots,
                      ExcMessage("A tracked boundary point was lost."));
          positions[slot] = Point<2>(state[1], state[2]);
          stresses[slot]  = Voigt({state[3], state[4], state[5]});
          if (states != nullptr)
            std::copy(state.begin() + 6, state.end(), (*states)[slot].begin());
        }
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



  Voigt
  MaterialPoints::boundary_strain(
    const Q1CellKernel                               &kernel,
    const DoFHandler<2>::active_cell_iterator        &cell,
    const Point<2>                                   &st,
    const LinearAlgebra::distributed::Vector<double> &increment,
    const LinearAlgebra::distributed::Vector<double> *prescribed) const
  {
    const auto [source, where] = boundary_source(cell, st);
    std::vector<types::global_dof_index> dof_indices(
      Q1CellKernel::dofs_per_cell);
    const auto e = kernel.strain_coefficients(
      cell_increment(source, increment, prescribed, dof_indices));
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
    const auto [source, where] = boundary_source(cell, st);
    std::vector<types::global_dof_index> dof_indices(
      Q1CellKernel::dofs_per_cell);
    return kernel.gradient(
      cell_increment(source, increment, prescribed, dof_indices), where);
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
                               "det_F"})
        names.emplace_back(name);
    return names;
  }
} // namespace bsmpm
