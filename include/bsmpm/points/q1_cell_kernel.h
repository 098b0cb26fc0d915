#ifndef bsmpm_q1_cell_kernel_h
#define bsmpm_q1_cell_kernel_h

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <deal.II/fe/fe.h>

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include <bsmpm/materials/material.h>

#include <array>

namespace bsmpm
{
  using namespace dealii;

  /**
   * Volume-weighted sums over the material points of one cell, in the local
   * coordinates (s, t) in [0, 1]^2 of that cell: the six volume moments and
   * the three stress moments of method-notes Sec. 8. With them the
   * stiffness, internal force and body force of the cell are exact, whatever
   * the number of points in it.
   */
  struct CellMoments
  {
    double v = 0, vs = 0, vt = 0, vss = 0, vtt = 0, vst = 0;
    Voigt  stress, stress_s, stress_t;

    void
    add(const Point<2> &st, const double volume, const Voigt &sigma)
    {
      const double s = st[0], t = st[1];
      const double vs_ = volume * s, vt_ = volume * t;
      v += volume;
      vs += vs_;
      vt += vt_;
      vss += vs_ * s;
      vtt += vt_ * t;
      vst += vs_ * t;
      stress += volume * sigma;
      stress_s += vs_ * sigma;
      stress_t += vt_ * sigma;
    }
  };



  /**
   * The vector-valued bilinear element FESystem(FE_Q(1), 2) on an
   * axis-aligned cell of size hx x hy, written down in closed form.
   *
   * In local coordinates s = (x - x0)/hx, t = (y - y0)/hy the
   * strain-displacement matrix is affine, B(s, t) = B0 + s Bs + t Bt, because
   * dN/dx depends on t only and dN/dy on s only. Hence the material-point
   * stiffness sum_p V_p B^T C B is a combination of six fixed 8x8 matrices
   * weighted by the CellMoments (method-notes Sec. 8), and reading the points
   * once per step is all the assembly costs.
   *
   * With B-bar (the default of the linear path, doc/b-bar.md) every point's
   * volumetric strain theta = eps_xx + eps_yy is replaced by the mean over
   * the cell's material, theta at the centroid (vs/v, vt/v) of the moments
   * (theta is affine in the cell). For an isotropic C = lambda m m^T +
   * mu diag(2, 2, 1) the B-bar stress is C eps + kappa (theta_bar - theta)
   * (1, 1, 0) with kappa = lambda + mu, and the stiffness is the standard
   * one minus kappa times the covariance of the points' volumetric strain
   * columns: a rank-two update from the second central moments.
   */
  class Q1CellKernel
  {
  public:
    static constexpr unsigned int dofs_per_cell = 8;
    using LocalVector = std::array<double, dofs_per_cell>;

    /**
     * @p fe must be FESystem(FE_Q(1), 2): its numbering of local DoFs is read
     * from it. @p C is the Voigt stiffness of the material. With
     * @p b_bar the cell-mean volumetric strain replaces the points' own
     * (C must then be isotropic).
     */
    Q1CellKernel(const FiniteElement<2> &fe,
                 const Tensor<1, 2>     &cell_size,
                 const Tensor<2, 3>     &C,
                 const bool              b_bar = false);

    /** Whether the volumetric strain is the cell's mean (B-bar). */
    bool
    uses_b_bar() const
    {
      return kappa > 0;
    }

    /**
     * The local coordinates of the volume-weighted centroid of the moments
     * @p m, where the volumetric strain takes its mean over the cell
     * (B-bar); (0.5, 0.5) for an empty cell.
     */
    static Point<2>
    centroid(const CellMoments &m)
    {
      return m.v > 0 ? Point<2>(m.vs / m.v, m.vt / m.v) : Point<2>(0.5, 0.5);
    }

