#include <bsmpm/analysis/scene.h>
#include <bsmpm/analysis/strength_reduction.h>
#include <bsmpm/base/parameter_tools.h>
#include <bsmpm/io/error_report.h>
#include <bsmpm/io/input_checks.h>
#include <bsmpm/points/move_diagnosis.h>
#include <bsmpm/verification/error_measures.h>

#include <boost/archive/binary_iarchive.hpp>
#include <boost/archive/binary_oarchive.hpp>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

namespace bsmpm
{
  namespace
  {
    /** The figures of the Newton iterations of one increment, and of their
     * linear solves, into the step's record. */
    void
    record_newton(const IncrementSolver::LinearSolves &solves,
                  const NewtonSolver::Result          &result,
                  RunSummary::Step                    &record)
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



  Scene::Scene(const MPI_Comm communicator)
    : communicator(communicator)
    , pcout(std::cout, Utilities::MPI::this_mpi_process(communicator) == 0)
    // The timer's own communicator is only used for output at destruction,
    // which is off; statistics over processes are printed explicitly.
    , timer(MPI_COMM_SELF, pcout, TimerOutput::never, TimerOutput::wall_times)
    , grid(communicator)
    , points(grid)
    , output(communicator)
    , step_output(output,
                  grid,
                  points,
                  boundary_curves,
                  neumann_loads,
                  implicit_boundary)
    , checkpoint(communicator)
  {}



  void
  Scene::declare_parameters(ParameterHandler &prm)
  {
    prm.declare_entry("Scene name",
                      "",
                      Patterns::Anything(),
                      "Name of the scene in the summary; empty means the "
                      "name of the parameter file.");
    prm.enter_subsection("Loading");
    prm.declare_entry("Load steps",
                      "1",
                      Patterns::Integer(1, 100000),
                      "Number of equal load increments; the load factor of "
                      "step n is n / (load steps). One serves a linear "
                      "elastic scene in small strain; nonlinear materials, "
                      "finite strain and contact want enough steps for each "
                      "increment to converge and to follow the load path (a "
                      "step that does not converge is halved, Nonlinear "
                      "solver/Maximum step cuts). At most 100000.");
    prm.declare_entry("Gravity",
                      "0, 0",
                      ParameterTools::point_pattern(),
                      "Gravitational acceleration in m/s^2; with the "
                      "material density it gives the body force, applied in "
                      "load steps like every other load.");
    prm.leave_subsection();

    SupportReaction::declare_parameters(prm);
    Probe::declare_parameters(prm);

    BackgroundGrid::declare_parameters(prm);
    LinearElasticMaterial::declare_parameters(prm);
    ConstitutiveUpdate::declare_parameters(prm);
    BodyRegion::declare_parameters(prm);
    MaterialPointLayout::declare_parameters(prm);
    BoundaryCurves::declare_parameters(prm);
    NeumannLoads::declare_parameters(prm);
    ImplicitBoundary::declare_parameters(prm);
    NitscheBoundary::declare_parameters(prm);
    CurveContact::declare_parameters(prm);
    GhostPenalty::declare_parameters(prm);
    CutCellQuadrature::declare_parameters(prm);
    LinearSolver::declare_parameters(prm);
    NewtonSolver::declare_parameters(prm);
    CollapseDetector::declare_parameters(prm);
    DisplacementControl::declare_parameters(prm);
    StrengthReduction::declare_parameters(prm);
    ExactSolution::declare_parameters(prm);
    OutputWriter::declare_parameters(prm);
    Checkpoint::declare_parameters(prm);
    Verification::declare_parameters(prm);
  }



