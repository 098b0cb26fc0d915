#include <bsmpm/nonlinear/increment_solver.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>

namespace bsmpm
{
  void
  IncrementSolver::LinearSolves::add(const LinearSolver::Report &report)
  {
    const auto note = [](const std::string &m) {
      const auto comma = m.find(", ");
      return comma == std::string::npos ? std::string() : m.substr(comma);
    };
    const std::string earlier = note(method);
    ++n_solves;
    method = report.method;
    if (note(method).empty())
      method += earlier;
    iterations += report.iterations;
    refinement_steps += report.refinement_steps;
    relative_residual = report.relative_residual;
  }



  IncrementSolver::IncrementSolver(const Parts &parts, TimerOutput &timer)
    : parts(parts)
    , timer(timer)
  {}



  LinearSolver::Report
  IncrementSolver::solve_linear(
    const unsigned int                          step,
    LinearAlgebra::distributed::Vector<double> &increment) const
  {
    TimerOutput::Scope    t(timer, "solve");
    const BackgroundGrid &grid     = parts.grid;
    SystemAssembly       &assembly = parts.assembly;
    assembly.check_loads_finite(step);
    TrilinosWrappers::MPI::Vector solution(grid.locally_owned_dofs(),
                                           grid.mpi_communicator());
    const auto report = parts.linear_solver.solve(assembly.matrix(),
                                                  solution,
                                                  assembly.rhs(),
                                                  grid.dof_handler());
    assembly.constraints().distribute(solution);
    AssertThrow(std::isfinite(solution.l2_norm()),
                ExcMessage("The linear solver returned a displacement that is "
                           "not finite in load step " +
                           std::to_string(step) +
                           " although the loads are finite: the system is "
                           "singular (a body that is not held against rigid "
                           "motion, or cells without stabilisation: Ghost "
                           "penalty/Enable)."));

    for (const auto i : grid.locally_owned_dofs())
      increment(i) = solution(i);
    increment.update_ghost_values();
    return report;
  }



  void
  IncrementSolver::prepare_increment()
  {
    TimerOutput::Scope t(timer, "newton system");
    parts.constitutive_update->prepare_elastic_cells(parts.points,
                                                     parts.grid,
                                                     elastic_cells);
  }



  double
  IncrementSolver::newton_residual(
    const LinearAlgebra::distributed::Vector<double> *prescribed,
    const LinearAlgebra::distributed::Vector<double> &increment,
    const RigidBodyMotion                            *motion,
    const bool                                        keep_best)
  {
    const double grid_norm =
      parts.assembly.newton_system(*parts.constitutive_update,
                                   parts.points,
                                   increment,
                                   prescribed,
                                   &elastic_cells);
    // |(R, r_c)| with the bodies' equilibrium.
    const double norm =
      motion == nullptr ?
        grid_norm :
        std::sqrt(grid_norm * grid_norm + std::pow(motion->residual_norm(), 2));
    // The best iterate so far (take_best_iterate()): a copy of the
    // increment per improvement, only where it may be taken.
    if (keep_best && norm < best_norm)
      {
        best_norm      = norm;
        best_increment = increment;
        if (motion != nullptr)
          best_places = motion->values();
      }
    return norm;
  }



