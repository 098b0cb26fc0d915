#include <deal.II/base/mpi.h>

#include <bsmpm/assembly/constitutive_update.h>
#include <bsmpm/assembly/plane_strain_kinematics.h>
#include <bsmpm/assembly/point_moments.h>

#include <algorithm>
#include <cmath>

// ConstitutiveUpdate, part 5: the state at the end of a converged step,
// stored in the points, and how much of its elastic stiffness the material
// keeps round each vertex (support_stiffness_ratios()).

namespace bsmpm
{
  namespace
  {
    /** The 2x2 blocks of the vertices in the points' tangent with their
     * algorithmic (a) and elastic (e) tangents: K_xx, K_yy on the vertex's
     * two DoFs, K_xy on its first. */
    struct VertexStiffnessBlocks
    {
      explicit VertexStiffnessBlocks(const BackgroundGrid &grid)
        : diagonal_a(grid.locally_owned_dofs(),
                     grid.locally_relevant_dofs(),
                     grid.mpi_communicator())
        , diagonal_e(diagonal_a)
        , off_a(diagonal_a)
        , off_e(diagonal_a)
      {}

      /** Sums the blocks over the processes, with ghost values. */
      void
      compress()
      {
        for (auto *v : {&diagonal_a, &diagonal_e, &off_a, &off_e})
          {
            v->compress(VectorOperation::add);
            v->update_ghost_values();
          }
      }

      LinearAlgebra::distributed::Vector<double> diagonal_a, diagonal_e, off_a,
        off_e;
    };

    /** The points' tangents in a cell as moments (cell_system()): H_ab of
     * the points that yield, M_ab of those that do not, and of all. */
    struct CommittedTangentMoments
    {
      double H[6][16] = {}, M_elastic[6] = {}, M_all[6] = {};
      bool   plastic = false;

      /** Adds a point of weighted moments @p m (PointMoments::weighted())
       * and Voigt tangent @p tangent, if it yielded. */
      void
      add(const std::array<double, 6>  &m,
          const bool                    yielded,
          const std::array<double, 16> &tangent)
      {
        // A point that does not yield has the elastic tangent
        // (ConstitutiveResponse::yielded).
        plastic = plastic || yielded;
        for (unsigned int q = 0; q < 6; ++q)
          {
            M_all[q] += m[q];
            if (yielded)
              for (unsigned int k = 0; k < 16; ++k)
                H[q][k] += m[q] * tangent[k];
            else
              M_elastic[q] += m[q];
          }
      }
    };

    /**
     * Stores in the point of properties @p props the state of the end of
     * the step: @p state, the stress @p stress (xx, yy, zz, xy; Kirchhoff
     * in finite strain), whether it @p yielded, and its motion, F_n+1 =
     * (1 + @p grad) F_n; in finite strain also the volume, scaled by det f
     * = @p det_f, and the logarithmic strain.
     */
    void
    store_committed_state(const ArrayView<double>     &props,
                          const ConstitutiveState     &state,
                          const std::array<double, 4> &stress,
                          const bool                   yielded,
                          const Tensor<2, 2>          &grad,
                          const double                 det_f,
                          const bool                   finite)
    {
      using Property = MaterialPoints::Property;
      const Tensor<2, 2> F_n =
        PlaneStrainKinematics::stored_deformation_gradient(props);
      const auto &eps                     = state.elastic_strain;
      props[Property::elastic_strain]     = eps[0][0];
      props[Property::elastic_strain + 1] = eps[1][1];
      props[Property::elastic_strain + 2] = eps[2][2];
      props[Property::elastic_strain + 3] = eps[0][1];
      props[Property::plastic_strain]     = state.equivalent_plastic_strain;
      props[Property::yielded]            = yielded ? 1. : 0.;

      // The motion of the point: F_n+1 = f F_n.
      const Tensor<2, 2> F = (unit_symmetric_tensor<2>() + grad) * F_n;
      const double       J = determinant(F);
      props[Property::deformation_gradient]     = F[0][0];
      props[Property::deformation_gradient + 1] = F[0][1];
      props[Property::deformation_gradient + 2] = F[1][0];
      props[Property::deformation_gradient + 3] = F[1][1];
      props[Property::det_F]                    = J;

      // Cauchy stress: the Kirchhoff stress over J in finite strain.
      const double scale          = finite ? 1. / J : 1.;
      props[Property::stress]     = scale * stress[0];
      props[Property::stress + 1] = scale * stress[1];
      props[Property::stress + 2] = scale * stress[3];
      props[Property::stress_zz]  = scale * stress[2];
      if (finite)
        {
          // V = det(f) V_n; the strain is the logarithmic strain
          // ln(F F^T) / 2 (MaterialPoints::move() leaves it alone).
          props[Property::volume] *= det_f;
          Tensor<1, 3> log_strain;
          PlaneStrainKinematics::in_plane_function(
            PlaneStrainKinematics::push_forward(F, Tensor<1, 3>({1., 1., 0.})),
            PlaneStrainKinematics::log_of,
            PlaneStrainKinematics::inverse_of,
            log_strain,
            nullptr);
          props[Property::strain]     = log_strain[0] / 2;
          props[Property::strain + 1] = log_strain[1] / 2;
          props[Property::strain + 2] = log_strain[2] / 2;
        }
    }

