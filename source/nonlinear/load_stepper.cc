#include <bsmpm/base/exception_message.h>
#include <bsmpm/contact/rigid_body_motion.h>
#include <bsmpm/nonlinear/load_stepper.h>

#include <algorithm>
#include <cmath>
#include <iomanip>

namespace bsmpm
{
  namespace
  {
    /** The figures of the Newton iterations of one increment, and of their
     * linear solves, into the step's record. */
    void
    record_newton_iterations(const IncrementSolver::LinearSolves &solves,
                             const NewtonSolver::Result          &result,
                             LoadStepRecord                      &record)
    {
      if (solves.n_solves > 0)
        {
          record.solver            = solves.method;
          record.relative_residual = solves.relative_residual;
        }
      record.iterations = solves.iterations;
      record.refinement_steps += solves.refinement_steps;
      for (const auto &iteration : result.iterations)
        {
          record.newton_residuals.push_back(iteration.relative_residual);
          record.newton_corrections.push_back(iteration.relative_correction);
        }
    }
  } // namespace



  LoadStepper::LoadStepper(const Parts                   &parts,
                           const Phases                  &phases,
                           TimerOutput                   &timer,
                           ConditionalOStream            &pcout,
                           std::map<std::string, double> &quantities)
    : parts(parts)
    , phases(phases)
    , timer(timer)
    , pcout(pcout)
    , quantities(quantities)
  {}



  void
  LoadStepper::initialize(const bool may_yield, const bool resuming)
  {
    const bool nonlinear = parts.constitutive_update != nullptr;
    if (parts.displacement_control.enabled())
      {
        // What the bordered Newton iterations do not handle is refused here.
        AssertThrow(
          nonlinear &&
            parts.constitutive_update->kinematics() ==
              ConstitutiveUpdate::Kinematics::small_strain &&
            !parts.curves.prescribe_displacement() &&
            parts.contact == nullptr && !resuming &&
            parts.stages.stage(parts.stages.n_stages()).excavation.empty() &&
            parts.curves.loads_proportional(),
          ExcMessage("Loading/Control = displacement needs a nonlinear "
                     "material in small strain, no prescribed "
                     "displacement on the boundary curves, no rigid "
                     "bodies, no load given as an expression of t, no "
                     "excavation in the last stage (the stage it controls) "
                     "and no resumed "
                     "checkpoint (the load factor is not in it)."));
        parts.displacement_control.locate(parts.grid);
        pcout << "displacement control at the vertex "
              << parts.displacement_control.vertex() << ", "
              << parts.displacement_control.displacement_increment()
              << " m per step"
              << (parts.stages.staged() ? " in the last stage" : "") << "\n";
      }
    // A limit load needs a material that yields: contact or finite strain
    // alone make the run nonlinear, but an elastic body has no strength,
    // and a step it cannot take is a failure, not a limit load. Under a
    // rigid body that the load factor moves, the run follows the mechanism
    // (as under a prescribed displacement); under one held or
    // force-controlled, the load factor scales loads.
    begin_stage(1, may_yield);
  }



  bool
  LoadStepper::controls_displacement(const unsigned int k) const
  {
    return parts.displacement_control.enabled() && k == parts.stages.n_stages();
  }



  void
  LoadStepper::begin_stage(const unsigned int k, const bool may_yield)
  {
    stage_may_yield = may_yield;
    stage           = k;
    // The predictions from the last increment belong to another load.
    if (k > 1)
      parts.increment_solver.forget_last_increment();
    if (controls_displacement(k))
      {
        // The stage's load factor is the bordered iterations' unknown,
        // from the stage's start on.
        controlled_load_factor = k - 1.;
        return;
      }
    // Under a prescribed displacement, or a rigid body that the load
    // factor moves, the stage follows the mechanism; a stage that leaves
    // them where they are (the ground's weight) has loads that can
    // collapse.
    const bool moves_supports =
      parts.stages.level(k - 1.).loads != parts.stages.level(k).loads &&
      (parts.curves.prescribe_displacement() ||
       (parts.contact != nullptr && parts.contact->moves_bodies_with_load()));
    parts.collapse_detector.initialize(parts.constitutive_update != nullptr &&
                                         may_yield,
                                       moves_supports,
                                       parts.stages.stage(k).detect_collapse,
                                       k - 1.);
  }