  IncrementSolver::NewtonStart
  IncrementSolver::start_newton(
    const double                                      delta,
    const LinearAlgebra::distributed::Vector<double> *prescribed,
    LinearAlgebra::distributed::Vector<double>       &increment,
    RigidBodyMotion                                  *motion,
    const bool                                        keep_best)
  {
    const ConstitutiveUpdate &update   = *parts.constitutive_update;
    SystemAssembly           &assembly = parts.assembly;
    // The scale of the tolerance, as for the grid, is the residual of a
    // zero increment: the bodies where the last increment left them (their
    // force increment unbalanced), not at the predicted place.
    Vector<double> predicted_place;
    if (motion != nullptr)
      {
        predicted_place = motion->values();
        motion->set_values(motion->start_values());
      }
    // The predictor (Nonlinear solver/Predictor, doc/newton.md): a start
    // from plain zero would see the points on the yield surface with the
    // elastic tangent and undershoot. Either the tangent of the last
    // converged state at zero (a forward Euler step), or the last converged
    // increment scaled to this one (the points that yielded then on the
    // plastic branch from the first iteration).
    // Zeroing a ghosted vector leaves it without ghost values: import the
    // zeros, or the cells next to another process read ghosts it does not
    // have.
    increment = 0;
    increment.update_ghost_values();
    // No best iterate of this increment yet (newton_residual()).
    best_norm = std::numeric_limits<double>::infinity();
    const bool small_strain =
      update.kinematics() == ConstitutiveUpdate::Kinematics::small_strain;
    const NewtonSolver::Predictor predictor =
      parts.newton.predictor() != NewtonSolver::Predictor::automatic ?
        parts.newton.predictor() :
        (small_strain ? NewtonSolver::Predictor::tangent :
                        NewtonSolver::Predictor::last_increment);
    const bool has_last_increment =
      previous_delta > 0 && previous_increment.size() == increment.size();
    const bool tangent_start =
      predictor == NewtonSolver::Predictor::tangent && has_last_increment;
    if (tangent_start)
      {
        // The tangent of the last converged state at zero increment: a
        // vanishing step along the last increment puts the points that
        // yielded in it on the plastic branch with a vanishing plastic
        // multiplier (the continuum elasto-plastic tangent), the others on
        // the elastic one. A step from zero sees all of them elastic.
        increment.add(1e-6 * delta / previous_delta, previous_increment);
        assembly.constraints().set_zero(increment);
        increment.update_ghost_values();
      }
    // The tolerance's scale, |R(0)|; with the tangent predictor |R| at its
    // vanishing step, which differs from it by a millionth of the
    // increment's force: one system is the scale and the start (one Newton
    // system less per increment). Not below 1e-5 of the largest internal
    // force of the run so far: an increment that asks next to nothing (a
    // body that a rigid body has let go of, its residual stresses in
    // balance, a ground that starts with the initial stress of its weight)
    // has an |R(0)| that is round-off of forces a billion times larger,
    // which a relative tolerance cannot reach (the column in its K0 state:
    // |R| stays at 2e-15 of the internal force, above a millionth of it
    // times the default tolerance). Finite strain balances forces of the
    // points' places, not of their displacements, and its round-off is
    // larger (the column in its K0 state: 5e-14 of the internal force):
    // not below 1e-3 there.
    NewtonStart  start;
    const double at_start =
      newton_residual(prescribed, increment, motion, keep_best);
    largest_internal_force =
      std::max(largest_internal_force, assembly.internal_force_size());
    const bool finite_strain = parts.constitutive_update->kinematics() ==
                               ConstitutiveUpdate::Kinematics::finite_strain;
    start.reference =
      std::max(at_start,
               (finite_strain ? 1e-3 : 1e-5) * largest_internal_force);
    // |R| of the system the assembly holds, that of the start.
    start.norm = at_start;
    // The tangent predictor keeps force-controlled bodies where the last
    // increment left them (its first correction moves them with the
    // grid); the scaled last increment moves them as it moves the grid.
    if (motion != nullptr && !tangent_start)
      {
        motion->set_values(predicted_place);
        start.norm = -1; // the held system is not that of the prediction
      }
    if (!tangent_start && has_last_increment)
      {
        increment.add(delta / previous_delta, previous_increment);
        assembly.constraints().set_zero(increment);
        increment.update_ghost_values();
        // Where the last increment is a poor guess (finite rotations, a
        // load path that turns), start from zero after all. The residual
        // weighs the stiff modes most, so a guess that is closer in
        // displacement may still leave a larger one: only one ten times
        // larger than that of zero is dropped (cantilever in finite
        // strain: 26 times in step 3).
        start.norm = newton_residual(prescribed, increment, motion, keep_best);
        if (!(start.norm < 10 * start.reference))
          {
            increment = 0;
            increment.update_ghost_values();
            start.norm = -1; // the held system is not that of zero
          }
      }
    return start;
  }



  bool
  IncrementSolver::symmetric_newton_tangent() const
  {
    // A pressure that follows the boundary within the step (finite
    // strain) has an unsymmetric load stiffness, and so have the
    // supports' terms in finite strain (the band's mismatch term,
    // Nitsche's consistency term with dP/df against its symmetric term's
    // C: doc/finite-strain.md, "Supports in finite strain").
    const ConstitutiveUpdate &update = *parts.constitutive_update;
    const auto               &curves = parts.boundary_curves;
    return update.symmetric_tangent() &&
           parts.assembly.contact_tangent_symmetric() &&
           !(update.kinematics() ==
               ConstitutiveUpdate::Kinematics::finite_strain &&
             (curves.has_loads() || curves.has_supports()));
  }



