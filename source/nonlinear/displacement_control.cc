#include <deal.II/base/mpi.h>

#include <bsmpm/base/parameter_tools.h>
#include <bsmpm/nonlinear/displacement_control.h>

#include <limits>

namespace bsmpm
{
  void
  DisplacementControl::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Loading");
    prm.declare_entry(
      "Control",
      "load",
      Patterns::Selection("load|displacement"),
      "load: step n applies load factor n / (Load steps) of the tractions and "
      "the body force (a run stops at a limit load, Limit load). "
      "displacement: the load factor is an unknown of every step, fixed by "
      "a displacement component that grows by 'Displacement increment' per "
      "step (Batoz and Dhatt 1979), so that a run follows the load past a "
      "peak or along a plateau; summary.json gives the load factor reached "
      "per step. In a staged scene it controls the last stage, the stages "
      "before it load controlled. Small strain, nonlinear material, no "
      "prescribed displacements, no checkpoints (doc/limit-loads.md).");
    prm.declare_entry("Control point",
                      "0, 0",
                      ParameterTools::point_pattern(),
                      "Control = displacement: the point (m) whose nearest "
                      "grid vertex controls. Choose one that stays inside "
                      "the body (a vertex that the body leaves has no "
                      "displacement).");
    prm.declare_entry("Control direction",
                      "0, -1",
                      ParameterTools::point_pattern(),
                      "Control = displacement: the direction c (normalised) "
                      "of the controlled component c . u (0, -1: "
                      "settlement).");
    prm.declare_entry("Displacement increment",
                      "0.001",
                      Patterns::Double(0),
                      "Control = displacement: growth of c . u per load "
                      "step, in m.");
    prm.leave_subsection();
  }



  void
  DisplacementControl::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Loading");
    active         = prm.get("Control") == "displacement";
    control_point  = ParameterTools::get_point(prm, "Control point");
    direction      = ParameterTools::get_point(prm, "Control direction");
    step_increment = prm.get_double("Displacement increment");
    prm.leave_subsection();
    if (!active)
      return;
    AssertThrow(direction.norm() > 0,
                ExcMessage("Loading/Control direction must not be zero."));
    AssertThrow(step_increment > 0,
                ExcMessage("Loading/Displacement increment must be positive "
                           "with Control = displacement."));
    direction /= direction.norm();
  }



  void
  DisplacementControl::locate(const BackgroundGrid &grid)
  {
    communicator = grid.mpi_communicator();
    dofs.clear();
    weights.clear();
    double distance = std::numeric_limits<double>::max();
    for (const auto &cell : grid.dof_handler().active_cell_iterators())
      if (cell->is_locally_owned())
        for (const unsigned int v : cell->vertex_indices())
          if (cell->vertex(v).distance(control_point) < distance)
            {
              distance       = cell->vertex(v).distance(control_point);
              control_vertex = cell->vertex(v);
              dofs           = {cell->vertex_dof_index(v, 0),
                                cell->vertex_dof_index(v, 1)};
            }
    // Every process with the nearest vertex keeps its owned DoFs; value()
    // sums over processes.
    const double nearest = Utilities::MPI::min(distance, communicator);
    std::vector<types::global_dof_index> owned;
    if (distance == nearest && dofs.size() == 2)
      for (unsigned int d = 0; d < 2; ++d)
        if (grid.locally_owned_dofs().is_element(dofs[d]) && direction[d] != 0.)
          {
            owned.push_back(dofs[d]);
            weights.push_back(direction[d]);
          }
    dofs = owned;
    // Tell every process where the vertex is (for messages).
    Point<2> here = distance == nearest ? control_vertex : Point<2>();
    for (unsigned int d = 0; d < 2; ++d)
      control_vertex[d] =
        Utilities::MPI::max(distance == nearest ?
                              here[d] :
                              -std::numeric_limits<double>::max(),
                            communicator);
  }



  double
  DisplacementControl::value(
    const LinearAlgebra::distributed::Vector<double> &x) const
  {
    double sum = 0;
    for (unsigned int i = 0; i < dofs.size(); ++i)
      sum += weights[i] * x(dofs[i]);
    return Utilities::MPI::sum(sum, communicator);
  }



  double
  DisplacementControl::value(const TrilinosWrappers::MPI::Vector &x) const
  {
    double sum = 0;
    for (unsigned int i = 0; i < dofs.size(); ++i)
      sum += weights[i] * x(dofs[i]);
    return Utilities::MPI::sum(sum, communicator);
  }
} // namespace bsmpm
