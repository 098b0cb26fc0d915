// Material points on a small background grid, set up through a
// ParameterHandler as a scene does it:
// - the volumes of the points of every layout sum to the exact area of the
//   body region (per cell over an aligned rectangle, lattice over a
//   rectangle, polar over annulus sectors), and the volume defect of the
//   per-cell layout over a rotated rectangle and a rectangle minus a disc;
// - the cell moments of the per-cell layout, and that zero-volume tracking
//   points do not enter them;
// - BodyRegion::contains for every shape;
// - errors: a point outside the grid, an empty region, the polar layout on a
//   region that is not an annulus sector.
#ifndef bsmpm_tests_material_point_layout_01_h
#define bsmpm_tests_material_point_layout_01_h

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <bsmpm/geometry/background_grid.h>
#include <bsmpm/geometry/body_region.h>
#include <bsmpm/points/material_point_layout.h>
#include <bsmpm/points/material_points.h>

#include <memory>
#include <string>

// tests.h uses deallog unqualified: the using directive must come first.
using namespace dealii;

#include "../tests.h"

using namespace bsmpm;

namespace material_point_layout_01
{
  namespace
  {
    // The grid [0, 4] x [0, 3] with 8 x 6 cells of size h = 0.5.
    const std::string grid_settings = "subsection Background grid\n"
                                      "  set Lower left corner = 0, 0\n"
                                      "  set Upper right corner = 4, 3\n"
                                      "  set Cells per direction = 8, 6\n"
                                      "end\n";

    // Grid, region, layout and material points of one parameter set.
    struct Setup
    {
      explicit Setup(const std::string &settings)
        : grid(MPI_COMM_WORLD)
      {
        BackgroundGrid::declare_parameters(prm);
        BodyRegion::declare_parameters(prm);
        MaterialPointLayout::declare_parameters(prm);
        prm.parse_input_from_string(grid_settings + settings);
        grid.parse_parameters(prm);
        region.parse_parameters(prm);
        layout.parse_parameters(prm);
        grid.create();
        points = std::make_unique<MaterialPoints>(grid);
      }

      void
      generate()
      {
        points->generate(layout, region);
      }

      ParameterHandler                prm;
      BackgroundGrid                  grid;
      BodyRegion                      region;
      MaterialPointLayout             layout;
      std::unique_ptr<MaterialPoints> points;
    };

    std::string
    region(const std::string &lines)
    {
      return "subsection Body region\n" + lines + "end\n";
    }

    std::string
    layout(const std::string &lines)
    {
      return "subsection Material points\n" + lines + "end\n";
    }

    // Generates the points and prints their number and the relative volume
    // error (as a yes/no against 1e-13 when @p exact).
    void
    check_volume(const std::string &name,
                 const std::string &settings,
                 const bool         exact)
    {
      Setup setup(settings);
      setup.generate();
      const double volume = setup.points->global_volume();
      const double area   = setup.region.area();
      const double defect = (volume - area) / area;
      deallog << name << ": " << setup.points->n_global_material_points()
              << " points, area " << area << ", ";
      if (exact)
        deallog << "relative volume error below 1e-13: "
                << yes_no(std::abs(defect) < 1e-13) << std::endl;
      else
        deallog << "relative volume defect " << defect << std::endl;

      // The cell moments hold the same volume.
      std::vector<CellMoments> moments;
      setup.points->compute_cell_moments(moments);
      double moment_volume = 0;
      for (const auto &m : moments)
        moment_volume += m.v;
      deallog << name << ": cell moments sum to the point volume: "
              << yes_no(std::abs(moment_volume - volume) < 1e-13 * volume)
              << std::endl;
    }



