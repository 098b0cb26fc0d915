#ifndef bsmpm_ghost_penalty_h
#define bsmpm_ghost_penalty_h

#include <deal.II/base/parameter_handler.h>

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/la_parallel_vector.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <bsmpm/geometry/background_grid.h>
#include <bsmpm/points/q1_cell_kernel.h>

#include <vector>

namespace bsmpm
{
  using namespace dealii;

  /**
   * Ghost-penalty stabilisation of weakly held DoFs (beyond the paper;
   * method-notes Sec. 7, as in CutFEM), on by default.
   *
   * A DoF whose cells hold only a sliver of material, or a few points far
   * from it, is held by almost nothing, and the condition number grows
   * without bound (like one over the fill fraction of a sliver). How well
   * the material holds the DoFs of a vertex v is measured by its support
   * quality
   *
   *   q_v = int |grad N_v|^2 dA over the material of the cells round v,
   *         divided by the same over four full cells,
   *
   * which the cell moments give exactly (N_v is bilinear, so |grad N_v|^2
   * needs the moments up to second order). It is the diagonal stiffness of
   * v's DoFs in units of a full patch's: a sliver of fraction f next to v
   * gives q_v of about f / 4, a lone point far from v almost nothing, full
   * cells 1. A vertex whose DoFs are both constrained needs no support. A
   * cell's quality is the least of its free vertices'.
   *
   * On every face between two cells with material, one of them below the
   * quality threshold q0, this adds
   *
   *   gamma (1 - min(q, q0) / q0) E h int_F [d u / d n] . [d v / d n] ds,
   *
   * the jump of the normal derivative across the face, which extends the
   * stiffness of the neighbour into the weak cell. The penalty is only as
   * strong as the missing support: it fades out as q reaches q0, and q0 is
   * the quality below which the condition number would exceed ten times a
   * full grid's (measured: about 15 / f for a row of slivers of fraction
   * f). That keeps its bias small (doc/stability.md). The jump vanishes for
   * linear displacement fields, so patch tests stay exact; for smooth ones
   * the bias falls faster than the discretisation error.
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

    /** The quality below which a vertex counts as weakly held. */
    double
    quality_threshold() const
    {
      return threshold;
    }

    /**
     * Adds the face terms. @p quality holds the support quality of every
     * locally owned cell, by active_cell_index() (negative: no material). The
     * matrix needs the couplings across faces
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
             const std::vector<double>                        &quality,
             const LinearAlgebra::distributed::Vector<double> *prescribed,
             const AffineConstraints<double>                  &constraints,
             TrilinosWrappers::SparseMatrix                   &matrix,
             TrilinosWrappers::MPI::Vector                    &rhs) const;

    /**
     * The support quality of every locally owned cell (by
     * active_cell_index()), from its material moments @p moments: the least
     * quality of its vertices that @p constraints leave free, 1 if there is
     * none, and -1 for a cell without material (see the class
     * documentation). A cell without material gets 0 instead if every
     * vertex has a free DoF and one of them no material round it: its DoFs
     * are free only because a support crosses it (a boundary that its
     * points have left), and the penalty must hold them.
     *
     * With @p stiffness_ratio (by DoF, with ghost values: a nonlinear
     * material, ConstitutiveUpdate::support_stiffness_ratios()) the support
     * of each vertex is scaled by the fraction of its elastic stiffness
     * that the material keeps round it: points that have lost their
     * stiffness in the direction in which they would hold a vertex (perfect
     * plasticity) do not hold it.
     */
    static std::vector<double>
    cell_qualities(const BackgroundGrid            &grid,
                   const std::vector<CellMoments>  &moments,
                   const AffineConstraints<double> &constraints,
                   const LinearAlgebra::distributed::Vector<double>
                     *stiffness_ratio = nullptr);

    /**
     * The cells (by active_cell_index(), locally owned and ghost) whose
     * faces assemble() can stabilise, given the qualities of the locally
     * owned cells: those with material below the quality threshold. The
     * matrix needs the couplings across their faces.
     */
    std::vector<bool>
    weak_cells(const BackgroundGrid      &grid,
               const std::vector<double> &quality) const;

    /** Number of faces stabilised by the last assemble() on this process. */
    unsigned int
    n_faces() const
    {
      return faces;
    }

  private:
    bool                 use       = true;
    double               penalty   = 0.02;
    double               threshold = 0.005;
    mutable unsigned int faces     = 0;
  };
} // namespace bsmpm

#endif
