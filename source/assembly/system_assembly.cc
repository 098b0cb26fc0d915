#include <deal.II/base/mpi.h>

#include <deal.II/dofs/dof_tools.h>

#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/sparsity_tools.h>

#include <bsmpm/assembly/system_assembly.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <string>

namespace bsmpm
{
  SystemAssembly::SystemAssembly(const Parts &parts, TimerOutput &timer)
    : parts(parts)
    , timer(timer)
  {}



  void
  SystemAssembly::setup()
  {
    const BackgroundGrid &grid = parts.grid;
    cell_kernel                = std::make_unique<Q1CellKernel>(grid.fe(),
                                                 grid.cell_size(),
                                                 parts.material.stiffness(),
                                                 parts.b_bar);

    const MPI_Comm comm = grid.mpi_communicator();
    // With a ghost penalty the first assembly makes the matrix, with the
    // couplings across the faces of the weak cells it then knows: making
    // it here too would double the set-up of the matrix.
    fitting_method =
      parts.supports.fitting_prescribed_displacement(parts.curves);
    if (!parts.ghost_penalty.enabled() || fitting_method != nullptr)
      make_matrix(
        std::vector<bool>(grid.triangulation().n_active_cells(), false));
    system_rhs.reinit(grid.locally_owned_dofs(), comm);
    if (fitting_method != nullptr)
      boundary_fit_matrix.reinit(system_matrix);
  }



  void
  SystemAssembly::make_matrix(const std::vector<bool> &weak)
  {
    // The couplings of every cell of the grid: valid whichever cells hold
    // points. Couplings across faces (ghost penalty) only near weak cells:
    // on all faces they would make the matrix 2.8 times larger. Faces of
    // ghost cells too: the rows of ghost DoFs that this process adds to
    // must be in its own pattern. The neighbours of the weak cells too, so
    // that a boundary that moves by less than a cell per step needs no
    // new matrix.
    ++matrix_layouts;
    const BackgroundGrid  &grid = parts.grid;
    const MPI_Comm         comm = grid.mpi_communicator();
    DynamicSparsityPattern dsp(grid.locally_relevant_dofs());
    DoFTools::make_sparsity_pattern(grid.dof_handler(), dsp);
    weak_cells_of_matrix = weak;
    coupled_faces        = weak;
    for (const auto &cell : grid.triangulation().active_cell_iterators())
      if (weak[cell->active_cell_index()])
        for (const unsigned int f : cell->face_indices())
          if (!cell->at_boundary(f))
            coupled_faces[cell->neighbor(f)->active_cell_index()] = true;
    if (std::find(coupled_faces.begin(), coupled_faces.end(), true) !=
        coupled_faces.end())
      {
        std::vector<types::global_dof_index> here(Q1CellKernel::dofs_per_cell),
          there(Q1CellKernel::dofs_per_cell);
        for (const auto &cell : grid.dof_handler().active_cell_iterators())
          if (!cell->is_artificial())
            for (const unsigned int f : cell->face_indices())
              if (!cell->at_boundary(f) &&
                  !cell->neighbor(f)->is_artificial() &&
                  (coupled_faces[cell->active_cell_index()] ||
                   coupled_faces[cell->neighbor(f)->active_cell_index()]))
                {
                  cell->get_dof_indices(here);
                  cell->neighbor(f)->get_dof_indices(there);
                  // The face matrix couples every DoF of the two cells with
                  // every other, those of a ghost neighbour among
                  // themselves too: the cell pattern above holds only the
                  // owned cells' couplings.
                  here.insert(here.end(), there.begin(), there.end());
                  for (const auto i : here)
                    for (const auto j : here)
                      dsp.add(i, j);
                  here.resize(Q1CellKernel::dofs_per_cell);
                }
      }
    SparsityTools::distribute_sparsity_pattern(dsp,
                                               grid.locally_owned_dofs(),
                                               comm,
                                               grid.locally_relevant_dofs());
    // Kept for a tangent whose pattern contact widens.
    if (parts.contact != nullptr && parts.contact->coupled_cells() != nullptr)
      contact_pattern.keep(dsp);
    support_layout_current = false;
    scatter.clear();
    tangent_scatter.clear();
    system_matrix.clear();
    system_matrix.reinit(grid.locally_owned_dofs(),
                         grid.locally_owned_dofs(),
                         dsp,
                         comm);
  }