    void
    check_volumes()
    {
      deallog.push("volume");
      check_volume("per cell 3x3, aligned rectangle",
                   region("  set Shape = rectangle\n"
                          "  set Lower left corner = 0.5, 0.5\n"
                          "  set Upper right corner = 3.5, 2.5\n") +
                     layout("  set Layout = per cell\n"
                            "  set Points per cell = 3\n"),
                   true);
      check_volume("per cell 2x2, whole grid",
                   region("  set Shape = rectangle\n"
                          "  set Lower left corner = 0, 0\n"
                          "  set Upper right corner = 4, 3\n") +
                     layout("  set Layout = per cell\n"
                            "  set Points per cell = 2\n"),
                   true);
      check_volume("lattice 7x9, rectangle",
                   region("  set Shape = rectangle\n"
                          "  set Lower left corner = 0.3, 0.2\n"
                          "  set Upper right corner = 3.1, 2.9\n") +
                     layout("  set Layout = lattice\n"
                            "  set Lattice points = 7, 9\n"),
                   true);
      check_volume("lattice 40x30 over the grid, rectangle 2x1",
                   region("  set Shape = rectangle\n"
                          "  set Lower left corner = 1, 1\n"
                          "  set Upper right corner = 3, 2\n") +
                     layout("  set Layout = lattice\n"
                            "  set Lattice points = 40, 30\n"
                            "  set Lattice lower left corner = 0, 0\n"
                            "  set Lattice upper right corner = 4, 3\n"),
                   true);
      check_volume("polar 5x12, quarter annulus",
                   region("  set Shape = annulus sector\n"
                          "  set Center = 0, 0\n"
                          "  set Inner radius = 1\n"
                          "  set Outer radius = 2.5\n"
                          "  set Start angle = 0\n"
                          "  set End angle = 90\n") +
                     layout("  set Layout = polar\n"
                            "  set Polar points = 5, 12\n"),
                   true);
      check_volume("polar 3x17, annulus sector 30..300 degrees",
                   region("  set Shape = annulus sector\n"
                          "  set Center = 2, 1.5\n"
                          "  set Inner radius = 0.3\n"
                          "  set Outer radius = 1.2\n"
                          "  set Start angle = 30\n"
                          "  set End angle = 300\n") +
                     layout("  set Layout = polar\n"
                            "  set Polar points = 3, 17\n"),
                   true);
      for (const unsigned int n : {2, 4, 8})
        check_volume("per cell " + std::to_string(n) + "x" + std::to_string(n) +
                       ", rotated rectangle",
                     region("  set Shape = rotated rectangle\n"
                            "  set Center = 2, 1.5\n"
                            "  set Width = 2.4\n"
                            "  set Height = 1.2\n"
                            "  set Angle = 30\n") +
                       layout("  set Layout = per cell\n"
                              "  set Points per cell = " +
                              std::to_string(n) + "\n"),
                     false);
      for (const unsigned int n : {2, 8})
        {
          check_volume("per cell " + std::to_string(n) + "x" +
                         std::to_string(n) + ", rectangle minus quarter disc",
                       region("  set Shape = rectangle minus disc\n"
                              "  set Lower left corner = 0, 0\n"
                              "  set Upper right corner = 3, 3\n"
                              "  set Disc center = 0, 0\n"
                              "  set Disc radius = 1\n") +
                         layout("  set Layout = per cell\n"
                                "  set Points per cell = " +
                                std::to_string(n) + "\n"),
                       false);
          check_volume("per cell " + std::to_string(n) + "x" +
                         std::to_string(n) + ", rectangle minus whole disc",
                       region("  set Shape = rectangle minus disc\n"
                              "  set Lower left corner = 0.5, 0.5\n"
                              "  set Upper right corner = 3.5, 2.5\n"
                              "  set Disc center = 2, 1.5\n"
                              "  set Disc radius = 0.6\n") +
                         layout("  set Layout = per cell\n"
                                "  set Points per cell = " +
                                std::to_string(n) + "\n"),
                       false);
        }
      deallog.pop();
    }