  std::pair<double, unsigned int>
  IncrementSolver::newton_correction(
    const double                                enough,
    LinearAlgebra::distributed::Vector<double> &increment,
    RigidBodyMotion                            *motion,
    NewtonCorrection                           &last,
    LinearSolves                               &solves)
  {
    TimerOutput::Scope            t(timer, "solve");
    const BackgroundGrid         &grid     = parts.grid;
    SystemAssembly               &assembly = parts.assembly;
    TrilinosWrappers::MPI::Vector correction(grid.locally_owned_dofs(),
                                             grid.mpi_communicator());
    const bool                    symmetric = symmetric_newton_tangent();
    const auto report = parts.linear_solver.solve(assembly.tangent(),
                                                  correction,
                                                  assembly.residual(),
                                                  grid.dof_handler(),
                                                  symmetric,
                                                  enough);
    assembly.constraints().distribute(correction);
    solves.add(report);
    unsigned int linear_iterations = report.iterations;
    double       motion_size = 0, motion_correction = 0;
    if (motion != nullptr)
      {
        // Block elimination of [K B; G H] [du; dc] = [R; r_c] with the
        // grid's matrix: K X = R (above), K Y_k = B_k, then
        // (H - G Y) dc = r_c - G X and du = X - Y dc.
        const unsigned int m = motion->get_unknowns().size();
        std::vector<TrilinosWrappers::MPI::Vector> Y(m);
        for (unsigned int k = 0; k < m; ++k)
          {
            Y[k].reinit(grid.locally_owned_dofs(), grid.mpi_communicator());
            const auto column_report =
              parts.linear_solver.solve_unchanged(assembly.tangent(),
                                                  Y[k],
                                                  motion->column(k),
                                                  grid.dof_handler(),
                                                  symmetric);
            assembly.constraints().distribute(Y[k]);
            solves.add(column_report);
            linear_iterations += column_report.iterations;
          }
        last.motion = motion->bordered_correction(correction, Y);
        for (unsigned int k = 0; k < m; ++k)
          correction.add(-last.motion[k], Y[k]);
        motion->add(1., last.motion);
        motion_correction = last.motion.norm_sqr();
        // The body's motion in the increment, as du is the grid's.
        Vector<double> moved = motion->values();
        moved -= motion->start_values();
        motion_size = moved.norm_sqr();
      }
    for (const auto i : grid.locally_owned_dofs())
      increment(i) += correction(i);
    increment.update_ghost_values();
    ++solves.n_corrections;
    const double size =
      std::sqrt(std::pow(increment.l2_norm(), 2) + motion_size);
    last.grid = correction;
    return std::make_pair(size > 0 ?
                            std::sqrt(std::pow(correction.l2_norm(), 2) +
                                      motion_correction) /
                              size :
                            0.,
                          linear_iterations);
  }