  void
  Scene::parse_parameters(ParameterHandler &prm)
  {
    scene_name = prm.get("Scene name");
    prm.enter_subsection("Loading");
    n_load_steps = prm.get_integer("Load steps");
    gravity      = ParameterTools::get_point(prm, "Gravity");
    prm.leave_subsection();

    reactions.parse_parameters(prm);
    probe.parse_parameters(prm);

    grid.parse_parameters(prm);
    material.parse_parameters(prm);
    constitutive_model = create_constitutive_model(prm);
    if (strength_factor != 1.)
      constitutive_model =
        constitutive_model->with_reduced_strength(strength_factor);
    contact.parse_parameters(prm);
    // Contact makes every run nonlinear: Newton iterations decide where the
    // curves touch.
    constitutive_update = ConstitutiveUpdate::create(prm,
                                                     *constitutive_model,
                                                     material,
                                                     contact.enabled());
    linear_b_bar = !constitutive_update && ConstitutiveUpdate::uses_b_bar(prm);
    points.store_inelastic_state(constitutive_update != nullptr);
    run_summary.nonlinear = constitutive_update != nullptr;
    newton.parse_parameters(prm);
    newton.accept_stall(contact.enabled());
    collapse_detector.parse_parameters(prm);
    displacement_control.parse_parameters(prm);
    region.parse_parameters(prm);
    layout.parse_parameters(prm);
    if (this->finite_strain())
      BoundaryCurves::enclose_body_region(prm, region, grid.min_cell_size());
    boundary_curves.parse_parameters(prm);
    neumann_loads.parse_parameters(prm);
    implicit_boundary.parse_parameters(prm);
    nitsche_boundary.parse_parameters(prm);
    ghost_penalty.parse_parameters(prm);
    cut_cell_quadrature.parse_parameters(prm);
    linear_solver.parse_parameters(prm);
    output.parse_parameters(prm);
    checkpoint.parse_parameters(prm);
    verification.parse_parameters(prm);
    exact_solution =
      ExactSolution::create(prm, material, gravity, this->finite_strain());
  }



  void
  Scene::setup()
  {
    {
      TimerOutput::Scope                            t(timer, "setup: checks");
      std::vector<std::pair<std::string, Point<2>>> named;
      if (probe.enabled())
        named.emplace_back("Probe/Point", probe.position());
      InputChecks::check(grid, region, layout, boundary_curves, named);
    }
    {
      TimerOutput::Scope t(timer, "setup: grid");
      output.prepare_directory();
      grid.create(checkpoint.triangulation_file());
    }
    {
      TimerOutput::Scope t(timer, "setup: points");
      // Curves given by positions exist before the material points, which
      // they may trim; curves through material points after them.
      boundary_curves.create_initial_curves(region, grid);
      points.generate(layout, region, [this](const Point<2> &p) {
        return boundary_curves.trims(p);
      });
      std::vector<types::particle_index> tracked;
      if (!boundary_curves.empty())
        tracked = boundary_curves.create_points(points, region);
      if (probe.enabled())
        probe.add_to(points, tracked);
      if (!tracked.empty())
        {
          points.track(tracked);
          boundary_curves.read_initial_positions(points);
        }
      if (checkpoint.resuming())
        {
          // The checkpoint's points replace those generated as at the
          // start, which gave the same ids, slots and initial positions.
          checkpoint.read_points(points);
          if (!tracked.empty())
            points.track(tracked);
        }
      cut_cell_quadrature.initialize(boundary_curves);
    }
    InputChecks::check_supports(grid, boundary_curves, contact.enabled());
    {
      TimerOutput::Scope t(timer, "setup: system");
      assembly = std::make_unique<SystemAssembly>(
        SystemAssembly::Parts{grid,
                              material,
                              boundary_curves,
                              neumann_loads,
                              implicit_boundary,
                              nitsche_boundary,
                              ghost_penalty,
                              exact_solution.get(),
                              gravity,
                              linear_b_bar},
        timer);
      assembly->setup();
      assembly->keep_support_terms(reactions.curves());
      if (contact.enabled())
        {
          assembly->use_contact(&contact);
          step_output.show_contact(contact);
        }
      if (constitutive_update)
        {
          constitutive_update->use_cut_cell_quadrature(
            cut_cell_quadrature.active() ? &cell_moments : nullptr);
          assembly->leave_material_to_points(
            &points, constitutive_update->completes_moments());
          assembly->use_finite_strain(
            constitutive_update->kinematics() ==
            ConstitutiveUpdate::Kinematics::finite_strain);
        }
      increment_solver = std::make_unique<IncrementSolver>(
        IncrementSolver::Parts{grid,
                               *assembly,
                               linear_solver,
                               newton,
                               points,
                               boundary_curves,
                               constitutive_update.get(),
                               contact.enabled() ? &contact : nullptr},
        timer);
      increment.reinit(grid.locally_owned_dofs(),
                       grid.locally_relevant_dofs(),
                       communicator);
    }

    run_summary.scene   = scene_name;
    run_summary.n_cells = grid.triangulation().n_global_active_cells();
    run_summary.n_dofs  = grid.dof_handler().n_dofs();
    run_summary.n_material_points = points.n_global_material_points();
    run_summary.n_tracking_points =
      points.particle_handler().n_global_particles() -
      points.n_global_material_points();
    run_summary.load_steps = n_load_steps;
    if (displacement_control.enabled())
      {
        // What the bordered Newton iterations do not handle is refused here.
        AssertThrow(constitutive_update && !this->finite_strain() &&
                      !boundary_curves.prescribe_displacement() &&
                      !contact.enabled() && !checkpoint.resuming(),
                    ExcMessage(
                      "Loading/Control = displacement needs a nonlinear "
                      "material in small strain, no prescribed "
                      "displacement on the boundary curves, no rigid "
                      "bodies, and no resumed "
                      "checkpoint (the load factor is not in it)."));
        displacement_control.locate(grid);
        pcout << "displacement control at the vertex "
              << displacement_control.vertex() << ", "
              << displacement_control.displacement_increment()
              << " m per step\n";
      }
    else
      // A limit load needs a material that yields (or large deformation):
      // contact alone makes the run nonlinear, but an elastic body in
      // contact has none. Under a rigid body that the load factor moves,
      // the run follows the mechanism (as under a prescribed displacement);
      // under one held or force-controlled, the load factor scales loads.
      collapse_detector.initialize(constitutive_update != nullptr &&
                                     (!constitutive_model->is_linear() ||
                                      finite_strain()),
                                   boundary_curves.prescribe_displacement() ||
                                     contact.moves_bodies_with_load());
  }