  const std::vector<CellMoments> &
  LoadStepper::prepare_increment(const unsigned int cuts, const double tau)
  {
    const std::vector<CellMoments> &moments = phases.cell_moments(tau);
    parts.assembly.make_constraints(moments);
    cell_quality =
      parts.assembly.support_qualities(moments, parts.constitutive_update);
    // A Newton failure that cutting the increment does not cure comes
    // from a mechanism that the stabilisation leaves free: perfectly
    // plastic points at their limit, driven by the imbalance that the
    // new quadrature of the moved points leaves (doc/newton.md). Every
    // cut of the increment therefore also lowers the qualities ten times
    // (the ghost penalty's threshold raised ten times), at most a
    // hundred times, for the rest of the step.
    if (cuts > 0)
      {
        const double factor = std::pow(10., std::min(cuts, 2u));
        for (auto &q : cell_quality)
          if (q > 0)
            q /= factor;
      }
    return moments;
  }



  void
  LoadStepper::advance(const unsigned int step,
                       const double       from,
                       const double       to,
                       LoadStepRecord    &record)
  {
    SystemAssembly   &assembly          = parts.assembly;
    CollapseDetector &collapse_detector = parts.collapse_detector;
    double            lambda            = from;
    double            delta             = to - from;
    unsigned int      cuts              = 0;
    record.increments                   = 0;
    while (lambda < to - 1e-12 * (to - from))
      {
        delta = std::min(delta, to - lambda);
        const std::vector<CellMoments> &moments =
          prepare_increment(cuts, lambda + delta);
        const LoadLevel end = parts.stages.level(lambda + delta);
        // The prescribed displacements change with the loads multiplier
        // (not in a stage that keeps it, such as the ground's weight alone).
        const LoadIncrement load_increment{parts.stages.level(lambda).loads,
                                           end.loads};
        if (assembly.fits_prescribed_displacement())
          {
            const double misfit =
              assembly.fit_prescribed_displacement(load_increment);
            // The fit is linear in u^a: the misfit of u^a itself.
            if (load_increment.share() != 0)
              quantities["boundary_fit_error"] =
                misfit / std::abs(load_increment.share());
          }
        assembly.assemble(end, load_increment, moments, cell_quality);
        if (parts.linear_solver.estimates_condition() &&
            assembly.rhs().l2_norm() > 0)
          {
            TimerOutput::Scope t(timer, "condition estimate");
            const double       estimate =
              parts.linear_solver.estimate_condition_number(assembly.matrix(),
                                                            assembly.rhs());
            double &largest = quantities["condition_estimate"];
            largest         = std::max(largest, estimate);
          }
        if (parts.contact != nullptr)
          begin_contact(lambda, delta);
        if (parts.constitutive_update)
          {
            if (!solve_nonlinear(step, lambda, delta, cuts, record))
              {
                if (collapse_detector.collapsed())
                  break;
                ++cuts;
                delta /= 2;
                continue;
              }
          }
        else
          {
            const auto report =
              parts.increment_solver.solve_linear(step, parts.increment);
            record.solver            = report.method;
            record.iterations        = report.iterations;
            record.refinement_steps  = report.refinement_steps;
            record.relative_residual = report.relative_residual;
          }
        record.n_active_cells = assembly.n_active_cells();
        // The increment's size per unit load, before the points take it.
        const bool collapsed = collapse_detector.converged_increment(
          step, lambda, delta, parts.increment.linfty_norm());
        if (collapsed)
          {
            // A mechanism: at the limit load its size is arbitrary (and may
            // carry the points off the grid), so the body stays where the
            // last increment left it; the grid's output shows the
            // increment.
            ++record.increments;
            break;
          }
        if (parts.contact != nullptr)
          {
            parts.contact->finish_increment(parts.curves,
                                            parts.grid,
                                            assembly.kernel(),
                                            parts.increment,
                                            assembly.prescribed_displacement());
            // What the contact's solves left open (pressures that did not
            // converge).
            const std::string note = parts.contact->motion().take_notes();
            if (!note.empty())
              pcout << "       load " << lambda << " + " << delta << ": "
                    << note << '\n';
          }
        phases.move(step, load_increment);
        lambda += delta;
        ++record.increments;
      }
    // The step's own factor where it finished (the sum of cut increments
    // may differ from it in the last bits).
    record.load_factor = collapse_detector.collapsed() ? lambda : to;
    record_tangent_check();
  }



