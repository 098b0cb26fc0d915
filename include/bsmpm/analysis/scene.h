#ifndef bsmpm_scene_h
#define bsmpm_scene_h

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/timer.h>

#include <deal.II/lac/la_parallel_vector.h>

#include <bsmpm/assembly/constitutive_update.h>
#include <bsmpm/assembly/system_assembly.h>
#include <bsmpm/bodies/bodies.h>
#include <bsmpm/boundary/boundary_curves.h>
#include <bsmpm/boundary/ghost_penalty.h>
#include <bsmpm/boundary/neumann_loads.h>
#include <bsmpm/boundary/support_methods.h>
#include <bsmpm/boundary/support_reaction.h>
#include <bsmpm/contact/curve_contact.h>
#include <bsmpm/geometry/background_grid.h>
#include <bsmpm/geometry/body_region.h>
#include <bsmpm/io/checkpoint.h>
#include <bsmpm/io/output_writer.h>
#include <bsmpm/io/run_checkpoint.h>
#include <bsmpm/io/run_summary.h>
#include <bsmpm/io/step_output.h>
#include <bsmpm/linear_algebra/linear_solver.h>
#include <bsmpm/materials/constitutive_model.h>
#include <bsmpm/materials/material.h>
#include <bsmpm/nonlinear/collapse_detector.h>
#include <bsmpm/nonlinear/displacement_control.h>
#include <bsmpm/nonlinear/increment_solver.h>
#include <bsmpm/nonlinear/load_stages.h>
#include <bsmpm/nonlinear/load_stepper.h>
#include <bsmpm/nonlinear/newton_solver.h>
#include <bsmpm/points/excavation.h>
#include <bsmpm/points/initial_stress.h>
#include <bsmpm/points/material_point_layout.h>
#include <bsmpm/points/material_points.h>
#include <bsmpm/points/probe.h>
#include <bsmpm/points/q1_cell_kernel.h>
#include <bsmpm/quadrature/cut_cell_quadrature.h>
#include <bsmpm/verification/exact_solution.h>
#include <bsmpm/verification/verification.h>

#include <map>
#include <memory>
#include <string>
#include <vector>

namespace bsmpm
{
  using namespace dealii;

  /**
   * One analysis: an implicit, quasi-static MPM run in load steps (paper
   * Sec. 2, method-notes Sec. 1). The Scene makes the parts of the run from
   * the parameters and keeps the order of a load step:
   *
   *   per increment (LoadStepper: increments, cuts, the solve):
   *     sort the points into cells, their cell moments (cut-cell
   *     quadrature) -> system and solve -> move the points (strain,
   *     stress, displacement, position) -> rebuild the boundary curves
   *     through their moved points;
   *   then the step's quantities, its line of the table, output and
   *   checkpoint; at the end errors and the summary.
   *
   * The grid is reset after every step: only the points move.
   */
  class Scene
  {
  public:
    explicit Scene(const MPI_Comm communicator);

    /** Declares every parameter of bsmpm (all sections). */
    static void
    declare_parameters(ParameterHandler &prm);

    void
    parse_parameters(ParameterHandler &prm);

    /** Divides the strength of the constitutive model by @p factor
     * (strength reduction, StrengthReduction); call before
     * parse_parameters(). */
    void
    reduce_strength(const double factor)
    {
      strength_factor = factor;
    }

    /** Prints nothing (the trials of a strength reduction). */
    void
    quiet()
    {
      pcout.set_condition(false);
    }

    /** Whether run() stopped at a limit load, and the detector's figures. */
    const CollapseDetector &
    collapse() const
    {
      return collapse_detector;
    }

    /** Runs all load steps and writes the summary. */
    void
    run();

    /** Makes run() continue from the checkpoint @p directory (see
     * Checkpoint) instead of starting; call after parse_parameters(). */
    void
    resume_from(const std::string &directory)
    {
      checkpoint.resume_from(directory);
    }

    const RunSummary &
    summary() const
    {
      return run_summary;
    }

