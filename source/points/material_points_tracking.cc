#include <deal.II/base/mpi.h>

#include <bsmpm/points/material_points.h>

#include <boost/archive/binary_iarchive.hpp>
#include <boost/archive/binary_oarchive.hpp>
#include <boost/serialization/utility.hpp>
#include <boost/serialization/vector.hpp>

#include <algorithm>
#include <map>
#include <set>
#include <sstream>

// MaterialPoints, part 3: the tracked points (the boundary curves' points),
// whose positions and states every process gathers, and the tracking points
// inserted and removed as the curves' points are respaced, and what a
// checkpoint keeps of them.

namespace bsmpm
{
  std::vector<Point<2>>
  MaterialPoints::locations(const std::vector<types::particle_index> &ids) const
  {
    std::map<types::particle_index, unsigned int> index;
    for (unsigned int k = 0; k < ids.size(); ++k)
      index.emplace(ids[k], k);
    std::vector<std::pair<unsigned int, Point<2>>> found;
    for (const auto &particle : particles)
      {
        const auto it = index.find(particle.get_id());
        if (it != index.end())
          found.emplace_back(it->second, particle.get_location());
      }
    std::vector<Point<2>> result(ids.size());
    for (const auto &part :
         Utilities::MPI::all_gather(grid.mpi_communicator(), found))
      for (const auto &[k, p] : part)
        result[k] = p;
    return result;
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
    std::array<double, 14> state{{double(slot),
                                  x[0],
                                  x[1],
                                  properties[Property::stress],
                                  properties[Property::stress + 1],
                                  properties[Property::stress + 2]}};
    state[11] = 1.; // det F
    state[12] = properties[Property::displacement];
    state[13] = properties[Property::displacement + 1];
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
                                 std::vector<TrackedState> *states,
                                 std::vector<Tensor<1, 2>> *displacements) const
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
    if (displacements != nullptr)
      displacements->assign(n_tracked_slots, Tensor<1, 2>());
    for (const auto &part : all)
      for (const auto &state : part)
        {
          const auto slot = static_cast<std::size_t>(state[0]);
          AssertThrow(slot < n_tracked_slots,
                      ExcMessage("A tracked boundary point was lost."));
          positions[slot] = Point<2>(state[1], state[2]);
          stresses[slot]  = Voigt({state[3], state[4], state[5]});
          if (states != nullptr)
            std::copy(state.begin() + 6,
                      state.begin() + 12,
                      (*states)[slot].begin());
          if (displacements != nullptr)
            (*displacements)[slot] = Tensor<1, 2>({state[12], state[13]});
        }
  }


  std::string
  MaterialPoints::tracking_state() const
  {
    std::ostringstream out;
    {
      boost::archive::binary_oarchive archive(out);
      archive << tracked_slots << n_tracked_slots << next_id;
    }
    return out.str();
  }



  void
  MaterialPoints::restore_tracking(const std::string &state)
  {
    std::istringstream in(state);
    {
      boost::archive::binary_iarchive archive(in);
      types::particle_index           saved_next_id = 0;
      archive >> tracked_slots >> n_tracked_slots >> saved_next_id;
      // The ids reserved at the set-up for bodies built later come before
      // the points inserted since.
      next_id = std::max(next_id, saved_next_id);
    }
    is_tracked.assign(next_id, false);
    for (const auto &[id, slot] : tracked_slots)
      is_tracked[id] = true;
    neighbourhood_current = false;
    record_tracked_points();
  }
} // namespace bsmpm
