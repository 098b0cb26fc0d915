#include <bsmpm/points/q1_cell_kernel.h>

#include <cmath>

namespace bsmpm
{
  namespace
  {
    // dN_v/ds = a_v + t b_v and dN_v/dt = c_v + s d_v for the vertices
    // (0,0), (1,0), (0,1), (1,1) of the unit square.
    constexpr std::array<double, 4> a = {{-1., 1., 0., 0.}};
    constexpr std::array<double, 4> b = {{1., -1., -1., 1.}};
    constexpr std::array<double, 4> c = {{-1., 0., 1., 0.}};
    constexpr std::array<double, 4> d = {{1., -1., -1., 1.}};
  } // namespace



  Q1CellKernel::Q1CellKernel(const FiniteElement<2> &fe,
                             const Tensor<1, 2>     &cell_size,
                             const Tensor<2, 3>     &C,
                             const bool              b_bar)
    : C(C)
  {
    AssertThrow(fe.n_dofs_per_cell() == dofs_per_cell && fe.n_components() == 2,
                ExcMessage("Q1CellKernel needs FESystem(FE_Q(1), 2)."));
    const double hx = cell_size[0], hy = cell_size[1];
    Assert(hx > 0 && hy > 0, ExcMessage("Cell size must be positive."));

    for (unsigned int i = 0; i < dofs_per_cell; ++i)
      {
        const auto ci    = fe.system_to_component_index(i);
        dof_component[i] = ci.first;
        dof_vertex[i]    = ci.second;

        const unsigned int v = dof_vertex[i];
        // Rows of B: (d/dx, 0, d/dy) on component 0, (0, d/dy, d/dx) on 1.
        const unsigned int x_row = dof_component[i] == 0 ? 0 : 2;
        const unsigned int y_row = dof_component[i] == 0 ? 2 : 1;
        for (unsigned int r = 0; r < 3; ++r)
          B0[r][i] = Bs[r][i] = Bt[r][i] = 0.;
        B0[x_row][i] = a[v] / hx;
        Bt[x_row][i] = b[v] / hx;
        B0[y_row][i] = c[v] / hy;
        Bs[y_row][i] = d[v] / hy;
      }

    for (unsigned int i = 0; i < dofs_per_cell; ++i)
      {
        theta_s[i] = Bs[0][i] + Bs[1][i];
        theta_t[i] = Bt[0][i] + Bt[1][i];
      }
    if (b_bar)
      {
        // C = lambda m m^T + mu diag(2, 2, 1) (plane strain, or plane
        // stress with its own lambda): then C maps the in-plane volumetric
        // strain (1, 1, 0) theta / 2 to kappa theta (1, 1, 0) and the
        // deviatoric strain to a deviatoric stress, which is what the
        // rank-two form of add_stiffness() needs.
        const double scale = std::abs(C[0][0]) + std::abs(C[2][2]);
        const double tol   = 1e-12 * scale;
        AssertThrow(std::abs(C[0][0] - C[1][1]) <= tol &&
                      std::abs(C[0][2]) <= tol && std::abs(C[1][2]) <= tol &&
                      std::abs(C[0][0] - C[0][1] - 2 * C[2][2]) <= tol,
                    ExcMessage("B-bar in the linear kernel needs an isotropic "
                               "material matrix."));
        kappa = (C[0][0] + C[0][1]) / 2;
      }

    // X^T C Y for 3x8 arrays X, Y.
    const auto product = [&C](const auto        &X,
                              const auto        &Y,
                              const unsigned int i,
                              const unsigned int j) {
      double sum = 0;
      for (unsigned int p = 0; p < 3; ++p)
        for (unsigned int q = 0; q < 3; ++q)
          sum += X[p][i] * C[p][q] * Y[q][j];
      return sum;
    };
    for (unsigned int i = 0; i < dofs_per_cell; ++i)
      for (unsigned int j = 0; j < dofs_per_cell; ++j)
        {
          const unsigned int ij = i * dofs_per_cell + j;
          blocks[0][ij]         = product(B0, B0, i, j);
          blocks[1][ij]         = product(B0, Bs, i, j) + product(Bs, B0, i, j);
          blocks[2][ij]         = product(B0, Bt, i, j) + product(Bt, B0, i, j);
          blocks[3][ij]         = product(Bs, Bs, i, j);
          blocks[4][ij]         = product(Bt, Bt, i, j);
          blocks[5][ij]         = product(Bs, Bt, i, j) + product(Bt, Bs, i, j);
        }
  }



  Tensor<1, 2>
  Q1CellKernel::shape_value(const unsigned int i, const Point<2> &st) const
  {
    Tensor<1, 2> value;
    value[dof_component[i]] = vertex_shape_values(st)[dof_vertex[i]];
    return value;
  }



