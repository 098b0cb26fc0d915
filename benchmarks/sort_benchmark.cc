// Sorting material points into the cells of the uniform grid after they
// moved, two ways, on the same points moved the same way:
//
// deal.II: ParticleHandler::sort_particles_into_subdomains_and_cells() (a
//          search from the old cell through the cells around its nearest
//          vertex, a mapping for every point, a copy of every point into
//          iteration order, the exchange with the ghost owners);
// bsmpm:   bsmpm::sort_into_cells() (the cell by arithmetic, only the
//          points that left their cell removed and inserted again).
//
// Every step moves all points by u = a h sin(pi x) sin(pi y) (cos t, sin t),
// t = 2.4 k in step k (a of the command line, in cells; the field vanishes
// on the grid's edges, so no point leaves it), then both handlers sort. The
// time of moving the points (one pass that reads and writes every location)
// is printed as the floor of a pass over the points. After each step the
// two handlers must hold the same points (by id) in the same cells, with
// reference locations that agree to 1e-12; the program fails otherwise.
// Times are per step (wall, the slowest process), the first two steps
// apart (fresh memory), then the median of the rest.
//
// Usage: sort_benchmark [cells per direction] [points per direction]
//                       [steps] [amplitude in cells] [deal|bsmpm|both]
// Default: 128 8 8 0.25 both (1,048,576 points). With mpirun, both sorts
// exchange points between the processes.

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/timer.h>

#include <bsmpm/geometry/background_grid.h>
#include <bsmpm/geometry/body_region.h>
#include <bsmpm/points/material_point_layout.h>
#include <bsmpm/points/material_points.h>
#include <bsmpm/points/point_sorting.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <map>
#include <string>
#include <vector>

using namespace dealii;
using namespace bsmpm;

namespace
{
  double
  median(std::vector<double> v)
  {
    if (v.empty())
      return 0;
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
  }

  // Moves every point of @p particles by the step's field.
  void
  move(Particles::ParticleHandler<2> &particles,
       const double                   amplitude,
       const double                   angle)
  {
    const Tensor<1, 2> direction({std::cos(angle), std::sin(angle)});
    for (auto &particle : particles)
      {
        const Point<2> x = particle.get_location();
        particle.set_location(x + amplitude * std::sin(M_PI * x[0]) *
                                    std::sin(M_PI * x[1]) * direction);
      }
  }

  // Cell index and reference location of every locally owned point, by id.
  std::map<types::particle_index, std::pair<unsigned int, Point<2>>>
  state(const Particles::ParticleHandler<2> &particles)
  {
    std::map<types::particle_index, std::pair<unsigned int, Point<2>>> s;
    for (const auto &particle : particles)
      s[particle.get_id()] = {
        particle.get_surrounding_cell()->active_cell_index(),
        particle.get_reference_location()};
    return s;
  }
} // namespace



