#ifndef bsmpm_system_assembly_h
#define bsmpm_system_assembly_h

#include <deal.II/base/timer.h>

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/la_parallel_vector.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <bsmpm/assembly/cell_scatter.h>
#include <bsmpm/assembly/constitutive_update.h>
#include <bsmpm/base/load_level.h>
#include <bsmpm/boundary/boundary_curves.h>
#include <bsmpm/boundary/ghost_penalty.h>
#include <bsmpm/boundary/neumann_loads.h>
#include <bsmpm/boundary/support_methods.h>
#include <bsmpm/contact/contact_pattern.h>
#include <bsmpm/contact/curve_contact.h>
#include <bsmpm/geometry/background_grid.h>
#include <bsmpm/materials/material.h>
#include <bsmpm/points/excavation.h>
#include <bsmpm/points/q1_cell_kernel.h>
#include <bsmpm/verification/exact_solution.h>

#include <memory>
#include <vector>

namespace bsmpm
{
  using namespace dealii;

  /**
   * The linear system K du = r of a load step (method-notes Sec. 1):
   *
   * - constraints: the DoFs that no cell with material (or crossed by a
   *   support) touches are fixed at zero, or K would be singular; the grid's
   *   face supports;
   * - K and r = f_ext(lambda) - f_int(sigma_n) from the cell moments of the
   *   material points (Q1CellKernel), the ghost penalty, the supports on
   *   the boundary curves (every SupportMethod in turn: the implicit
   *   boundary method, Nitsche, ...) and the loads on them.
   *
   * The sparsity pattern holds the couplings of the full grid, so it is
   * built once for all load steps, whichever cells hold material.
   */
  class SystemAssembly
  {
  public:
    /** What the system is made of; all owned by the caller. */
    struct Parts
    {
      const BackgroundGrid        &grid;
      const LinearElasticMaterial &material;
      const BoundaryCurves        &curves;
      NeumannLoads                &neumann_loads;
      /** The support methods, each called in turn. */
      SupportMethods     &supports;
      const GhostPenalty &ghost_penalty;
      /** The scene's exact solution, or nullptr. */
      const ExactSolution *exact_solution;
      /** Gravitational acceleration (the body force is density times it). */
      Tensor<1, 2> gravity;
      /** Whether the linear kernel takes the cell-mean volumetric strain
       * (B-bar, "Material/Volumetric strain"); the boundary terms then pair
       * the same B-bar stress with it. */
      bool b_bar;
      /**
       * A nonlinear material's points, or nullptr: assemble() then leaves
       * out the stiffness and internal force of the cells where they hold
       * material, which a nonlinear model adds per iteration
       * (ConstitutiveUpdate). A cell of the body that holds no point (a
       * sliver the boundary has just cut off, given its exact moments and
       * the neighbours' stress by CutCellQuadrature) keeps the elastic
       * stiffness and that stress, as in a linear run: without them its
       * outer vertices would hold nothing.
       */
      const MaterialPoints *material_points;
      /** With material points: such a cell is left to the points too where
       * a face neighbour holds material (the cut-cell quadrature is on):
       * ConstitutiveUpdate integrates it with the neighbourhood's state
       * (MaterialPoints::neighbourhood_mean_properties()). */
      bool cells_without_points;
      /** Finite strain: the body force acts on the points' masses
       * (ConstitutiveUpdate integrates it), and a pressure follows the
       * boundary within the step, so that its load stiffness enters the
       * matrix (NeumannLoads). */
      bool finite_strain;
      /** Contact of the curves with rigid bodies, or nullptr:
       * newton_system() adds its forces and their derivative
       * (CurveContact::add_newton_terms()). */
      CurveContact *contact;
      /** The boundary curves (by index) whose supports' terms assemble()
       * keeps apart, each in a matrix of the system's pattern, for
       * support_forces(). */
      std::vector<unsigned int> reaction_curves;
      /** The material a stage removed, whose forces on the rest assemble()
       * adds times LoadLevel::release. */
      const Excavation &excavation;
      /** Several bodies (Bodies): the moments of the points' masses
       * (MaterialPoints::compute_mass_moments(), kept by the caller), from
       * which the body force is integrated with the gravity alone; nullptr:
       * the material's density times the volume moments. */
      const std::vector<CellMoments> *mass_moments = nullptr;
    };

