#include <bsmpm/points/move_diagnosis.h>

#include <sstream>

namespace bsmpm
{
  std::string
  MoveDiagnosis::message(const MaterialPoints::MoveReport &report,
                         const unsigned int                step,
                         const BackgroundGrid             &grid,
                         const double                      quality_threshold,
                         const bool                        stabilised)
  {
    return std::to_string(report.n_left_grid) +
           " material point(s) left the background grid "
           "in load step " +
           std::to_string(step) + ", one of them to " +
           [&] {
             std::ostringstream p;
             p.precision(6);
             p << '(' << report.example[0] << ", " << report.example[1]
               << "). ";
             return p.str();
           }() +
           cause(report, grid, quality_threshold, stabilised) +
           " The output of the previous step is intact.";
  }



  std::string
  MoveDiagnosis::cause(const MaterialPoints::MoveReport &report,
                       const BackgroundGrid             &grid,
                       const double                      quality_threshold,
                       const bool                        stabilised)
  {
    std::ostringstream cause;
    cause.precision(3);
    const double h = grid.min_cell_size();
    if (report.n_non_finite > 0)
      cause << "The displacements of " << report.n_non_finite
            << " point(s) are not finite (NaN or inf): a parameter or an "
               "expression of the scene gives a non-finite value.";
    else if (report.example_quality >= 0 &&
             report.example_quality < quality_threshold)
      cause << "The point came from a poorly filled cell (support quality "
            << report.example_quality << ", below the stabilisation threshold "
            << quality_threshold
            << "): its material holds the cell's DoFs by almost nothing. "
            << (stabilised ?
                  "Raise Ghost penalty/Penalty, or use more points per cell." :
                  "Enable the stabilisation (Ghost penalty/Enable = true).");
    else if (report.max_increment >
             100 * grid.lower_left().distance(grid.upper_right()))
      cause << "The loads are far too large for the material: the largest "
               "displacement increment of a point is "
            << report.max_increment
            << " m, far beyond the grid. Check the magnitudes of the loads "
               "(tractions, pressure, density and gravity) against the "
               "moduli.";
    else if (report.max_increment > 0.5 * h)
      cause << "The load step is too large: the largest displacement "
               "increment of a point is "
            << report.max_increment << " m, " << report.max_increment / h
            << " cells, where small-strain MPM needs increments well below "
               "a cell. Use more load steps (Loading/Load steps).";
    else
      cause << "The body reaches the edge of the grid: enlarge the grid "
               "(Background grid).";
    return cause.str();
  }
} // namespace bsmpm
