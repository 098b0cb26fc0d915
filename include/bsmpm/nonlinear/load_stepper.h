#ifndef bsmpm_load_stepper_h
#define bsmpm_load_stepper_h

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/timer.h>

#include <deal.II/lac/la_parallel_vector.h>
#include <deal.II/lac/trilinos_vector.h>

#include <bsmpm/assembly/constitutive_update.h>
#include <bsmpm/assembly/system_assembly.h>
#include <bsmpm/boundary/boundary_curves.h>
#include <bsmpm/boundary/neumann_loads.h>
#include <bsmpm/contact/curve_contact.h>
#include <bsmpm/geometry/background_grid.h>
#include <bsmpm/linear_algebra/linear_solver.h>
#include <bsmpm/materials/material.h>
#include <bsmpm/nonlinear/collapse_detector.h>
#include <bsmpm/nonlinear/displacement_control.h>
#include <bsmpm/nonlinear/increment_solver.h>
#include <bsmpm/nonlinear/load_stages.h>
#include <bsmpm/nonlinear/load_step_record.h>
#include <bsmpm/nonlinear/newton_solver.h>
#include <bsmpm/points/material_points.h>

#include <functional>
#include <map>
#include <string>
#include <vector>

namespace bsmpm
{
  using namespace dealii;

  /**
   * One load step in load increments (method-notes Sec. 1): per increment
   * the system at the load factor reached plus the increment (SystemAssembly),
   * its solve (IncrementSolver: linear, or Newton for a nonlinear material),
   * the contact's touching parts before and after, and the points moved by
   * the converged increment. Where Newton's iterations fail the increment
   * is halved and tried again (a cut); where no cut converges under load
   * control the step is the limit load (CollapseDetector), or, at the last
   * cut, the best iterate is accepted if its residual is small enough
   * (doc/newton.md, "Stalled increments"). Under displacement control the
   * control displacement grows instead, and the load factor follows
   * (DisplacementControl).
   *
   * What happens to the points and curves around the solve is the
   * analysis' (Scene): the cell moments of the points as they are, and the
   * move of the points by a converged increment (Phases).
   */
  class LoadStepper
  {
  public:
    /** What the load steps are made of; all owned by the caller. */
    struct Parts
    {
      const BackgroundGrid        &grid;
      MaterialPoints              &points;
      const BoundaryCurves        &curves;
      const NeumannLoads          &neumann_loads;
      const LinearElasticMaterial &material;
      /** Gravitational acceleration (the body force is density times it). */
      Tensor<1, 2> gravity;
      /** The multipliers of the loads along the load path. */
      const LoadStages    &stages;
      SystemAssembly      &assembly;
      IncrementSolver     &increment_solver;
      const LinearSolver  &linear_solver;
      const NewtonSolver  &newton;
      CollapseDetector    &collapse_detector;
      DisplacementControl &displacement_control;
      /** Null for linear elasticity in small strain. */
      ConstitutiveUpdate *constitutive_update;
      /** Contact with rigid bodies, or null. */
      CurveContact *contact;
      /** The displacement increment (with ghost values), solved here. */
      LinearAlgebra::distributed::Vector<double> &increment;
    };

    /** What the analysis does around the solve of an increment. */
    struct Phases
    {
      /** The material moments of every cell (by active_cell_index()) of
       * the points as they are now, for an increment that ends at load
       * path parameter tau (the weight of a body being built). */
      std::function<const std::vector<CellMoments> &(const double tau)>
        cell_moments;
      /** Moves the points by the converged increment of load step
       * @p step, whose prescribed displacements changed over
       * @p increment, and rebuilds the curves. */
      std::function<void(const unsigned int   step,
                         const LoadIncrement &increment)>
        move;
    };

    LoadStepper(const Parts                   &parts,
                const Phases                  &phases,
                TimerOutput                   &timer,
                ConditionalOStream            &pcout,
                std::map<std::string, double> &quantities);

    /**
     * Under displacement control: refuses what its bordered Newton
     * iterations do not handle and finds the control vertex. Otherwise
     * sets the collapse detector up: a limit load is sought where the
     * material may yield (@p may_yield: a material model with a
     * strength). @p resuming: the run goes on from a checkpoint.
     */
    void
    initialize(const bool may_yield, const bool resuming);