  void
  Scene::fit_prescribed_displacement(const double increment_factor)
  {
    TimerOutput::Scope t(timer, "prescribed displacement fit");
    const double       misfit =
      implicit_boundary.fit_prescribed_displacement(boundary_curves,
                                                    grid,
                                                    assembly->kernel(),
                                                    exact_solution.get(),
                                                    increment_factor,
                                                    assembly->fit_matrix(),
                                                    prescribed);
    // The fit is linear in u^a: report the misfit of u^a itself.
    run_summary.quantities["boundary_fit_error"] = misfit / increment_factor;
  }



  void
  Scene::compute_cell_moments()
  {
    TimerOutput::Scope t(timer, "assembly");
    points.compute_cell_moments(cell_moments);
    if (cut_cell_quadrature.active())
      {
        cut_cell_quadrature.correct_cell_moments(points, grid, cell_moments);
        for (const auto &[name, count] : cut_cell_quadrature.statistics())
          run_summary.quantities[name] = count;
      }
    // The cells of the body without points borrow their neighbours'
    // state, across the partition's edges too.
    if (constitutive_update && constitutive_update->completes_moments())
      points.exchange_neighbourhood_state();
  }



  void
  Scene::move_points(const unsigned int step, const double delta)
  {
    TimerOutput::Scope t(timer, "update points");
    const bool         ibm = boundary_curves.has_supports(
      BoundaryCurve::DirichletMethod::implicit_boundary);
    if (ibm)
      {
        band_cells.assign(grid.triangulation().n_active_cells(), false);
        boundary_curves.mark_support_cells(
          grid,
          BoundaryCurve::DirichletMethod::implicit_boundary,
          false,
          band_cells);
      }
    if (!boundary_curves.empty())
      points.set_rigid_increments(boundary_curves.rigid_support_increments(
        points.n_tracked(), exact_solution.get(), delta));
    const auto report = points.move(
      assembly->kernel(),
      material,
      increment,
      has_prescribed ? &prescribed : nullptr,
      ibm ? &band_cells : nullptr,
      [this](const Point<2>                                      &x,
             const std::function<Tensor<1, 2>(const Point<2> &)> &field,
             Tensor<1, 2>                                        &w) {
        return implicit_boundary.support_displacement(
          boundary_curves, grid, x, field, w);
      },
      &cell_quality,
      /*update_stress=*/constitutive_update == nullptr,
      /*update_strain=*/!constitutive_update ||
        constitutive_update->kinematics() ==
          ConstitutiveUpdate::Kinematics::small_strain,
      &cell_moments);
    run_summary.quantities["max_displacement"] = report.max_displacement;
    run_summary.quantities["max_stress"]       = report.max_stress;
    if (report.n_left_grid > 0)
      AssertThrow(false,
                  ExcMessage(
                    MoveDiagnosis::message(report,
                                           step,
                                           grid,
                                           ghost_penalty.quality_threshold(),
                                           ghost_penalty.enabled())));
  }



