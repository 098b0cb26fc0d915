#include <deal.II/base/mpi.h>

#include <bsmpm/assembly/constitutive_update.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <limits>
#include <memory>

namespace bsmpm
{
  namespace
  {
    using Property = MaterialPoints::Property;

    /** The @p n_points points of a cell as ConstitutiveUpdate::cell_system()
     * takes them. */
    void
    gather_points(
      const Particles::ParticleHandler<2>::particle_iterator_range &range,
      const unsigned int                                            n_points,
      std::vector<ConstitutiveUpdate::PointView>                   &views)
    {
      // Written by index into a vector sized once (push_back checked the
      // capacity of every point).
      views.resize(n_points);
      auto view = views.begin();
      for (const auto &particle : range)
        {
          view->st    = particle.get_reference_location();
          view->props = particle.get_properties();
          ++view;
        }
    }

    /** The elastic strain stored in a point (zz included). */
    SymmetricTensor<2, 3>
    stored_elastic_strain(const ArrayView<const double> &props)
    {
      SymmetricTensor<2, 3> e;
      e[0][0] = props[Property::elastic_strain];
      e[1][1] = props[Property::elastic_strain + 1];
      e[2][2] = props[Property::elastic_strain + 2];
      e[0][1] = props[Property::elastic_strain + 3];
      return e;
    }

    /** The deformation gradient stored in a point. */
    Tensor<2, 2>
    stored_deformation_gradient(const ArrayView<const double> &props)
    {
      const double *F = &props[Property::deformation_gradient];
      return Tensor<2, 2>({{F[0], F[1]}, {F[2], F[3]}});
    }

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
    void
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

    /** The in-plane block of a symmetric 3x3 tensor as (xx, yy, xy). */
    Tensor<1, 3>
    in_plane(const SymmetricTensor<2, 3> &t)
    {
      return Tensor<1, 3>({t[0][0], t[1][1], t[0][1]});
    }

    /** (xx, yy, xy) as a 2x2 tensor. */
    Tensor<2, 2>
    as_tensor(const Tensor<1, 3> &v)
    {
      return Tensor<2, 2>({{v[0], v[2]}, {v[2], v[1]}});
    }

    /** The symmetric 2x2 tensor a b a^T as (xx, yy, xy). */
    Tensor<1, 3>
    push_forward(const Tensor<2, 2> &a, const Tensor<1, 3> &b)
    {
      const Tensor<2, 2> t = a * as_tensor(b) * transpose(a);
      return Tensor<1, 3>({t[0][0], t[1][1], (t[0][1] + t[1][0]) / 2});
    }

    /**
     * Four points, a quarter of the area v each, at (c_s +- r_s, c_t +-
     * r_t), c the centroid of @p m and r_s^2 = vss / v - c_s^2,
     * r_t^2 = vtt / v - c_t^2 the variances of s and t over it: they
     * integrate 1, s, t, s^2 and t^2 exactly, so a constant tangent gives
     * the cell a stiffness that holds every deformation mode (the exact
     * moments of the linear path do the same).
     */
    std::array<Point<2>, 4>
    exact_four_point_rule(const CellMoments &m)
    {
      const Point<2> c(m.vs / m.v, m.vt / m.v);
      const double   r_s = std::sqrt(std::max(0., m.vss / m.v - c[0] * c[0]));
      const double   r_t = std::sqrt(std::max(0., m.vtt / m.v - c[1] * c[1]));
      std::array<Point<2>, 4> rule;
      unsigned int            q = 0;
      for (const double a : {-1., 1.})
        for (const double b : {-1., 1.})
          rule[q++] = Point<2>(c[0] + a * r_s, c[1] + b * r_t);
      return rule;
    }

    /**
     * The weighted moments w m_a m_b of a point at @p st, m = (1, s, t), in
     * the order of the sums H_ab and M_ab of ConstitutiveUpdate::
     * cell_system(): (1, 1), (1, s), (1, t), (s, s), (s, t), (t, t); the
     * first three are also w m_a.
     */
    std::array<double, 6>
    point_moments(const double w, const Point<2> &st)
    {
      const double ws = w * st[0], wt = w * st[1];
      return {{w, ws, wt, ws * st[0], ws * st[1], wt * st[1]}};
    }

    /** Where H_ab and M_ab (a, b in 1, s, t) are stored, by a and b. */
    constexpr unsigned int moment_index[3][3] = {{0, 1, 2},
                                                 {1, 3, 4},
                                                 {2, 4, 5}};

    const auto log_of     = [](const double x) { return std::log(x); };
    const auto inverse_of = [](const double x) { return 1. / x; };
    const auto exp_of     = [](const double x) { return std::exp(x); };
  } // namespace



  void
  ConstitutiveUpdate::declare_parameters(ParameterHandler &prm)
  {
    // The material's own entries are LinearElasticMaterial's and the
    // constitutive model's: these two choose how the points integrate it.
    prm.enter_subsection("Material");
    prm.declare_entry(
      "Volumetric strain",
      "B-bar",
      Patterns::Selection("B-bar|standard"),
      "B-bar (the default) replaces the volumetric strain of every point by "
      "its mean over the cell's material, so that neither isochoric plastic "
      "flow nor a nearly incompressible elastic material (Poisson's ratio "
      "near 0.5) locks the bilinear grid; standard keeps the points' own, as "
      "the paper does, and locks there: choose it only to reproduce the "
      "paper's kernel. Linear elasticity (small strain): the in-plane split, "
      "mean of eps_xx + eps_yy at the centroid of the cell's moments (fitted "
      "ones in cut cells), stress C eps + (lambda + mu)(theta_mean - "
      "theta)(1, 1, 0), also in the Nitsche and implicit-boundary terms "
      "(doc/b-bar.md). Nonlinear models: the 3D split (zz included). Finite "
      "strain: F-bar for nonlinear models, none for linear elasticity.");
    prm.declare_entry(
      "Kinematics",
      "small strain",
      Patterns::Selection("small strain|finite strain"),
      "small strain (the default): the paper's formulation (strain increments "
      "added, stress of the small-strain model). finite strain: updated "
      "Lagrangian, a deformation gradient per point, logarithmic (Hencky) "
      "elastic strain with the exponential map, Kirchhoff stress, point "
      "volumes det(F) V0, a pressure that follows the boundary within the "
      "load step (doc/finite-strain.md); choose it where rotations or strains "
      "are no longer small. Finite strain always uses Newton iterations, also "
      "for linear elasticity, and needs plane strain. Without boundary "
      "curves, a free closed curve round the body region is added (Curve 1), "
      "so that the cut-cell quadrature integrates the cells the moving points "
      "fill unevenly.");
    prm.leave_subsection();
  }