    SystemAssembly(const Parts &parts, TimerOutput &timer);

    /** Builds the sparsity pattern, matrix and vectors; makes the kernel. */
    void
    setup();

    const Q1CellKernel &
    kernel() const
    {
      return *cell_kernel;
    }

    /** Constrains the DoFs that no cell with material (moments by
     * active_cell_index()) supports, and adds the grid's face supports. */
    void
    make_constraints(const std::vector<CellMoments> &moments);

    /** Whether a support method imposes the prescribed displacements
     * through nodal values fitted by least squares
     * (SupportMethod::fits_prescribed_displacement()). */
    bool
    fits_prescribed_displacement() const
    {
      return fitting_method != nullptr;
    }

    /**
     * Fits those nodal values d^a to the prescribed displacements' change
     * over the load increment @p increment; assemble() and
     * prescribed_displacement() then take them. Returns the root mean
     * square misfit along the supports.
     */
    double
    fit_prescribed_displacement(const LoadIncrement &increment);

    /** The nodal values of the last fit_prescribed_displacement(), or
     * nullptr if there was none. */
    const LinearAlgebra::distributed::Vector<double> *
    prescribed_displacement() const
    {
      return has_prescribed ? &prescribed : nullptr;
    }

    /**
     * Assembles K and r for the load multipliers @p level (LoadStages) at
     * the end of the load increment @p increment (prescribed displacements
     * are applied by their change over it; fitted ones as of the last
     * fit_prescribed_displacement()). @p quality: support quality of every
     * locally owned cell (for the ghost penalty).
     */
    void
    assemble(const LoadLevel                &level,
             const LoadIncrement            &increment,
             const std::vector<CellMoments> &moments,
             const std::vector<double>      &quality);

    /**
     * The loads' growth along the load path, @p slope (LoadStages::slope():
     * the body force times its gravity, the tractions times its loads)
     * with the constraints of the last make_constraints(), into @p loads:
     * the derivative of the residual by the load factor, for displacement
     * control (small strain only). The traction resultant of
     * NeumannLoads is then that of load factor 1, until the next
     * assemble().
     */
    void
    reference_loads(const std::vector<CellMoments> &moments,
                    const LoadLevel                &slope,
                    TrilinosWrappers::MPI::Vector  &loads);

    /**
     * The Newton system of a nonlinear material at the increment
     * @p increment (ghosted, zero at constrained DoFs) after assemble()
     * without the material (leave_material_to_points()): tangent
     * K_T = K + K_m and residual R = r - K x - f_int, with K and r the
     * linear system of the boundaries, loads and stabilisation and K_m,
     * f_int the material's, from @p update (see ConstitutiveUpdate).
     * Returns |R|, or infinity if the increment inverts a material point
     * or a support's point (finite strain; those cells and points are left
     * out of the system, which holds no NaN): an inadmissible iterate,
     * from which the line search backs away. With @p elastic_cells (from
     * ConstitutiveUpdate::prepare_elastic_cells() for these points), the
     * cells that stay elastic take their moments instead of their points.
     */
    double
    newton_system(
      const ConstitutiveUpdate                         &update,
      const MaterialPoints                             &points,
      const LinearAlgebra::distributed::Vector<double> &increment,
      const LinearAlgebra::distributed::Vector<double> *prescribed,
      const ConstitutiveUpdate::ElasticCells *elastic_cells = nullptr);

    const TrilinosWrappers::SparseMatrix &
    tangent() const
    {
      return tangent_matrix;
    }
    const TrilinosWrappers::MPI::Vector &
    residual() const
    {
      return newton_residual;
    }
    /** Whether the contact terms of the last newton_system() kept the
     * tangent symmetric (nothing slides). */
    bool
    contact_tangent_symmetric() const
    {
      return contact_symmetric;
    }