    /** Before the first step of stage @p k (LoadStages): the collapse
     * detector measures the stage against its own first increment, and the
     * Newton solver forgets the last stage's increments. */
    void
    begin_stage(const unsigned int k)
    {
      begin_stage(k, stage_may_yield);
    }

    /** Whether stage @p k runs under displacement control
     * (Loading/Control = displacement: the last stage; the stages before
     * it are load controlled). */
    bool
    controls_displacement(const unsigned int k) const;

    /**
     * Takes the load from factor @p from to @p to: one increment, or more
     * where a nonlinear material's Newton iterations fail and the
     * increment is halved. Fills the solver figures of @p record and its
     * load factor, which stays below @p to where the collapse detector
     * stops the step.
     */
    void
    advance(const unsigned int step,
            const double       from,
            const double       to,
            LoadStepRecord    &record);

    /**
     * Load step @p step under displacement control: the control
     * displacement grows by its increment (halved where Newton fails), the
     * load factor follows (DisplacementControl). Fills @p record with the
     * load factor reached.
     */
    void
    advance_under_displacement_control(const unsigned int step,
                                       LoadStepRecord    &record);

    /**
     * The out-of-balance force F_ext - F_int of the points as they are, at
     * load path parameter @p tau: the system's residual at a zero
     * increment (the linear system's right-hand side, or Newton's
     * residual), into @p balance. What an excavation releases
     * (Excavation::release()).
     */
    void
    out_of_balance(const double tau, TrilinosWrappers::MPI::Vector &balance);

    /** The resultant of the tractions on the curves at the load factor
     * reached (that of the last assembly under load control). */
    Tensor<1, 2>
    traction_resultant() const;

    /** CurveContact::friction_hint() for an increment that failed at load
     * factor @p load_factor, with the body's loads if nothing but contact
     * supports it. Collective. */
    std::string
    friction_hint(const double load_factor) const;

    /** The support quality of every locally owned cell in the last
     * increment (GhostPenalty), as the increment's cuts lowered it. */
    const std::vector<double> &
    cell_qualities() const
    {
      return cell_quality;
    }

  private:
    void
    begin_stage(const unsigned int k, const bool may_yield);

    /** The system's constraints and the cells' support qualities for the
     * points as they are, after @p cuts cuts of the increment, which ends
     * at load path parameter @p tau. */
    const std::vector<CellMoments> &
    prepare_increment(const unsigned int cuts, const double tau);

    /** Newton iterations of a nonlinear material for the assembled load
     * increment @p delta from @p lambda, cut @p cuts times so far; commits
     * the points' state if they converge. Returns whether they did. */
    bool
    solve_nonlinear(const unsigned int step,
                    const double       lambda,
                    const double       delta,
                    const unsigned int cuts,
                    LoadStepRecord    &record);

    /** Accepts the best iterate of a last cut that did not converge if its
     * residual is within the stall tolerance; returns whether it did. */
    bool
    accept_stalled(const NewtonSolver::Result &result,
                   const double                lambda,
                   const double                delta,
                   LoadStepRecord             &record);

    /** The contact's touching parts for the load increment from @p lambda
     * by @p delta, before its iterations. */
    void
    begin_contact(const double lambda, const double delta);

    /** 'Nonlinear solver/Check tangent': newton_tangent_error and
     * newton_tangent_checks of the run so far into the quantities. */
    void
    record_tangent_check();

    /** Where the log goes (nullptr when quiet). */
    std::ostream *
    log() const
    {
      return pcout.is_active() ? &pcout.get_stream() : nullptr;
    }

    Parts                          parts;
    Phases                         phases;
    TimerOutput                   &timer;
    ConditionalOStream            &pcout;
    std::map<std::string, double> &quantities;

    std::vector<double> cell_quality;
    /** Under displacement control: the load factor reached, the loads of
     * load factor 1 and their traction resultant. */
    double controlled_load_factor = 0;
    /** The stage of the steps being taken (begin_stage()). */
    unsigned int stage = 1;
    /** Whether the material may yield (initialize()). */
    bool                          stage_may_yield = false;
    TrilinosWrappers::MPI::Vector reference_loads;
    Tensor<1, 2>                  unit_traction_resultant;
  };
} // namespace bsmpm

#endif