  void
  Scene::update_curves(const unsigned int step)
  {
    if (boundary_curves.empty())
      return;
    TimerOutput::Scope t(timer, "curves");
    try
      {
        boundary_curves.update(points, grid);
        // Points where the moved curves stretched or crowded, on the
        // splines through the moved points, then the splines through the
        // new chains.
        if (step > 0)
          {
            const auto origins =
              boundary_curves.adapt_point_spacing(points, grid);
            if (std::any_of(origins.begin(), origins.end(), [](const auto &o) {
                  return !o.empty();
                }))
              {
                boundary_curves.update(points, grid);
                if (contact.enabled())
                  contact.follow_point_changes(origins);
              }
            boundary_curves.check_touching(grid.min_cell_size());
          }
      }
    catch (const ExceptionBase &e)
      {
        // The curves were fine the step before: say which step broke them.
        AssertThrow(step == 0,
                    ExcMessage("Load step " + std::to_string(step) +
                               ", after the points moved: " + message_of(e)));
        throw;
      }
    cut_cell_quadrature.update_geometry(boundary_curves, grid);
  }



  void
  Scene::write_output(const unsigned int step, const double load_factor)
  {
    TimerOutput::Scope        t(timer, "output");
    const std::vector<double> fractions =
      cut_cell_quadrature.fill_fractions(grid, cell_moments);
    step_output.write(step,
                      load_factor,
                      increment,
                      fractions,
                      cell_moments.empty() ?
                        std::vector<double>(fractions.size()) :
                        assembly->support_qualities(cell_moments,
                                                    constitutive_update.get()));
  }



  void
  Scene::evaluate_errors()
  {
    TimerOutput::Scope t(timer, "errors");
    run_summary.errors =
      compute_errors(points, *exact_solution, communicator, finite_strain());
    if (const auto lame =
          dynamic_cast<const LameCylinder *>(exact_solution.get()))
      {
        std::vector<BoundaryArc> arcs;
        for (const auto &curve : boundary_curves.get_curves())
          arcs.push_back({curve.initial_positions, *curve.spline});
        for (const auto &[name, value] : compute_radius_errors(arcs, *lame))
          run_summary.quantities[name] = value;
      }
  }



  void
  Scene::run()
  {
    total_timer.restart();
    setup();
    if (pcout.is_active())
      run_summary.print_header(pcout.get_stream());
    if (exact_solution && pcout.is_active())
      pcout << "exact solution     " << exact_solution->description() << '\n';

    unsigned int first_step = 1;
    if (checkpoint.resuming())
      {
        std::vector<CellId> weak_cells;
        first_step = checkpoint.read_state(run_summary, output, weak_cells) + 1;
        // The curves and the tracked list are rebuilt as at the start,
        // which no longer matches points that were inserted or removed
        // (their records begin with the first change).
        for (const auto &record : run_summary.steps)
          AssertThrow(record.quantities.count("curve1_points") == 0,
                      ExcMessage(
                        "This checkpoint cannot be resumed: the boundary "
                        "curves gained or lost tracking points before it "
                        "(from load step " +
                        std::to_string(record.number) +
                        "), and a resumed run rebuilds the curves as they "
                        "were at the start. Resume from an earlier "
                        "checkpoint, or run with 'Boundary curves/Point "
                        "spacing/Adapt = false'."));
        assembly->restore_matrix(weak_cells);
        // Checkpoints of earlier versions have no such state: resumed,
        // their next step starts from zero; with rigid bodies they are
        // refused (the friction history is not in them).
        const std::string state = checkpoint.read_scene_state();
        AssertThrow(!state.empty() || !contact.enabled(),
                    ExcMessage("This checkpoint has no contact state "
                               "(written by a version of bsmpm that did "
                               "not keep it): a run with rigid bodies "
                               "cannot resume from it."));
        if (!state.empty())
          {
            std::istringstream              in(state);
            boost::archive::binary_iarchive archive(in);
            IncrementSolver::Memory         memory;
            archive >> memory >> collapse_detector;
            increment_solver->restore(memory);
            if (contact.enabled())
              archive >> contact;
          }
      }
    if (pcout.is_active())
      for (const auto &record : run_summary.steps)
        run_summary.print_step(pcout.get_stream(), record);
    update_curves(0);
    if (output.enabled() && first_step == 1)
      write_output(0, 0.);

    points_moved      = first_step > 1;
    unsigned int step = first_step;
    try
      {
        for (; step <= n_load_steps; ++step)
          {
            const double     load_factor = double(step) / n_load_steps;
            RunSummary::Step record;
            record.number = step;
            if (displacement_control.enabled())
              advance_under_displacement_control(step, record);
            else
              advance(step,
                      double(step - 1) / n_load_steps,
                      load_factor,
                      record);
            const bool collapsed = collapse_detector.collapsed();
            // A step that collapsed before any increment converged leaves
            // the body as the step before: nothing to record.
            if (!collapsed || record.increments > 0)
              {
                record_quantities(record);
                record.quantities = run_summary.quantities;
                run_summary.record_step(record, output, pcout);
                if (output.writes_step(step, n_load_steps) ||
                    (collapsed && output.enabled()))
                  write_output(step, record.load_factor);
                if (checkpoint.writes_step(step, n_load_steps))
                  write_checkpoint(step);
              }
            if (collapsed)
              {
                collapse_detector.record(run_summary.quantities);
                run_summary.limit_load_reason = collapse_detector.reason();
                pcout << "\nLimit load reached: limit load factor "
                      << collapse_detector.limit_load_factor() << " ("
                      << collapse_detector.reason()
                      << "). The run stops here; summary.json gives "
                         "limit_load_factor and its bracket.\n";
                break;
              }
          }

        if (exact_solution)
          evaluate_errors();
        report_stalled_increments();
        run_summary.finish(verification,
                           output,
                           timer,
                           total_timer.wall_time(),
                           pcout,
                           communicator);
      }
    catch (const ExceptionBase &e)
      {
        // The record of the steps done survives the error (main reports it).
        run_summary.record_failure(step, message_of(e), output);
        throw;
      }
    catch (const std::exception &e)
      {
        run_summary.record_failure(step, e.what(), output);
        throw;
      }
  }



