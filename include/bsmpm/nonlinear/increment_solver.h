#ifndef bsmpm_increment_solver_h
#define bsmpm_increment_solver_h

#include <deal.II/base/timer.h>

#include <deal.II/lac/la_parallel_vector.h>
#include <deal.II/lac/trilinos_vector.h>

#include <bsmpm/assembly/constitutive_update.h>
#include <bsmpm/assembly/system_assembly.h>
#include <bsmpm/boundary/boundary_curves.h>
#include <bsmpm/contact/rigid_body_motion.h>
#include <bsmpm/geometry/background_grid.h>
#include <bsmpm/linear_algebra/linear_solver.h>
#include <bsmpm/nonlinear/displacement_control.h>
#include <bsmpm/nonlinear/newton_solver.h>
#include <bsmpm/points/material_points.h>

#include <limits>
#include <string>
#include <utility>

namespace bsmpm
{
  using namespace dealii;

  /**
   * The displacement increment of one load increment from the system that
   * SystemAssembly holds: one linear solve for linear elasticity, Newton
   * iterations (NewtonSolver) for a nonlinear material or finite strain,
   * started from the last converged increment.
   */
  class IncrementSolver
  {
  public:
    struct Parts
    {
      const BackgroundGrid &grid;
      SystemAssembly       &assembly;
      const LinearSolver   &linear_solver;
      const NewtonSolver   &newton;
      const MaterialPoints &points;
      const BoundaryCurves &boundary_curves;
      /** Null for linear elasticity in small strain. */
      const ConstitutiveUpdate *constitutive_update;
      /** Contact with rigid bodies, or null. */
      CurveContact *contact = nullptr;
    };

    /** What the linear solves of Newton iterations did: the method and
     * relative residual of the last, the iterations and refinement steps
     * of all. */
    struct LinearSolves
    {
      unsigned int n_solves = 0;
      /** Newton corrections completed (the grid's and the rigid bodies'
       * motion): none where the increment's first system failed. */
      unsigned int n_corrections = 0;
      std::string  method;
      unsigned int iterations        = 0;
      unsigned int refinement_steps  = 0;
      double       relative_residual = 0;

      /** Counts the solve of @p report; the method is the last solve's,
       * with the note of an earlier one (", cg slow") if it has none. */
      void
      add(const LinearSolver::Report &report);
    };

    IncrementSolver(const Parts &parts, TimerOutput &timer);

    /** Solves the assembled linear system of load step @p step into
     * @p increment (with ghost values); throws if the loads or the
     * displacement are not finite. */
    LinearSolver::Report
    solve_linear(const unsigned int                          step,
                 LinearAlgebra::distributed::Vector<double> &increment) const;

    /**
     * Newton iterations of the nonlinear material for the assembled load
     * increment @p delta into @p increment; @p prescribed: the nodal
     * values of a prescribed displacement increment, or null. Adds the
     * figures of the linear solves to @p solves. With contact, the
     * iterations go on after convergence while the parts of the curves
     * that touch a rigid body or the contact's multipliers change
     * (CurveContact::after_convergence()). With @p keep_best, the iterate
     * of smallest residual is kept for take_best_iterate().
     */
    NewtonSolver::Result
    solve_newton(const double                                      delta,
                 const LinearAlgebra::distributed::Vector<double> *prescribed,
                 LinearAlgebra::distributed::Vector<double>       &increment,
                 LinearSolves                                     &solves,
                 const bool keep_best = false);

    /**
     * Newton iterations under displacement control (DisplacementControl)
     * for the system assembled at the last converged load factor: the
     * increment @p increment and the load factor increment @p load_increment
     * such that R_0(x) + d lambda @p loads = 0 and control.value(x) =
     * @p target. Two solves per iteration with the same tangent.
     */
    NewtonSolver::Result
    solve_controlled(const DisplacementControl                  &control,
                     const double                                target,
                     const TrilinosWrappers::MPI::Vector        &loads,
                     LinearAlgebra::distributed::Vector<double> &increment,
                     double                                     &load_increment,
                     LinearSolves                               &solves);

    /**
     * After solve_newton() with keep_best did not converge: puts the iterate
     * with the
     * smallest residual back into @p increment (and the bodies under a
     * force where it had them) and assembles the system there. Returns
     * that residual relative to the largest internal force of the run (or
     * of this state, if larger) when it is at most @p tolerance; else a
     * negative number (the increment is then to be discarded).
     */
    double
    take_best_iterate(
      const double                                      tolerance,
      const LinearAlgebra::distributed::Vector<double> *prescribed,
      LinearAlgebra::distributed::Vector<double>       &increment);

    /** Keeps the converged @p increment of load increment @p delta as the
     * start of the next Newton iterations. */
    void
    accept(const LinearAlgebra::distributed::Vector<double> &increment,
           const double                                      delta);

    /** The next Newton iterations start from zero (a new stage, whose
     * loads change differently). */
    void
    forget_last_increment()
    {
      previous_delta = 0;
    }