  std::vector<CellId>
  SystemAssembly::weak_cells_of_last_matrix() const
  {
    std::vector<CellId> cells;
    for (const auto &cell : parts.grid.triangulation().active_cell_iterators())
      if (cell->is_locally_owned() &&
          cell->active_cell_index() < weak_cells_of_matrix.size() &&
          weak_cells_of_matrix[cell->active_cell_index()])
        cells.push_back(cell->id());
    return cells;
  }



  void
  SystemAssembly::restore_matrix(const std::vector<CellId> &cells)
  {
    if (!parts.ghost_penalty.enabled())
      return;
    // Owned and ghost cells, as GhostPenalty::weak_cells() marks them.
    const std::set<CellId> listed(cells.begin(), cells.end());
    const auto            &tria = parts.grid.triangulation();
    std::vector<bool>      weak(tria.n_active_cells(), false);
    for (const auto &cell : tria.active_cell_iterators())
      if (!cell->is_artificial())
        weak[cell->active_cell_index()] = listed.count(cell->id()) > 0;
    make_matrix(weak);
  }



  void
  SystemAssembly::make_constraints(const std::vector<CellMoments> &moments)
  {
    TimerOutput::Scope    t(timer, "constraints");
    const BackgroundGrid &grid = parts.grid;
    const MPI_Comm        comm = grid.mpi_communicator();
    // A DoF none of whose cells holds material is fixed at zero, or K would
    // be singular (method-notes Sec. 1, step 1).
    // Supports of both components in a cell without material hold its DoFs
    // too (a roller alone would leave them free to slide).
    std::vector<bool> supporting(grid.triangulation().n_active_cells(), false);
    if (!parts.curves.empty())
      for (const auto &method : parts.supports)
        method->mark_cells(grid, parts.curves, true, supporting);
    LinearAlgebra::distributed::Vector<double> support(
      grid.locally_owned_dofs(), grid.locally_relevant_dofs(), comm);
    std::vector<types::global_dof_index> dof_indices(
      Q1CellKernel::dofs_per_cell);
    active_cells = 0;
    for (const auto &cell : grid.dof_handler().active_cell_iterators())
      if (cell->is_locally_owned() &&
          (moments[cell->active_cell_index()].v > 0 ||
           supporting[cell->active_cell_index()]))
        {
          ++active_cells;
          cell->get_dof_indices(dof_indices);
          for (const auto i : dof_indices)
            support(i) += 1;
        }
    support.compress(VectorOperation::add);
    support.update_ghost_values();
    active_cells = Utilities::MPI::sum(active_cells, comm);

    system_constraints.clear();
    system_constraints.reinit(grid.locally_relevant_dofs());
    unsupported_dofs.clear();
    for (const auto i : grid.locally_relevant_dofs())
      if (support(i) == 0.)
        {
          system_constraints.add_line(i);
          if (grid.locally_owned_dofs().is_element(i))
            unsupported_dofs.push_back(i);
        }
    grid.make_face_constraints(system_constraints);
    system_constraints.close();
  }



  double
  SystemAssembly::fit_prescribed_displacement(const LoadIncrement &increment)
  {
    TimerOutput::Scope t(timer, "prescribed displacement fit");
    has_prescribed = true;
    return fitting_method->fit_prescribed_displacement(support_context(),
                                                       increment,
                                                       boundary_fit_matrix,
                                                       prescribed);
  }



  SupportMethod::Context
  SystemAssembly::support_context() const
  {
    return {parts.curves,
            parts.grid,
            *cell_kernel,
            parts.material,
            parts.exact_solution,
            parts.finite_strain};
  }