  void
  Scene::report_stalled_increments()
  {
    // Said at the end as well as in the table: the answer of such a run
    // holds to that residual, not to the Newton tolerance.
    unsigned int n       = 0;
    double       largest = 0;
    for (const auto &s : run_summary.steps)
      {
        n += s.stalled_increments;
        largest = std::max(largest, s.stalled_residual);
      }
    if (n == 0)
      return;
    run_summary.quantities["stalled_increments"]   = n;
    run_summary.quantities["stalled_residual_max"] = largest;
    pcout << "\nNote: " << n
          << " load increment(s) did not converge in their last cut and took "
             "their best iterate (Nonlinear solver/Stall tolerance), the "
             "largest residual "
          << std::setprecision(2) << largest << std::setprecision(6)
          << " of the largest internal force: see the step table.\n";
  }



  void
  Scene::record_quantities(const RunSummary::Step &record)
  {
    if (probe.enabled())
      probe.record(points, run_summary.quantities);
    if (!reactions.curves().empty())
      {
        TimerOutput::Scope t(timer, "reactions");
        reactions.record(
          grid,
          [this](const unsigned int c) {
            return assembly->support_forces(c, increment);
          },
          run_summary.quantities);
      }
    if (boundary_curves.has_loads())
      {
        // Under displacement control the last assemble() had the load
        // factor of the step's start.
        const Tensor<1, 2> force =
          displacement_control.enabled() ?
            controlled_load_factor * unit_traction_resultant :
            neumann_loads.resultant(communicator);
        run_summary.quantities["traction_resultant_x"] = force[0];
        run_summary.quantities["traction_resultant_y"] = force[1];
      }

    if (constitutive_update)
      run_summary.quantities["yielded_points"] = record.n_yielded;
    contact.record(run_summary.quantities);
    boundary_curves.record_point_changes(run_summary.quantities);
    collapse_detector.record(run_summary.quantities);
  }