int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const MPI_Comm                   comm = MPI_COMM_WORLD;
  const unsigned int n_cells            = argc > 1 ? std::stoi(argv[1]) : 128;
  const unsigned int n_points           = argc > 2 ? std::stoi(argv[2]) : 8;
  const unsigned int n_steps            = argc > 3 ? std::stoi(argv[3]) : 8;
  const double       a                  = argc > 4 ? std::stod(argv[4]) : 0.25;
  const std::string  mode               = argc > 5 ? argv[5] : "both";
  const bool         root = Utilities::MPI::this_mpi_process(comm) == 0;

  ParameterHandler    prm;
  BackgroundGrid      grid(comm);
  BodyRegion          region;
  MaterialPointLayout layout;
  BackgroundGrid::declare_parameters(prm);
  BodyRegion::declare_parameters(prm);
  MaterialPointLayout::declare_parameters(prm);
  const std::string n = std::to_string(n_cells);
  prm.parse_input_from_string("subsection Background grid\n"
                              "  set Upper right corner = 1, 1\n"
                              "  set Cells per direction = " +
                              n + ", " + n +
                              "\n"
                              "end\n"
                              "subsection Body region\n"
                              "  set Shape = rectangle\n"
                              "  set Upper right corner = 1, 1\n"
                              "end\n"
                              "subsection Material points\n"
                              "  set Layout = per cell\n"
                              "  set Points per cell = " +
                              std::to_string(n_points) + "\nend\n");
  grid.parse_parameters(prm);
  region.parse_parameters(prm);
  layout.parse_parameters(prm);
  grid.create();

  const bool     run_deal = mode != "bsmpm", run_bsmpm = mode != "deal";
  MaterialPoints deal_points(grid), bsmpm_points(grid);
  if (run_deal)
    deal_points.generate(layout, region);
  if (run_bsmpm)
    bsmpm_points.generate(layout, region);
  auto        &deal  = deal_points.particle_handler();
  auto        &arith = bsmpm_points.particle_handler();
  const double h     = 1. / n_cells;

  if (root)
    std::cout << "sort_benchmark: " << n_cells << "^2 cells, " << n_points
              << "^2 points per cell ("
              << (run_deal ? deal : arith).n_global_particles()
              << " points), amplitude " << a << " cells, "
              << Utilities::MPI::n_mpi_processes(comm) << " process(es)\n"
              << " step  moved(%)  sent(%)   move(ms)  deal.II(ms)  "
                 "bsmpm(ms)\n";

  std::vector<double> t_move, t_deal, t_bsmpm;
  Timer               timer;
  bool                agree = true;
  for (unsigned int step = 0; step < n_steps; ++step)
    {
      const double    angle      = 2.4 * step;
      double          seconds[3] = {0, 0, 0};
      PointSortReport report;

      MPI_Barrier(comm);
      timer.restart();
      move(run_bsmpm ? arith : deal, a * h, angle);
      MPI_Barrier(comm);
      seconds[0] = timer.wall_time();
      if (run_bsmpm && run_deal)
        move(deal, a * h, angle);

      if (run_deal)
        {
          MPI_Barrier(comm);
          timer.restart();
          deal.sort_particles_into_subdomains_and_cells();
          MPI_Barrier(comm);
          seconds[1] = timer.wall_time();
        }
      if (run_bsmpm)
        {
          MPI_Barrier(comm);
          timer.restart();
          report = sort_into_cells(arith, grid);
          MPI_Barrier(comm);
          seconds[2] = timer.wall_time();
        }

      if (run_deal && run_bsmpm)
        {
          const auto s_deal = state(deal), s_bsmpm = state(arith);
          bool       same = s_deal.size() == s_bsmpm.size();
          for (auto p = s_deal.begin(), q = s_bsmpm.begin();
               same && p != s_deal.end();
               ++p, ++q)
            same = p->first == q->first && p->second.first == q->second.first &&
                   p->second.second.distance(q->second.second) < 1e-12;
          same = Utilities::MPI::min(same ? 1 : 0, comm) == 1 &&
                 deal.n_global_particles() == arith.n_global_particles();
          agree = agree && same;
        }

      const double moved = Utilities::MPI::sum(double(report.n_moved), comm);
      const double sent  = Utilities::MPI::sum(double(report.n_sent), comm);
      const double total =
        double((run_deal ? deal : arith).n_global_particles());
      if (root)
        std::cout << std::setw(5) << step << std::fixed << std::setprecision(2)
                  << std::setw(10) << 100 * moved / total << std::setw(9)
                  << 100 * sent / total << std::setprecision(1) << std::setw(11)
                  << 1e3 * seconds[0] << std::setw(13) << 1e3 * seconds[1]
                  << std::setw(11) << 1e3 * seconds[2] << '\n';
      if (step >= 2)
        {
          t_move.push_back(seconds[0]);
          t_deal.push_back(seconds[1]);
          t_bsmpm.push_back(seconds[2]);
        }
    }
  if (root)
    {
      std::cout << "median of steps 2..: move " << 1e3 * median(t_move)
                << " ms, deal.II sort " << 1e3 * median(t_deal)
                << " ms, bsmpm sort " << 1e3 * median(t_bsmpm) << " ms\n";
      if (run_deal && run_bsmpm)
        std::cout << (agree ? "both sorts agree on every point\n" :
                              "THE SORTS DISAGREE\n");
    }
  return agree ? 0 : 1;
}