  std::unique_ptr<ConstitutiveUpdate>
  ConstitutiveUpdate::create(ParameterHandler            &prm,
                             const ConstitutiveModel     &model,
                             const LinearElasticMaterial &material,
                             const bool                   newton)
  {
    prm.enter_subsection("Material");
    const bool b_bar         = prm.get("Volumetric strain") == "B-bar";
    const bool finite_strain = prm.get("Kinematics") == "finite strain";
    prm.leave_subsection();
    AssertThrow(!finite_strain || material.model() ==
                                    LinearElasticMaterial::Model::plane_strain,
                ExcMessage("Material/Kinematics = finite strain needs "
                           "'Model = plane strain': in plane stress the "
                           "thickness stretch would be a further unknown."));
    if (!model.is_linear() || finite_strain || newton)
      return std::make_unique<ConstitutiveUpdate>(model,
                                                  b_bar && !model.is_linear(),
                                                  finite_strain ?
                                                    Kinematics::finite_strain :
                                                    Kinematics::small_strain);
    return nullptr;
  }



  bool
  ConstitutiveUpdate::uses_b_bar(ParameterHandler &prm)
  {
    prm.enter_subsection("Material");
    const bool b_bar = prm.get("Volumetric strain") == "B-bar";
    prm.leave_subsection();
    return b_bar;
  }



  ConstitutiveUpdate::ConstitutiveUpdate(const ConstitutiveModel &model,
                                         const bool               b_bar,
                                         const Kinematics         kinematics)
    : model(model)
    , b_bar(b_bar)
    , elastic_voigt(voigt_tangent(model.elastic_tangent()))
    , point_kinematics(kinematics)
  {}



  double
  ConstitutiveUpdate::integration_weight(
    const ArrayView<const double> &props) const
  {
    return props[Property::volume] == 0. ? 0. :
           quadrature_weights            ? props[Property::weight] :
                                           props[Property::volume];
  }



  Tensor<2, 4>
  ConstitutiveUpdate::voigt_tangent(const SymmetricTensor<4, 3> &tangent)
  {
    // sigma_ij = T_ijkl eps_kl; the engineering shear gamma = 2 eps_xy
    // takes both T_ij01 and T_ij10 = T_ij01. deal.II stores T as the 6x6
    // table of the pairs (00, 11, 22, 01, 02, 12), whose first four are
    // (xx, yy, zz, xy): read it directly (the chained [i][j][k][l] looks
    // every entry up by its indices).
    Tensor<2, 4> D;
    for (unsigned int r = 0; r < 4; ++r)
      for (unsigned int c = 0; c < 4; ++c)
        D[r][c] = tangent.access_raw_entry(6 * r + c);
    return D;
  }



  ConstitutiveUpdate::CellStrain
  ConstitutiveUpdate::cell_strain(const Q1CellKernel              &kernel,
                                  const std::vector<PointView>    &cell_points,
                                  const Q1CellKernel::LocalVector &d,
                                  const CellMoments *exact_moments) const
  {
    VolumeMoments volume;
    if (b_bar)
      for (const auto &point : cell_points)
        volume.add(point.st, point.props[Property::volume]);
    return cell_strain(kernel, volume, d, exact_moments);
  }



  ConstitutiveUpdate::CellStrain
  ConstitutiveUpdate::cell_strain(const Q1CellKernel              &kernel,
                                  const VolumeMoments             &volume,
                                  const Q1CellKernel::LocalVector &d,
                                  const CellMoments *exact_moments) const
  {
    CellStrain strain;
    strain.coefficients = kernel.strain_coefficients(d);
    strain.use_b_bar    = false;
    if (b_bar)
      centroid_strain(kernel, volume, d, exact_moments, strain);
    // B-bar columns: B_i + (theta_i(centroid) - theta_i(s, t)) / 3
    // (1, 1, 1, 0), each part affine in (s, t).
    for (unsigned int i = 0; i < Q1CellKernel::dofs_per_cell; ++i)
      {
        const std::array<Voigt, 3> parts = kernel.strain_column_parts(i);
        for (unsigned int a = 0; a < 3; ++a)
          {
            double shift = 0;
            if (strain.use_b_bar)
              shift = ((a == 0 ? strain.centroid_volumetric[i] : 0.) -
                       parts[a][0] - parts[a][1]) /
                      3;
            strain.columns[a][i] = Tensor<1, 4>(
              {parts[a][0] + shift, parts[a][1] + shift, shift, parts[a][2]});
          }
      }
    if (point_kinematics == Kinematics::small_strain)
      {
        for (unsigned int a = 0; a < 3; ++a)
          {
            strain.increment[a] = Tensor<1, 4>();
            for (unsigned int i = 0; i < Q1CellKernel::dofs_per_cell; ++i)
              strain.increment[a] += d[i] * strain.columns[a][i];
          }
      }
    return strain;
  }



  void
  ConstitutiveUpdate::centroid_strain(const Q1CellKernel              &kernel,
                                      const VolumeMoments             &volume,
                                      const Q1CellKernel::LocalVector &d,
                                      const CellMoments *exact_moments,
                                      CellStrain        &strain) const
  {
    // The volumetric strain of Q1 is affine in the cell, so its mean over
    // the points is its value at their volume-weighted centroid.
    if (volume.v == 0.)
      return;
    strain.use_b_bar = true;
    strain.centroid  = Point<2>(volume.vs / volume.v, volume.vt / volume.v);
    // With the cut-cell quadrature the cell is integrated over its exact
    // part in the body (the points' fitted weights, completed by
    // cell_system()): the mean is that of the exact centroid, so that the
    // B-bar shift integrates to zero over the cell and a homogeneous
    // state stays exact.
    if (completes_moments() && exact_moments != nullptr && exact_moments->v > 0)
      strain.centroid = Point<2>(exact_moments->vs / exact_moments->v,
                                 exact_moments->vt / exact_moments->v);
    for (unsigned int i = 0; i < Q1CellKernel::dofs_per_cell; ++i)
      {
        const Voigt mean = kernel.strain_column(i, strain.centroid);
        strain.centroid_volumetric[i] = mean[0] + mean[1];
      }
    if (point_kinematics == Kinematics::finite_strain)
      {
        // F-bar: the same idea for ln det f, which is not affine; its value
        // at the centroid stands for the cell.
        const Tensor<2, 2> f =
          unit_symmetric_tensor<2>() + kernel.gradient(d, strain.centroid);
        if (!(determinant(f) > 0))
          {
            strain.inverted = true;
            return;
          }
        strain.log_det_centroid    = std::log(determinant(f));
        const Tensor<2, 2> f_inv_T = transpose(invert(f));
        for (unsigned int i = 0; i < Q1CellKernel::dofs_per_cell; ++i)
          strain.centroid_gradients[i] =
            f_inv_T * kernel.scalar_gradient(i, strain.centroid);
      }
  }



