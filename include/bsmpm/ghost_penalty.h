#ifndef bsmpm_ghost_penalty_h
#define bsmpm_ghost_penalty_h

#include <deal.II/base/parameter_handler.h>

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/la_parallel_vector.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <bsmpm/background_grid.h>
#include <bsmpm/q1_cell_kernel.h>

#include <vector>

namespace bsmpm
{
  using namespace dealii;

  /**
   * Ghost-penalty stabilisation of partly filled cells (beyond the paper;
   * method-notes Sec. 7, as in CutFEM). A cell whose material points fill
   * less than a fraction of it integrates its stiffness over a sliver, so
   * the DoFs at its far side are held by almost nothing and the system's
   * condition number grows like one over the fill fraction. On every face
   * between two cells with material, at least one of them partly filled,
   * this adds
   *
   *   gamma E h int_F [d u / d n] . [d v / d n] ds,
   *
   * the jump of the normal derivative across the face, which extends the
   * stiffness of the full neighbour into the sliver. The jump vanishes for
   * linear displacement fields, so patch tests stay exact; for smooth ones
   * it is O(h), like the discretisation error.
   */
  class GhostPenalty
  {
  public:
    static void
    declare_parameters(ParameterHandler &prm);
    void
    parse_parameters(ParameterHandler &prm);

    bool
    enabled() const
    {
      return use;
    }

    /**
     * Adds the face terms. @p fraction holds the material fraction
     * (volume / cell area) of every locally owned cell, by
     * active_cell_index(). The matrix needs the couplings across faces
     * (DoFTools::make_flux_sparsity_pattern). With @p prescribed (the nodal
     * values d^a of an IBM prescribed displacement), the penalty acts on the
     * total field w + M d^a, which adds -J d^a to @p rhs: d^a is fitted to
     * the boundary and has kinks that the grid field must not be made to
     * smooth away.
     */
    void
    assemble(const BackgroundGrid                             &grid,
             const Q1CellKernel                               &kernel,
             const double                                      youngs_modulus,
             const std::vector<double>                        &fraction,
             const LinearAlgebra::distributed::Vector<double> *prescribed,
             const AffineConstraints<double>                  &constraints,
             TrilinosWrappers::SparseMatrix                   &matrix,
             TrilinosWrappers::MPI::Vector                    &rhs) const;

    /** Number of faces stabilised by the last assemble() on this process. */
    unsigned int
    n_faces() const
    {
      return faces;
    }

  private:
    bool                 use       = false;
    double               penalty   = 0.01;
    double               threshold = 0.99;
    mutable unsigned int faces     = 0;
  };
} // namespace bsmpm

#endif
