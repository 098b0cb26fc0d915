// The B-spline curves, their cut by the grid's cells and the grid's
// rectangle: one compiled test, whose parts are the numbered files it
// includes.

#include "../unit_test.h"
#include "b_spline_curve_01.h"
#include "background_grid_01.h"
#include "curve_cell_intersection_01.h"

BSMPM_UNIT_TEST("geometry/b_spline_curves")
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  initlog();
  deallog << std::setprecision(8);
  deallog.push("b_spline_curve_01");
  b_spline_curve_01::run();
  deallog.pop();
  deallog << std::setprecision(8);
  deallog.push("curve_cell_intersection_01");
  curve_cell_intersection_01::run();
  deallog.pop();
  deallog << std::setprecision(8);
  deallog.push("background_grid_01");
  background_grid_01::run();
  deallog.pop();
}