  void
  Scene::advance(const unsigned int step,
                 const double       from,
                 const double       to,
                 RunSummary::Step  &record)
  {
    double       lambda = from;
    double       delta  = to - from;
    unsigned int cuts   = 0;
    record.increments   = 0;
    while (lambda < to - 1e-12 * (to - from))
      {
        delta = std::min(delta, to - lambda);
        if (points_moved)
          {
            TimerOutput::Scope t(timer, "sort points");
            points.sort_into_cells();
            points_moved = false;
          }
        compute_cell_moments();
        assembly->make_constraints(cell_moments);
        has_prescribed =
          implicit_boundary.fits_prescribed_displacement(boundary_curves);
        if (has_prescribed)
          fit_prescribed_displacement(delta);
        cell_quality =
          assembly->support_qualities(cell_moments, constitutive_update.get());
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
        assembly->assemble(lambda + delta,
                           delta,
                           cell_moments,
                           cell_quality,
                           has_prescribed ? &prescribed : nullptr);
        if (linear_solver.estimates_condition() &&
            assembly->rhs().l2_norm() > 0)
          {
            TimerOutput::Scope t(timer, "condition estimate");
            const double       estimate =
              linear_solver.estimate_condition_number(assembly->matrix(),
                                                      assembly->rhs());
            double &largest = run_summary.quantities["condition_estimate"];
            largest         = std::max(largest, estimate);
          }
        if (contact.enabled())
          {
            contact.begin_increment(boundary_curves,
                                    grid,
                                    material.penalty_modulus(),
                                    lambda,
                                    lambda + delta);
            // A body under a force moved to touch before the iterations.
            const std::string note = contact.motion().take_notes();
            if (!note.empty())
              pcout << "       load " << lambda << " + " << delta << ": "
                    << note << '\n';
          }
        if (constitutive_update)
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
            const auto report = increment_solver->solve_linear(step, increment);
            record.solver     = report.method;
            record.iterations = report.iterations;
            record.refinement_steps  = report.refinement_steps;
            record.relative_residual = report.relative_residual;
          }
        record.n_active_cells = assembly->n_active_cells();
        // The increment's size per unit load, before the points take it.
        const bool collapsed = collapse_detector.converged_increment(
          step, lambda, delta, increment.linfty_norm());
        if (contact.enabled())
          contact.finish_increment(boundary_curves,
                                   grid,
                                   assembly->kernel(),
                                   increment,
                                   has_prescribed ? &prescribed : nullptr);
        move_points(step, delta);
        points_moved = true;
        update_curves(step);
        lambda += delta;
        ++record.increments;
        if (collapsed)
          break;
      }
    // The step's own factor where it finished (the sum of cut increments
    // may differ from it in the last bits).
    record.load_factor = collapse_detector.collapsed() ? lambda : to;
  }



  void
  Scene::advance_under_displacement_control(const unsigned int step,
                                            RunSummary::Step  &record)
  {
    const double step_increment = displacement_control.displacement_increment();
    double       done           = 0;
    double       portion        = step_increment;
    unsigned int cuts           = 0;
    record.increments           = 0;
    while (done < step_increment * (1 - 1e-12))
      {
        portion = std::min(portion, step_increment - done);
        if (points_moved)
          {
            TimerOutput::Scope t(timer, "sort points");
            points.sort_into_cells();
            points_moved = false;
          }
        compute_cell_moments();
        assembly->make_constraints(cell_moments);
        has_prescribed = false;
        cell_quality =
          assembly->support_qualities(cell_moments, constitutive_update.get());
        if (cuts > 0)
          {
            const double factor = std::pow(10., std::min(cuts, 2u));
            for (auto &q : cell_quality)
              if (q > 0)
                q /= factor;
          }
        // The loads of load factor 1, then the system at the load factor
        // reached: the load increment is the Newton iterations' unknown.
        assembly->reference_loads(cell_moments, reference_loads);
        if (boundary_curves.has_loads())
          unit_traction_resultant = neumann_loads.resultant(communicator);
        assembly->assemble(
          controlled_load_factor, 0., cell_moments, cell_quality, nullptr);
        assembly->check_loads_finite(step);
        constitutive_update->set_body_force(controlled_load_factor *
                                            material.density() * gravity);

        IncrementSolver::LinearSolves solves;
        double                        load_increment = 0;
        const NewtonSolver::Result    result =
          increment_solver->solve_controlled(displacement_control,
                                             portion,
                                             reference_loads,
                                             increment,
                                             load_increment,
                                             solves);
        record_newton(solves, result, record);
        if (!result.converged)
          {
            newton.report_failure(result,
                                  step,
                                  controlled_load_factor,
                                  load_increment,
                                  cuts,
                                  pcout.is_active() ? &pcout.get_stream() :
                                                      nullptr);
            ++cuts;
            portion /= 2;
            continue;
          }
        {
          TimerOutput::Scope t(timer, "update points");
          record.n_yielded = constitutive_update->commit(
            points, grid, assembly->kernel(), increment, nullptr);
        }
        record.n_active_cells = assembly->n_active_cells();
        move_points(step, load_increment);
        points_moved = true;
        update_curves(step);
        controlled_load_factor += load_increment;
        done += portion;
        ++record.increments;
      }
    record.load_factor = controlled_load_factor;
  }



