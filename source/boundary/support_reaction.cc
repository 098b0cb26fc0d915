#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/component_mask.h>

#include <bsmpm/boundary/support_reaction.h>

namespace bsmpm
{
  void
  SupportReaction::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Reactions");
    prm.declare_entry("Curves",
                      "",
                      Patterns::List(Patterns::Integer(1)),
                      "Boundary curves (by number) whose supports' force on "
                      "the body is reported after every load step as "
                      "quantities curve<k>_force_x and _y (SupportReaction: "
                      "the nodal force of the supports' terms in the "
                      "discrete equations, summed; it balances the internal "
                      "force as the solver integrates it).");
    prm.leave_subsection();
  }



  void
  SupportReaction::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Reactions");
    reported_curves.clear();
    for (const auto &k : Utilities::split_string_list(prm.get("Curves")))
      reported_curves.push_back(Utilities::string_to_int(k) - 1);
    prm.leave_subsection();
  }



  void
  SupportReaction::record(
    const BackgroundGrid &grid,
    const std::function<TrilinosWrappers::MPI::Vector(const unsigned int)>
                                  &support_forces,
    std::map<std::string, double> &quantities) const
  {
    for (const unsigned int c : reported_curves)
      {
        const Tensor<1, 2> force      = resultant(grid, support_forces(c));
        const std::string  name       = "curve" + std::to_string(c + 1);
        quantities[name + "_force_x"] = force[0];
        quantities[name + "_force_y"] = force[1];
      }
  }



  Tensor<1, 2>
  SupportReaction::resultant(
    const BackgroundGrid                &grid,
    const TrilinosWrappers::MPI::Vector &support_forces)
  {
    Tensor<1, 2> force;
    for (unsigned int k = 0; k < 2; ++k)
      {
        std::vector<bool> selected(2, false);
        selected[k] = true;
        for (const auto i : DoFTools::extract_dofs(grid.dof_handler(),
                                                   ComponentMask(selected)))
          force[k] += support_forces(i);
      }
    return Utilities::MPI::sum(force, grid.mpi_communicator());
  }
} // namespace bsmpm