  NewtonSolver::Result
  IncrementSolver::solve_newton(
    const double                                      delta,
    const LinearAlgebra::distributed::Vector<double> *prescribed,
    LinearAlgebra::distributed::Vector<double>       &increment,
    LinearSolves                                     &solves,
    const bool                                        keep_best)
  {
    const BackgroundGrid     &grid     = parts.grid;
    SystemAssembly           &assembly = parts.assembly;
    const ConstitutiveUpdate &update   = *parts.constitutive_update;

    NewtonCorrection last;
    // Rigid bodies under a force: their free translation c joins the
    // unknowns, and its equilibrium r_c the residual (RigidBodyMotion).
    RigidBodyMotion *motion =
      parts.contact != nullptr && parts.contact->motion().has_unknowns() ?
        &parts.contact->motion() :
        nullptr;
    prepare_increment();
    const NewtonStart start =
      start_newton(delta, prescribed, increment, motion, keep_best);
    const auto residual = [&]() {
      return newton_residual(prescribed, increment, motion, keep_best);
    };
    // The direct solver refines a correction only while its residual is
    // above a thousandth of what the convergence test accepts: below that
    // the next iteration sees no difference (the first back-substitution
    // leaves 1e-16 .. 4e-13 of |R_k| on the plastic footing, and a
    // refinement step did not lower it).
    const double enough =
      1e-3 * parts.newton.residual_tolerance() * start.reference;
    const bool check = parts.newton.checks_tangent() && motion == nullptr;
    LinearAlgebra::distributed::Vector<double> before;
    double                                     first_product = 0;
    const auto                                 correct       = [&]() {
      if (check)
        before = increment;
      const auto result =
        newton_correction(enough, increment, motion, last, solves);
      if (check)
        check_tangent(prescribed, before, last.grid, first_product);
      return result;
    };
    const auto step_back = [&](const double alpha) {
      // From x + a dx to x + (a - alpha) dx.
      for (const auto i : grid.locally_owned_dofs())
        increment(i) -= alpha * last.grid(i);
      increment.update_ghost_values();
      if (motion != nullptr)
        motion->add(-alpha, last.motion);
    };
    // dx . R(x): the slope of the potential along dx, for the line search
    // (with dc . r_c: the applied force on a body is a dead load, whose
    // potential is -F . c).
    const auto slope = [&]() {
      return last.grid * assembly.residual() +
             (motion != nullptr ? last.motion * motion->get_residual() : 0.);
    };

    // Small strain with a symmetric tangent: the potential is convex and
    // the tangent positive, so a correction that does not descend is
    // round-off (NewtonSolver::solve).
    const bool positive_tangent =
      update.kinematics() == ConstitutiveUpdate::Kinematics::small_strain &&
      update.symmetric_tangent() && assembly.contact_tangent_symmetric();
    // With the augmented Lagrangian the solves before a multiplier update
    // stop at a looser residual (CurveContact::tolerance_between_updates()):
    // the update moves the increment by more than what they leave.
    double looser = parts.contact != nullptr ?
                      parts.contact->tolerance_between_updates() :
                      0.;
    // Iterations from the increment as it stands, whose residual's norm
    // is @p norm.
    const auto iterate = [&](const double norm) {
      return parts.newton.solve(start.reference,
                                residual,
                                correct,
                                step_back,
                                slope,
                                norm,
                                positive_tangent,
                                looser);
    };
    NewtonSolver::Result result = iterate(start.norm);
    const auto           go_on  = [&]() {
      const NewtonSolver::Result more = iterate(residual());
      result.iterations.insert(result.iterations.end(),
                               more.iterations.begin(),
                               more.iterations.end());
      result.converged = more.converged;
      result.failure   = more.failure;
    };
    // Which Gauss points of the curves touch a rigid body is fixed within
    // the iterations, and so are the augmented Lagrangian's multipliers
    // (CurveContact): where the converged increment changes them, iterate
    // on from there (CurveContact bounds how often). Once they stand, the
    // iterations go on to the Newton tolerance, and the parts and the
    // multipliers are checked again there.
    for (;;)
      {
        while (parts.contact != nullptr && result.converged &&
               parts.contact->after_convergence(
                 grid, assembly.kernel(), increment, prescribed))
          go_on();
        if (!result.converged || looser == 0. ||
            result.iterations.back().relative_residual <=
              parts.newton.residual_tolerance())
          break;
        looser = 0.;
        go_on();
      }
    return result;
  }



  double
  IncrementSolver::take_best_iterate(
    const double                                      tolerance,
    const LinearAlgebra::distributed::Vector<double> *prescribed,
    LinearAlgebra::distributed::Vector<double>       &increment)
  {
    if (!std::isfinite(best_norm) || best_increment.size() != increment.size())
      return -1;
    increment = best_increment;
    increment.update_ghost_values();
    if (parts.contact != nullptr && parts.contact->motion().has_unknowns())
      parts.contact->motion().set_values(best_places);
    parts.assembly.newton_system(*parts.constitutive_update,
                                 parts.points,
                                 increment,
                                 prescribed,
                                 &elastic_cells);
    // The scale: the stresses the residual balances, in this state or
    // earlier in the run (in the first step only this one's).
    const double scale =
      std::max(largest_internal_force, parts.assembly.internal_force_size());
    const double ratio =
      scale > 0 ? best_norm / scale : std::numeric_limits<double>::infinity();
    return ratio <= tolerance ? ratio : -1.;
  }