  // inline: called for every point of every Newton system, where the call
  // cost about as much as filling the state.
  inline bool
  ConstitutiveUpdate::respond(const ArrayView<const double> &props,
                              const Tensor<1, 4>            &de,
                              ConstitutiveState             &state,
                              std::array<double, 4>         &stress,
                              std::array<double, 16>        &tangent) const
  {
    SymmetricTensor<2, 3> &e = state.elastic_strain;
    e[0][0]                  = props[Property::elastic_strain] + de[0];
    e[1][1]                  = props[Property::elastic_strain + 1] + de[1];
    e[2][2]                  = props[Property::elastic_strain + 2] + de[2];
    e[0][1]                  = props[Property::elastic_strain + 3] + de[3] / 2;
    e[0][2] = e[1][2]               = 0;
    state.equivalent_plastic_strain = props[Property::plastic_strain];
    return model.plane_strain_update(state, stress, tangent);
  }



  ConstitutiveUpdate::FiniteStrainPoint
  ConstitutiveUpdate::finite_strain_trial(const Q1CellKernel            &kernel,
                                          const CellStrain              &strain,
                                          const Point<2>                &st,
                                          const ArrayView<const double> &props,
                                          const Q1CellKernel::LocalVector &d,
                                          const Tensor<2, 2> *gradient,
                                          ConstitutiveState  &state) const
  {
    FiniteStrainPoint point;
    point.f = unit_symmetric_tensor<2>() +
              (gradient ? *gradient : kernel.gradient(d, st));
    point.det_f = determinant(point.f);
    if (!(point.det_f > 0))
      return point; // the caller reports an inverted point
    const Tensor<2, 2> f_inv_T = transpose(invert(point.f));
    for (unsigned int i = 0; i < Q1CellKernel::dofs_per_cell; ++i)
      point.gradients[i] = f_inv_T * kernel.scalar_gradient(i, st);

    // b_e,n = exp(2 eps_e,n); b_e^tr = f b_e,n f^T. With f_zz = 1 the zz
    // elastic strain is unchanged and zz stays a principal direction, so
    // the in-plane block is all that the exponential and logarithm see.
    const SymmetricTensor<2, 3> eps_n = stored_elastic_strain(props);
    Tensor<1, 3>                b_n, log_b;
    in_plane_function(2 * in_plane(eps_n), exp_of, exp_of, b_n, nullptr);
    const Tensor<1, 3> b_trial = push_forward(point.f, b_n);
    in_plane_function(
      b_trial, log_of, inverse_of, log_b, &point.log_derivative);
    point.trial_b = as_tensor(b_trial);

    SymmetricTensor<2, 3> &e = state.elastic_strain;
    e                        = SymmetricTensor<2, 3>();
    e[0][0]                  = log_b[0] / 2;
    e[1][1]                  = log_b[1] / 2;
    e[0][1]                  = log_b[2] / 2;
    e[2][2]                  = eps_n[2][2];
    // F-bar: f scaled by (det f_c / det f)^(1/3) (zz included), so that
    // ln det f is that of the centroid; in small strain this is B-bar.
    if (strain.use_b_bar)
      state.elastic_strain +=
        (strain.log_det_centroid - std::log(point.det_f)) / 3 *
        unit_symmetric_tensor<3>();
    state.equivalent_plastic_strain = props[Property::plastic_strain];
    return point;
  }



  bool
  ConstitutiveUpdate::first_piola_stress(const ArrayView<const double> &props,
                                         const Tensor<2, 2>            &f,
                                         Tensor<2, 2>                  &P,
                                         Tensor<4, 2>                  &A) const
  {
    const double det_f = determinant(f);
    if (!(det_f > 0))
      return false;
    // The trial state of finite_strain_trial(): b_e^tr = f b_e,n f^T.
    const SymmetricTensor<2, 3> eps_n = stored_elastic_strain(props);
    Tensor<1, 3>                b_n, log_b;
    Tensor<2, 3>                log_derivative;
    in_plane_function(2 * in_plane(eps_n), exp_of, exp_of, b_n, nullptr);
    const Tensor<1, 3> b_trial = push_forward(f, b_n);
    in_plane_function(b_trial, log_of, inverse_of, log_b, &log_derivative);
    ConstitutiveState state;
    state.elastic_strain[0][0]      = log_b[0] / 2;
    state.elastic_strain[1][1]      = log_b[1] / 2;
    state.elastic_strain[0][1]      = log_b[2] / 2;
    state.elastic_strain[2][2]      = eps_n[2][2];
    state.equivalent_plastic_strain = props[Property::plastic_strain];
    const auto response             = model.update(state);

    // d tau / d eps^tr on (xx, yy, xy), the xy column counted twice, as in
    // cell_system().
    static constexpr unsigned int index[3][2] = {{0, 0}, {1, 1}, {0, 1}};
    Tensor<2, 3>                  D;
    for (unsigned int r = 0; r < 3; ++r)
      for (unsigned int c = 0; c < 3; ++c)
        D[r][c] =
          response.tangent[index[r][0]][index[r][1]][index[c][0]][index[c][1]] *
          (c == 2 ? 2. : 1.);
    const Tensor<2, 3> DL = D * log_derivative;
    const Tensor<2, 2> tau({{response.stress[0][0], response.stress[0][1]},
                            {response.stress[0][1], response.stress[1][1]}});
    const Tensor<2, 2> b       = as_tensor(b_trial);
    const Tensor<2, 2> f_inv_T = transpose(invert(f));
    const double       c       = 1. / props[Property::det_F];
    P                          = c * tau * f_inv_T;
    // A change df gives dl = df f^-1, delta b^tr = 2 sym(dl b^tr),
    // delta eps^tr = L : sym(dl b^tr), delta tau = D : delta eps^tr and
    // delta P = (delta tau f^-T - tau f^-T df^T f^-T) / J_n.
    for (unsigned int k = 0; k < 2; ++k)
      for (unsigned int l = 0; l < 2; ++l)
        {
          Tensor<2, 2> df;
          df[k][l]              = 1.;
          const Tensor<2, 2> lb = df * transpose(f_inv_T) * b;
          const Tensor<1, 3> dtau =
            DL * Tensor<1, 3>({lb[0][0], lb[1][1], (lb[0][1] + lb[1][0]) / 2});
          const Tensor<2, 2> dP = c * (as_tensor(dtau) * f_inv_T -
                                       tau * f_inv_T * transpose(df) * f_inv_T);
          for (unsigned int i = 0; i < 2; ++i)
            for (unsigned int j = 0; j < 2; ++j)
              A[i][j][k][l] = dP[i][j];
        }
    return true;
  }



