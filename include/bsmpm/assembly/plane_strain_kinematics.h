#ifndef bsmpm_plane_strain_kinematics_h
#define bsmpm_plane_strain_kinematics_h

#include <deal.II/base/array_view.h>
#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>

#include <bsmpm/materials/constitutive_model.h>
#include <bsmpm/points/material_points.h>

#include <cmath>

namespace bsmpm
{
  using namespace dealii;

  /**
   * The tensor algebra of the finite-strain kinematics in plane strain
   * (doc/finite-strain.md), shared by the files of ConstitutiveUpdate: the
   * in-plane block of a plane-strain tensor (whose zz direction is
   * principal) and isotropic functions of it in closed form, the trial
   * elastic state b_e^tr = f b_e,n f^T of the exponential map, and the
   * state a material point stores. Inline: they are called for every point
   * of every Newton system.
   */
  namespace PlaneStrainKinematics
  {
    /**
     * An isotropic function y = f(X) of a symmetric 2x2 tensor (the
     * in-plane block of a plane-strain tensor, whose zz direction is
     * principal) by its closed-form eigenvalues, and its derivative. Both on
     * the components (xx, yy, xy); the derivative as the matrix M with
     * dy = M dX, M[r][c] = T_rc w_c, w = (1, 1, 2) (dX_xy stands for
     * dX_xy and dX_yx). With the eigenprojections E_1, E_2:
     *
     *   T = f'(x_1) E_1 (x) E_1 + f'(x_2) E_2 (x) E_2
     *       + rho (I - E_1 (x) E_1 - E_2 (x) E_2),
     *   rho = (f(x_1) - f(x_2)) / (x_1 - x_2)
     *
     * (SpectralDecomposition::spin_modulus near equal eigenvalues). The
     * plane-strain kinematics need only these, at a fraction of the cost of
     * the three-dimensional decomposition.
     */
    template <typename F, typename DF>
    inline void
    in_plane_function(const Tensor<1, 3> &X,
                      const F            &f,
                      const DF           &df,
                      Tensor<1, 3>       &y,
                      Tensor<2, 3>       *derivative)
    {
      const double m  = (X[0] + X[1]) / 2;
      const double d  = (X[0] - X[1]) / 2;
      const double r  = std::sqrt(d * d + X[2] * X[2]);
      const double x1 = m + r, x2 = m - r;
      // E_1 = (X - x_2 1) / (x_1 - x_2); for r = 0 any split will do.
      Tensor<1, 3> E1, E2;
      if (r > 0)
        E1 =
          Tensor<1, 3>({(d + r) / (2 * r), (r - d) / (2 * r), X[2] / (2 * r)});
      else
        E1 = Tensor<1, 3>({1., 0., 0.});
      E2              = Tensor<1, 3>({1. - E1[0], 1. - E1[1], -E1[2]});
      const double y1 = f(x1), y2 = f(x2);
      y = y1 * E1 + y2 * E2;
      if (derivative == nullptr)
        return;
      const double a1 = df(x1), a2 = df(x2);
      const double rho =
        SpectralDecomposition::spin_modulus(x1, x2, y1, y2, a1, a2);
      static constexpr double w[3]        = {1., 1., 2.};
      static constexpr double identity[3] = {1., 1., 0.5};
      for (unsigned int r = 0; r < 3; ++r)
        for (unsigned int c = 0; c < 3; ++c)
          (*derivative)[r][c] =
            ((a1 - rho) * E1[r] * E1[c] + (a2 - rho) * E2[r] * E2[c] +
             (r == c ? rho * identity[r] : 0.)) *
            w[c];
    }

    /** The functions in_plane_function() takes. */
    inline const auto log_of     = [](const double x) { return std::log(x); };
    inline const auto inverse_of = [](const double x) { return 1. / x; };
    inline const auto exp_of     = [](const double x) { return std::exp(x); };

    /** The in-plane block of a symmetric 3x3 tensor as (xx, yy, xy). */
    inline Tensor<1, 3>
    in_plane(const SymmetricTensor<2, 3> &t)
    {
      return Tensor<1, 3>({t[0][0], t[1][1], t[0][1]});
    }