  void
  LoadStepper::out_of_balance(const double                   tau,
                              TrilinosWrappers::MPI::Vector &balance)
  {
    SystemAssembly                 &assembly = parts.assembly;
    const std::vector<CellMoments> &moments  = prepare_increment(0, tau);
    const LoadLevel                 level    = parts.stages.level(tau);
    const LoadIncrement             none{level.loads, level.loads};
    if (assembly.fits_prescribed_displacement())
      assembly.fit_prescribed_displacement(none);
    assembly.assemble(level, none, moments, cell_quality);
    if (parts.constitutive_update == nullptr)
      {
        balance = assembly.rhs();
        return;
      }
    if (parts.contact != nullptr)
      begin_contact(tau, 0.);
    parts.constitutive_update->set_body_force(level.gravity, parts.gravity);
    parts.increment = 0;
    parts.increment.update_ghost_values();
    assembly.newton_system(*parts.constitutive_update,
                           parts.points,
                           parts.increment,
                           assembly.prescribed_displacement());
    balance = assembly.residual();
  }



  void
  LoadStepper::begin_contact(const double lambda, const double delta)
  {
    parts.contact->begin_increment(parts.curves,
                                   parts.grid,
                                   parts.material.penalty_modulus(),
                                   parts.stages.level(lambda).loads,
                                   parts.stages.level(lambda + delta).loads);
    // A body under a force moved to touch before the iterations.
    const std::string note = parts.contact->motion().take_notes();
    if (!note.empty())
      pcout << "       load " << lambda << " + " << delta << ": " << note
            << '\n';
  }



  void
  LoadStepper::advance_under_displacement_control(const unsigned int step,
                                                  LoadStepRecord    &record)
  {
    SystemAssembly &assembly = parts.assembly;
    const double    step_increment =
      parts.displacement_control.displacement_increment();
    double       done    = 0;
    double       portion = step_increment;
    unsigned int cuts    = 0;
    record.increments    = 0;
    while (done < step_increment * (1 - 1e-12))
      {
        portion = std::min(portion, step_increment - done);
        // (No body is built under displacement control: the load factor
        // is the iterations' unknown.)
        const std::vector<CellMoments> &moments =
          prepare_increment(cuts, controlled_load_factor);
        // The loads of load factor 1, then the system at the load factor
        // reached: the load increment is the Newton iterations' unknown.
        assembly.reference_loads(moments,
                                 parts.stages.slope(parts.stages.n_stages()),
                                 reference_loads);
        if (parts.curves.has_loads())
          unit_traction_resultant =
            parts.neumann_loads.resultant(parts.grid.mpi_communicator());
        const LoadLevel level = parts.stages.level(controlled_load_factor);
        assembly.assemble(level,
                          LoadIncrement{level.loads, level.loads},
                          moments,
                          cell_quality);
        assembly.check_loads_finite(step);
        parts.constitutive_update->set_body_force(level.gravity, parts.gravity);

        IncrementSolver::LinearSolves solves;
        double                        load_increment = 0;
        const NewtonSolver::Result    result =
          parts.increment_solver.solve_controlled(parts.displacement_control,
                                                  portion,
                                                  reference_loads,
                                                  parts.increment,
                                                  load_increment,
                                                  solves);
        record_newton_iterations(solves, result, record);
        if (!result.converged)
          {
            parts.newton.report_failure(result,
                                        step,
                                        controlled_load_factor,
                                        load_increment,
                                        cuts,
                                        log());
            ++cuts;
            portion /= 2;
            continue;
          }
        {
          TimerOutput::Scope t(timer, "update points");
          record.n_yielded =
            parts.constitutive_update->commit(parts.points,
                                              parts.grid,
                                              assembly.kernel(),
                                              parts.increment,
                                              nullptr);
        }
        record.n_active_cells = assembly.n_active_cells();
        phases.move(step, LoadIncrement{level.loads, level.loads});
        controlled_load_factor += load_increment;
        done += portion;
        ++record.increments;
      }
    record.load_factor = controlled_load_factor;
    record_tangent_check();
  }



  void
  LoadStepper::record_tangent_check()
  {
    if (!parts.newton.checks_tangent())
      return;
    const auto [error, checks]         = parts.increment_solver.tangent_check();
    quantities["newton_tangent_error"] = error;
    quantities["newton_tangent_checks"] = checks;
  }