  unsigned int
  ConstitutiveUpdate::cell_system(
    const Q1CellKernel                  &kernel,
    const std::vector<PointView>        &cell_points,
    const Q1CellKernel::LocalVector     &d,
    FullMatrix<double>                  &K,
    Vector<double>                      &f,
    const CellMoments                   *exact_moments,
    const std::vector<SupportBandPoint> *band) const
  {
    constexpr unsigned int n = Q1CellKernel::dofs_per_cell;
    const CellStrain       strain =
      cell_strain(kernel, cell_points, d, exact_moments);
    std::array<Tensor<1, 2>, n> tau_g;
    ConstitutiveState           state;
    unsigned int                n_yielded = 0;
    K                                     = 0;
    f                                     = 0;
    // An inverted point has no stress: f NaN, which assemble() leaves out
    // (element by element: in Debug, Vector's operator= refuses a NaN).
    const auto mark_inverted = [&f]() {
      for (auto &v : f)
        v = std::numeric_limits<double>::quiet_NaN();
    };
    if (strain.inverted)
      {
        mark_inverted();
        return 0;
      }
    // Small strain: the strain columns are affine in the cell,
    // Bbar_i(s, t) = sum_a m_a P_a,i with m = (1, s, t), so the points
    // enter K = sum_p w_p Bbar_p^T D_p Bbar_p and f = sum_p w_p Bbar_p^T
    // sigma_p only through the sums
    //
    //   H_ab = sum_p w_p m_a m_b D_p,   S_a = sum_p w_p m_a sigma_p,
    //
    // K_ij = sum_ab P_a,i^T H_ab P_b,j, f_i = sum_a P_a,i^T S_a: the
    // moment sums of the linear kernel (Q1CellKernel) with a modulus per
    // point. A point costs its return map and these sums (6 x 16 + 3 x 4
    // products) instead of the 8 x 4 products D Bbar and 36 entries
    // Bbar^T (D Bbar). H_ab is stored for a <= b in the order (1, 1),
    // (1, s), (1, t), (s, s), (s, t), (t, t). Points that respond
    // elastically share D_e: they add to the scalar moments
    // M_ab = sum_p w_p m_a m_b alone, and the cell to H_ab + M_ab D_e, as
    // the linear kernel's moments do (a cell whose points all stay elastic
    // costs their return maps and six sums each).
    double     H[6][16] = {};
    double     M[6]     = {};
    double     S[3][4]  = {};
    bool       plastic  = false;
    const bool small    = point_kinematics == Kinematics::small_strain;
    // The Voigt tangent of a point that yields, row by row.
    std::array<double, 16> D_flat;
    // Small strain: adds the stress @p sigma of the point at @p st with
    // weight @p w to S and its tangent to H (D_flat, if it yields) or to M.
    const auto add_sums = [&](const Point<2>              &st,
                              const double                 w,
                              const std::array<double, 4> &sigma,
                              const bool                   yielded) {
      const std::array<double, 6> m = point_moments(w, st);
      for (unsigned int a = 0; a < 3; ++a)
        for (unsigned int r = 0; r < 4; ++r)
          S[a][r] += m[a] * sigma[r];
      // A step that did not yield has the elastic tangent
      // (ConstitutiveModel::plane_strain_update()).
      if (!yielded)
        {
          for (unsigned int q = 0; q < 6; ++q)
            M[q] += m[q];
          return;
        }
      plastic = true;
      for (unsigned int q = 0; q < 6; ++q)
        for (unsigned int k = 0; k < 16; ++k)
          H[q][k] += m[q] * D_flat[k];
    };
    // Adds the point at @p st with properties @p props and weight @p w;
    // false if it is inverted (f is then NaN).
    // With @p elastic, the point responds with the elastic stiffness
    // whatever its state (the band's elastic layer below).
    const auto add_point = [&](const Point<2>                &st,
                               const ArrayView<const double> &props,
                               const double                   w,
                               const bool                     count,
                               const bool                     elastic = false) {
      if (point_kinematics == Kinematics::small_strain)
        {
          const Tensor<1, 4> de = strain_increment(strain, st);
          // The stress, and the Voigt tangent only where the point yields
          // (a point that does not adds D_e through M below).
          std::array<double, 4> sigma;
          bool                  yielded = false;
          if (!elastic)
            yielded = respond(props, de, state, sigma, D_flat);
          else
            {
              SymmetricTensor<2, 3> e = stored_elastic_strain(props);
              e[0][0] += de[0];
              e[1][1] += de[1];
              e[2][2] += de[2];
              e[0][1] += de[3] / 2;
              const SymmetricTensor<2, 3> stress = model.elastic_tangent() * e;
              sigma[0]                           = stress[0][0];
              sigma[1]                           = stress[1][1];
              sigma[2]                           = stress[2][2];
              sigma[3]                           = stress[0][1];
            }
          n_yielded += count && yielded;
          add_sums(st, w, sigma, yielded);
          return true;
        }

      // Finite strain (doc/finite-strain.md).
      const FiniteStrainPoint kin =
        finite_strain_trial(kernel, strain, st, props, d, nullptr, state);
      if (!(kin.det_f > 0))
        {
          mark_inverted();
          return false;
        }
      const auto response = model.update(state);
      n_yielded += count && response.yielded;
      const SymmetricTensor<2, 3> &tau = response.stress;
      const double                 c   = w / props[Property::det_F];
      // d tau / d eps^tr on in-plane strains (rows and columns xx, yy,
      // xy, the xy column counted twice) and D : 1.
      static constexpr unsigned int index[3][2] = {{0, 0}, {1, 1}, {0, 1}};
      Tensor<2, 3>                  D;
      Tensor<1, 3>                  D1;
      for (unsigned int r = 0; r < 3; ++r)
        {
          const unsigned int i = index[r][0], j = index[r][1];
          for (unsigned int c = 0; c < 3; ++c)
            D[r][c] = response.tangent[i][j][index[c][0]][index[c][1]] *
                      (c == 2 ? 2. : 1.);
          D1[r] = response.tangent[i][j][0][0] + response.tangent[i][j][1][1] +
                  response.tangent[i][j][2][2];
        }
      const Tensor<2, 3> DL = D * kin.log_derivative;
      const auto         N  = Q1CellKernel::vertex_shape_values(st);
      for (unsigned int i = 0; i < n; ++i)
        for (unsigned int r = 0; r < 2; ++r)
          tau_g[i][r] =
            tau[r][0] * kin.gradients[i][0] + tau[r][1] * kin.gradients[i][1];
      for (unsigned int a = 0; a < n; ++a)
        f[a] += c * (tau_g[a][kernel.component(a)] -
                     body_force[kernel.component(a)] * N[kernel.vertex(a)]);
      for (unsigned int b = 0; b < n; ++b)
        {
          // The unit increment of DoF b (component k) gives
          // delta b^tr = 2 sym(e_k (x) h), h = b^tr g_b, and
          // delta eps^tr = L : sym(e_k (x) h) (+ F-bar's volumetric part).
          const unsigned int k = kernel.component(b);
          const Tensor<1, 2> h = kin.trial_b * kin.gradients[b];
          // sym(e_k (x) h) as (xx, yy, xy).
          const Tensor<1, 3> S = k == 0 ? Tensor<1, 3>({h[0], 0., h[1] / 2}) :
                                          Tensor<1, 3>({0., h[1], h[0] / 2});
          Tensor<1, 3>       dtau = DL * S;
          if (strain.use_b_bar)
            dtau +=
              (strain.centroid_gradients[b][k] - kin.gradients[b][k]) / 3 * D1;
          // Rows (xx, xy) and (xy, yy) of delta tau.
          const Tensor<1, 2> row[2] = {Tensor<1, 2>({dtau[0], dtau[2]}),
                                       Tensor<1, 2>({dtau[2], dtau[1]})};
          for (unsigned int a = 0; a < n; ++a)
            {
              const unsigned int  i = kernel.component(a);
              const Tensor<1, 2> &g = kin.gradients[a];
              K(a, b) += c * (row[i] * g - tau_g[b][i] * g[k]);
            }
        }
      return true;
    };

    // One point in a cell (one point per cell, or a cut cell the body has
    // just entered): a one-point rule holds none of the cell's hourglass
    // modes (their strain vanishes at the point), so Newton's tangent is
    // singular and the curves' tracking points, which the hourglass modes
    // move, wander (doc/finite-strain.md). With the cell's exact moments
    // the cell is integrated instead by the four points of the rule of
    // exact_four_point_rule() with the one point's state: exact for a
    // homogeneous state (the integrand is affine), and their tangent
    // holds every deformation mode of the cell.
    const PointView *single = nullptr;
    if (completes_moments() && exact_moments != nullptr && exact_moments->v > 0)
      for (const auto &point : cell_points)
        {
          const double w = point.props[Property::weight];
          if (point.props[Property::volume] == 0. || w == 0.)
            continue;
          single = single == nullptr ? &point : nullptr;
          if (single == nullptr)
            break;
        }
    if (single != nullptr)
      {
        const auto rule = exact_four_point_rule(*exact_moments);
        for (unsigned int q = 0; q < rule.size(); ++q)
          // The point yields if its state yields at the first of them.
          if (!add_point(rule[q], single->props, exact_moments->v / 4, q == 0))
            break;
        return n_yielded;
      }

    // The points, and the sums of their weights and first moments.
    double W = 0, Ws = 0, Wt = 0;
    for (const auto &point : cell_points)
      {
        const auto  &props = point.props;
        const double w     = integration_weight(props);
        if (w == 0.)
          continue;
        if (small)
          {
            // add_point()'s small-strain part, written out: this loop is
            // most of a Newton system, and add_point() is too large to be
            // inlined (its call cost a sixth of the loop). (Two passes, the
            // return maps first and then the sums in a loop without calls,
            // cost 1 % more instructions.)
            std::array<double, 4> sigma;
            const bool            yielded = respond(
              props, strain_increment(strain, point.st), state, sigma, D_flat);
            n_yielded += yielded;
            add_sums(point.st, w, sigma, yielded);
            // W is only needed in a cell crossed by a support's band:
            // summed below, then.
            continue;
          }
        if (!add_point(point.st, props, w, true))
          return n_yielded;
        W += w;
        Ws += w * point.st[0];
        Wt += w * point.st[1];
      }
    if (small && band != nullptr)
      for (const auto &point : cell_points)
        {
          const auto  &props = point.props;
          const double w     = integration_weight(props);
          if (w == 0.)
            continue;
          W += w;
        }

    // The mean state of the points, weighted as they integrate.
    const auto mean_state = [&]() {
      std::vector<double> mean;
      for (const auto &point : cell_points)
        {
          const auto  &props = point.props;
          const double w     = integration_weight(props);
          if (w == 0.)
            continue;
          if (mean.empty())
            mean.assign(props.size(), 0.);
          for (unsigned int k = 0; k < props.size(); ++k)
            mean[k] += w / W * props[k];
        }
      return mean;
    };

    // Moment completion (doc/finite-strain.md): where the fitted weights
    // miss the exact area or first moments of the cell's part inside the
    // body (a cut cell fitted to its area only), add the one-point rule of
    // the exact moments, weight v at the exact centroid, and subtract that
    // of the points, weight W at their centroid. Both virtual points carry
    // the cell's mean state with their own strain, so a homogeneous
    // deformation gives every point the same stress and the cell's force
    // is that of the exact geometry, while the tangent stays the
    // derivative of the force (and symmetric where the model's is).
    if (completes_moments() && exact_moments != nullptr && W > 0)
      {
        const CellMoments &m         = *exact_moments;
        const double       tolerance = 1e-10 * std::max(m.v, W);
        if (std::abs(m.v - W) > tolerance || std::abs(m.vs - Ws) > tolerance ||
            std::abs(m.vt - Wt) > tolerance)
          {
            const std::vector<double>     mean = mean_state();
            const ArrayView<const double> mean_props(mean.data(), mean.size());
            if (m.v > 0 && !add_point(Point<2>(m.vs / m.v, m.vt / m.v),
                                      mean_props,
                                      m.v,
                                      false))
              return n_yielded;
            if (!add_point(Point<2>(Ws / W, Wt / W), mean_props, -W, false))
              return n_yielded;
          }
      }

    // An implicit boundary band in the cell (small strain): the band is an
    // elastic layer, so the points' material is taken out of it and the
    // elastic one put in, each by virtual points with the points' mean
    // state at the band's quadrature points (see the header). Where that
    // state responds elastically the two cancel exactly.
    if (band != nullptr && point_kinematics == Kinematics::small_strain &&
        W > 0)
      {
        const std::vector<double>     mean = mean_state();
        const ArrayView<const double> mean_props(mean.data(), mean.size());
        for (const auto &q : *band)
          {
            add_point(q.st, mean_props, q.weight, false, true);
            add_point(q.st, mean_props, -q.weight, false);
          }
      }

    // Small strain: K and f from the sums; finite strain summed them point
    // by point (its tangent is not symmetric in general).
    if (small)
      system_from_moments(strain, H, plastic, M, S, K, f);
    return n_yielded;
  }