    // Moments of the per-cell layout over full cells, and tracking points.
    void
    check_moments()
    {
      deallog.push("moments");
      Setup setup(region("  set Shape = rectangle\n"
                         "  set Lower left corner = 0.5, 0.5\n"
                         "  set Upper right corner = 3.5, 2.5\n") +
                  layout("  set Layout = per cell\n"
                         "  set Points per cell = 3\n"));
      setup.generate();
      std::vector<CellMoments> moments;
      setup.points->compute_cell_moments(moments);

      // A full cell: v = h^2, vs = vt = h^2/2, vss = vtt = h^2 * 35/108 (the
      // mean of s^2 over s = 1/6, 1/2, 5/6), vst = h^2/4.
      const double       A      = 0.25;
      unsigned int       n_full = 0, n_empty = 0, n_other = 0;
      const unsigned int n_cells = setup.grid.triangulation().n_active_cells();
      for (const auto &cell : setup.grid.dof_handler().active_cell_iterators())
        {
          const CellMoments &m = moments[cell->active_cell_index()];
          const Point<2>     c = cell->center();
          const bool         inside =
            c[0] > 0.5 && c[0] < 3.5 && c[1] > 0.5 && c[1] < 2.5;
          const bool full =
            std::abs(m.v - A) < 1e-15 && std::abs(m.vs - A / 2) < 1e-15 &&
            std::abs(m.vt - A / 2) < 1e-15 &&
            std::abs(m.vss - A * 35. / 108) < 1e-15 &&
            std::abs(m.vtt - A * 35. / 108) < 1e-15 &&
            std::abs(m.vst - A / 4) < 1e-15 && m.stress.norm() == 0;
          const bool empty = m.v == 0 && m.vs == 0 && m.vss == 0;
          if (inside && full)
            ++n_full;
          else if (!inside && empty)
            ++n_empty;
          else
            ++n_other;
        }
      deallog << n_cells << " cells: " << n_full
              << " full with the exact moments, " << n_empty << " empty, "
              << n_other << " wrong" << std::endl;

      // Zero-volume tracking points are particles but not material points.
      const auto n_before =
        setup.points->particle_handler().n_global_particles();
      const auto ids = setup.points->add_tracking_points(
        {Point<2>(1, 1), Point<2>(0.5, 2.5), Point<2>(4, 3)});
      std::vector<CellMoments> moments_after;
      setup.points->compute_cell_moments(moments_after);
      bool unchanged = true;
      for (unsigned int c = 0; c < moments.size(); ++c)
        unchanged = unchanged && moments[c].v == moments_after[c].v &&
                    moments[c].vs == moments_after[c].vs &&
                    moments[c].vst == moments_after[c].vst;
      deallog << "tracking points: ids " << ids[0] << ' ' << ids[1] << ' '
              << ids[2] << ", particles " << n_before << " -> "
              << setup.points->particle_handler().n_global_particles()
              << ", material points "
              << setup.points->n_global_material_points()
              << ", moments unchanged: " << yes_no(unchanged) << std::endl;

      // Reference locations are the local coordinates of the cell.
      double max_error = 0;
      for (const auto &particle : setup.points->particle_handler())
        {
          const Point<2> x  = particle.get_location();
          const Point<2> st = particle.get_reference_location();
          const auto     ij = setup.grid.cell_index(x);
          max_error         = std::max(max_error,
                               (setup.grid.cell_origin(ij) +
                                Tensor<1, 2>({st[0] * 0.5, st[1] * 0.5}) - x)
                                 .norm());
          const auto cell   = particle.get_surrounding_cell();
          max_error =
            std::max(max_error,
                     (cell->vertex(0) - setup.grid.cell_origin(ij)).norm());
        }
      deallog << "reference locations and cells agree with the grid: "
              << yes_no(max_error < 1e-15) << std::endl;
      deallog.pop();
    }