  Tensor<2, 2>
  Q1CellKernel::shape_gradient(const unsigned int i, const Point<2> &st) const
  {
    // Recover d/dx and d/dy from the rows of B.
    const Voigt        col = strain_column(i, st);
    Tensor<2, 2>       grad;
    const unsigned int comp = dof_component[i];
    if (comp == 0)
      {
        grad[0][0] = col[0];
        grad[0][1] = col[2];
      }
    else
      {
        grad[1][1] = col[1];
        grad[1][0] = col[2];
      }
    return grad;
  }



  void
  Q1CellKernel::add_stiffness(const CellMoments &m, FullMatrix<double> &K) const
  {
    const std::array<double, 6> w = {{m.v, m.vs, m.vt, m.vss, m.vtt, m.vst}};
    double                     *k = &K(0, 0);
    for (unsigned int ij = 0; ij < dofs_per_cell * dofs_per_cell; ++ij)
      k[ij] += w[0] * blocks[0][ij] + w[1] * blocks[1][ij] +
               w[2] * blocks[2][ij] + w[3] * blocks[3][ij] +
               w[4] * blocks[4][ij] + w[5] * blocks[5][ij];
    if (kappa > 0 && m.v > 0)
      {
        // B-bar: minus kappa sum_p V_p (g_p - g_bar)(g_p - g_bar)^T, with
        // g_p - g_bar = (s - s_bar) theta_s + (t - t_bar) theta_t: the
        // central second moments times the volumetric columns
        // (doc/b-bar.md).
        const double css = m.vss - m.vs * m.vs / m.v;
        const double ctt = m.vtt - m.vt * m.vt / m.v;
        const double cst = m.vst - m.vs * m.vt / m.v;
        LocalVector  a, b;
        for (unsigned int i = 0; i < dofs_per_cell; ++i)
          {
            a[i] = kappa * (css * theta_s[i] + cst * theta_t[i]);
            b[i] = kappa * (cst * theta_s[i] + ctt * theta_t[i]);
          }
        for (unsigned int i = 0; i < dofs_per_cell; ++i)
          for (unsigned int j = 0; j < dofs_per_cell; ++j)
            k[i * dofs_per_cell + j] -= a[i] * theta_s[j] + b[i] * theta_t[j];
      }
  }



  void
  Q1CellKernel::add_internal_force(const CellMoments &m,
                                   Vector<double>    &f) const
  {
    for (unsigned int i = 0; i < dofs_per_cell; ++i)
      {
        double sum = 0;
        for (unsigned int r = 0; r < 3; ++r)
          sum += B0[r][i] * m.stress[r] + Bs[r][i] * m.stress_s[r] +
                 Bt[r][i] * m.stress_t[r];
        f[i] += sum;
      }
    if (kappa > 0 && m.v > 0)
      {
        // B-bar: sum_p V_p (theta_i(centroid) - theta_i(p)) tr(sigma_p) / 2.
        const Point<2> c  = centroid(m);
        const double   as = ((m.stress[0] + m.stress[1]) * c[0] -
                           (m.stress_s[0] + m.stress_s[1])) /
                          2;
        const double at = ((m.stress[0] + m.stress[1]) * c[1] -
                           (m.stress_t[0] + m.stress_t[1])) /
                          2;
        for (unsigned int i = 0; i < dofs_per_cell; ++i)
          f[i] += theta_s[i] * as + theta_t[i] * at;
      }
  }



  void
  Q1CellKernel::add_body_force(const CellMoments  &m,
                               const Tensor<1, 2> &body_force,
                               Vector<double>     &f) const
  {
    // sum_p V_p N_v(s_p, t_p) for the bilinear N_v, from the moments.
    const std::array<double, 4> weight = {
      {m.v - m.vs - m.vt + m.vst, m.vs - m.vst, m.vt - m.vst, m.vst}};
    for (unsigned int i = 0; i < dofs_per_cell; ++i)
      f[i] += weight[dof_vertex[i]] * body_force[dof_component[i]];
  }



  std::array<Voigt, 3>
  Q1CellKernel::strain_coefficients(const LocalVector &u) const
  {
    std::array<Voigt, 3> e;
    for (unsigned int r = 0; r < 3; ++r)
      for (unsigned int i = 0; i < dofs_per_cell; ++i)
        {
          e[0][r] += B0[r][i] * u[i];
          e[1][r] += Bs[r][i] * u[i];
          e[2][r] += Bt[r][i] * u[i];
        }
    return e;
  }
} // namespace bsmpm