  void
  ConstitutiveUpdate::system_from_moments(const CellStrain &strain,
                                          const double (&H)[6][16],
                                          const bool plastic,
                                          const double (&M)[6],
                                          const double (&S)[3][4],
                                          FullMatrix<double> &K,
                                          Vector<double>     &f) const
  {
    constexpr unsigned int n         = Q1CellKernel::dofs_per_cell;
    const bool             symmetric = model.symmetric_tangent();
    // K and f from the sums (see H in cell_system()):
    // G_a,j = sum_b (H_ab P_b,j + M_ab D_e P_b,j),
    // K_ij = sum_a P_a,i^T G_a,j; for a symmetric tangent the upper
    // triangle, mirrored below.
    const auto &P          = strain.columns;
    double      G[3][n][4] = {};
    for (unsigned int b = 0; b < 3; ++b)
      for (unsigned int j = 0; j < n; ++j)
        {
          const Tensor<1, 4> DP = elastic_voigt * P[b][j];
          for (unsigned int a = 0; a < 3; ++a)
            for (unsigned int r = 0; r < 4; ++r)
              G[a][j][r] += M[moment_index[a][b]] * DP[r];
        }
    if (plastic)
      for (unsigned int a = 0; a < 3; ++a)
        for (unsigned int b = 0; b < 3; ++b)
          {
            const double *h = H[moment_index[a][b]];
            for (unsigned int j = 0; j < n; ++j)
              for (unsigned int r = 0; r < 4; ++r)
                G[a][j][r] +=
                  h[4 * r] * P[b][j][0] + h[4 * r + 1] * P[b][j][1] +
                  h[4 * r + 2] * P[b][j][2] + h[4 * r + 3] * P[b][j][3];
          }
    for (unsigned int i = 0; i < n; ++i)
      {
        double force = 0;
        for (unsigned int a = 0; a < 3; ++a)
          for (unsigned int r = 0; r < 4; ++r)
            force += P[a][i][r] * S[a][r];
        f[i] = force;
        for (unsigned int j = symmetric ? i : 0; j < n; ++j)
          {
            double sum = 0;
            for (unsigned int a = 0; a < 3; ++a)
              for (unsigned int r = 0; r < 4; ++r)
                sum += P[a][i][r] * G[a][j][r];
            K(i, j) = sum;
          }
      }
    if (symmetric)
      for (unsigned int i = 0; i < n; ++i)
        for (unsigned int j = 0; j < i; ++j)
          K(i, j) = K(j, i);
  }



