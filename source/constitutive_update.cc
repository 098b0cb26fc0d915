#include <deal.II/base/mpi.h>

#include <bsmpm/constitutive_update.h>

namespace bsmpm
{
  namespace
  {
    using Property = MaterialPoints::Property;

    /** The nodal increment of the cell (with the prescribed part). */
    void
    local_increment(
      const DoFHandler<2>::active_cell_iterator        &cell,
      const LinearAlgebra::distributed::Vector<double> &increment,
      const LinearAlgebra::distributed::Vector<double> *prescribed,
      std::vector<types::global_dof_index>             &dof_indices,
      Q1CellKernel::LocalVector                        &d)
    {
      cell->get_dof_indices(dof_indices);
      for (unsigned int i = 0; i < Q1CellKernel::dofs_per_cell; ++i)
        d[i] = increment(dof_indices[i]) +
               (prescribed ? (*prescribed)(dof_indices[i]) : 0.);
    }
  } // namespace



  ConstitutiveUpdate::ConstitutiveUpdate(const ConstitutiveModel &model,
                                         const bool               b_bar)
    : model(model)
    , b_bar(b_bar)
  {}



  Tensor<2, 4>
  ConstitutiveUpdate::voigt_tangent(const SymmetricTensor<4, 3> &tangent)
  {
    // sigma_ij = T_ijkl eps_kl; the engineering shear gamma = 2 eps_xy
    // takes both T_ij01 and T_ij10 = T_ij01.
    static constexpr unsigned int index[4][2] = {{0, 0},
                                                 {1, 1},
                                                 {2, 2},
                                                 {0, 1}};
    Tensor<2, 4>                  D;
    for (unsigned int r = 0; r < 4; ++r)
      for (unsigned int c = 0; c < 4; ++c)
        D[r][c] = tangent[index[r][0]][index[r][1]][index[c][0]][index[c][1]];
    return D;
  }



  ConstitutiveUpdate::CellStrain
  ConstitutiveUpdate::cell_strain(
    const Q1CellKernel                                           &kernel,
    const Particles::ParticleHandler<2>::particle_iterator_range &cell_points,
    const Q1CellKernel::LocalVector                              &d) const
  {
    CellStrain strain;
    strain.coefficients = kernel.strain_coefficients(d);
    strain.use_b_bar    = false;
    if (!b_bar)
      return strain;
    // The volumetric strain of Q1 is affine in the cell, so its mean over
    // the points is its value at their volume-weighted centroid.
    double v = 0, vs = 0, vt = 0;
    for (const auto &particle : cell_points)
      {
        const double   volume = particle.get_properties()[Property::volume];
        const Point<2> st     = particle.get_reference_location();
        v += volume;
        vs += volume * st[0];
        vt += volume * st[1];
      }
    if (v == 0.)
      return strain;
    strain.use_b_bar = true;
    strain.centroid  = Point<2>(vs / v, vt / v);
    return strain;
  }



  void
  ConstitutiveUpdate::strain_columns(const Q1CellKernel          &kernel,
                                     const CellStrain            &strain,
                                     const Point<2>              &st,
                                     std::array<Voigt, 8>        &B,
                                     std::array<Tensor<1, 4>, 8> &B_bar)
  {
    for (unsigned int i = 0; i < Q1CellKernel::dofs_per_cell; ++i)
      {
        B[i] = kernel.strain_column(i, st);
        // B-bar: the point's volumetric strain replaced by the cell's mean,
        // eps_bar = eps + (theta_mean - theta) / 3 * 1 (zz included).
        double shift = 0;
        if (strain.use_b_bar)
          {
            const Voigt mean = kernel.strain_column(i, strain.centroid);
            shift            = (mean[0] + mean[1] - B[i][0] - B[i][1]) / 3;
          }
        B_bar[i] =
          Tensor<1, 4>({B[i][0] + shift, B[i][1] + shift, shift, B[i][2]});
      }
  }



  ConstitutiveResponse
  ConstitutiveUpdate::respond(const ArrayView<const double> &props,
                              const Tensor<1, 4>            &de,
                              ConstitutiveState             &state) const
  {
    SymmetricTensor<2, 3> &e = state.elastic_strain;
    e[0][0]                  = props[Property::elastic_strain] + de[0];
    e[1][1]                  = props[Property::elastic_strain + 1] + de[1];
    e[2][2]                  = props[Property::elastic_strain + 2] + de[2];
    e[0][1]                  = props[Property::elastic_strain + 3] + de[3] / 2;
    e[0][2] = e[1][2]               = 0;
    state.equivalent_plastic_strain = props[Property::plastic_strain];
    return model.update(state);
  }