  void
  SystemAssembly::assemble(const LoadLevel                &level,
                           const LoadIncrement            &increment,
                           const std::vector<CellMoments> &moments,
                           const std::vector<double>      &quality)
  {
    const LinearAlgebra::distributed::Vector<double> *prescribed =
      prescribed_displacement();
    const BackgroundGrid &grid        = parts.grid;
    const Q1CellKernel   &kernel      = *cell_kernel;
    const auto           &constraints = system_constraints;
    if (parts.ghost_penalty.enabled())
      {
        // The matrix must hold the couplings across the faces of the weak
        // cells. If it does not, rebuild it for them and the cells next to
        // them, so that a boundary that moves by less than a cell per step
        // needs no rebuild.
        TimerOutput::Scope      t(timer, "ghost penalty");
        const std::vector<bool> weak =
          parts.ghost_penalty.weak_cells(grid, quality);
        bool held = !coupled_faces.empty();
        for (unsigned int c = 0; c < weak.size() && held; ++c)
          held = !weak[c] || coupled_faces[c];
        if (Utilities::MPI::min(held ? 1 : 0, grid.mpi_communicator()) == 0)
          make_matrix(weak);
      }
    assembly_moments = &moments;
    timer.enter_subsection("assembly");
    system_matrix = 0;
    system_rhs    = 0;
    if (!scatter.serves(system_matrix))
      scatter.reinit(system_matrix, grid.triangulation().n_active_cells());

    const Tensor<1, 2> body_force = level.gravity * density() * parts.gravity;
    const bool         has_body_force = body_force.norm() > 0;
    // In finite strain the points carry their weight with their stress
    // (ConstitutiveUpdate), so the internal force that Newton's tolerance
    // is scaled by is the difference of the two, next to nothing for a
    // ground at rest: the weight itself is kept as that scale.
    TrilinosWrappers::MPI::Vector weight;
    if (parts.finite_strain && has_body_force)
      weight.reinit(system_rhs, false);

    constexpr unsigned int n = Q1CellKernel::dofs_per_cell;
    FullMatrix<double>     cell_matrix(n, n);
    Vector<double>         cell_rhs(n), internal(n), da(n), cell_weight(n);
    std::vector<types::global_dof_index> dof_indices(n);

    for (const auto &cell : grid.dof_handler().active_cell_iterators())
      {
        if (!cell->is_locally_owned())
          continue;
        const CellMoments &m = moments[cell->active_cell_index()];
        if (m.v == 0.)
          continue;

        cell_matrix                  = 0;
        cell_rhs                     = 0;
        internal                     = 0;
        const MaterialPoints *points = parts.material_points;
        const bool            points_here =
          points != nullptr &&
          (points->holds_material(cell) ||
           (parts.cells_without_points &&
            !points->neighbourhood_mean_properties(cell).empty()));
        if (!points_here)
          {
            kernel.add_stiffness(m, cell_matrix);
            kernel.add_internal_force(m, internal);
          }
        cell->get_dof_indices(dof_indices);
        // In finite strain the points carry the body force on their masses.
        if (has_body_force && parts.finite_strain && points_here)
          {
            cell_weight = 0;
            kernel.add_body_force(mass_moments(m, cell),
                                  body_force,
                                  cell_weight);
            constraints.distribute_local_to_global(cell_weight,
                                                   dof_indices,
                                                   weight);
          }
        else if (has_body_force)
          kernel.add_body_force(mass_moments(m, cell), body_force, cell_rhs);
        cell_rhs -= internal;

        // Material-point part of the force f^d of a prescribed displacement
        // (eq. 33): the regular stiffness times d^a.
        if (prescribed && !points_here)
          {
            for (unsigned int i = 0; i < n; ++i)
              da[i] = (*prescribed)(dof_indices[i]);
            cell_matrix.vmult_add(internal = 0, da);
            cell_rhs -= internal;
          }
        scatter.add(cell->active_cell_index(),
                    cell_matrix,
                    cell_rhs,
                    dof_indices,
                    constraints,
                    system_matrix,
                    system_rhs);
      }
    // No cell assembles into the rows of unsupported DoFs: give them a
    // diagonal of the material's scale (their solution is zero).
    for (const auto i : unsupported_dofs)
      system_matrix.add(i, i, parts.material.stiffness()[0][0]);
    timer.leave_subsection("assembly");

    if (parts.ghost_penalty.enabled())
      {
        TimerOutput::Scope t(timer, "ghost penalty");
        parts.ghost_penalty.assemble(grid,
                                     kernel,
                                     parts.material.youngs_modulus(),
                                     quality,
                                     prescribed,
                                     constraints,
                                     system_matrix,
                                     system_rhs);
      }
    // Before the system's own implicit boundary terms, whose band points
    // the implicit boundary keeps.
    if (!parts.reaction_curves.empty())
      assemble_support_terms(increment);
    add_support_terms(
      increment, constraints, system_matrix, system_rhs, nullptr);
    if (parts.curves.has_loads())
      {
        TimerOutput::Scope t(timer, "neumann loads");
        parts.neumann_loads.assemble(parts.curves,
                                     grid,
                                     kernel,
                                     parts.exact_solution,
                                     level.loads,
                                     constraints,
                                     system_rhs,
                                     parts.finite_strain ? &system_matrix :
                                                           nullptr);
      }
    system_matrix.compress(VectorOperation::add);
    system_rhs.compress(VectorOperation::add);
    parts.excavation.add_released_forces(level.release,
                                         constraints,
                                         system_rhs);
    weight_norm = 0;
    if (weight.size() > 0)
      {
        weight.compress(VectorOperation::add);
        weight_norm = weight.l2_norm();
      }
    assembly_moments = nullptr;
  }



