#ifndef bsmpm_point_sorting_h
#define bsmpm_point_sorting_h

#include <deal.II/particles/particle_handler.h>

#include <bsmpm/geometry/background_grid.h>

namespace bsmpm
{
  using namespace dealii;

  /** What one call of sort_into_cells() did on this process. */
  struct PointSortReport
  {
    /** Points that left their cell (on this process, before the exchange). */
    types::particle_index n_moved = 0;
    /** Of those, the points sent to other processes. */
    types::particle_index n_sent = 0;
    /** Points received from other processes. */
    types::particle_index n_received = 0;
    /** Points outside the grid, removed. */
    types::particle_index n_lost = 0;
  };

  /**
   * Sorts the locally owned particles of @p particles into the cells of the
   * uniform grid @p grid after they moved, and ships those that entered a
   * cell of another process to it: the work of deal.II's
   * ParticleHandler::sort_particles_into_subdomains_and_cells(), by
   * arithmetic instead of a search.
   *
   * A particle still inside its cell (closed, as deal.II counts it) stays
   * and gets its reference location from its position; only the particles
   * that left it are removed and inserted again, into the cell that
   * BackgroundGrid::cell_index() gives, here or on the process that owns
   * that cell (any cell of the grid, not only ghost cells). Particles
   * outside the grid are removed and counted. Collective.
   *
   * Unlike deal.II's sort this leaves the memory of the particles where it
   * is (no copy of every particle per call), and it costs one pass over the
   * particles plus a constant per particle that changed cell.
   */
  PointSortReport
  sort_into_cells(Particles::ParticleHandler<2> &particles,
                  const BackgroundGrid          &grid);
} // namespace bsmpm

#endif