  NewtonSolver::Result
  IncrementSolver::solve_controlled(
    const DisplacementControl                  &control,
    const double                                target,
    const TrilinosWrappers::MPI::Vector        &loads,
    LinearAlgebra::distributed::Vector<double> &increment,
    double                                     &load_increment,
    LinearSolves                               &solves)
  {
    const BackgroundGrid     &grid     = parts.grid;
    SystemAssembly           &assembly = parts.assembly;
    const ConstitutiveUpdate &update   = *parts.constitutive_update;
    const MaterialPoints     &points   = parts.points;
    AssertThrow(update.kinematics() ==
                    ConstitutiveUpdate::Kinematics::small_strain &&
                  update.symmetric_tangent(),
                ExcMessage("Loading/Control = displacement needs small strain "
                           "and a symmetric tangent."));
    prepare_increment();

    const auto solve = [&](const TrilinosWrappers::MPI::Vector &rhs,
                           TrilinosWrappers::MPI::Vector       &solution) {
      TimerOutput::Scope t(timer, "solve");
      solution.reinit(grid.locally_owned_dofs(), grid.mpi_communicator());
      const auto report = parts.linear_solver.solve(assembly.tangent(),
                                                    solution,
                                                    rhs,
                                                    grid.dof_handler());
      assembly.constraints().distribute(solution);
      solves.add(report);
      return report.iterations;
    };

    // R(x, d lambda) = R_0(x) + d lambda F_ref: R_0 what newton_system()
    // assembles at the last converged load factor.
    TrilinosWrappers::MPI::Vector residual, a, b, correction;
    double                        last_load_correction = 0;
    const auto                    evaluate             = [&]() {
      assembly.newton_system(
        update, points, increment, nullptr, &elastic_cells);
      residual = assembly.residual();
      residual.add(load_increment, loads);
      return residual.l2_norm();
    };

    increment = 0;
    increment.update_ghost_values();
    load_increment = 0;
    // The scale of the tolerance: |R| at zero increment with the load
    // increment that the start's tangent needs for the prescribed
    // displacement (as |R(0)| of a load-controlled step holds its load
    // increment).
    evaluate();
    solve(loads, b);
    const double cb = control.value(b);
    AssertThrow(cb != 0.,
                ExcMessage("Loading/Control = displacement: the loads do not "
                           "move the control vertex (it is held, or outside "
                           "the body)."));
    residual.add(target / cb, loads);
    const double reference = residual.l2_norm();
    // Start from that predictor, x = (target / c.b) b: it meets the
    // control condition already.
    load_increment = target / cb;
    for (const auto i : grid.locally_owned_dofs())
      increment(i) = load_increment * b(i);
    increment.update_ghost_values();

    return parts.newton.solve(
      reference,
      evaluate,
      [&]() {
        const unsigned int iterations = solve(residual, a) + solve(loads, b);
        // Batoz and Dhatt: the load correction that brings c . x to the
        // target after dx = a + d(d lambda) b.
        const double d_lambda =
          (target - control.value(increment) - control.value(a)) /
          control.value(b);
        correction = a;
        correction.add(d_lambda, b);
        for (const auto i : grid.locally_owned_dofs())
          increment(i) += correction(i);
        increment.update_ghost_values();
        load_increment += d_lambda;
        last_load_correction = d_lambda;
        const double size    = increment.l2_norm();
        return std::make_pair(size > 0 ? correction.l2_norm() / size : 0.,
                              iterations);
      },
      [&](const double alpha) {
        for (const auto i : grid.locally_owned_dofs())
          increment(i) -= alpha * correction(i);
        increment.update_ghost_values();
        load_increment -= alpha * last_load_correction;
      });
  }



  void
  IncrementSolver::accept(
    const LinearAlgebra::distributed::Vector<double> &increment,
    const double                                      delta)
  {
    previous_increment = increment;
    previous_delta     = delta;
  }


  template <typename Function>
  void
  IncrementSolver::for_each_owned_vertex_dof(const Function &f) const
  {
    // Vertex v of cell (i, j) is vertex (i + v % 2, j + v / 2) of the
    // uniform grid (deal.II's numbering of a quadrilateral's vertices).
    const BackgroundGrid &grid = parts.grid;
    const unsigned int    nx   = grid.n_cells(0) + 1;
    for (const auto &[cell, ij] : grid.locally_owned_cells())
      for (unsigned int v = 0; v < 4; ++v)
        for (unsigned int c = 0; c < 2; ++c)
          {
            const auto dof = cell->vertex_dof_index(v, c);
            if (grid.locally_owned_dofs().is_element(dof))
              f(dof, 2 * ((ij[1] + v / 2) * nx + ij[0] + v % 2) + c);
          }
  }



