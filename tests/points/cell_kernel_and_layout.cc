// The Q1 cell kernel and the layout of material points: one compiled
// test, whose parts are the numbered files it includes.

#include "../unit_test.h"
#include "material_point_layout_01.h"
#include "q1_cell_kernel_01.h"

BSMPM_UNIT_TEST("points/cell_kernel_and_layout")
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  initlog();
  deallog << std::setprecision(8);
  deallog.push("q1_cell_kernel_01");
  q1_cell_kernel_01::run();
  deallog.pop();
  deallog << std::setprecision(8);
  deallog.push("material_point_layout_01");
  material_point_layout_01::run();
  deallog.pop();
}