  private:
    void
    setup();
    /** The system, its solvers and the load steps' driver, once the grid,
     * points and curves exist. */
    void
    make_solvers();
    /** Material moments of every cell, plain or by the cut-cell quadrature,
     * of the points sorted into cells if they moved, for an increment that
     * ends at load path parameter @p tau (set_weight_shares()). */
    const std::vector<CellMoments> &
    compute_cell_moments(const double tau);
    /** Bodies built by a stage: the densities that weigh the points, each
     * body's times the share of its weight it carries at load path
     * parameter @p tau (LoadStages::weight_share()). */
    void
    set_weight_shares(const double tau);
    /** Stage @p k's start: adds the bodies it builds. */
    void
    build_bodies(const unsigned int k);
    /** Moves the points by the converged increment of load step @p step,
     * whose prescribed displacements changed over @p load_increment. */
    void
    move_points(const unsigned int step, const LoadIncrement &load_increment);
    /** Rebuilds the curves through the moved points and their cuts; an
     * error names load step @p step (0: before the first step). */
    void
    update_curves(const unsigned int step);
    /** The probe, support reactions, traction resultant and yielded
     * points after a load step, into the run's quantities. */
    void
    record_quantities(const RunSummary::Step &record);
    void
    write_output(const unsigned int step, const double load_factor);

    /** Before load step @p step, the first of stage @p k: its line in the
     * log, and what the stage restarts, removes or builds
     * (LoadStages::Stage). */
    void
    begin_stage(const unsigned int k, const unsigned int step);
    void
    evaluate_errors();
    /** Several bodies: where the cut-cell quadrature corrected a cell's
     * moments (@p points_moments: the points' own), the mass moments
     * follow (the exact moments times the density of the cell's points). */
    void
    correct_mass_moments(const std::vector<CellMoments> &points_moments);
    /** Refuses what several bodies cannot do yet, naming the parameter. */
    void
    check_several_bodies() const;
    void
    write_checkpoint(const unsigned int step);

    MPI_Comm            communicator;
    ConditionalOStream  pcout;
    mutable TimerOutput timer;
    Timer               total_timer;

    std::string   scene_name;
    LoadStages    stages;
    InitialStress initial_stress;
    /** The material the current stage removes (LoadStages). */
    Excavation excavation;
    /** The constitutive model's strength is divided by this. */
    double                             strength_factor = 1;
    CollapseDetector                   collapse_detector;
    DisplacementControl                displacement_control;
    Tensor<1, 2>                       gravity;
    BackgroundGrid                     grid;
    LinearElasticMaterial              material;
    std::unique_ptr<ConstitutiveModel> constitutive_model;
    /** Only for a nonlinear constitutive model or finite strain. */
    std::unique_ptr<ConstitutiveUpdate> constitutive_update;
    /** The linear path's volumetric strain is the cell's mean (B-bar). */
    bool linear_b_bar = false;

    /** Whether the points follow the finite-strain kinematics. */
    bool
    finite_strain() const
    {
      return constitutive_update &&
             constitutive_update->kinematics() ==
               ConstitutiveUpdate::Kinematics::finite_strain;
    }
    NewtonSolver        newton;
    BodyRegion          region;
    MaterialPointLayout layout;
    /** The bodies beyond the first (region, layout, material above). */
    Bodies                           bodies;
    MaterialPoints                   points;
    Probe                            probe;
    BoundaryCurves                   boundary_curves;
    NeumannLoads                     neumann_loads;
    SupportMethods                   supports;
    CurveContact                     contact;
    GhostPenalty                     ghost_penalty;
    SupportReaction                  reactions;
    CutCellQuadrature                cut_cell_quadrature;
    LinearSolver                     linear_solver;
    OutputWriter                     output;
    StepOutput                       step_output;
    Checkpoint                       checkpoint;
    Verification                     verification;
    std::unique_ptr<ExactSolution>   exact_solution;
    std::unique_ptr<SystemAssembly>  assembly;
    std::unique_ptr<IncrementSolver> increment_solver;
    std::unique_ptr<LoadStepper>     load_stepper;
    std::unique_ptr<RunCheckpoint>   run_checkpoint;

    LinearAlgebra::distributed::Vector<double> increment;
    /** Whether points moved since they were last sorted into cells. */
    bool points_moved = false;
    /** Locally owned cells where a support method displaces the points. */
    std::vector<bool>        band_cells;
    std::vector<CellMoments> cell_moments;
    /** Several bodies: the moments of the points' masses (body force). */
    std::vector<CellMoments> mass_moments;
    /** The density of every body, by Property::body. */
    std::vector<double> densities;
    /** Bodies built by a stage: the first id of their points, by body
     * number (MaterialPoints::reserve_ids()). */
    std::map<unsigned int, types::particle_index> first_ids;

    RunSummary run_summary;
  };
} // namespace bsmpm

#endif