  IncrementSolver::Memory
  IncrementSolver::memory() const
  {
    const BackgroundGrid &grid = parts.grid;
    Memory                memory;
    memory.delta                  = previous_delta;
    memory.largest_internal_force = largest_internal_force;
    const unsigned int n_vertex_dofs =
      2 * (grid.n_cells(0) + 1) * (grid.n_cells(1) + 1);
    memory.at_vertices.assign(n_vertex_dofs, 0.);
    if (previous_increment.size() > 0)
      for_each_owned_vertex_dof(
        [&](const types::global_dof_index dof, const unsigned int k) {
          memory.at_vertices[k] = previous_increment(dof);
        });
    // Each DoF is owned by one process.
    Utilities::MPI::sum(memory.at_vertices,
                        grid.mpi_communicator(),
                        memory.at_vertices);
    const auto *ratios =
      parts.constitutive_update != nullptr ?
        parts.constitutive_update->support_stiffness_ratios() :
        nullptr;
    if (ratios != nullptr)
      {
        memory.stiffness_ratios.assign(n_vertex_dofs, 0.);
        for_each_owned_vertex_dof(
          [&](const types::global_dof_index dof, const unsigned int k) {
            memory.stiffness_ratios[k] = (*ratios)(dof);
          });
        Utilities::MPI::sum(memory.stiffness_ratios,
                            grid.mpi_communicator(),
                            memory.stiffness_ratios);
      }
    return memory;
  }



  void
  IncrementSolver::restore(const Memory &memory)
  {
    const BackgroundGrid &grid = parts.grid;
    previous_delta             = memory.delta;
    largest_internal_force     = memory.largest_internal_force;
    previous_increment.reinit(grid.locally_owned_dofs(),
                              grid.locally_relevant_dofs(),
                              grid.mpi_communicator());
    if (memory.delta > 0)
      for_each_owned_vertex_dof(
        [&](const types::global_dof_index dof, const unsigned int k) {
          previous_increment(dof) = memory.at_vertices[k];
        });
    previous_increment.update_ghost_values();
    if (!memory.stiffness_ratios.empty() &&
        parts.constitutive_update != nullptr)
      {
        LinearAlgebra::distributed::Vector<double> ratios(
          grid.locally_owned_dofs(),
          grid.locally_relevant_dofs(),
          grid.mpi_communicator());
        for_each_owned_vertex_dof(
          [&](const types::global_dof_index dof, const unsigned int k) {
            ratios(dof) = memory.stiffness_ratios[k];
          });
        ratios.update_ghost_values();
        parts.constitutive_update->restore_support_stiffness_ratios(ratios);
      }
  }


  void
  IncrementSolver::check_tangent(
    const LinearAlgebra::distributed::Vector<double> *prescribed,
    const LinearAlgebra::distributed::Vector<double> &before,
    const TrilinosWrappers::MPI::Vector              &correction,
    double                                           &first_product)
  {
    // K dx with the tangent at the increment before the correction, and
    // -(R(x + e dx) - R(x - e dx)) / (2 e), on the unconstrained DoFs. The
    // Newton solver assembles the system anew at the corrected increment
    // next: the two assemblies here leave nothing behind.
    SystemAssembly               &assembly = parts.assembly;
    const BackgroundGrid         &grid     = parts.grid;
    TrilinosWrappers::MPI::Vector dx = correction, product = correction;
    assembly.constraints().set_zero(dx);
    assembly.tangent().vmult(product, dx);
    assembly.constraints().set_zero(product);
    const double size = product.l2_norm();
    if (first_product == 0)
      first_product = size;
    if (!(size > 0) || size < 1e-3 * first_product)
      return;
    // A relative step of 1e-4: the differences' round-off stays near 1e-12
    // of |K dx|, and a point that yields or unloads between them is rare.
    constexpr double                             e = 1e-4;
    std::array<TrilinosWrappers::MPI::Vector, 2> residuals;
    for (unsigned int s = 0; s < 2; ++s)
      {
        LinearAlgebra::distributed::Vector<double> x = before;
        for (const auto i : grid.locally_owned_dofs())
          x(i) += (s == 0 ? e : -e) * dx(i);
        x.update_ghost_values();
        // An increment that inverts a point has no residual.
        if (!std::isfinite(assembly.newton_system(*parts.constitutive_update,
                                                  parts.points,
                                                  x,
                                                  prescribed,
                                                  &elastic_cells)))
          return;
        residuals[s] = assembly.residual();
      }
    TrilinosWrappers::MPI::Vector difference = residuals[1];
    difference -= residuals[0];
    difference /= 2 * e;
    assembly.constraints().set_zero(difference);
    difference -= product;
    largest_tangent_error =
      std::max(largest_tangent_error, difference.l2_norm() / size);
    ++n_tangent_checks;
  }
} // namespace bsmpm