    /**
     * Adds a cell's share to the vertices' 2 x 2 blocks @p blocks (at the
     * DoFs @p dof_indices) from the moments @p sums: with the (B-bar) strain
     * columns Bbar_i = sum_a m_a P_a,i (@p P), the block entry
     * sum_p w_p Bbar_i^T D_p Bbar_j is sum_ab P_a,i^T (H_ab + M_ab D_e)
     * P_b,j (its symmetric part for unsymmetric tangents), D_e =
     * @p elastic_voigt. Where no point yields, H is zero and M_elastic is
     * M_all, summed alike: the two blocks are then equal to the last bit.
     */
    void
    add_vertex_blocks(
      const Q1CellKernel &kernel,
      const Tensor<2, 4> &elastic_voigt,
      const std::array<std::array<Tensor<1, 4>, Q1CellKernel::dofs_per_cell>, 3>
                                                 &P,
      const CommittedTangentMoments              &sums,
      const std::vector<types::global_dof_index> &dof_indices,
      VertexStiffnessBlocks                      &blocks)
    {
      constexpr unsigned int n = Q1CellKernel::dofs_per_cell;
      std::array<std::array<Tensor<1, 4>, n>, 3> DP;
      for (unsigned int a = 0; a < 3; ++a)
        for (unsigned int i = 0; i < n; ++i)
          DP[a][i] = elastic_voigt * P[a][i];
      // The entry (i, j) of the points' tangent (a) and of the elastic
      // one (e).
      const auto entries = [&](const unsigned int i, const unsigned int j) {
        double held = 0, elastic = 0;
        for (unsigned int a = 0; a < 3; ++a)
          for (unsigned int b = 0; b < 3; ++b)
            {
              const unsigned int q   = PointMoments::index[a][b];
              const double       PP  = P[a][i] * DP[b][j];
              double             PHP = 0;
              if (sums.plastic)
                for (unsigned int r = 0; r < 4; ++r)
                  for (unsigned int c = 0; c < 4; ++c)
                    PHP += P[a][i][r] * sums.H[q][4 * r + c] * P[b][j][c];
              held += PHP + sums.M_elastic[q] * PP;
              elastic += sums.M_all[q] * PP;
            }
        return std::make_pair(held, elastic);
      };
      for (unsigned int i = 0; i < n; ++i)
        {
          const auto [held, elastic] = entries(i, i);
          blocks.diagonal_a(dof_indices[i]) += held;
          blocks.diagonal_e(dof_indices[i]) += elastic;
          if (kernel.component(i) == 0)
            for (unsigned int j = 0; j < n; ++j)
              if (kernel.component(j) == 1 &&
                  kernel.vertex(j) == kernel.vertex(i))
                {
                  const auto [held_ij, elastic_ij] = entries(i, j);
                  // The symmetric part (unsymmetric tangents).
                  blocks.off_a(dof_indices[i]) +=
                    (held_ij + entries(j, i).first) / 2;
                  blocks.off_e(dof_indices[i]) += elastic_ij;
                }
        }
    }

    /** The ratios rho_v of ConstitutiveUpdate::support_stiffness_ratios()
     * into @p ratios from the summed blocks @p blocks. */
    void
    set_stiffness_ratios(
      const BackgroundGrid                             &grid,
      const Q1CellKernel                               &kernel,
      const LinearAlgebra::distributed::Vector<double> *prescribed,
      const VertexStiffnessBlocks                      &blocks,
      LinearAlgebra::distributed::Vector<double>       &ratios)
    {
      constexpr unsigned int n = Q1CellKernel::dofs_per_cell;
      ratios.reinit(blocks.diagonal_a);
      const auto smallest_eigenvalue =
        [](const double a, const double b, const double c) {
          // Of [[a, c], [c, b]].
          return (a + b) / 2 - std::sqrt((a - b) * (a - b) / 4 + c * c);
        };
      std::vector<types::global_dof_index> vertex_dofs(n);
      for (const auto &cell : grid.dof_handler().active_cell_iterators())
        {
          if (!cell->is_locally_owned())
            continue;
          cell->get_dof_indices(vertex_dofs);
          for (unsigned int i = 0; i < n; ++i)
            if (kernel.component(i) == 0)
              for (unsigned int j = 0; j < n; ++j)
                if (kernel.component(j) == 1 &&
                    kernel.vertex(j) == kernel.vertex(i))
                  {
                    const auto   x = vertex_dofs[i], y = vertex_dofs[j];
                    const double elastic =
                      smallest_eigenvalue(blocks.diagonal_e(x),
                                          blocks.diagonal_e(y),
                                          blocks.off_e(x));
                    const double held =
                      smallest_eigenvalue(blocks.diagonal_a(x),
                                          blocks.diagonal_a(y),
                                          blocks.off_a(x));
                    // Exactly 1 where the sums are the same (every point
                    // elastic); nothing held: 1 as well (no material). A
                    // vertex that a prescribed displacement moves (a
                    // footing's base crosses its cells) is held by it.
                    const bool supported =
                      prescribed != nullptr &&
                      ((*prescribed)(x) != 0. || (*prescribed)(y) != 0.);
                    const double ratio =
                      (elastic > 0 && held != elastic && !supported) ?
                        std::clamp(held / elastic, 0., 1.) :
                        1.;
                    if (grid.locally_owned_dofs().is_element(x))
                      ratios(x) = ratio;
                    if (grid.locally_owned_dofs().is_element(y))
                      ratios(y) = ratio;
                  }
        }
      ratios.update_ghost_values();
    }
  } // namespace



