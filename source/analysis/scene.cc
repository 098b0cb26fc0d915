#include <bsmpm/analysis/scene.h>
#include <bsmpm/analysis/strength_reduction.h>
#include <bsmpm/base/parameter_tools.h>
#include <bsmpm/io/error_report.h>
#include <bsmpm/io/input_checks.h>
#include <bsmpm/points/move_diagnosis.h>
#include <bsmpm/verification/error_measures.h>

#include <algorithm>

namespace bsmpm
{
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
                  supports)
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
                      "solver/Maximum step cuts). At most 100000. A scene "
                      "in stages gives each stage its own (Stages).");
    prm.declare_entry("Gravity",
                      "0, 0",
                      ParameterTools::point_pattern(),
                      "Gravitational acceleration in m/s^2; with the "
                      "material density it gives the body force, applied in "
                      "load steps like every other load (in a scene in "
                      "stages, by each stage's Gravity factor; with an "
                      "initial stress, from the start).");
    prm.leave_subsection();
    LoadStages::declare_parameters(prm);
    InitialStress::declare_parameters(prm);

    SupportReaction::declare_parameters(prm);
    Probe::declare_parameters(prm);

    BackgroundGrid::declare_parameters(prm);
    LinearElasticMaterial::declare_parameters(prm);
    ConstitutiveUpdate::declare_parameters(prm);
    BodyRegion::declare_parameters(prm);
    MaterialPointLayout::declare_parameters(prm);
    Bodies::declare_parameters(prm);
    BoundaryCurves::declare_parameters(prm);
    NeumannLoads::declare_parameters(prm);
    SupportMethods::declare_parameters(prm);
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
    gravity = ParameterTools::get_point(prm, "Gravity");
    prm.leave_subsection();
    initial_stress.parse_parameters(prm);
    stages.parse_parameters(prm, initial_stress.enabled());

    reactions.parse_parameters(prm);
    probe.parse_parameters(prm);

    grid.parse_parameters(prm);
    material.parse_parameters(prm);
    constitutive_model = create_constitutive_model(prm);
    bodies.parse_parameters(prm, strength_factor);
    {
      std::vector<std::vector<std::string>> construction;
      for (unsigned int k = 1; k <= stages.n_stages(); ++k)
        construction.push_back(stages.stage(k).construction);
      bodies.build_in_stages(construction);
    }
    // With several bodies only those with a strength are weakened (an
    // elastic structure on the soil keeps its stiffness).
    if (strength_factor != 1. &&
        !(bodies.several() && constitutive_model->is_linear()))
      constitutive_model =
        constitutive_model->with_reduced_strength(strength_factor);
    contact.parse_parameters(prm);
    // Contact makes every run nonlinear (Newton iterations decide where the
    // curves touch), and so do several bodies (every point is integrated
    // with its body's model).
    bool nonlinear_bodies = false;
    for (const auto &body : bodies.further())
      nonlinear_bodies = nonlinear_bodies || !body.model->is_linear();
    constitutive_update =
      ConstitutiveUpdate::create(prm,
                                 *constitutive_model,
                                 material,
                                 contact.enabled() || bodies.several(),
                                 contact.enabled(),
                                 nonlinear_bodies);
    if (bodies.several())
      {
        std::vector<const ConstitutiveModel *> models;
        for (const auto &body : bodies.further())
          models.push_back(body.model.get());
        constitutive_update->set_further_bodies(models);
      }
    linear_b_bar = !constitutive_update && ConstitutiveUpdate::uses_b_bar(prm);
    points.store_inelastic_state(constitutive_update != nullptr);
    run_summary.nonlinear = constitutive_update != nullptr;
    newton.parse_parameters(prm);
    collapse_detector.parse_parameters(prm);
    displacement_control.parse_parameters(prm);
    region.parse_parameters(prm);
    layout.parse_parameters(prm);
    // The closed curve of finite strain goes round all bodies where they
    // fill a rectangle (Bodies::filled_rectangle()).
    const std::optional<BodyRegion> filled = bodies.filled_rectangle(region);
    if (this->finite_strain() && filled)
      BoundaryCurves::enclose_body_region(prm, *filled, grid.min_cell_size());
    boundary_curves.parse_parameters(prm);
    neumann_loads.parse_parameters(prm);
    supports.parse_parameters(prm);
    ghost_penalty.parse_parameters(prm);
    cut_cell_quadrature.parse_parameters(prm);
    linear_solver.parse_parameters(prm);
    output.parse_parameters(prm);
    checkpoint.parse_parameters(prm);
    checkpoint.keep_stage_ends(stages.stage_ends());
    verification.parse_parameters(prm);
    exact_solution =
      ExactSolution::create(prm, material, gravity, this->finite_strain());
    if (bodies.several())
      check_several_bodies();
  }



  void
  Scene::correct_mass_moments(const std::vector<CellMoments> &points_moments)
  {
    // Where the cut-cell quadrature replaced a cell's volume moments by the
    // exact ones, the body force takes them too, times the density of the
    // cell's points (their mass over their volume; the first body's in a
    // cell without points), as one body's would.
    for (unsigned int c = 0; c < cell_moments.size(); ++c)
      {
        const CellMoments &exact = cell_moments[c];
        const CellMoments &own   = points_moments[c];
        if (exact.v == own.v && exact.vs == own.vs && exact.vt == own.vt &&
            exact.vss == own.vss && exact.vtt == own.vtt &&
            exact.vst == own.vst)
          continue;
        const double density =
          own.v > 0 ? mass_moments[c].v / own.v : material.density();
        CellMoments &mass = mass_moments[c];
        mass.v            = density * exact.v;
        mass.vs           = density * exact.vs;
        mass.vt           = density * exact.vt;
        mass.vss          = density * exact.vss;
        mass.vtt          = density * exact.vtt;
        mass.vst          = density * exact.vst;
      }
  }



  void
  Scene::check_several_bodies() const
  {
    const std::string what = "With several bodies (" +
                             bodies.further().front().section +
                             "/Name is set) ";
    AssertThrow(!finite_strain() || bodies.filled_rectangle(region),
                ExcMessage(what + "in finite strain the bodies' regions "
                                  "must be rectangles that fill a rectangle "
                                  "together (layers), for now: Material/"
                                  "Kinematics = finite strain is not "
                                  "available with these regions."));
    AssertThrow(!initial_stress.enabled() || bodies.horizontal_layers(region),
                ExcMessage(what + "the K0 procedure needs bodies stacked "
                                  "as horizontal layers (rectangles of the "
                                  "same width, one on another): Initial "
                                  "stress/Kind = K0 procedure is not "
                                  "available with these regions; let a "
                                  "first stage bring the weight."));
    AssertThrow(!exact_solution,
                ExcMessage(what + "no exact solution is known: leave "
                                  "Exact solution/Name empty."));
    if (!bodies.built_later())
      return;
    unsigned int builds = 2;
    while (stages.stage(builds).construction.empty())
      ++builds;
    // No curve goes round a built body, and contact acts on curves.
    AssertThrow(!contact.enabled(),
                ExcMessage("Stages/Stage " + std::to_string(builds) +
                           "/Construction: a built body has no boundary "
                           "curve, which the rigid bodies would need to "
                           "touch it; rigid bodies are not available in a "
                           "scene that builds, for now."));
    const unsigned int last = stages.n_stages();
    AssertThrow(!displacement_control.enabled() ||
                  stages.stage(last).construction.empty(),
                ExcMessage("Stages/Stage " + std::to_string(last) +
                           "/Construction: Loading/Control = displacement "
                           "drives the last stage by its load factor, which "
                           "cannot also build a body; build it in a stage "
                           "before."));
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
      // With several bodies the curves refer to the rectangle that they
      // fill together, if they do, and are completed round it; else they
      // lie on the first body's edges and are not completed (those edges
      // may be where it meets the others).
      const std::optional<BodyRegion> filled = bodies.filled_rectangle(region);
      const BodyRegion               &curve_region = filled ? *filled : region;
      boundary_curves.create_initial_curves(curve_region,
                                            grid,
                                            filled.has_value());
      const auto trimmed = [this](const Point<2> &p) {
        return boundary_curves.trims(p);
      };
      points.generate(layout, region, trimmed);
      densities = {material.density()};
      for (unsigned int k = 0; k < bodies.further().size(); ++k)
        {
          const Bodies::Body &body = bodies.further()[k];
          if (body.stage == 1)
            points.add_body(body.layout,
                            body.region,
                            k + 1,
                            body.section,
                            [&](const Point<2> &p) {
                              return trimmed(p) ||
                                     bodies.in_earlier_body(p, k + 1, region);
                            });
          densities.push_back(body.material.density());
        }
      set_weight_shares(0.);
      if (bodies.several())
        bodies.check_overlaps(points, grid, region, communicator);
      std::vector<types::particle_index> tracked;
      if (!boundary_curves.empty())
        tracked = boundary_curves.create_points(points, curve_region);
      if (probe.enabled())
        probe.add_to(points, tracked);
      if (!tracked.empty())
        {
          points.track(tracked);
          boundary_curves.read_initial_positions(points);
        }
      // A body that a later stage builds keeps its ids for then, after
      // all others: its layout may change on a resume before that stage.
      for (unsigned int k = 0; k < bodies.further().size(); ++k)
        if (bodies.further()[k].stage > 1)
          first_ids[k + 1] = points.reserve_ids(bodies.further()[k].layout);
      if (initial_stress.enabled())
        {
          const auto layer = [](const LinearElasticMaterial &material,
                                const ConstitutiveModel     &model,
                                const BodyRegion            &region) {
            const auto box = region.bounding_box().get_boundary_points();
            return InitialStress::Layer{&material,
                                        &model,
                                        box.first[1],
                                        box.second[1]};
          };
          std::vector<InitialStress::Layer> layers{
            layer(material, *constitutive_model, region)};
          for (const auto &body : bodies.further())
            {
              layers.push_back(layer(body.material, *body.model, body.region));
              layers.back().present = body.stage == 1;
            }
          initial_stress.initialize(layers, gravity);
          initial_stress.apply(points);
        }
      if (checkpoint.resuming())
        {
          // The checkpoint's points replace those generated as at the
          // start, which gave the same ids, slots and initial positions.
          checkpoint.read_points(points);
          points.count_material_points();
          if (!tracked.empty())
            points.track(tracked);
        }
      cut_cell_quadrature.initialize(boundary_curves);
      // Curves that enclose the first body alone would give its points'
      // fitting the exact part of the first body in a cell the bodies
      // share.
      if (bodies.several() && !filled)
        cut_cell_quadrature.switch_off(
          "several bodies that do not fill a rectangle together");
      // A body built later has no curves round it: the cells it fills are
      // integrated by their points.
      if (bodies.built_later())
        cut_cell_quadrature.switch_off("bodies built by a later stage");
    }
    InputChecks::check_supports(grid, boundary_curves, contact.enabled());
    {
      TimerOutput::Scope t(timer, "setup: system");
      make_solvers();
    }

    run_summary.scene   = scene_name;
    run_summary.n_cells = grid.triangulation().n_global_active_cells();
    run_summary.n_dofs  = grid.dof_handler().n_dofs();
    run_summary.n_material_points = points.n_global_material_points();
    run_summary.n_tracking_points =
      points.particle_handler().n_global_particles() -
      points.n_global_material_points();
    run_summary.load_steps = stages.n_load_steps();
    load_stepper->initialize(!constitutive_model->is_linear(),
                             checkpoint.resuming());
  }



  void
  Scene::make_solvers()
  {
    CurveContact *const curve_contact = contact.enabled() ? &contact : nullptr;
    const bool          nonlinear     = constitutive_update != nullptr;
    if (nonlinear)
      constitutive_update->use_cut_cell_quadrature(
        cut_cell_quadrature.active() ? &cell_moments : nullptr);
    assembly = std::make_unique<SystemAssembly>(
      SystemAssembly::Parts{grid,
                            material,
                            boundary_curves,
                            neumann_loads,
                            supports,
                            ghost_penalty,
                            exact_solution.get(),
                            gravity,
                            linear_b_bar,
                            nonlinear ? &points : nullptr,
                            nonlinear &&
                              constitutive_update->completes_moments(),
                            finite_strain(),
                            curve_contact,
                            reactions.curves(),
                            excavation,
                            bodies.several() ? &mass_moments : nullptr},
      timer);
    assembly->setup();
    if (curve_contact != nullptr)
      step_output.show_contact(contact);
    increment_solver = std::make_unique<IncrementSolver>(
      IncrementSolver::Parts{grid,
                             *assembly,
                             linear_solver,
                             newton,
                             points,
                             boundary_curves,
                             constitutive_update.get(),
                             curve_contact},
      timer);
    increment.reinit(grid.locally_owned_dofs(),
                     grid.locally_relevant_dofs(),
                     communicator);
    load_stepper = std::make_unique<LoadStepper>(
      LoadStepper::Parts{grid,
                         points,
                         boundary_curves,
                         neumann_loads,
                         material,
                         gravity,
                         stages,
                         *assembly,
                         *increment_solver,
                         linear_solver,
                         newton,
                         collapse_detector,
                         displacement_control,
                         constitutive_update.get(),
                         curve_contact,
                         increment},
      LoadStepper::Phases{
        [this](const double tau) -> const std::vector<CellMoments> & {
          return compute_cell_moments(tau);
        },
        [this](const unsigned int step, const LoadIncrement &increment) {
          move_points(step, increment);
          update_curves(step);
        }},
      timer,
      pcout,
      run_summary.quantities);
    run_checkpoint =
      std::make_unique<RunCheckpoint>(checkpoint,
                                      RunCheckpoint::Parts{grid,
                                                           points,
                                                           boundary_curves,
                                                           *assembly,
                                                           *increment_solver,
                                                           collapse_detector,
                                                           linear_solver,
                                                           curve_contact});
  }



  const std::vector<CellMoments> &
  Scene::compute_cell_moments(const double tau)
  {
    if (bodies.built_later())
      set_weight_shares(tau);
    if (points_moved)
      {
        TimerOutput::Scope t(timer, "sort points");
        points.sort_into_cells();
        points_moved = false;
      }
    TimerOutput::Scope t(timer, "assembly");
    points.compute_cell_moments(cell_moments);
    if (bodies.several())
      points.compute_mass_moments(mass_moments);
    if (cut_cell_quadrature.active())
      {
        std::vector<CellMoments> points_moments;
        if (bodies.several())
          points_moments = cell_moments;
        cut_cell_quadrature.correct_cell_moments(points, grid, cell_moments);
        for (const auto &[name, count] : cut_cell_quadrature.statistics())
          run_summary.quantities[name] = count;
        if (bodies.several())
          correct_mass_moments(points_moments);
      }
    // The cells of the body without points borrow their neighbours'
    // state, across the partition's edges too.
    if (constitutive_update && constitutive_update->completes_moments())
      points.exchange_neighbourhood_state();
    return cell_moments;
  }



  void
  Scene::set_weight_shares(const double tau)
  {
    std::vector<double> weighed = densities;
    for (unsigned int k = 0; k < bodies.further().size(); ++k)
      weighed[k + 1] *=
        LoadStages::weight_share(tau, bodies.further()[k].stage);
    points.set_densities(weighed);
    if (constitutive_update)
      constitutive_update->set_densities(weighed);
  }



  void
  Scene::build_bodies(const unsigned int k)
  {
    for (unsigned int b = 0; b < bodies.further().size(); ++b)
      {
        const Bodies::Body &body = bodies.further()[b];
        if (body.stage != k)
          continue;
        // Where the region says, in the coordinates of the start: on ground
        // that has settled a little, the grid's field bonds the body across
        // the gap, as it does across a cell. No curve trims it.
        const types::particle_index n = points.add_body(
          body.layout,
          body.region,
          b + 1,
          body.section,
          [&](const Point<2> &p) {
            return bodies.in_earlier_body(p, b + 1, region);
          },
          first_ids.at(b + 1));
        points_moved = true;
        run_summary.quantities["built_points"] += n;
        pcout << "       " << body.name << " (" << body.section
              << ") built: " << n << " points\n";
      }
  }



  void
  Scene::move_points(const unsigned int   step,
                     const LoadIncrement &load_increment)
  {
    TimerOutput::Scope t(timer, "update points");
    const bool         displaced =
      supports.mark_point_displacement_cells(grid, boundary_curves, band_cells);
    if (!boundary_curves.empty())
      points.set_rigid_increments(boundary_curves.rigid_support_increments(
        points.n_tracked(), exact_solution.get(), load_increment));
    const auto report = points.move(
      assembly->kernel(),
      material,
      increment,
      assembly->prescribed_displacement(),
      displaced ? &band_cells : nullptr,
      [this](const Point<2>                                      &x,
             const std::function<Tensor<1, 2>(const Point<2> &)> &field,
             Tensor<1, 2>                                        &w) {
        return supports.support_displacement(
          boundary_curves, grid, x, field, w);
      },
      &load_stepper->cell_qualities(),
      /*update_stress=*/constitutive_update == nullptr,
      /*update_strain=*/!constitutive_update ||
        constitutive_update->kinematics() ==
          ConstitutiveUpdate::Kinematics::small_strain,
      &cell_moments);
    points_moved                               = true;
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
  Scene::begin_stage(const unsigned int k, const unsigned int step)
  {
    if (k > 1)
      load_stepper->begin_stage(k);
    if (!stages.staged())
      return;
    const LoadLevel before = stages.level(k - 1.);
    const LoadLevel after  = stages.level(k);
    pcout << "\n"
          << stages.stage_name(k) << " (stage " << k << " of "
          << stages.n_stages() << "): " << stages.stage(k).load_steps
          << " load steps, gravity x" << before.gravity << " -> x"
          << after.gravity << ", loads x" << before.loads << " -> x"
          << after.loads;
    if (stages.stage(k).reset_displacements)
      {
        points.reset_displacements();
        pcout << ", displacements from zero";
      }
    pcout << '\n';
    // The weights at the stage's start (a run resumed here starts at 0).
    if (bodies.built_later())
      set_weight_shares(k - 1.);
    if (!stages.stage(k).excavation.empty())
      {
        const std::string where =
          "Stages/Stage " + std::to_string(k) + "/Excavation";
        // The tracked points that must keep away from the region: the
        // probe's, and those of curves that do not follow the cut.
        std::vector<Point<2>> tracked, kept;
        std::vector<Voigt>    stresses;
        points.tracked_states(tracked, stresses);
        if (probe.enabled())
          kept.push_back(tracked[probe.tracked_slot()]);
        const auto &curves = boundary_curves.get_curves();
        for (unsigned int c = 0; c < curves.size(); ++c)
          if (contact.enabled() || !boundary_curves.follows_excavation(c))
            for (const unsigned int slot : curves[c].tracked_slots)
              kept.push_back(tracked[slot]);
        const LoadStages::Stage    &stage = stages.stage(k);
        const std::vector<Point<2>> region =
          Excavation::region_outline(stage.excavation,
                                     stage.excavation_spline,
                                     grid.min_cell_size() / 16,
                                     where);
        const auto removed =
          excavation.remove(region, points, grid, kept, where);
        // The face joins the closed curves round the body.
        if (!contact.enabled() &&
            boundary_curves.excavate(
              region, stage.excavation_spline, points, grid, where))
          update_curves(step);
        // What the rest is out of balance by, released over the stage.
        TrilinosWrappers::MPI::Vector balance;
        load_stepper->out_of_balance(k - 1., balance);
        excavation.release(balance);
        run_summary.quantities["excavated_points"] += removed;
        pcout << "       " << removed << " points excavated\n";
      }
    if (k > 1)
      build_bodies(k);
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

    const unsigned int first_step =
      checkpoint.resuming() ? run_checkpoint->resume(run_summary, output) : 1;
    // Stages after the checkpoint's may have changed their steps.
    run_summary.load_steps = stages.n_load_steps();
    if (first_step > 1 && first_step <= stages.n_load_steps())
      {
        const LoadStages::Step resumed = stages.step(first_step);
        AssertThrow(resumed.first_of_stage ||
                      stages.stage(resumed.stage).excavation.empty(),
                    ExcMessage(
                      "The checkpoint lies inside stage " +
                      std::to_string(resumed.stage) +
                      ", which excavates: the forces it releases are not in "
                      "the checkpoint. Resume from the checkpoint at the end "
                      "of the stage before."));
      }
    if (pcout.is_active())
      for (const auto &record : run_summary.steps)
        run_summary.print_step(pcout.get_stream(), record);
    update_curves(0);
    if (contact.enabled() && first_step == 1)
      {
        // The bodies' prescribed motions over the whole load path.
        double largest_load_factor = 0;
        for (unsigned int k = 1; k <= stages.n_stages(); ++k)
          largest_load_factor =
            std::max(largest_load_factor, stages.level(k).loads);
        contact.check_initial_places(boundary_curves,
                                     points,
                                     grid,
                                     largest_load_factor);
      }
    if (output.enabled() && first_step == 1)
      write_output(0, 0.);

    points_moved      = first_step > 1;
    unsigned int step = first_step;
    try
      {
        const unsigned int n_load_steps = stages.n_load_steps();
        for (; step <= n_load_steps; ++step)
          {
            const LoadStages::Step path = stages.step(step);
            if (path.first_of_stage)
              begin_stage(path.stage, step);
            RunSummary::Step record;
            record.number = step;
            record.stage  = path.stage;
            if (load_stepper->controls_displacement(path.stage))
              load_stepper->advance_under_displacement_control(step, record);
            else
              load_stepper->advance(step, path.from, path.to, record);
            // The step table and summary.json give the stage's own factor.
            const double tau     = record.load_factor;
            record.load_factor   = LoadStages::fraction(tau, path.stage);
            const bool collapsed = collapse_detector.collapsed();
            // A step that collapsed before any increment converged leaves
            // the body as the step before: nothing to record.
            if (!collapsed || record.increments > 0)
              {
                record_quantities(record);
                record.quantities = run_summary.quantities;
                run_summary.record_step(record, output, pcout);
                step_output.write_contact_tractions(step);
                if (output.writes_step(step, n_load_steps) ||
                    (collapsed && output.enabled()))
                  write_output(step, tau);
                if (checkpoint.writes_step(step, n_load_steps))
                  write_checkpoint(step);
              }
            if (collapsed)
              {
                collapse_detector.record(run_summary.quantities);
                if (stages.staged())
                  run_summary.quantities["limit_load_stage"] = path.stage;
                run_summary.limit_load_reason = collapse_detector.reason();
                pcout << "\nLimit load reached"
                      << (stages.staged() ?
                            " in " + stages.stage_name(path.stage) :
                            std::string())
                      << ": limit load factor "
                      << collapse_detector.limit_load_factor() << " ("
                      << collapse_detector.reason()
                      << "). The run stops here; summary.json gives "
                         "limit_load_factor and its bracket.\n";
                break;
              }
          }

        if (exact_solution)
          evaluate_errors();
        run_summary.report_stalled_increments(pcout);
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
        const Tensor<1, 2> force = load_stepper->traction_resultant();
        run_summary.quantities["traction_resultant_x"] = force[0];
        run_summary.quantities["traction_resultant_y"] = force[1];
      }

    if (constitutive_update)
      run_summary.quantities["yielded_points"] = record.n_yielded;
    if (bodies.several())
      bodies.record(points, communicator, run_summary.quantities);
    contact.record(run_summary.quantities);
    boundary_curves.record_point_changes(run_summary.quantities);
    collapse_detector.record(run_summary.quantities);
  }



  void
  Scene::write_checkpoint(const unsigned int step)
  {
    RunSummary so_far = run_summary;
    so_far.add_timing(timer, total_timer.wall_time());
    TimerOutput::Scope t(timer, "checkpoint");
    run_checkpoint->write(step, so_far, output);
  }
} // namespace bsmpm