    /**
     * The force that the supports of curve @p curve (one of
     * Parts::reaction_curves) exert on the grid's DoFs at the end of a step
     * whose converged increment is @p increment: r_s - K_s x, their share
     * of the system of the last assemble() (without constraints, so that
     * DoFs that the grid's faces hold keep their share). The rest of the
     * system balances it: the internal force with the solver's own
     * quadrature (fitted weights, cells without points), the ghost penalty
     * and the loads.
     */
    TrilinosWrappers::MPI::Vector
    support_forces(
      const unsigned int                                curve,
      const LinearAlgebra::distributed::Vector<double> &increment) const;

    /**
     * The support quality (GhostPenalty::cell_qualities()) of every locally
     * owned cell with the material moments @p moments under the constraints
     * of the last make_constraints(). With @p update (a nonlinear material)
     * the stiffness that its points have lost lowers it.
     */
    std::vector<double>
    support_qualities(const std::vector<CellMoments> &moments,
                      const ConstitutiveUpdate       *update) const;

    /** Throws if the loads of the last assemble() (of load step @p step)
     * are not finite. */
    void
    check_loads_finite(const unsigned int step) const;

    /** |f_int| of the points at the last newton_system(): the scale of
     * the stresses that the residual balances (in finite strain, where the
     * points' force is net of their weight, at least that of the weight
     * of the last assemble()). */
    double
    internal_force_size() const
    {
      return internal_force_norm;
    }

    /** Locally owned points with volume that yield at the last
     * newton_system(), over all processes. */
    unsigned long long
    n_yielding() const
    {
      return yielding;
    }

    const AffineConstraints<double> &
    constraints() const
    {
      return system_constraints;
    }
    const TrilinosWrappers::SparseMatrix &
    matrix() const
    {
      return system_matrix;
    }
    const TrilinosWrappers::MPI::Vector &
    rhs() const
    {
      return system_rhs;
    }
    /**
     * The locally owned cells of the weak cells the matrix was last made
     * for. Which cells the matrix couples across faces depends on the
     * steps a run went through; a checkpoint keeps these so that the run
     * resumed from it makes the same matrix (a direct solver orders its
     * work by the pattern, so another one changes the last digits).
     */
    std::vector<CellId>
    weak_cells_of_last_matrix() const;

    /**
     * Makes the matrix for the weak cells @p cells (every process's
     * weak_cells_of_last_matrix() of the run that wrote the checkpoint):
     * the same pattern as that run had. Collective; nothing to do without
     * a ghost penalty.
     */
    void
    restore_matrix(const std::vector<CellId> &cells);

    /** Number of cells with material or supports, over all processes, at
     * the last make_constraints(). */
    unsigned int
    n_active_cells() const
    {
      return active_cells;
    }

  private:
    /** The density that multiplies the gravity in the body force: the
     * material's, or 1 where the moments carry the masses
     * (Parts::mass_moments). */
    double
    density() const
    {
      return parts.mass_moments ? 1. : parts.material.density();
    }

    /** The moments the body force of @p cell is integrated from: its
     * volume moments @p m, or its mass moments (Parts::mass_moments). */
    const CellMoments &
    mass_moments(const CellMoments                         &m,
                 const DoFHandler<2>::active_cell_iterator &cell) const
    {
      return parts.mass_moments ?
               (*parts.mass_moments)[cell->active_cell_index()] :
               m;
    }

    Parts        parts;
    TimerOutput &timer;