    // BodyRegion::contains.
    void
    check_contains()
    {
      deallog.push("contains");
      const auto check = [](const std::string           &name,
                            const std::string           &settings,
                            const std::vector<Point<2>> &points,
                            const std::vector<bool>     &expected) {
        Setup        setup(settings);
        unsigned int n_wrong = 0;
        deallog << name << ":";
        for (unsigned int i = 0; i < points.size(); ++i)
          {
            const bool inside = setup.region.contains(points[i]);
            deallog << ' ' << (inside ? "in" : "out");
            if (inside != expected[i])
              ++n_wrong;
          }
        deallog << (n_wrong == 0 ? ", as expected" : ", WRONG") << std::endl;
      };

      check("rectangle",
            region("  set Shape = rectangle\n"
                   "  set Lower left corner = 0.5, 0.5\n"
                   "  set Upper right corner = 3.5, 2.5\n"),
            {Point<2>(2, 1),
             Point<2>(0.5, 0.5),
             Point<2>(3.5, 2.5),
             Point<2>(3.6, 1),
             Point<2>(2, 2.5000001),
             Point<2>(0.4999999, 1)},
            {true, true, true, false, false, false});

      // Rotated rectangle: points given in its own frame (x', y').
      {
        const double c = std::cos(numbers::PI / 6),
                     s = std::sin(numbers::PI / 6);
        const auto at  = [&](const double x, const double y) {
          return Point<2>(2 + c * x - s * y, 1.5 + s * x + c * y);
        };
        check("rotated rectangle",
              region("  set Shape = rotated rectangle\n"
                     "  set Center = 2, 1.5\n"
                     "  set Width = 2.4\n"
                     "  set Height = 1.2\n"
                     "  set Angle = 30\n"),
              {at(0, 0),
               at(1.19, 0.59),
               at(-1.19, -0.59),
               at(1.21, 0),
               at(0, 0.61),
               at(-1.1, -0.65),
               Point<2>(3.19, 1.5),
               Point<2>(3.2, 2.1)},
              {true, true, true, false, false, false, true, false});
      }

      check("quarter annulus",
            region("  set Shape = annulus sector\n"
                   "  set Center = 0, 0\n"
                   "  set Inner radius = 1\n"
                   "  set Outer radius = 2.5\n"
                   "  set Start angle = 0\n"
                   "  set End angle = 90\n"),
            {Point<2>(1.5, 0.1),
             Point<2>(0.001, 1.5),
             Point<2>(0.5, 0.5),
             Point<2>(2, 2),
             Point<2>(-1, 1),
             Point<2>(1.5, -0.001),
             Point<2>(1, 0.0001)},
            {true, true, false, false, false, false, true});

      check("annulus sector -45..45 degrees (across angle 0)",
            region("  set Shape = annulus sector\n"
                   "  set Center = 2, 1.5\n"
                   "  set Inner radius = 0.3\n"
                   "  set Outer radius = 1.2\n"
                   "  set Start angle = -45\n"
                   "  set End angle = 45\n"),
            {Point<2>(2.5, 1.4),
             Point<2>(2.5, 1.6),
             Point<2>(1.5, 1.5),
             Point<2>(2.5, 0.9),
             Point<2>(2.5, 2.1)},
            {true, true, false, false, false});

      check("annulus sector 30..300 degrees (across 180)",
            region("  set Shape = annulus sector\n"
                   "  set Center = 2, 1.5\n"
                   "  set Inner radius = 0.3\n"
                   "  set Outer radius = 1.2\n"
                   "  set Start angle = 30\n"
                   "  set End angle = 300\n"),
            {Point<2>(1.5, 1.5),
             Point<2>(2, 2),
             Point<2>(2, 1),
             Point<2>(2.5, 1.5),
             Point<2>(2.5, 1.3),
             Point<2>(2.5, 1.8)},
            {true, true, true, false, false, true});

      check("rectangle minus quarter disc",
            region("  set Shape = rectangle minus disc\n"
                   "  set Lower left corner = 0, 0\n"
                   "  set Upper right corner = 3, 3\n"
                   "  set Disc center = 0, 0\n"
                   "  set Disc radius = 1\n"),
            {Point<2>(0.5, 0.5),
             Point<2>(1, 1),
             Point<2>(0.999, 0),
             Point<2>(1, 0),
             Point<2>(3, 3),
             Point<2>(3.001, 2)},
            {false, true, false, true, true, false});
      deallog.pop();
    }



    // Input that must fail, with the message it must give.
    void
    check_errors()
    {
      deallog.push("errors");
      const auto expect_throw = [](const std::string              &name,
                                   const std::string              &settings,
                                   const std::vector<std::string> &phrases) {
        bool        thrown = false;
        std::string message;
        try
          {
            Setup setup(settings);
            setup.generate();
          }
        catch (const ExceptionBase &e)
          {
            thrown  = true;
            message = e.what();
          }
        deallog << name << ": " << (thrown ? "thrown" : "NOT thrown");
        for (const auto &phrase : phrases)
          deallog << ", message contains \"" << phrase << "\": "
                  << yes_no(message.find(phrase) != std::string::npos);
        deallog << std::endl;
      };

      // Lattice points at x = 3.25, 3.75, 4.25, ...: point 2 is the first
      // outside the grid [0, 4] x [0, 3].
      expect_throw("lattice beyond the grid",
                   region("  set Shape = rectangle\n"
                          "  set Lower left corner = 3, 0\n"
                          "  set Upper right corner = 5, 1\n") +
                     layout("  set Layout = lattice\n"
                            "  set Lattice points = 4, 2\n"),
                   {"outside the background grid",
                    "Material point 2 at (4.25, 0.25)"});
      expect_throw("region between the points of a cell",
                   region("  set Shape = rectangle\n"
                          "  set Lower left corner = 0.01, 0.01\n"
                          "  set Upper right corner = 0.02, 0.02\n") +
                     layout("  set Layout = per cell\n"
                            "  set Points per cell = 2\n"),
                   {"holds no material point"});
      expect_throw("polar layout on a rectangle",
                   region("  set Shape = rectangle\n") +
                     layout("  set Layout = polar\n"),
                   {"annulus sector"});
      expect_throw("lattice rectangle of zero width",
                   region("  set Shape = rectangle\n") +
                     layout("  set Layout = lattice\n"
                            "  set Lattice lower left corner = 1, 0\n"
                            "  set Lattice upper right corner = 1, 1\n"),
                   {"lattice rectangle is empty"});
      deallog.pop();
    }
  } // namespace



  void
  run()
  {
    check_volumes();
    check_moments();
    check_contains();
    check_errors();
    deallog << "OK" << std::endl;
  }
} // namespace material_point_layout_01

#endif