  bool
  LoadStepper::solve_nonlinear(const unsigned int step,
                               const double       lambda,
                               const double       delta,
                               const unsigned int cuts,
                               LoadStepRecord    &record)
  {
    const CollapseDetector &collapse_detector = parts.collapse_detector;
    const NewtonSolver     &newton            = parts.newton;
    parts.assembly.check_loads_finite(step);
    parts.constitutive_update->set_body_force(
      parts.stages.level(lambda + delta).gravity, parts.gravity);
    IncrementSolver::LinearSolves solves;
    NewtonSolver::Result          result;
    // The last cut that may still cycle (doc/newton.md, "Stalled
    // increments"): its best iterate, if close enough, rather than a
    // failed run. Under load control such a step is the limit load.
    const bool may_stall =
      !collapse_detector.active() && cuts >= newton.max_step_cuts();
    try
      {
        result = parts.increment_solver.solve_newton(
          delta,
          parts.assembly.prescribed_displacement(),
          parts.increment,
          solves,
          may_stall);
      }
    catch (const ExceptionBase &e)
      {
        // A tangent that the linear solver finds singular once a Newton
        // correction of the run has been solved is a body whose plastic
        // points leave a mechanism free (at or beyond the limit load, also
        // within the first step): a failed increment, to be cut. The run's
        // very first system singular (with a rigid body's motion: a body
        // that nothing holds) is a missing support: the error stands.
        // A rigid body's force-controlled motion that no contact resists in
        // the first step is the input's (a force that pulls it off).
        const bool first =
          dynamic_cast<const ExcUnresistedMotion *>(&e) != nullptr ?
            step == 1 :
            step == 1 && record.increments == 0 && cuts == 0 &&
              solves.n_corrections == 0;
        if (!collapse_detector.active() || first)
          throw;
        result.converged = false;
        result.failure   = "the linear solve failed: " + message_of(e);
      }
    record_newton_iterations(solves, result, record);
    // The residual an accepted iterate leaves is part of the next
    // increment's.
    if (!result.converged && may_stall)
      result.converged = accept_stalled(result, lambda, delta, record);
    if (!result.converged)
      {
        // Under load control a step that cannot be converged however far it
        // is cut is the limit load (CollapseDetector), not an error; unless
        // its residual is not even finite: that is a numerical failure (a
        // singular system), whatever the material.
        if (collapse_detector.active() && cuts >= newton.max_step_cuts() &&
            !result.not_finite)
          {
            newton.log_failure(result, lambda, delta, log());
            parts.collapse_detector.failed_increment(step,
                                                     lambda,
                                                     delta,
                                                     result.failure);
            return false;
          }
        newton.report_failure(result,
                              step,
                              lambda,
                              delta,
                              cuts,
                              log(),
                              parts.contact != nullptr &&
                                  cuts >= newton.max_step_cuts() ?
                                friction_hint(lambda + delta) :
                                "");
        return false;
      }
    TimerOutput::Scope t(timer, "update points");
    parts.increment_solver.accept(parts.increment, delta);
    record.n_yielded = parts.constitutive_update->commit(
      parts.points,
      parts.grid,
      parts.assembly.kernel(),
      parts.increment,
      parts.assembly.prescribed_displacement());
    return true;
  }



  bool
  LoadStepper::accept_stalled(const NewtonSolver::Result &result,
                              const double                lambda,
                              const double                delta,
                              LoadStepRecord             &record)
  {
    const double ratio = parts.increment_solver.take_best_iterate(
      parts.newton.stall_tolerance(),
      parts.assembly.prescribed_displacement(),
      parts.increment);
    if (ratio < 0)
      return false;
    parts.newton.log_failure(result, lambda, delta, log());
    pcout << "       load " << lambda << " + " << delta
          << ": accepted the best iterate, |R| = " << std::setprecision(2)
          << ratio << std::setprecision(6)
          << " of the largest internal force (Nonlinear "
             "solver/Stall tolerance)\n";
    ++record.stalled_increments;
    record.stalled_residual = std::max(record.stalled_residual, ratio);
    return true;
  }



  std::string
  LoadStepper::friction_hint(const double load_factor) const
  {
    // A body that nothing but contact holds (InputChecks::check_supports())
    // must rest on the rigid bodies under its own loads.
    const bool supported =
      parts.grid.has_face_conditions() || parts.curves.has_supports();
    const Tensor<1, 2> load = parts.stages.level(load_factor).gravity *
                                parts.points.global_mass() * parts.gravity +
                              traction_resultant();
    return parts.contact->friction_hint(parts.grid,
                                        supported ? nullptr : &load);
  }



  Tensor<1, 2>
  LoadStepper::traction_resultant() const
  {
    // Under displacement control the last assemble() had the load factor
    // of the step's start.
    return controls_displacement(stage) ?
             parts.stages.level(controlled_load_factor).loads *
               unit_traction_resultant :
             parts.neumann_loads.resultant(parts.grid.mpi_communicator());
  }
} // namespace bsmpm
