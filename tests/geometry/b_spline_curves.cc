// The B-spline curves and their cut by the grid's cells: one compiled
// test, whose parts are the numbered files it includes.

#include "../unit_test.h"
#include "b_spline_curve_01.h"
#include "curve_cell_intersection_01.h"

BSMPM_UNIT_TEST("geometry/b_spline_curves")
{
  initlog();
  deallog << std::setprecision(8);
  deallog.push("b_spline_curve_01");
  b_spline_curve_01::run();
  deallog.pop();
  deallog << std::setprecision(8);
  deallog.push("curve_cell_intersection_01");
  curve_cell_intersection_01::run();
  deallog.pop();
}
