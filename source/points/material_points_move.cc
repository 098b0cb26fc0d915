#include <deal.II/base/mpi.h>

#include <bsmpm/points/material_points.h>

#include <cmath>

// MaterialPoints, part 2: the move of the points by a load increment
// (paper eqs 5-8), and what it reports.

namespace bsmpm
{
  namespace
  {
    /** The squares of the largest total displacement, stress (Frobenius)
     * and displacement increment of the points with volume that a move has
     * seen: squares in the loop, one square root after it (a square root,
     * and hypot's care for overflow, per point was a tenth of the loop). */
    struct MoveMaxima
    {
      double displacement_square = 0;
      double stress_square       = 0;
      double increment_square    = 0;

      /** The point of the moved properties @p props; its increment @p du
       * counts if @p finite. */
      void
      add(const ArrayView<double> &props,
          const Tensor<1, 2>      &du,
          const bool               finite)
      {
        using Property = MaterialPoints::Property;
        if (props[Property::volume] > 0)
          {
            displacement_square =
              std::max(displacement_square,
                       props[Property::displacement] *
                           props[Property::displacement] +
                         props[Property::displacement + 1] *
                           props[Property::displacement + 1]);
            stress_square = std::max(
              stress_square,
              props[Property::stress] * props[Property::stress] +
                props[Property::stress + 1] * props[Property::stress + 1] +
                2 * props[Property::stress + 2] * props[Property::stress + 2]);
          }
        if (finite && props[Property::volume] > 0)
          increment_square = std::max(increment_square, du.norm_square());
      }
    };

    /**
     * A point on a face of the grid (a curve that ends on a face's support,
     * as the footing's base at the symmetry line) stays in the grid when
     * the increment carries it out by no more than the implicit boundary's
     * inexactness (1e-9 .. 1e-7 h seen where a support lies on a grid
     * line); a real departure is reported by move(). The position @p x
     * itself is set to the face, and the increment @p du from @p location
     * with it: adding the overshoot to the increment is lost to rounding
     * when the increment is much larger than the overshoot.
     */
    void
    keep_on_grid_faces(Point<2>           &x,
                       Tensor<1, 2>       &du,
                       const Point<2>     &location,
                       const Point<2>     &lower,
                       const Point<2>     &upper,
                       const Tensor<1, 2> &face_tolerance)
    {
      for (unsigned int k = 0; k < 2; ++k)
        {
          const double tolerance = face_tolerance[k];
          const double face =
            x[k] < lower[k] && x[k] >= lower[k] - tolerance ? lower[k] :
            x[k] > upper[k] && x[k] <= upper[k] + tolerance ? upper[k] :
                                                              x[k];
          if (face != x[k])
            {
              x[k]  = face;
              du[k] = face - location[k];
            }
        }
    }

    /** Makes @p report the same on every process of @p comm: the maxima
     * @p maxima and counts over all of them, the example point (and its
     * cell's quality) of the first process that @p found_example. */
    void
    gather_move_report(MaterialPoints::MoveReport &report,
                       const MoveMaxima           &maxima,
                       const bool                  found_example,
                       const MPI_Comm              comm)
    {
      report.max_displacement =
        Utilities::MPI::max(std::sqrt(maxima.displacement_square), comm);
      report.max_stress =
        Utilities::MPI::max(std::sqrt(maxima.stress_square), comm);
      report.n_left_grid  = Utilities::MPI::sum(report.n_left_grid, comm);
      report.n_non_finite = Utilities::MPI::sum(report.n_non_finite, comm);
      report.max_increment =
        Utilities::MPI::max(std::sqrt(maxima.increment_square), comm);
      const unsigned int rank     = Utilities::MPI::this_mpi_process(comm);
      const unsigned int reporter = Utilities::MPI::min(
        found_example ? rank : numbers::invalid_unsigned_int, comm);
      if (reporter != numbers::invalid_unsigned_int)
        {
          report.example =
            Utilities::MPI::broadcast(comm, report.example, reporter);
          report.example_quality =
            Utilities::MPI::broadcast(comm, report.example_quality, reporter);
        }
    }
  } // namespace