  void
  SystemAssembly::reference_loads(const std::vector<CellMoments> &moments,
                                  const LoadLevel                &slope,
                                  TrilinosWrappers::MPI::Vector  &loads)
  {
    AssertThrow(!parts.finite_strain,
                ExcMessage("Displacement control is for small strain only: "
                           "in finite strain the loads follow the body."));
    TimerOutput::Scope t(timer, "assembly");
    loads.reinit(system_rhs, false);
    // The tractions at load factor 1 (their resultant is then the unit
    // one), scaled by the stage's growth of the loads.
    if (parts.curves.has_loads())
      {
        parts.neumann_loads.assemble(parts.curves,
                                     parts.grid,
                                     *cell_kernel,
                                     parts.exact_solution,
                                     1.,
                                     system_constraints,
                                     loads,
                                     nullptr);
        loads.compress(VectorOperation::add);
        loads *= slope.loads;
      }
    const Tensor<1, 2> body_force = slope.gravity * density() * parts.gravity;
    if (body_force.norm() > 0)
      {
        constexpr unsigned int               n = Q1CellKernel::dofs_per_cell;
        Vector<double>                       cell_rhs(n);
        std::vector<types::global_dof_index> dof_indices(n);
        for (const auto &cell :
             parts.grid.dof_handler().active_cell_iterators())
          {
            if (!cell->is_locally_owned())
              continue;
            const CellMoments &m = moments[cell->active_cell_index()];
            if (m.v == 0.)
              continue;
            cell_rhs = 0;
            cell_kernel->add_body_force(mass_moments(m, cell),
                                        body_force,
                                        cell_rhs);
            cell->get_dof_indices(dof_indices);
            system_constraints.distribute_local_to_global(cell_rhs,
                                                          dof_indices,
                                                          loads);
          }
      }
    loads.compress(VectorOperation::add);
  }



  void
  SystemAssembly::assemble_support_terms(const LoadIncrement &increment)
  {
    TimerOutput::Scope               t(timer, "reactions");
    const std::vector<unsigned int> &support_curves = parts.reaction_curves;
    const unsigned int               n              = support_curves.size();
    if (!support_layout_current || support_matrices.size() != n)
      {
        support_matrices.resize(n);
        support_rhs.resize(n);
        for (unsigned int c = 0; c < n; ++c)
          {
            support_matrices[c].reinit(system_matrix);
            support_rhs[c].reinit(system_rhs);
          }
        support_layout_current = true;
      }
    // Without constraints: a DoF that a face of the grid holds still
    // receives the supports' force.
    AffineConstraints<double> none;
    none.close();
    const auto &curves = parts.curves.get_curves();
    for (unsigned int c = 0; c < n; ++c)
      {
        AssertThrow(support_curves[c] < curves.size(),
                    ExcMessage("Reactions/Curves: there is no curve " +
                               std::to_string(support_curves[c] + 1) + "."));
        support_matrices[c] = 0;
        support_rhs[c]      = 0;
        add_support_terms(increment,
                          none,
                          support_matrices[c],
                          support_rhs[c],
                          &curves[support_curves[c]]);
        support_matrices[c].compress(VectorOperation::add);
        support_rhs[c].compress(VectorOperation::add);
      }
  }



  void
  SystemAssembly::add_support_terms(
    const LoadIncrement             &increment,
    const AffineConstraints<double> &constraints,
    TrilinosWrappers::SparseMatrix  &matrix,
    TrilinosWrappers::MPI::Vector   &rhs,
    const BoundaryCurve             *only)
  {
    const SupportMethod::Context context = support_context();
    bool                         any     = false;
    for (const auto &method : parts.supports)
      if (only != nullptr ? method->imposes(*only) :
                            method->used_by(parts.curves))
        {
          TimerOutput::Scope t(timer, method->name());
          method->assemble(context,
                           increment,
                           prescribed_displacement(),
                           assembly_moments,
                           constraints,
                           matrix,
                           rhs,
                           only);
          any = true;
        }
    // The bands by cell, for the tangent of nonlinear materials.
    if (any && only == nullptr && parts.material_points != nullptr)
      {
        support_bands.assign(parts.grid.triangulation().n_active_cells(), {});
        for (const auto &method : parts.supports)
          for (const auto &b : method->band_points())
            support_bands[b.cell_index].push_back(
              {b.reference_position, b.weight});
      }
  }