    std::unique_ptr<Q1CellKernel> cell_kernel;
    /** The cell moments of the current assemble(), for the B-bar stress of
     * the boundary terms (nullptr outside it). */
    const std::vector<CellMoments> *assembly_moments = nullptr;
    AffineConstraints<double>       system_constraints;
    TrilinosWrappers::SparseMatrix  system_matrix;
    TrilinosWrappers::MPI::Vector   system_rhs;
    /** Where the cells' entries lie in system_matrix. */
    CellScatter scatter;
    /** The support method that fits prescribed displacements by least
     * squares, or nullptr; the matrix of the fit (the system's pattern),
     * and the nodal values of the last fit. */
    const SupportMethod                       *fitting_method = nullptr;
    TrilinosWrappers::SparseMatrix             boundary_fit_matrix;
    LinearAlgebra::distributed::Vector<double> prescribed;
    bool                                       has_prescribed = false;
    TrilinosWrappers::SparseMatrix             tangent_matrix;
    /** How many times make_matrix() has built system_matrix's layout, and
     * which of them tangent_matrix has (see newton_system()). */
    unsigned int matrix_layouts = 0;
    unsigned int tangent_layout = 0;
    /** With mortar contact pressures: tangent_matrix's pattern
     * widened round the contact (CurveContact::coupled_cells()). */
    ContactPattern contact_pattern;
    /** The pattern of system_matrix, kept with rigid bodies only. */
    DynamicSparsityPattern        system_pattern;
    TrilinosWrappers::MPI::Vector newton_residual;
    unsigned long long            yielding            = 0;
    bool                          contact_symmetric   = true;
    double                        internal_force_norm = 0;
    /** Finite strain: |the points' weight| at the last assemble(). */
    double weight_norm = 0;
    /** The supports' bands by cell, for the tangent of nonlinear
     * materials (ConstitutiveUpdate::cell_system()). */
    ConstitutiveUpdate::SupportBands support_bands;
    /** The supports' terms of Parts::reaction_curves. */
    std::vector<TrilinosWrappers::SparseMatrix> support_matrices;
    std::vector<TrilinosWrappers::MPI::Vector>  support_rhs;
    /** Whether support_matrices have the layout of system_matrix. */
    bool support_layout_current = false;
    /** Where the cells' entries lie in tangent_matrix. */
    CellScatter tangent_scatter;
    /**
     * Builds the sparsity pattern and the matrix: the couplings of every
     * cell, and across the faces of the cells flagged in @p weak (by
     * active_cell_index(), owned and ghost) and of their neighbours, where
     * the ghost penalty acts now or may act after the boundary has moved
     * by less than a cell.
     */
    void
    make_matrix(const std::vector<bool> &weak);

    /** What the support methods' terms are made of. */
    SupportMethod::Context
    support_context() const;

    /** Adds the terms of every support method of all curves, or of
     * @p only, to @p matrix and @p rhs. */
    void
    add_support_terms(const LoadIncrement             &increment,
                      const AffineConstraints<double> &constraints,
                      TrilinosWrappers::SparseMatrix  &matrix,
                      TrilinosWrappers::MPI::Vector   &rhs,
                      const BoundaryCurve             *only);

    /** Finite strain: the supports' terms that depend on the stress of
     * the increment @p increment (SupportMethod::
     * add_finite_strain_terms()) of all curves, or of @p only, as internal
     * forces into @p force and, unless nullptr, their derivative into
     * @p tangent. Returns how many of the supports' points the increment
     * inverts (left out). */
    unsigned long long
    add_finite_strain_support_terms(
      const ConstitutiveUpdate                         &update,
      const LinearAlgebra::distributed::Vector<double> &increment,
      const AffineConstraints<double>                  &constraints,
      TrilinosWrappers::SparseMatrix                   *tangent,
      TrilinosWrappers::MPI::Vector                    &force,
      const BoundaryCurve                              *only = nullptr) const;

    /** Finite strain: the share of the supports of the reaction curves
     * in the internal force of the last newton_system(). */
    std::vector<TrilinosWrappers::MPI::Vector> support_finite_strain_forces;

    /** Assembles the supports' terms of the reaction curves. */
    void
    assemble_support_terms(const LoadIncrement &increment);

    /** The weak cells the matrix was made for (make_matrix()), and the
     * cells whose face couplings it holds: those and their neighbours. */
    std::vector<bool> weak_cells_of_matrix;
    std::vector<bool> coupled_faces;
    /** Locally owned DoFs that no cell with material touches. */
    std::vector<types::global_dof_index> unsupported_dofs;
    unsigned int                         active_cells = 0;
  };
} // namespace bsmpm

#endif