    /** What the next load step starts from (the last converged increment,
     * at the grid's vertices so that it does not depend on the processes,
     * its load increment, the residual's scale, and how much of its
     * elastic stiffness the material keeps round each vertex: the support
     * qualities of the next step's system depend on it, ConstitutiveUpdate::
     * support_stiffness_ratios()), for checkpoints. */
    struct Memory
    {
      std::vector<double> at_vertices;
      double              delta                  = 0;
      double              largest_internal_force = 0;
      /** By vertex as at_vertices; empty before the first commit. */
      std::vector<double> stiffness_ratios;

      template <class Archive>
      void
      serialize(Archive &archive, const unsigned int)
      {
        archive &at_vertices &delta &largest_internal_force &stiffness_ratios;
      }
    };

    /** 'Nonlinear solver/Check tangent': the largest relative difference
     * of the tangent times the correction from central differences of the
     * residual along it, over the run's Newton iterations (those whose
     * |K dx| is at least 1e-3 of the increment's first: below, round-off
     * of the differences dominates), and how many were compared. */
    std::pair<double, unsigned int>
    tangent_check() const
    {
      return {largest_tangent_error, n_tangent_checks};
    }

    /** Collective. */
    Memory
    memory() const;

    void
    restore(const Memory &memory);

  private:
    /** 'Nonlinear solver/Check tangent' of the correction @p dx taken at
     * @p before (the tangent and residual there still held). Collective. */
    void
    check_tangent(const LinearAlgebra::distributed::Vector<double> *prescribed,
                  const LinearAlgebra::distributed::Vector<double> &before,
                  const TrilinosWrappers::MPI::Vector              &dx,
                  double &first_product);

    double       largest_tangent_error = 0;
    unsigned int n_tangent_checks      = 0;

    /** Calls @p f(dof, k) for every locally owned DoF at the grid's
     * vertices, k = 2 (vertex index on the uniform grid) + component. */
    template <typename Function>
    void
    for_each_owned_vertex_dof(const Function &f) const;

    Parts        parts;
    TimerOutput &timer;

    /** The last converged increment of a nonlinear material and its load
     * increment: the start of the next Newton iterations. */
    LinearAlgebra::distributed::Vector<double> previous_increment;
    double                                     previous_delta = 0;
    /** The largest |f_int| of the run's Newton systems at zero increment:
     * a floor of the residual's scale. */
    double largest_internal_force = 0;
    /** The iterate of the last solve_newton() with keep_best with the
     * smallest residual
     * |(R, r_c)|, and the places of the bodies under a force there. */
    LinearAlgebra::distributed::Vector<double> best_increment;
    Vector<double>                             best_places;
    double best_norm = std::numeric_limits<double>::infinity();
    /** The moments of the cells whose points may stay elastic, for the
     * points of the increment being solved (prepare_increment()). */
    ConstitutiveUpdate::ElasticCells elastic_cells;

    /** What the Newton systems of an increment share: the points' moments
     * of prepare_elastic_cells(). */
    void
    prepare_increment();

    /** Where solve_newton()'s iterations start. */
    struct NewtonStart
    {
      /** The scale of the tolerance: |R(0)|, but not below a millionth of
       * the largest internal force of the run. */
      double reference = 0;
      /** |R| of the system the assembly holds (that of the start), or -1
       * if it holds another one. */
      double norm = -1;
    };

    /**
     * The predictor of solve_newton() (Nonlinear solver/Predictor,
     * doc/newton.md) for the load increment @p delta: the start
     * @p increment, the bodies' places in @p motion (if any), and the
     * scale of the tolerance.
     */
    NewtonStart
    start_newton(const double                                      delta,
                 const LinearAlgebra::distributed::Vector<double> *prescribed,
                 LinearAlgebra::distributed::Vector<double>       &increment,
                 RigidBodyMotion                                  *motion,
                 const bool                                        keep_best);

    /** Assembles the Newton system at @p increment and returns |(R, r_c)|
     * (r_c the equilibrium of the bodies of @p motion, if any); with
     * @p keep_best, remembers the iterate if it is the best so far. */
    double
    newton_residual(
      const LinearAlgebra::distributed::Vector<double> *prescribed,
      const LinearAlgebra::distributed::Vector<double> &increment,
      const RigidBodyMotion                            *motion,
      const bool                                        keep_best);

    /** Whether the Newton system's tangent is symmetric (the material's,
     * the contact's, and no follower load or support in finite strain). */
    bool
    symmetric_newton_tangent() const;

    /** The last Newton correction of the grid and of the bodies. */
    struct NewtonCorrection
    {
      TrilinosWrappers::MPI::Vector grid;
      Vector<double>                motion;
    };

    /**
     * Solves the Newton system for the correction (with the bodies of
     * @p motion by block elimination), adds it to @p increment and keeps it
     * in @p last; the linear solver may stop refining below @p enough.
     * Returns the size of the correction relative to the increment, and
     * the linear iterations.
     */
    std::pair<double, unsigned int>
    newton_correction(const double                                enough,
                      LinearAlgebra::distributed::Vector<double> &increment,
                      RigidBodyMotion                            *motion,
                      NewtonCorrection                           &last,
                      LinearSolves                               &solves);
  };
} // namespace bsmpm

#endif