  unsigned long long
  ConstitutiveUpdate::commit(
    MaterialPoints                                   &points,
    const BackgroundGrid                             &grid,
    const Q1CellKernel                               &kernel,
    const LinearAlgebra::distributed::Vector<double> &increment,
    const LinearAlgebra::distributed::Vector<double> *prescribed) const
  {
    constexpr unsigned int               n = Q1CellKernel::dofs_per_cell;
    auto                                &particles = points.particle_handler();
    std::vector<types::global_dof_index> dof_indices(n);
    Q1CellKernel::LocalVector            d;
    std::vector<PointView>               views;
    ConstitutiveState                    state;
    unsigned long long                   n_yielded = 0;
    points.find_material_cells();
    const bool finite = point_kinematics == Kinematics::finite_strain;
    VertexStiffnessBlocks blocks(grid);
    for (const auto &cell : grid.dof_handler().active_cell_iterators())
      {
        if (!cell->is_locally_owned() ||
            particles.n_particles_in_cell(cell) == 0)
          continue;
        d                      = MaterialPoints::cell_increment(cell,
                                           increment,
                                           prescribed,
                                           dof_indices);
        const auto cell_points = particles.particles_in_cell(cell);
        gather_points(cell_points, particles.n_particles_in_cell(cell), views);
        const bool has_material = points.holds_material(cell);
        CellStrain strain;
        if (has_material)
          strain = cell_strain(kernel,
                               views,
                               d,
                               exact_moments ?
                                 &(*exact_moments)[cell->active_cell_index()] :
                                 nullptr);
        CommittedTangentMoments sums;
        // grad u is affine in the cell: its three parts once.
        const std::array<Tensor<2, 2>, 3> gradient =
          kernel.gradient_coefficients(d);
        for (auto &particle : cell_points)
          {
            const Point<2> st    = particle.get_reference_location();
            auto           props = particle.get_properties();
            // Tracking points on the face of a cell without material take
            // the field of the neighbour that holds material.
            const Tensor<2, 2> grad =
              has_material ?
                gradient[0] + st[0] * gradient[1] + st[1] * gradient[2] :
                points.boundary_gradient(
                  kernel, cell, st, increment, prescribed);
            std::array<double, 4>  stress;
            std::array<double, 16> tangent;
            bool                   yielded = false;
            double                 det_f   = 1;
            if (finite)
              {
                const FiniteStrainPoint kin = finite_strain_trial(
                  kernel, strain, st, props, d, &grad, state);
                det_f                        = kin.det_f;
                const ConstitutiveResponse r = model_of(props).update(state);
                ConstitutiveModel::plane_strain_response(r, stress, tangent);
                yielded = r.yielded;
              }
            else
              {
                Tensor<1, 4> de;
                if (has_material)
                  de = strain_increment(strain, st);
                else
                  {
                    const Voigt e = points.boundary_strain(
                      kernel, cell, st, increment, prescribed);
                    de = Tensor<1, 4>({e[0], e[1], 0., e[2]});
                  }
                yielded = respond(props, de, state, stress, tangent);
              }
            if (has_material && props[Property::volume] > 0.)
              sums.add(PointMoments::weighted(integration_weight(props), st),
                       yielded || other_body_tangent(props, tangent),
                       tangent);
            n_yielded += yielded && props[Property::volume] > 0;
            store_committed_state(
              props, state, stress, yielded, grad, det_f, finite);
          }
        if (has_material)
          add_vertex_blocks(
            kernel, elastic_voigt, strain.columns, sums, dof_indices, blocks);
      }
    blocks.compress();
    set_stiffness_ratios(grid, kernel, prescribed, blocks, stiffness_ratio);
    return Utilities::MPI::sum(n_yielded, grid.mpi_communicator());
  }
} // namespace bsmpm