  TrilinosWrappers::MPI::Vector
  SystemAssembly::support_forces(
    const unsigned int                                curve,
    const LinearAlgebra::distributed::Vector<double> &increment) const
  {
    const std::vector<unsigned int> &support_curves = parts.reaction_curves;
    const auto                       c              = static_cast<unsigned int>(
      std::find(support_curves.begin(), support_curves.end(), curve) -
      support_curves.begin());
    AssertThrow(c < support_matrices.size(),
                ExcMessage("The supports' terms of curve " +
                           std::to_string(curve + 1) + " were not kept."));
    TrilinosWrappers::MPI::Vector x(support_rhs[c]), force(support_rhs[c]);
    for (const auto i : parts.grid.locally_owned_dofs())
      x(i) = increment(i);
    x.compress(VectorOperation::insert);
    support_matrices[c].vmult(force, x);
    force.sadd(-1., 1., support_rhs[c]);
    // Finite strain: the supports' terms of the last Newton system.
    if (c < support_finite_strain_forces.size())
      force -= support_finite_strain_forces[c];
    return force;
  }


  double
  SystemAssembly::newton_system(
    const ConstitutiveUpdate                         &update,
    const MaterialPoints                             &points,
    const LinearAlgebra::distributed::Vector<double> &increment,
    const LinearAlgebra::distributed::Vector<double> *prescribed,
    const ConstitutiveUpdate::ElasticCells           *elastic_cells)
  {
    TimerOutput::Scope    t(timer, "newton system");
    const BackgroundGrid &grid = parts.grid;
    // copy_from() keeps the matrix object while the pattern stays. Where it
    // does not, deal.II 9.4's copy_from() decides so row by row on each
    // process and rebuilds the matrix there alone (FillComplete(), a
    // collective): a new layout on some processes only (the ghost
    // penalty's faces moved on one, the global count of entries the same)
    // left the others in the next collective, and the footing at h = 1/64
    // on two processes stopped with MPI_ERR_TRUNCATE in step 13. A new
    // layout is taken on every process first.
    // Mortar contact pressures couple DoFs two cells
    // apart: the tangent then has a pattern of its own, the system's
    // widened round the contact (the same cells on every process), and
    // takes the system matrix's entries by add().
    const std::vector<std::array<unsigned int, 2>> *coupled =
      parts.contact != nullptr ? parts.contact->coupled_cells() : nullptr;
    if (coupled != nullptr)
      {
        if (tangent_layout != matrix_layouts ||
            !contact_pattern.covers(grid, *coupled))
          {
            contact_pattern.widen(grid, *coupled, tangent_matrix);
            tangent_layout = matrix_layouts;
          }
        tangent_matrix = 0;
        tangent_matrix.add(1., system_matrix);
      }
    else
      {
        if (tangent_layout != matrix_layouts)
          {
            tangent_matrix.reinit(system_matrix);
            tangent_layout = matrix_layouts;
          }
        tangent_matrix.copy_from(system_matrix);
      }
    if (!tangent_scatter.serves(tangent_matrix))
      tangent_scatter.reinit(tangent_matrix,
                             grid.triangulation().n_active_cells());
    TrilinosWrappers::MPI::Vector x(grid.locally_owned_dofs(),
                                    grid.mpi_communicator());
    for (const auto i : grid.locally_owned_dofs())
      x(i) = increment(i);
    x.compress(VectorOperation::insert);
    newton_residual.reinit(x, true);
    system_matrix.vmult(newton_residual, x);
    newton_residual.sadd(-1., 1., system_rhs);
    TrilinosWrappers::MPI::Vector internal_force(newton_residual);
    internal_force = 0;
    const ConstitutiveUpdate::AssemblyCount count =
      update.assemble(points,
                      grid,
                      *cell_kernel,
                      increment,
                      prescribed,
                      system_constraints,
                      tangent_matrix,
                      internal_force,
                      tangent_scatter,
                      support_bands.empty() ? nullptr : &support_bands,
                      elastic_cells);
    yielding = count.yielded;
    // Cells or support points that the increment inverts (finite strain)
    // are left out of the system: such an increment has no residual.
    unsigned long long inverted = count.inverted_cells;
    // Contact forces are loads that depend on the increment: they join the
    // residual with the sign of the loads and their derivative the tangent.
    TrilinosWrappers::MPI::Vector contact_force;
    if (parts.contact != nullptr)
      {
        contact_force.reinit(newton_residual);
        contact_symmetric = parts.contact->add_newton_terms(grid,
                                                            *cell_kernel,
                                                            increment,
                                                            prescribed,
                                                            system_constraints,
                                                            tangent_matrix,
                                                            contact_force);
        contact_force.compress(VectorOperation::add);
      }
    // Finite strain: the supports' terms that depend on the stress of the
    // step's deformation (doc/finite-strain.md, "Supports in finite
    // strain"), apart from the points' internal force, whose size stays
    // the scale of the residual.
    TrilinosWrappers::MPI::Vector support_force;
    if (parts.finite_strain)
      {
        support_force.reinit(newton_residual);
        inverted += add_finite_strain_support_terms(update,
                                                    increment,
                                                    system_constraints,
                                                    &tangent_matrix,
                                                    support_force);
        support_force.compress(VectorOperation::add);
        // The share of the curves whose reactions are asked for, without
        // constraints (support_forces()).
        AffineConstraints<double> none;
        none.close();
        const auto &curves         = parts.curves.get_curves();
        const auto &support_curves = parts.reaction_curves;
        support_finite_strain_forces.resize(support_curves.size());
        for (unsigned int c = 0; c < support_curves.size(); ++c)
          {
            support_finite_strain_forces[c].reinit(newton_residual);
            add_finite_strain_support_terms(update,
                                            increment,
                                            none,
                                            nullptr,
                                            support_finite_strain_forces[c],
                                            &curves[support_curves[c]]);
            support_finite_strain_forces[c].compress(VectorOperation::add);
          }
      }
    tangent_matrix.compress(VectorOperation::add);
    internal_force.compress(VectorOperation::add);
    internal_force_norm = std::max(internal_force.l2_norm(), weight_norm);
    newton_residual -= internal_force;
    if (parts.finite_strain)
      newton_residual -= support_force;
    if (parts.contact != nullptr)
      newton_residual += contact_force;
    yielding = Utilities::MPI::sum(yielding, grid.mpi_communicator());
    // An increment that inverts a point is no admissible state: its |R| is
    // infinite, and Newton's line search takes a shorter step (or, at the
    // start of an increment, the load increment is cut).
    if (Utilities::MPI::sum(inverted, grid.mpi_communicator()) > 0)
      return std::numeric_limits<double>::infinity();
    return newton_residual.l2_norm();
  }


