#include <deal.II/base/function.h>
#include <deal.II/base/mpi.h>

#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/fe_q.h>

#include <deal.II/grid/grid_generator.h>

#include <deal.II/numerics/vector_tools.h>

#include <bsmpm/base/parameter_tools.h>
#include <bsmpm/geometry/background_grid.h>

#include <cmath>
#include <iomanip>
#include <sstream>

namespace bsmpm
{
  namespace
  {
    const char *face_names[4] = {"Left", "Right", "Bottom", "Top"};
  }



  BackgroundGrid::BackgroundGrid(const MPI_Comm communicator)
    : communicator(communicator)
    , tria(communicator)
    , finite_element(FE_Q<2>(1), 2)
    , dofs(tria)
  {
    face_conditions.fill(FaceCondition::free);
  }



  void
  BackgroundGrid::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Background grid");
    prm.declare_entry("Lower left corner",
                      "0, 0",
                      ParameterTools::point_pattern(),
                      "Lower left corner of the rectangular grid, in m.");
    prm.declare_entry("Upper right corner",
                      "1, 1",
                      ParameterTools::point_pattern(),
                      "Upper right corner of the rectangular grid, in m.");
    prm.declare_entry("Cells per direction",
                      "2, 2",
                      Patterns::List(Patterns::Integer(1), 2, 2, ","),
                      "Number of cells in x and y. Ignored when 'Cell size' "
                      "is positive.");
    prm.declare_entry("Cell size",
                      "0",
                      Patterns::Double(0.),
                      "Side length h of the square cells, in m; it must "
                      "divide both sides of the rectangle. 0 means: use "
                      "'Cells per direction'.");
    prm.enter_subsection("Face conditions");
    for (const char *face : face_names)
      prm.declare_entry(face,
                        "free",
                        Patterns::Selection("free|fixed|roller"),
                        std::string("Support on the ") + face +
                          " face of the grid: free, fixed (both components "
                          "zero) or roller (normal component zero).");
    prm.leave_subsection();
    prm.leave_subsection();
  }



  void
  BackgroundGrid::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Background grid");
    corner_lower = ParameterTools::get_point(prm, "Lower left corner");
    corner_upper = ParameterTools::get_point(prm, "Upper right corner");
    AssertThrow(corner_upper[0] > corner_lower[0] &&
                  corner_upper[1] > corner_lower[1],
                ExcMessage("Background grid: the upper right corner must lie "
                           "above and to the right of the lower left corner."));
    for (unsigned int d = 0; d < 2; ++d)
      ParameterTools::require_finite(corner_upper[d] - corner_lower[d],
                                     "Background grid: the side of the grid "
                                     "in direction " +
                                       std::to_string(d));
    const double cell_length = prm.get_double("Cell size");
    if (cell_length > 0)
      for (unsigned int d = 0; d < 2; ++d)
        {
          const double n = (corner_upper[d] - corner_lower[d]) / cell_length;
          // Cells are counted in unsigned int: refuse what it cannot hold
          // before the conversion (InputChecks refuses more than 2e9 cells
          // in all).
          if (!(n <= 2e9))
            {
              std::ostringstream message;
              message << std::setprecision(3) << "Background grid: the cell "
                      << "size " << cell_length << " gives " << n
                      << " cells in direction " << d
                      << ", beyond what bsmpm can index (2e9 cells). Use a "
                         "larger cell size.";
              AssertThrow(false, ExcMessage(message.str()));
            }
          AssertThrow(std::abs(n - std::round(n)) < 1e-8 * n && n >= 1,
                      ExcMessage("Background grid: the cell size " +
                                 std::to_string(cell_length) +
                                 " does not divide the side of the grid in "
                                 "direction " +
                                 std::to_string(d) + "."));
          cells[d] = static_cast<unsigned int>(std::round(n));
        }
    else
      {
        const auto n = ParameterTools::get_unsigned(prm, "Cells per direction");
        cells        = {{n[0], n[1]}};
      }
    for (unsigned int d = 0; d < 2; ++d)
      h[d] = (corner_upper[d] - corner_lower[d]) / cells[d];

    prm.enter_subsection("Face conditions");
    for (unsigned int f = 0; f < 4; ++f)
      {
        const std::string value = prm.get(face_names[f]);
        face_conditions[f] =
          value == "fixed" ?
            FaceCondition::fixed :
            (value == "roller" ? FaceCondition::roller : FaceCondition::free);
      }
    prm.leave_subsection();
    prm.leave_subsection();
  }



  void
  BackgroundGrid::create(const std::string &saved_triangulation)
  {
    // Coarse cells are trees in p4est: make as few as the refinement of a
    // coarser rectangle allows, since refinement is cheaper than many trees.
    unsigned int                refinements = 0;
    std::array<unsigned int, 2> coarse      = cells;
    while (coarse[0] % 2 == 0 && coarse[1] % 2 == 0 && refinements < 20)
      {
        coarse[0] /= 2;
        coarse[1] /= 2;
        ++refinements;
      }

    tria.clear();
    GridGenerator::subdivided_hyper_rectangle(
      tria,
      std::vector<unsigned int>{coarse[0], coarse[1]},
      corner_lower,
      corner_upper,
      /*colorize=*/true);
    if (saved_triangulation.empty())
      tria.refine_global(refinements);
    else
      try
        {
          tria.load(saved_triangulation);
        }
      catch (const ExceptionBase &e)
        {
          // deal.II's message names neither the files nor the checkpoint.
          std::ostringstream message;
          e.print_info(message);
          std::string text = Utilities::trim(message.str());
          text             = text.substr(0, text.find('\n'));
          AssertThrow(false,
                      ExcMessage("Checkpoint: the grid saved in '" +
                                 saved_triangulation +
                                 "' (and its .info and _fixed.data files) "
                                 "cannot be read: the checkpoint is "
                                 "incomplete or damaged (" +
                                 text + ")"));
        }

    dofs.distribute_dofs(finite_element);
    owned_dofs = dofs.locally_owned_dofs();
    DoFTools::extract_locally_relevant_dofs(dofs, relevant_dofs);

    owned_cell_lookup.assign(std::size_t(cells[0]) * cells[1], dofs.end());
    // Owners of all cells: each process enters its own, the maximum over
    // the processes fills the table (4 bytes per cell).
    cell_owners.assign(std::size_t(cells[0]) * cells[1], 0);
    owned_positions.assign(std::size_t(cells[0]) * cells[1],
                           numbers::invalid_unsigned_int);
    owned_cells.clear();
    const types::subdomain_id rank =
      Utilities::MPI::this_mpi_process(communicator);
    for (const auto &cell : dofs.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          const auto ij                               = cell_index(cell);
          owned_cell_lookup[ij[1] * cells[0] + ij[0]] = cell;
          cell_owners[ij[1] * cells[0] + ij[0]]       = rank;
          owned_positions[ij[1] * cells[0] + ij[0]]   = owned_cells.size();
          owned_cells.emplace_back(cell, ij);
        }
    if (Utilities::MPI::n_mpi_processes(communicator) > 1)
      Utilities::MPI::max(cell_owners, communicator, cell_owners);
  }



  bool
  BackgroundGrid::contains(const Point<2> &p) const
  {
    return p[0] >= corner_lower[0] && p[0] <= corner_upper[0] &&
           p[1] >= corner_lower[1] && p[1] <= corner_upper[1];
  }



  Point<2>
  BackgroundGrid::pulled_onto(Point<2> p, const double fraction) const
  {
    for (unsigned int d = 0; d < 2; ++d)
      {
        const double tolerance = fraction * h[d];
        if (p[d] < corner_lower[d] && p[d] > corner_lower[d] - tolerance)
          p[d] = corner_lower[d];
        if (p[d] > corner_upper[d] && p[d] < corner_upper[d] + tolerance)
          p[d] = corner_upper[d];
      }
    return p;
  }



  bool
  BackgroundGrid::has_face_conditions() const
  {
    for (const auto c : face_conditions)
      if (c != FaceCondition::free)
        return true;
    return false;
  }



  void
  BackgroundGrid::make_face_constraints(
    AffineConstraints<double> &constraints) const
  {
    // Boundary ids of a colorized rectangle: 0 left, 1 right, 2 bottom, 3 top.
    for (unsigned int face = 0; face < 4; ++face)
      {
        if (face_conditions[face] == FaceCondition::free)
          continue;
        const unsigned int normal_component = face / 2;
        ComponentMask      mask(2, true);
        if (face_conditions[face] == FaceCondition::roller)
          mask.set(1 - normal_component, false);
        VectorTools::interpolate_boundary_values(cartesian_mapping,
                                                 dofs,
                                                 face,
                                                 Functions::ZeroFunction<2>(2),
                                                 constraints,
                                                 mask);
      }
  }
} // namespace bsmpm