  MaterialPoints::MoveReport
  MaterialPoints::move(
    const Q1CellKernel                               &kernel,
    const LinearElasticMaterial                      &material,
    const LinearAlgebra::distributed::Vector<double> &increment,
    const LinearAlgebra::distributed::Vector<double> *prescribed,
    const std::vector<bool>                          *support_cells,
    const SupportFunction                            &support,
    const std::vector<double>                        *cell_quality,
    const bool                                        update_stress,
    const bool                                        update_strain,
    const std::vector<CellMoments>                   *cell_moments)
  {
    const Tensor<2, 3> &C = material.stiffness();
    MoveReport          report;
    bool                found_example = false;
    MoveMaxima          maxima;
    tracked_local.clear();
    neighbourhood_current = false;
    find_material_cells();

    std::vector<types::global_dof_index> dof_indices(
      Q1CellKernel::dofs_per_cell);
    Q1CellKernel::LocalVector d, da{}, total;
    // The grid's faces and the tolerance on them, read once: in the loop
    // the compiler cannot keep them in registers across the writes to the
    // points' properties (the same values and comparisons as
    // BackgroundGrid::contains()).
    const Point<2>     lower = grid.lower_left();
    const Point<2>     upper = grid.upper_right();
    const Tensor<1, 2> face_tolerance(
      {1e-6 * grid.cell_size()[0], 1e-6 * grid.cell_size()[1]});
    const auto in_grid = [&lower, &upper](const Point<2> &p) {
      return p[0] >= lower[0] && p[0] <= upper[0] && p[1] >= lower[1] &&
             p[1] <= upper[1];
    };
    const bool any_rigid_increments = !rigid_increments.empty();
    const bool any_tracked          = !is_tracked.empty();
    for (const auto &cell : grid.dof_handler().active_cell_iterators())
      {
        if (!cell->is_locally_owned() ||
            particles.n_particles_in_cell(cell) == 0)
          continue;
        cell->get_dof_indices(dof_indices);
        for (unsigned int i = 0; i < Q1CellKernel::dofs_per_cell; ++i)
          {
            d[i] = increment(dof_indices[i]);
            if (prescribed)
              da[i] = (*prescribed)(dof_indices[i]);
            total[i] = d[i] + da[i];
          }
        const auto e = kernel.strain_coefficients(total);
        const bool near_support =
          support_cells && (*support_cells)[cell->active_cell_index()];
        const bool has_material = holds_material(cell);
        // B-bar: the volumetric strain of the stress is that at the
        // centroid of the moments the cell's stiffness was made of.
        const bool b_bar =
          kernel.uses_b_bar() && cell_moments != nullptr && has_material;
        const Point<2> centroid =
          b_bar ?
            Q1CellKernel::centroid((*cell_moments)[cell->active_cell_index()]) :
            Point<2>();

        for (auto &particle : particles.particles_in_cell(cell))
          {
            const Point<2> st = particle.get_reference_location();
            Voigt          de = e[0] + st[0] * e[1] + st[1] * e[2];
            if (!has_material)
              de = boundary_strain(kernel, cell, st, increment, prescribed);
            const Voigt ds = b_bar ? kernel.stress(e, st, centroid) : C * de;
            auto        du = kernel.displacement(d, st);
            double      D  = 1;
            if (near_support)
              D = support(
                particle.get_location(),
                [&](const Point<2> &y) {
                  return kernel.displacement(
                    d, grid.local_coordinates(y, grid.cell_index(cell)));
                },
                du);
            if (prescribed)
              du += kernel.displacement(da, st);
            // A tracking point of a rigid body pushed along its normal (a
            // smooth footing) moves with the body, not with the soil that
            // slides along it (BoundaryCurve::rigid_support()).
            if (any_rigid_increments &&
                particle.get_properties()[Property::volume] == 0.)
              {
                const unsigned int slot = tracked_slot(particle.get_id());
                if (slot < rigid_increments.size() &&
                    rigid_increments[slot].first)
                  du = rigid_increments[slot].second;
              }

            Point<2> x = particle.get_location() + du;
            keep_on_grid_faces(
              x, du, particle.get_location(), lower, upper, face_tolerance);
            auto props                  = particle.get_properties();
            props[Property::d_function] = D;
            for (unsigned int r = 0; r < 3; ++r)
              {
                if (update_stress)
                  props[Property::stress + r] += ds[r];
                // Stored strain is the tensor component: eps_xy = gamma/2.
                if (update_strain)
                  props[Property::strain + r] += (r == 2 ? de[r] / 2 : de[r]);
              }
            props[Property::displacement] += du[0];
            props[Property::displacement + 1] += du[1];

            const bool finite = std::isfinite(du[0]) && std::isfinite(du[1]);
            maxima.add(props, du, finite);
            report.n_non_finite += !finite;
            if (!finite || !in_grid(x))
              {
                ++report.n_left_grid;
                if (!found_example)
                  {
                    report.example = x;
                    if (cell_quality)
                      report.example_quality =
                        (*cell_quality)[cell->active_cell_index()];
                  }
                found_example = true;
              }
            particle.set_location(x);
            if (any_tracked)
              record_if_tracked(particle.get_id(), x, props);
          }
      }
    gather_move_report(report, maxima, found_example, grid.mpi_communicator());
    return report;
  }
} // namespace bsmpm
