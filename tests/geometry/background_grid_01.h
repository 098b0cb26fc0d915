// BackgroundGrid::pulled_onto(): a point outside the grid's rectangle by
// less than the given fraction of a cell comes back onto its face (or
// corner), in each direction on its own; a point inside, or farther out,
// stays where it is. (Points inserted on a boundary curve whose segment
// bulges past a face of the grid go back this way.)
#ifndef bsmpm_tests_background_grid_01_h
#define bsmpm_tests_background_grid_01_h

#include <deal.II/base/parameter_handler.h>

#include <bsmpm/geometry/background_grid.h>

// tests.h uses deallog unqualified: the using directive must come first.
using namespace dealii;

#include "../tests.h"

using namespace bsmpm;

namespace background_grid_01
{
  void
  run()
  {
    ParameterHandler prm;
    BackgroundGrid   grid(MPI_COMM_WORLD);
    BackgroundGrid::declare_parameters(prm);
    // Cells of 0.5 x 0.25: a tenth of a cell is 0.05 in x, 0.025 in y.
    prm.parse_input_from_string("subsection Background grid\n"
                                "  set Lower left corner = 0, 0\n"
                                "  set Upper right corner = 4, 3\n"
                                "  set Cells per direction = 8, 12\n"
                                "end\n");
    grid.parse_parameters(prm);
    grid.create();
    for (const Point<2> &p : {Point<2>(2, 1),        // inside
                              Point<2>(4, 1),        // on the right face
                              Point<2>(4.049, 1),    // just beyond it
                              Point<2>(4.051, 1),    // too far
                              Point<2>(-0.049, 1),   // beyond the left face
                              Point<2>(2, 3.024),    // beyond the top
                              Point<2>(2, 3.026),    // too far (y's cell)
                              Point<2>(2, -0.02),    // beyond the bottom
                              Point<2>(4.03, 3.02),  // beyond a corner
                              Point<2>(4.03, 3.03)}) // x back, y too far
      {
        const Point<2> q = grid.pulled_onto(p, 0.1);
        deallog << p << " -> " << q << (grid.contains(q) ? "" : " (outside)")
                << std::endl;
      }
  }
} // namespace background_grid_01

#endif