  bool
  Scene::solve_nonlinear(const unsigned int step,
                         const double       lambda,
                         const double       delta,
                         const unsigned int cuts,
                         RunSummary::Step  &record)
  {
    assembly->check_loads_finite(step);
    constitutive_update->set_body_force((lambda + delta) * material.density() *
                                        gravity);
    IncrementSolver::LinearSolves solves;
    NewtonSolver::Result          result;
    // The last cut that may still cycle (doc/newton.md, "Stalled
    // increments"): its best iterate, if close enough, rather than a
    // failed run. Under load control such a step is the limit load.
    const bool may_stall =
      !collapse_detector.active() && cuts >= newton.max_step_cuts();
    try
      {
        result =
          increment_solver->solve_newton(delta,
                                         has_prescribed ? &prescribed : nullptr,
                                         increment,
                                         solves,
                                         may_stall);
      }
    catch (const ExceptionBase &e)
      {
        // A tangent that the linear solver finds singular after the first
        // step is a body whose plastic points leave a mechanism free (at
        // or beyond the limit load): a failed increment, to be cut. Before
        // anything converged it is a missing support: the error stands.
        if (!collapse_detector.active() || step == 1)
          throw;
        result.converged = false;
        result.failure   = "the linear solve failed: " + message_of(e);
      }
    record_newton(solves, result, record);
    // The residual an accepted iterate leaves is part of the next
    // increment's.
    if (!result.converged && may_stall)
      {
        const double ratio =
          increment_solver->take_best_iterate(newton.stall_tolerance(),
                                              has_prescribed ? &prescribed :
                                                               nullptr,
                                              increment);
        if (ratio >= 0)
          {
            newton.log_failure(result,
                               lambda,
                               delta,
                               pcout.is_active() ? &pcout.get_stream() :
                                                   nullptr);
            pcout << "       load " << lambda << " + " << delta
                  << ": accepted the best iterate, |R| = "
                  << std::setprecision(2) << ratio << std::setprecision(6)
                  << " of the largest internal force (Nonlinear "
                     "solver/Stall tolerance)\n";
            ++record.stalled_increments;
            record.stalled_residual = std::max(record.stalled_residual, ratio);
            result.converged        = true;
          }
      }
    if (!result.converged)
      {
        // Under load control a step that cannot be converged however far it
        // is cut is the limit load (CollapseDetector), not an error.
        if (collapse_detector.active() && cuts >= newton.max_step_cuts())
          {
            newton.log_failure(result,
                               lambda,
                               delta,
                               pcout.is_active() ? &pcout.get_stream() :
                                                   nullptr);
            collapse_detector.failed_increment(step,
                                               lambda,
                                               delta,
                                               result.failure);
            return false;
          }
        newton.report_failure(
          result,
          step,
          lambda,
          delta,
          cuts,
          pcout.is_active() ? &pcout.get_stream() : nullptr,
          contact.enabled() ?
            " With rigid bodies: a body that only friction holds has no "
            "quasi-static equilibrium once it slides (on an incline steeper "
            "than its friction angle); hold it, or move the rigid body "
            "instead." :
            "");
        return false;
      }
    TimerOutput::Scope t(timer, "update points");
    increment_solver->accept(increment, delta);
    record.n_yielded =
      constitutive_update->commit(points,
                                  grid,
                                  assembly->kernel(),
                                  increment,
                                  has_prescribed ? &prescribed : nullptr);
    return true;
  }



  void
  Scene::write_checkpoint(const unsigned int step)
  {
    RunSummary so_far = run_summary;
    so_far.add_timing(timer, total_timer.wall_time());
    TimerOutput::Scope t(timer, "checkpoint");
    // Where the next step's Newton iterations start, and the contact's
    // state (the same on every process).
    std::ostringstream scene_state;
    {
      const IncrementSolver::Memory   memory = increment_solver->memory();
      boost::archive::binary_oarchive archive(scene_state);
      archive << memory << collapse_detector;
      if (contact.enabled())
        archive << contact;
    }
    checkpoint.write(step,
                     grid,
                     points,
                     so_far,
                     output,
                     assembly->weak_cells_of_last_matrix(),
                     scene_state.str());
  }
} // namespace bsmpm
