#include <deal.II/base/mpi.h>

#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/component_mask.h>

#include <bsmpm/boundary/support_reaction.h>

namespace bsmpm
{
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