  unsigned long long
  ConstitutiveUpdate::assemble(
    const MaterialPoints                             &points,
    const BackgroundGrid                             &grid,
    const Q1CellKernel                               &kernel,
    const LinearAlgebra::distributed::Vector<double> &increment,
    const LinearAlgebra::distributed::Vector<double> *prescribed,
    const AffineConstraints<double>                  &constraints,
    TrilinosWrappers::SparseMatrix                   &tangent,
    TrilinosWrappers::MPI::Vector                    &internal_force) const
  {
    constexpr unsigned int               n = Q1CellKernel::dofs_per_cell;
    const auto                          &particles = points.particle_handler();
    FullMatrix<double>                   cell_matrix(n, n);
    Vector<double>                       cell_vector(n);
    std::vector<types::global_dof_index> dof_indices(n);
    Q1CellKernel::LocalVector            d;
    std::array<Voigt, n>                 B;
    std::array<Tensor<1, 4>, n>          B_bar, DB_bar;
    ConstitutiveState                    state;
    unsigned long long                   n_yielded = 0;

    for (const auto &cell : grid.dof_handler().active_cell_iterators())
      {
        if (!cell->is_locally_owned() ||
            particles.n_particles_in_cell(cell) == 0)
          continue;
        local_increment(cell, increment, prescribed, dof_indices, d);
        const auto cell_points = particles.particles_in_cell(cell);
        const auto strain      = cell_strain(kernel, cell_points, d);
        bool       any         = false;
        cell_matrix            = 0;
        cell_vector            = 0;
        for (const auto &particle : cell_points)
          {
            const auto   props = particle.get_properties();
            const double w     = quadrature_weights ? props[Property::weight] :
                                                      props[Property::volume];
            if (props[Property::volume] == 0. || w == 0.)
              continue;
            any               = true;
            const Point<2> st = particle.get_reference_location();
            strain_columns(kernel, strain, st, B, B_bar);
            Tensor<1, 4> de;
            for (unsigned int i = 0; i < n; ++i)
              de += d[i] * B_bar[i];
            const auto response = respond(props, de, state);
            n_yielded += response.yielded;
            const Tensor<1, 4> sigma({response.stress[0][0],
                                      response.stress[1][1],
                                      response.stress[2][2],
                                      response.stress[0][1]});
            const Tensor<2, 4> D = voigt_tangent(response.tangent);
            for (unsigned int i = 0; i < n; ++i)
              DB_bar[i] = D * B_bar[i];
            for (unsigned int i = 0; i < n; ++i)
              {
                cell_vector[i] += w * (B_bar[i] * sigma);
                for (unsigned int j = 0; j < n; ++j)
                  cell_matrix(i, j) += w * (B_bar[i] * DB_bar[j]);
              }
          }
        if (any)
          constraints.distribute_local_to_global(
            cell_matrix, cell_vector, dof_indices, tangent, internal_force);
      }
    return n_yielded;
  }



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
    std::array<Voigt, n>                 B;
    std::array<Tensor<1, 4>, n>          B_bar;
    ConstitutiveState                    state;
    unsigned long long                   n_yielded = 0;
    for (const auto &cell : grid.dof_handler().active_cell_iterators())
      {
        if (!cell->is_locally_owned() ||
            particles.n_particles_in_cell(cell) == 0)
          continue;
        local_increment(cell, increment, prescribed, dof_indices, d);
        const auto cell_points  = particles.particles_in_cell(cell);
        const auto strain       = cell_strain(kernel, cell_points, d);
        const bool has_material = points.holds_material(cell);
        for (auto &particle : cell_points)
          {
            const Point<2> st = particle.get_reference_location();
            Tensor<1, 4>   de;
            if (has_material)
              {
                strain_columns(kernel, strain, st, B, B_bar);
                for (unsigned int i = 0; i < n; ++i)
                  de += d[i] * B_bar[i];
              }
            else
              {
                // Tracking points on the face of a cell without material.
                const Voigt e = points.boundary_strain(
                  kernel, cell, st, increment, prescribed);
                de = Tensor<1, 4>({e[0], e[1], 0., e[2]});
              }
            auto        props                   = particle.get_properties();
            const auto  response                = respond(props, de, state);
            const auto &eps                     = state.elastic_strain;
            props[Property::elastic_strain]     = eps[0][0];
            props[Property::elastic_strain + 1] = eps[1][1];
            props[Property::elastic_strain + 2] = eps[2][2];
            props[Property::elastic_strain + 3] = eps[0][1];
            props[Property::plastic_strain] = state.equivalent_plastic_strain;
            props[Property::stress]         = response.stress[0][0];
            props[Property::stress + 1]     = response.stress[1][1];
            props[Property::stress + 2]     = response.stress[0][1];
            props[Property::stress_zz]      = response.stress[2][2];
            props[Property::yielded]        = response.yielded ? 1. : 0.;
            n_yielded += response.yielded && props[Property::volume] > 0;
          }
      }
    return Utilities::MPI::sum(n_yielded, grid.mpi_communicator());
  }
} // namespace bsmpm