  unsigned long long
  SystemAssembly::add_finite_strain_support_terms(
    const ConstitutiveUpdate                         &update,
    const LinearAlgebra::distributed::Vector<double> &increment,
    const AffineConstraints<double>                  &constraints,
    TrilinosWrappers::SparseMatrix                   *tangent,
    TrilinosWrappers::MPI::Vector                    &force,
    const BoundaryCurve                              *only) const
  {
    // The supports leave out a point that the increment inverts; counted
    // here, so that newton_system() rejects the increment.
    unsigned long long  inverted = 0;
    const SupportStress stress =
      [&update, &inverted](const ArrayView<const double> &props,
                           const Tensor<2, 2>            &f,
                           Tensor<2, 2>                  &P,
                           Tensor<4, 2>                  &A) {
        const bool admissible = update.first_piola_stress(props, f, P, A);
        inverted += !admissible;
        return admissible;
      };
    const SupportMethod::Context context = support_context();
    for (const auto &method : parts.supports)
      if (only != nullptr ? method->imposes(*only) :
                            method->used_by(parts.curves))
        method->add_finite_strain_terms(
          context, increment, stress, constraints, tangent, force, only);
    return inverted;
  }



  std::vector<double>
  SystemAssembly::support_qualities(const std::vector<CellMoments> &moments,
                                    const ConstitutiveUpdate *update) const
  {
    return GhostPenalty::cell_qualities(parts.grid,
                                        moments,
                                        constraints(),
                                        update ?
                                          update->support_stiffness_ratios() :
                                          nullptr);
  }



  void
  SystemAssembly::check_loads_finite(const unsigned int step) const
  {
    // A load that is not finite (an expression dividing by zero, a density
    // or gravity of inf): say so before the solver turns it into NaN
    // displacements.
    AssertThrow(std::isfinite(rhs().l2_norm()),
                ExcMessage("The loads of load step " + std::to_string(step) +
                           " are not finite (NaN or inf): check the "
                           "tractions, prescribed displacements, density and "
                           "gravity of the scene."));
  }
} // namespace bsmpm