  ConstitutiveUpdate::ElasticCell
  ConstitutiveUpdate::elastic_cell(
    const std::vector<PointView> &cell_points) const
  {
    ElasticCell       cell;
    ConstitutiveState state;
    double            reach = std::numeric_limits<double>::infinity();
    double            s_min = 1, s_max = 0, t_min = 1, t_max = 0;
    for (const auto &point : cell_points)
      {
        const auto &props = point.props;
        cell.volume.add(point.st, props[Property::volume]);
        const double w = integration_weight(props);
        if (w == 0.)
          continue;
        state.elastic_strain[0][0]      = props[Property::elastic_strain];
        state.elastic_strain[1][1]      = props[Property::elastic_strain + 1];
        state.elastic_strain[2][2]      = props[Property::elastic_strain + 2];
        state.elastic_strain[0][1]      = props[Property::elastic_strain + 3];
        state.equivalent_plastic_strain = props[Property::plastic_strain];
        reach              = std::min(reach, model.elastic_reach(state));
        const Point<2> &st = point.st;
        s_min              = std::min(s_min, st[0]);
        s_max              = std::max(s_max, st[0]);
        t_min              = std::min(t_min, st[1]);
        t_max              = std::max(t_max, st[1]);
        const std::array<double, 6> m = point_moments(w, st);
        for (unsigned int q = 0; q < 6; ++q)
          cell.M[q] += m[q];
        const double e[4] = {props[Property::elastic_strain],
                             props[Property::elastic_strain + 1],
                             props[Property::elastic_strain + 2],
                             2 * props[Property::elastic_strain + 3]};
        for (unsigned int a = 0; a < 3; ++a)
          for (unsigned int r = 0; r < 4; ++r)
            cell.strain_moments[a][r] += m[a] * e[r];
      }
    // No point with weight: the cell is left to the point-by-point path.
    if (s_min > s_max)
      return ElasticCell();
    cell.reach        = reach;
    cell.centre       = Point<2>((s_min + s_max) / 2, (t_min + t_max) / 2);
    cell.half_width_s = (s_max - s_min) / 2;
    cell.half_width_t = (t_max - t_min) / 2;
    return cell;
  }