    /**
     * The stress of the strain coefficients @p e (strain_coefficients()) at
     * @p st of a cell whose points have the centroid @p centroid: C eps,
     * with B-bar plus kappa (theta(centroid) - theta(st)) (1, 1, 0).
     */
    Voigt
    stress(const std::array<Voigt, 3> &e,
           const Point<2>             &st,
           const Point<2>             &centroid) const
    {
      const Voigt eps   = e[0] + st[0] * e[1] + st[1] * e[2];
      Voigt       sigma = C * eps;
      if (kappa > 0)
        {
          const double shift =
            kappa * ((centroid[0] - st[0]) * (e[1][0] + e[1][1]) +
                     (centroid[1] - st[1]) * (e[2][0] + e[2][1]));
          sigma[0] += shift;
          sigma[1] += shift;
        }
      return sigma;
    }

    /**
     * The stress of shape function @p i at @p st: C B_i, with B-bar plus
     * kappa (theta_i(centroid) - theta_i(st)) (1, 1, 0). What boundary
     * terms (Nitsche, the implicit boundary's band) pair with the cell's
     * stiffness.
     */
    Voigt
    stress_column(const unsigned int i,
                  const Point<2>    &st,
                  const Point<2>    &centroid) const
    {
      Voigt sigma = C * strain_column(i, st);
      if (kappa > 0)
        {
          const double shift = kappa * ((centroid[0] - st[0]) * theta_s[i] +
                                        (centroid[1] - st[1]) * theta_t[i]);
          sigma[0] += shift;
          sigma[1] += shift;
        }
      return sigma;
    }

    /** Bilinear shape values of the four vertices (lexicographic order). */
    static std::array<double, 4>
    vertex_shape_values(const Point<2> &st)
    {
      const double s = st[0], t = st[1];
      return {{(1 - s) * (1 - t), s * (1 - t), (1 - s) * t, s * t}};
    }

    /** Vertex and vector component of local DoF @p i. */
    unsigned int
    vertex(const unsigned int i) const
    {
      return dof_vertex[i];
    }
    unsigned int
    component(const unsigned int i) const
    {
      return dof_component[i];
    }

    /** Value of shape function @p i (a vector) at @p st. */
    Tensor<1, 2>
    shape_value(const unsigned int i, const Point<2> &st) const;

    /** Gradient of shape function @p i (a 2x2 tensor, row = component). */
    Tensor<2, 2>
    shape_gradient(const unsigned int i, const Point<2> &st) const;

    /** Column @p i of B(s, t): the Voigt strain of shape function i. */
    Voigt
    strain_column(const unsigned int i, const Point<2> &st) const
    {
      Voigt b;
      for (unsigned int r = 0; r < 3; ++r)
        b[r] = B0[r][i] + st[0] * Bs[r][i] + st[1] * Bt[r][i];
      return b;
    }

    /**
     * The three parts of column @p i of B(s, t) = B0 + s Bs + t Bt:
     * column i of B0, Bs and Bt. What an assembly that sums its points'
     * moments itself (ConstitutiveUpdate::cell_system) multiplies them
     * with.
     */
    std::array<Voigt, 3>
    strain_column_parts(const unsigned int i) const
    {
      std::array<Voigt, 3> parts;
      for (unsigned int r = 0; r < 3; ++r)
        {
          parts[0][r] = B0[r][i];
          parts[1][r] = Bs[r][i];
          parts[2][r] = Bt[r][i];
        }
      return parts;
    }

    /** K += sum_p V_p B_p^T C B_p from the moments of the cell. */
    void
    add_stiffness(const CellMoments &m, FullMatrix<double> &K) const;

    /** f += sum_p V_p B_p^T sigma_p. */
    void
    add_internal_force(const CellMoments &m, Vector<double> &f) const;

    /** f += sum_p V_p N_p^T b for a uniform body force b per unit volume. */
    void
    add_body_force(const CellMoments  &m,
                   const Tensor<1, 2> &body_force,
                   Vector<double>     &f) const;