    /** (xx, yy, xy) as a 2x2 tensor. */
    inline Tensor<2, 2>
    as_tensor(const Tensor<1, 3> &v)
    {
      return Tensor<2, 2>({{v[0], v[2]}, {v[2], v[1]}});
    }

    /** The symmetric 2x2 tensor a b a^T as (xx, yy, xy). */
    inline Tensor<1, 3>
    push_forward(const Tensor<2, 2> &a, const Tensor<1, 3> &b)
    {
      const Tensor<2, 2> t = a * as_tensor(b) * transpose(a);
      return Tensor<1, 3>({t[0][0], t[1][1], (t[0][1] + t[1][0]) / 2});
    }

    /** The elastic strain stored in a point (zz included). */
    inline SymmetricTensor<2, 3>
    stored_elastic_strain(const ArrayView<const double> &props)
    {
      using Property = MaterialPoints::Property;
      SymmetricTensor<2, 3> e;
      e[0][0] = props[Property::elastic_strain];
      e[1][1] = props[Property::elastic_strain + 1];
      e[2][2] = props[Property::elastic_strain + 2];
      e[0][1] = props[Property::elastic_strain + 3];
      return e;
    }

    /** The deformation gradient stored in a point. */
    inline Tensor<2, 2>
    stored_deformation_gradient(const ArrayView<const double> &props)
    {
      using Property  = MaterialPoints::Property;
      const double *F = &props[Property::deformation_gradient];
      return Tensor<2, 2>({{F[0], F[1]}, {F[2], F[3]}});
    }

    /**
     * The trial state of a point with properties @p props under the
     * relative deformation gradient @p f (f_zz = 1): b_e,n = exp(2 eps_e,n),
     * b_e^tr = f b_e,n f^T, and into @p state the trial elastic strain
     * ln(b_e^tr) / 2 and the equivalent plastic strain. With f_zz = 1 the
     * zz elastic strain is unchanged and zz stays a principal direction, so
     * the in-plane block is all that the exponential and logarithm see.
     * Returns b_e^tr (xx, yy, xy); @p log_derivative receives
     * d ln(b_e^tr) / d b_e^tr (see in_plane_function()).
     */
    inline Tensor<1, 3>
    trial_state(const ArrayView<const double> &props,
                const Tensor<2, 2>            &f,
                ConstitutiveState             &state,
                Tensor<2, 3>                  &log_derivative)
    {
      const SymmetricTensor<2, 3> eps_n = stored_elastic_strain(props);
      Tensor<1, 3>                b_n, log_b;
      in_plane_function(2 * in_plane(eps_n), exp_of, exp_of, b_n, nullptr);
      const Tensor<1, 3> b_trial = push_forward(f, b_n);
      in_plane_function(b_trial, log_of, inverse_of, log_b, &log_derivative);
      SymmetricTensor<2, 3> &e = state.elastic_strain;
      e                        = SymmetricTensor<2, 3>();
      e[0][0]                  = log_b[0] / 2;
      e[1][1]                  = log_b[1] / 2;
      e[0][1]                  = log_b[2] / 2;
      e[2][2]                  = eps_n[2][2];
      state.equivalent_plastic_strain =
        props[MaterialPoints::Property::plastic_strain];
      return b_trial;
    }

    /** d tau / d eps^tr of @p tangent on in-plane strains: rows and
     * columns (xx, yy, xy), the xy column counted twice. */
    inline Tensor<2, 3>
    in_plane_tangent(const SymmetricTensor<4, 3> &tangent)
    {
      static constexpr unsigned int index[3][2] = {{0, 0}, {1, 1}, {0, 1}};
      Tensor<2, 3>                  D;
      for (unsigned int r = 0; r < 3; ++r)
        for (unsigned int c = 0; c < 3; ++c)
          D[r][c] =
            tangent[index[r][0]][index[r][1]][index[c][0]][index[c][1]] *
            (c == 2 ? 2. : 1.);
      return D;
    }
  } // namespace PlaneStrainKinematics
} // namespace bsmpm

#endif
