// sort_into_cells() (point_sorting.h) moves material points between cells
// and processes: 2304 points on a 16 x 16 grid are displaced in five steps
// by up to 2.6 cells per step (u = A sin(pi x) sin(pi y) (cos t, sin t),
// which keeps them in the grid): beyond the ghost layer, into cells that
// the sending process does not know. After every sort:
// - no point is lost and none is duplicated (ids over all processes);
// - every point lies in the closed cell that holds it, which is locally
//   owned, and its reference location is its position in that cell;
// - its properties travelled with it (they encode its id);
// - how many points changed cell, and a checksum of (id, cell index) over
//   all points: the same for every number of processes, so that the output
//   of mpirun = 4 is that of the serial run.

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <bsmpm/geometry/background_grid.h>
#include <bsmpm/geometry/body_region.h>
#include <bsmpm/points/material_point_layout.h>
#include <bsmpm/points/material_points.h>
#include <bsmpm/points/point_sorting.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

// tests.h uses deallog unqualified: the using directive must come first.
using namespace dealii;

#include "../tests.h"

#include "../unit_test.h"

using namespace bsmpm;

BSMPM_UNIT_TEST("points/point_sorting")
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const MPI_Comm                   comm = MPI_COMM_WORLD;
  if (Utilities::MPI::this_mpi_process(comm) == 0)
    initlog();

  ParameterHandler    prm;
  BackgroundGrid      grid(comm);
  BodyRegion          region;
  MaterialPointLayout layout;
  BackgroundGrid::declare_parameters(prm);
  BodyRegion::declare_parameters(prm);
  MaterialPointLayout::declare_parameters(prm);
  prm.parse_input_from_string("subsection Background grid\n"
                              "  set Upper right corner = 1, 1\n"
                              "  set Cells per direction = 16, 16\n"
                              "end\n"
                              "subsection Body region\n"
                              "  set Shape = rectangle\n"
                              "  set Upper right corner = 1, 1\n"
                              "end\n"
                              "subsection Material points\n"
                              "  set Layout = per cell\n"
                              "  set Points per cell = 3\n"
                              "end\n");
  grid.parse_parameters(prm);
  region.parse_parameters(prm);
  layout.parse_parameters(prm);
  grid.create();
  MaterialPoints points(grid);
  points.generate(layout, region);
  auto              &particles    = points.particle_handler();
  const unsigned int n_properties = particles.n_properties_per_particle();
  for (auto &particle : particles)
    {
      auto properties = particle.get_properties();
      for (unsigned int k = 0; k < n_properties; ++k)
        properties[k] = particle.get_id() + 0.01 * k;
    }
  const types::particle_index n_points = particles.n_global_particles();
  deallog << "points: " << n_points << std::endl;

  const double h = grid.cell_size()[0];
  for (unsigned int step = 1; step <= 5; ++step)
    {
      const double       amplitude = 2.6 * h * (step % 2 ? 1 : -0.7);
      const Tensor<1, 2> direction(
        {std::cos(1.3 * step), std::sin(1.3 * step)});
      for (auto &particle : particles)
        {
          const Point<2> x = particle.get_location();
          particle.set_location(x + amplitude * std::sin(M_PI * x[0]) *
                                      std::sin(M_PI * x[1]) * direction);
        }
      const PointSortReport report = sort_into_cells(particles, grid);

      bool                               placed = true, carried = true;
      std::vector<types::particle_index> ids;
      double                             checksum = 0;
      for (const auto &particle : particles)
        {
          const auto cell = particle.get_surrounding_cell();
          const auto ij   = grid.cell_index(cell->center());
          const auto s    = grid.local_coordinates(particle.get_location(), ij);
          placed          = placed && cell->is_locally_owned() && s[0] >= 0 &&
                   s[0] <= 1 && s[1] >= 0 && s[1] <= 1 &&
                   s.distance(particle.get_reference_location()) < 1e-14;
          const auto properties = particle.get_properties();
          for (unsigned int k = 0; k < n_properties; ++k)
            carried = carried && properties[k] == particle.get_id() + 0.01 * k;
          ids.push_back(particle.get_id());
          checksum += double(particle.get_id()) * (ij[0] + 1000. * ij[1]);
        }
      std::vector<types::particle_index> all_ids;
      for (const auto &part : Utilities::MPI::all_gather(comm, ids))
        all_ids.insert(all_ids.end(), part.begin(), part.end());
      std::sort(all_ids.begin(), all_ids.end());
      bool complete = all_ids.size() == n_points;
      for (std::size_t k = 0; complete && k < all_ids.size(); ++k)
        complete = all_ids[k] == k;

      deallog << "step " << step << ": changed cell "
              << Utilities::MPI::sum(report.n_moved, comm) << ", lost "
              << Utilities::MPI::sum(report.n_lost, comm)
              << ", every point once: "
              << yes_no(complete && particles.n_global_particles() == n_points)
              << ", in its cell: "
              << yes_no(Utilities::MPI::min(placed ? 1 : 0, comm) == 1)
              << ", properties carried: "
              << yes_no(Utilities::MPI::min(carried ? 1 : 0, comm) == 1)
              << ", sent = received: "
              << yes_no(Utilities::MPI::sum(report.n_sent, comm) ==
                        Utilities::MPI::sum(report.n_received, comm))
              << ", checksum " << std::setprecision(12)
              << Utilities::MPI::sum(checksum, comm) << std::endl;
    }
}