    /**
     * The strain of the local displacements @p d is affine in the cell:
     * eps(s, t) = e[0] + s e[1] + t e[2]. Returns e.
     */
    std::array<Voigt, 3>
    strain_coefficients(const LocalVector &d) const;

    /**
     * The gradient of the local displacements @p d is affine in the cell
     * too: grad u(s, t) = g[0] + s g[1] + t g[2] (row = component).
     * Returns g: what a loop over many points of the cell takes once.
     */
    std::array<Tensor<2, 2>, 3>
    gradient_coefficients(const LocalVector &d) const
    {
      std::array<Tensor<2, 2>, 3> g;
      for (unsigned int i = 0; i < dofs_per_cell; ++i)
        {
          const std::array<Voigt, 3> parts = strain_column_parts(i);
          for (unsigned int a = 0; a < 3; ++a)
            {
              const Voigt &b = parts[a];
              if (dof_component[i] == 0)
                {
                  g[a][0][0] += d[i] * b[0];
                  g[a][0][1] += d[i] * b[2];
                }
              else
                {
                  g[a][1][0] += d[i] * b[2];
                  g[a][1][1] += d[i] * b[1];
                }
            }
        }
      return g;
    }

    /** Gradient (row = component) of the local displacements @p d at
     * @p st. */
    Tensor<2, 2>
    gradient(const LocalVector &d, const Point<2> &st) const
    {
      Tensor<2, 2> grad;
      for (unsigned int i = 0; i < dofs_per_cell; ++i)
        grad[dof_component[i]] += d[i] * scalar_gradient(i, st);
      return grad;
    }

    /** Gradient of the scalar shape function of the vertex of DoF @p i. */
    Tensor<1, 2>
    scalar_gradient(const unsigned int i, const Point<2> &st) const
    {
      // Rows xx/yy and xy of B hold d/dx and d/dy of N for the component.
      const Voigt b = strain_column(i, st);
      return dof_component[i] == 0 ? Tensor<1, 2>({b[0], b[2]}) :
                                     Tensor<1, 2>({b[2], b[1]});
    }

    /** Displacement of the local displacements @p d at @p st. */
    Tensor<1, 2>
    displacement(const LocalVector &d, const Point<2> &st) const
    {
      // The two sums in local variables, not in the tensor through the
      // component index: adding into memory at a computed index and reading
      // the pair back stalled the point update (a fifth of
      // MaterialPoints::move). Same order of additions, same result.
      const auto N  = vertex_shape_values(st);
      double     u0 = 0, u1 = 0;
      for (unsigned int i = 0; i < dofs_per_cell; ++i)
        {
          const double v = N[dof_vertex[i]] * d[i];
          if (dof_component[i] == 0)
            u0 += v;
          else
            u1 += v;
        }
      return Tensor<1, 2>({u0, u1});
    }

  private:
    /** The material's Voigt stiffness. */
    Tensor<2, 3> C;
    /** B-bar: the bulk modulus lambda + mu of the in-plane split of C; 0
     * for the standard strain. */
    double kappa = 0;
    /** The volumetric strain of the shape functions,
     * theta_i(s, t) = theta0_i + s theta_s[i] + t theta_t[i]. */
    LocalVector theta_s{}, theta_t{};

    std::array<unsigned int, dofs_per_cell> dof_vertex;
    std::array<unsigned int, dofs_per_cell> dof_component;

    /** B0, Bs, Bt as 3 x 8 arrays. */
    std::array<std::array<double, dofs_per_cell>, 3> B0, Bs, Bt;

    /**
     * The six 8x8 blocks multiplying v, vs, vt, vss, vtt, vst:
     * B0'CB0, B0'CBs + Bs'CB0, B0'CBt + Bt'CB0, Bs'CBs, Bt'CBt,
     * Bs'CBt + Bt'CBs.
     */
    std::array<std::array<double, dofs_per_cell * dofs_per_cell>, 6> blocks;
  };
} // namespace bsmpm

#endif
