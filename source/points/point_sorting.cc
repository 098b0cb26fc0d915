#include <deal.II/base/mpi.h>

#include <bsmpm/points/point_sorting.h>

#include <algorithm>
#include <array>
#include <map>
#include <vector>

namespace bsmpm
{
  namespace
  {
    /** Buffers kept from one sort to the next, so that their memory is
     * allocated (and first touched) once. */
    struct Buffers
    {
      std::vector<Particles::ParticleIterator<2>> left_cell;
      /** Records of the points that moved to another own cell, and the
       * position of that cell in BackgroundGrid::locally_owned_cells(). */
      std::vector<double>                         records;
      std::vector<unsigned int>                   positions;
      std::vector<unsigned int>                   count, order;
      std::map<unsigned int, std::vector<double>> to_send;
    };
    Buffers buffers;

    /** Writes the record of @p particle at @p x to @p record: x, y, id
     * and the properties. */
    void
    write(double                               *record,
          const Particles::ParticleIterator<2> &particle,
          const Point<2>                       &x)
    {
      record[0]             = x[0];
      record[1]             = x[1];
      record[2]             = static_cast<double>(particle->get_id());
      const auto properties = particle->get_properties();
      std::copy(properties.begin(), properties.end(), record + 3);
    }
  } // namespace



  PointSortReport
  sort_into_cells(Particles::ParticleHandler<2> &particles,
                  const BackgroundGrid          &grid)
  {
    PointSortReport    report;
    const unsigned int n_properties = particles.n_properties_per_particle();
    const unsigned int record       = 3 + n_properties;
    const Point<2>     corner       = grid.lower_left();
    const Tensor<1, 2> h            = grid.cell_size();
    const auto        &owned        = grid.locally_owned_cells();
    auto              &left_cell    = buffers.left_cell;
    auto              &records      = buffers.records;
    auto              &positions    = buffers.positions;
    auto              &to_send      = buffers.to_send;
    records.clear();
    positions.clear();
    for (auto &[rank, data] : to_send)
      data.clear();

    // Inserts the point of the record @p data into the own cell at
    // @p position in the list of own cells.
    const auto insert = [&](const double *data, const unsigned int position) {
      const Point<2> x(data[0], data[1]);
      particles.insert_particle(
        x,
        grid.local_coordinates(x, owned[position].second),
        static_cast<types::particle_index>(data[2]),
        owned[position].first,
        ArrayView<const double>(data + 3, n_properties));
    };

    // 1. One pass over the points of the own cells: those still in their
    // cell get their reference location; those that left it are copied out
    // (for another own cell, or for the process that owns theirs) and
    // removed, from the back of the cell so that the indices of the ones
    // still to be removed stay valid.
    for (const auto &[cell, ij] : owned)
      {
        if (particles.n_particles_in_cell(cell) == 0)
          continue;
        left_cell.clear();
        const auto range = particles.particles_in_cell(cell);
        for (auto particle = range.begin(); particle != range.end(); ++particle)
          {
            const Point<2> &x = particle->get_location();
            // As BackgroundGrid::local_coordinates(), to the last bit.
            const Point<2> s((x[0] - corner[0]) / h[0] - ij[0],
                             (x[1] - corner[1]) / h[1] - ij[1]);
            if (s[0] >= 0. && s[0] <= 1. && s[1] >= 0. && s[1] <= 1.)
              particle->set_reference_location(s);
            else
              left_cell.push_back(particle);
          }
        if (left_cell.empty())
          continue;

        report.n_moved += left_cell.size();
        for (const auto &particle : left_cell)
          {
            const Point<2> x = particle->get_location();
            if (!grid.contains(x))
              {
                ++report.n_lost;
                continue;
              }
            const auto         target   = grid.cell_index(x);
            const unsigned int position = grid.owned_position(target);
            auto              &out = position != numbers::invalid_unsigned_int ?
                                       records :
                                       to_send[grid.owner(target)];
            out.resize(out.size() + record);
            write(out.data() + out.size() - record, particle, x);
            if (position != numbers::invalid_unsigned_int)
              positions.push_back(position);
            else
              ++report.n_sent;
          }
        for (auto particle = left_cell.rbegin(); particle != left_cell.rend();
             ++particle)
          particles.remove_particle(*particle);
      }

    // 2. The points that changed cell here, inserted cell by cell from the
    // last own cell to the first (a counting sort, stable): the memory that
    // the removals freed is handed out last-freed first, so the points
    // entering a cell take the places of those that left it and the
    // points of a cell stay together in memory.
    auto &count = buffers.count;
    auto &order = buffers.order;
    count.assign(owned.size() + 1, 0);
    for (const unsigned int position : positions)
      ++count[owned.size() - 1 - position];
    for (std::size_t c = 1; c < count.size(); ++c)
      count[c] += count[c - 1];
    order.resize(positions.size());
    for (std::size_t k = positions.size(); k-- > 0;)
      order[--count[owned.size() - 1 - positions[k]]] = k;
    for (const unsigned int k : order)
      insert(records.data() + std::size_t(k) * record, positions[k]);

    // 3. The points that entered other processes' cells go there.
    if (Utilities::MPI::n_mpi_processes(grid.mpi_communicator()) > 1)
      {
        std::map<unsigned int, std::vector<double>> non_empty;
        for (auto &[rank, data] : to_send)
          if (!data.empty())
            non_empty[rank].swap(data);
        const auto received =
          Utilities::MPI::some_to_some(grid.mpi_communicator(), non_empty);
        for (auto &[rank, data] : non_empty)
          to_send[rank].swap(data);
        for (const auto &[rank, data] : received)
          {
            (void)rank;
            AssertThrow(data.size() % record == 0, ExcInternalError());
            for (std::size_t k = 0; k < data.size(); k += record)
              {
                const unsigned int position = grid.owned_position(
                  grid.cell_index(Point<2>(data[k], data[k + 1])));
                AssertThrow(position != numbers::invalid_unsigned_int,
                            ExcMessage("A material point was sent to a "
                                       "process that does not own its "
                                       "cell."));
                insert(data.data() + k, position);
                ++report.n_received;
              }
          }
      }

    // Numbers of points and the order of the cells' entries (collective).
    particles.update_cached_numbers();
    return report;
  }
} // namespace bsmpm