  bool
  ConstitutiveUpdate::elastic_cell_system(
    const Q1CellKernel              &kernel,
    const ElasticCell               &cell,
    const Q1CellKernel::LocalVector &d,
    FullMatrix<double>              &K,
    Vector<double>                  &f,
    const CellMoments               *exact_moments) const
  {
    if (!(cell.reach > 0) || point_kinematics != Kinematics::small_strain)
      return false;
    const CellStrain strain =
      cell_strain(kernel, cell.volume, d, exact_moments);
    // The norm of a strain tensor from its (xx, yy, zz, engineering xy).
    const auto norm = [](const Tensor<1, 4> &e) {
      return std::sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2] +
                       e[3] * e[3] / 2);
    };
    // The largest |de| over the box of the points' coordinates.
    const auto  &E = strain.increment;
    const double largest =
      norm(E[0] + cell.centre[0] * E[1] + cell.centre[1] * E[2]) +
      cell.half_width_s * norm(E[1]) + cell.half_width_t * norm(E[2]);
    if (!(largest < cell.reach))
      return false;
    // S_a = D_e (sum_p w m_a e_n,p + sum_b M_ab E_b); H_ab = M_ab D_e.
    double S[3][4];
    for (unsigned int a = 0; a < 3; ++a)
      {
        Tensor<1, 4> e;
        for (unsigned int r = 0; r < 4; ++r)
          e[r] = cell.strain_moments[a][r];
        for (unsigned int b = 0; b < 3; ++b)
          e += cell.M[moment_index[a][b]] * E[b];
        const Tensor<1, 4> sigma = elastic_voigt * e;
        for (unsigned int r = 0; r < 4; ++r)
          S[a][r] = sigma[r];
      }
    static constexpr double no_plastic_moments[6][16] = {};
    system_from_moments(strain, no_plastic_moments, false, cell.M, S, K, f);
    return true;
  }



  void
  ConstitutiveUpdate::prepare_elastic_cells(const MaterialPoints &points,
                                            const BackgroundGrid &grid,
                                            ElasticCells         &cells) const
  {
    cells.clear();
    if (point_kinematics != Kinematics::small_strain)
      return;
    cells.resize(grid.triangulation().n_active_cells());
    const auto            &particles = points.particle_handler();
    std::vector<PointView> views;
    for (const auto &cell : grid.dof_handler().active_cell_iterators())
      if (cell->is_locally_owned() && particles.n_particles_in_cell(cell) > 0)
        {
          gather_points(particles.particles_in_cell(cell),
                        particles.n_particles_in_cell(cell),
                        views);
          cells[cell->active_cell_index()] = elastic_cell(views);
        }
  }



  ConstitutiveUpdate::AssemblyCount
  ConstitutiveUpdate::assemble(
    const MaterialPoints                             &points,
    const BackgroundGrid                             &grid,
    const Q1CellKernel                               &kernel,
    const LinearAlgebra::distributed::Vector<double> &increment,
    const LinearAlgebra::distributed::Vector<double> *prescribed,
    const AffineConstraints<double>                  &constraints,
    TrilinosWrappers::SparseMatrix                   &tangent,
    TrilinosWrappers::MPI::Vector                    &internal_force,
    CellScatter                                      &scatter,
    const SupportBands                               *bands,
    const ElasticCells                               *elastic_cells) const
  {
    constexpr unsigned int               n = Q1CellKernel::dofs_per_cell;
    const auto                          &particles = points.particle_handler();
    FullMatrix<double>                   cell_matrix(n, n);
    Vector<double>                       cell_vector(n);
    std::vector<types::global_dof_index> dof_indices(n);
    Q1CellKernel::LocalVector            d;
    std::vector<PointView>               views;
    std::vector<double>                  borrowed;
    AssemblyCount                        count;
    // A cell whose force is not finite (an inverted point) is counted and
    // left out: the caller then knows the increment is inadmissible, and
    // the system holds no NaN.
    const auto add_cell = [&](const unsigned int cell_index) {
      for (const double v : cell_vector)
        if (!std::isfinite(v))
          {
            ++count.inverted_cells;
            return;
          }
      scatter.add(cell_index,
                  cell_matrix,
                  cell_vector,
                  dof_indices,
                  constraints,
                  tangent,
                  internal_force);
    };

    for (const auto &cell : grid.dof_handler().active_cell_iterators())
      {
        if (!cell->is_locally_owned())
          continue;
        const unsigned int index = cell->active_cell_index();
        // A cell that stays elastic needs none of its points (outside a
        // support's band, whose virtual points take the points' mean
        // state).
        if (elastic_cells != nullptr && !elastic_cells->empty() &&
            (*elastic_cells)[index].reach > 0 &&
            (bands == nullptr || (*bands)[index].empty()))
          {
            d = MaterialPoints::cell_increment(cell,
                                               increment,
                                               prescribed,
                                               dof_indices);
            if (elastic_cell_system(kernel,
                                    (*elastic_cells)[index],
                                    d,
                                    cell_matrix,
                                    cell_vector,
                                    exact_moments ? &(*exact_moments)[index] :
                                                    nullptr))
              {
                add_cell(index);
                continue;
              }
          }
        // The points once (MaterialPoints::holds_material() would walk
        // them again).
        views.clear();
        if (particles.n_particles_in_cell(cell) > 0)
          gather_points(particles.particles_in_cell(cell),
                        particles.n_particles_in_cell(cell),
                        views);
        if (std::none_of(views.begin(), views.end(), [](const auto &point) {
              return point.props[Property::volume] > 0;
            }))
          {
            // A cell of the body without points (a sliver the boundary has
            // just entered, the part of the top row above the points): the
            // four points of exact_four_point_rule() with the state of the
            // neighbourhood. Their tangent holds every deformation mode of
            // the cell (as the exact moments of the linear path do), and a
            // homogeneous state stays exact (SystemAssembly leaves such
            // cells to us).
            const CellMoments *m =
              completes_moments() ?
                &(*exact_moments)[cell->active_cell_index()] :
                nullptr;
            if (m == nullptr || !(m->v > 0))
              continue;
            borrowed = points.neighbourhood_mean_properties(cell);
            if (borrowed.empty())
              continue;
            borrowed[Property::weight] = m->v / 4;
            const ArrayView<const double> state(borrowed.data(),
                                                borrowed.size());
            views.clear();
            for (const Point<2> &st : exact_four_point_rule(*m))
              views.push_back({st, state});
            d = MaterialPoints::cell_increment(cell,
                                               increment,
                                               prescribed,
                                               dof_indices);
            cell_system(kernel, views, d, cell_matrix, cell_vector);
            add_cell(cell->active_cell_index());
            continue;
          }
        d = MaterialPoints::cell_increment(cell,
                                           increment,
                                           prescribed,
                                           dof_indices);
        const auto *band =
          bands != nullptr && !(*bands)[cell->active_cell_index()].empty() ?
            &(*bands)[cell->active_cell_index()] :
            nullptr;
        count.yielded +=
          cell_system(kernel,
                      views,
                      d,
                      cell_matrix,
                      cell_vector,
                      exact_moments ?
                        &(*exact_moments)[cell->active_cell_index()] :
                        nullptr,
                      band);
        add_cell(cell->active_cell_index());
      }
    return count;
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
    std::vector<PointView>               views;
    ConstitutiveState                    state;
    unsigned long long                   n_yielded = 0;
    points.find_material_cells();
    const bool finite = point_kinematics == Kinematics::finite_strain;
    // The 2x2 blocks of the vertices in the points' tangent with their
    // algorithmic (a) and elastic (e) tangents: K_xx, K_yy on the vertex's
    // two DoFs, K_xy on its first (support_stiffness_ratios()).
    const MPI_Comm                             comm = grid.mpi_communicator();
    LinearAlgebra::distributed::Vector<double> diagonal_a(
      grid.locally_owned_dofs(), grid.locally_relevant_dofs(), comm);
    LinearAlgebra::distributed::Vector<double> diagonal_e(diagonal_a),
      off_a(diagonal_a), off_e(diagonal_a);
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
        // The points' tangents as moments (cell_system()): H_ab of the
        // points that yield, M_ab of those that do not, and of all.
        double H[6][16] = {}, M_elastic[6] = {}, M_all[6] = {};
        bool   plastic = false;
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
            const Tensor<2, 2>     F_n = stored_deformation_gradient(props);
            std::array<double, 4>  stress;
            std::array<double, 16> tangent;
            bool                   yielded = false;
            double                 det_f   = 1;
            if (finite)
              {
                const FiniteStrainPoint kin = finite_strain_trial(
                  kernel, strain, st, props, d, &grad, state);
                det_f                        = kin.det_f;
                const ConstitutiveResponse r = model.update(state);
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
              {
                const std::array<double, 6> m =
                  point_moments(integration_weight(props), st);
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
            const auto &eps                     = state.elastic_strain;
            props[Property::elastic_strain]     = eps[0][0];
            props[Property::elastic_strain + 1] = eps[1][1];
            props[Property::elastic_strain + 2] = eps[2][2];
            props[Property::elastic_strain + 3] = eps[0][1];
            props[Property::plastic_strain] = state.equivalent_plastic_strain;
            props[Property::yielded]        = yielded ? 1. : 0.;
            n_yielded += yielded && props[Property::volume] > 0;

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
                in_plane_function(push_forward(F, Tensor<1, 3>({1., 1., 0.})),
                                  log_of,
                                  inverse_of,
                                  log_strain,
                                  nullptr);
                props[Property::strain]     = log_strain[0] / 2;
                props[Property::strain + 1] = log_strain[1] / 2;
                props[Property::strain + 2] = log_strain[2] / 2;
              }
          }
        if (!has_material)
          continue;
        // The vertices' 2 x 2 blocks from the moments: with the (B-bar)
        // strain columns Bbar_i = sum_a m_a P_a,i, the block entry
        // sum_p w_p Bbar_i^T D_p Bbar_j is sum_ab P_a,i^T (H_ab +
        // M_ab D_e) P_b,j (its symmetric part for unsymmetric tangents).
        // Where no point yields, H is zero and M_elastic is M_all, summed
        // alike: the two blocks are then equal to the last bit.
        const auto                                &P = strain.columns;
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
                const unsigned int q   = moment_index[a][b];
                const double       PP  = P[a][i] * DP[b][j];
                double             PHP = 0;
                if (plastic)
                  for (unsigned int r = 0; r < 4; ++r)
                    for (unsigned int c = 0; c < 4; ++c)
                      PHP += P[a][i][r] * H[q][4 * r + c] * P[b][j][c];
                held += PHP + M_elastic[q] * PP;
                elastic += M_all[q] * PP;
              }
          return std::make_pair(held, elastic);
        };
        for (unsigned int i = 0; i < n; ++i)
          {
            const auto [held, elastic] = entries(i, i);
            diagonal_a(dof_indices[i]) += held;
            diagonal_e(dof_indices[i]) += elastic;
            if (kernel.component(i) == 0)
              for (unsigned int j = 0; j < n; ++j)
                if (kernel.component(j) == 1 &&
                    kernel.vertex(j) == kernel.vertex(i))
                  {
                    const auto [held_ij, elastic_ij] = entries(i, j);
                    // The symmetric part (unsymmetric tangents).
                    off_a(dof_indices[i]) +=
                      (held_ij + entries(j, i).first) / 2;
                    off_e(dof_indices[i]) += elastic_ij;
                  }
          }
      }
    for (auto *v : {&diagonal_a, &diagonal_e, &off_a, &off_e})
      {
        v->compress(VectorOperation::add);
        v->update_ghost_values();
      }
    stiffness_ratio.reinit(diagonal_a);
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
                    smallest_eigenvalue(diagonal_e(x), diagonal_e(y), off_e(x));
                  const double held =
                    smallest_eigenvalue(diagonal_a(x), diagonal_a(y), off_a(x));
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
                    stiffness_ratio(x) = ratio;
                  if (grid.locally_owned_dofs().is_element(y))
                    stiffness_ratio(y) = ratio;
                }
      }
    stiffness_ratio.update_ghost_values();
    return Utilities::MPI::sum(n_yielded, grid.mpi_communicator());
  }
} // namespace bsmpm
