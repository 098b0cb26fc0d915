#include <bsmpm/assembly/constitutive_update.h>
#include <bsmpm/assembly/plane_strain_kinematics.h>
#include <bsmpm/assembly/point_moments.h>

#include <algorithm>
#include <cmath>
#include <limits>

// ConstitutiveUpdate, part 3: the Newton system of one cell from its points
// (cell_system()), with the virtual points that complete the cut-cell
// moments and make a support's band an elastic layer.

namespace bsmpm
{
  namespace
  {
    /**
     * Small strain: the strain columns are affine in the cell,
     * Bbar_i(s, t) = sum_a m_a P_a,i with m = (1, s, t), so the points
     * enter K = sum_p w_p Bbar_p^T D_p Bbar_p and f = sum_p w_p Bbar_p^T
     * sigma_p only through the sums
     *
     *   H_ab = sum_p w_p m_a m_b D_p,   S_a = sum_p w_p m_a sigma_p,
     *
     * K_ij = sum_ab P_a,i^T H_ab P_b,j, f_i = sum_a P_a,i^T S_a: the
     * moment sums of the linear kernel (Q1CellKernel) with a modulus per
     * point. A point costs its return map and these sums (6 x 16 + 3 x 4
     * products) instead of the 8 x 4 products D Bbar and 36 entries
     * Bbar^T (D Bbar). H_ab is stored for a <= b in the order (1, 1),
     * (1, s), (1, t), (s, s), (s, t), (t, t). Points that respond
     * elastically share D_e: they add to the scalar moments
     * M_ab = sum_p w_p m_a m_b alone, and the cell to H_ab + M_ab D_e, as
     * the linear kernel's moments do (a cell whose points all stay elastic
     * costs their return maps and six sums each).
     */
    struct SmallStrainCellSums
    {
      double H[6][16] = {};
      double M[6]     = {};
      double S[3][4]  = {};
      bool   plastic  = false;

      /** Adds the stress @p sigma of the point at @p st with weight @p w
       * to S and its tangent to H (@p D, if it yields) or to M. */
      void
      add(const Point<2>               &st,
          const double                  w,
          const std::array<double, 4>  &sigma,
          const bool                    yielded,
          const std::array<double, 16> &D)
      {
        const std::array<double, 6> m = PointMoments::weighted(w, st);
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
            H[q][k] += m[q] * D[k];
      }
    };

    /** An inverted point has no stress: @p f NaN, which assemble() leaves
     * out (element by element: in Debug, Vector's operator= refuses a
     * NaN). */
    void
    mark_inverted(Vector<double> &f)
    {
      for (auto &v : f)
        v = std::numeric_limits<double>::quiet_NaN();
    }
  } // namespace



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
    const CellStrain strain =
      cell_strain(kernel, cell_points, d, exact_moments);
    ConstitutiveState state;
    unsigned int      n_yielded = 0;
    K                           = 0;
    f                           = 0;
    if (strain.inverted)
      {
        mark_inverted(f);
        return 0;
      }
    // Small strain: the sums (SmallStrainCellSums) make K and f at the end;
    // finite strain sums K and f point by point.
    SmallStrainCellSums sums;
    const bool          small = point_kinematics == Kinematics::small_strain;
    // The Voigt tangent of a point that yields, row by row.
    std::array<double, 16> D_flat;
    // Adds the point at @p st with properties @p props and weight @p w;
    // false if it is inverted (f is then NaN). With @p elastic, the point
    // responds with the elastic stiffness whatever its state (the band's
    // elastic layer below).
    const auto add_point = [&](const Point<2>                &st,
                               const ArrayView<const double> &props,
                               const double                   w,
                               const bool                     count,
                               const bool                     elastic = false) {
      bool yielded = false;
      if (small)
        {
          const Tensor<1, 4> de = strain_increment(strain, st);
          // The stress, and the Voigt tangent only where the point yields
          // (a point that does not adds D_e through M).
          std::array<double, 4> sigma;
          if (!elastic)
            yielded = respond(props, de, state, sigma, D_flat);
          else
            elastic_stress(props, de, sigma);
          sums.add(
            st, w, sigma, yielded || other_body_tangent(props, D_flat), D_flat);
        }
      else if (!add_finite_strain_point(
                 kernel, strain, st, props, w, d, state, K, f, yielded))
        {
          mark_inverted(f);
          return false;
        }
      n_yielded += count && yielded;
      return true;
    };

    // One point with weight: the four points of the exact moments with its
    // state (single_point()).
    if (const PointView *single = single_point(cell_points, exact_moments))
      {
        const auto rule = PointMoments::exact_four_point_rule(*exact_moments);
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
            sums.add(point.st,
                     w,
                     sigma,
                     yielded || other_body_tangent(props, D_flat),
                     D_flat);
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
          const double w = integration_weight(point.props);
          if (w == 0.)
            continue;
          W += w;
        }

    // Moment completion: virtual points with the points' mean state where
    // their weights miss the exact moments (completion_points()).
    const VirtualPoints completion =
      completion_points(exact_moments, W, Ws, Wt);
    if (completion.n > 0)
      {
        const std::vector<double>     mean = mean_state(cell_points, W);
        const ArrayView<const double> mean_props(mean.data(), mean.size());
        for (unsigned int q = 0; q < completion.n; ++q)
          if (!add_point(
                completion.st[q], mean_props, completion.weight[q], false))
            return n_yielded;
      }

    // An implicit boundary band in the cell (small strain): the band is an
    // elastic layer, so the points' material is taken out of it and the
    // elastic one put in, each by virtual points with the points' mean
    // state at the band's quadrature points (see the header). Where that
    // state responds elastically the two cancel exactly.
    if (band != nullptr && small && W > 0)
      {
        const std::vector<double>     mean = mean_state(cell_points, W);
        const ArrayView<const double> mean_props(mean.data(), mean.size());
        for (const auto &q : *band)
          {
            add_point(q.st, mean_props, q.weight, false, true);
            add_point(q.st, mean_props, -q.weight, false);
          }
      }

    if (small)
      system_from_moments(strain, sums.H, sums.plastic, sums.M, sums.S, K, f);
    return n_yielded;
  }



  void
  ConstitutiveUpdate::elastic_stress(const ArrayView<const double> &props,
                                     const Tensor<1, 4>            &de,
                                     std::array<double, 4>         &sigma) const
  {
    SymmetricTensor<2, 3> e;
    trial_strain(props, de, e);
    const SymmetricTensor<2, 3> stress = model_of(props).elastic_tangent() * e;
    sigma[0]                           = stress[0][0];
    sigma[1]                           = stress[1][1];
    sigma[2]                           = stress[2][2];
    sigma[3]                           = stress[0][1];
  }



  bool
  ConstitutiveUpdate::add_finite_strain_point(
    const Q1CellKernel              &kernel,
    const CellStrain                &strain,
    const Point<2>                  &st,
    const ArrayView<const double>   &props,
    const double                     w,
    const Q1CellKernel::LocalVector &d,
    ConstitutiveState               &state,
    FullMatrix<double>              &K,
    Vector<double>                  &f,
    bool                            &yielded) const
  {
    constexpr unsigned int  n = Q1CellKernel::dofs_per_cell;
    const FiniteStrainPoint kin =
      finite_strain_trial(kernel, strain, st, props, d, nullptr, state);
    if (!(kin.det_f > 0))
      return false;
    const auto response              = model_of(props).update(state);
    yielded                          = response.yielded;
    const SymmetricTensor<2, 3> &tau = response.stress;
    const double                 c   = w / props[Property::det_F];
    // d tau / d eps^tr on in-plane strains (rows and columns xx, yy,
    // xy, the xy column counted twice) and D : 1.
    const Tensor<2, 3> D =
      PlaneStrainKinematics::in_plane_tangent(response.tangent);
    static constexpr unsigned int index[3][2] = {{0, 0}, {1, 1}, {0, 1}};
    Tensor<1, 3>                  D1;
    for (unsigned int r = 0; r < 3; ++r)
      {
        const unsigned int i = index[r][0], j = index[r][1];
        D1[r] = response.tangent[i][j][0][0] + response.tangent[i][j][1][1] +
                response.tangent[i][j][2][2];
      }
    const Tensor<2, 3> DL = D * kin.log_derivative;
    const auto         N  = Q1CellKernel::vertex_shape_values(st);
    // tau g_i by shape function (a plain array: each entry is set below,
    // and a Tensor's zeros would be written for every point).
    double tau_g[n][2];
    for (unsigned int i = 0; i < n; ++i)
      for (unsigned int r = 0; r < 2; ++r)
        tau_g[i][r] =
          tau[r][0] * kin.gradients[i][0] + tau[r][1] * kin.gradients[i][1];
    // F-bar, variationally: the point's virtual strain is the variation of
    // its trial strain, F-bar's volumetric shift included, so the force is
    // the derivative of the points' incremental energy and the tangent its
    // symmetric Hessian (Moran, Ortiz and Shih 1990). The volumetric part
    // tr(tau) / 3 div(v) thus takes the divergence at the centroid,
    // tr(tau) / 3 (g_c - g), g_c = f_c^-T grad N there. Taking the point's
    // own divergence instead (de Souza Neto et al. 1996) leaves an
    // unsymmetric tangent that is indefinite in plastic flow at large
    // increments, where Newton's corrections then climb the energy and
    // cycle (doc/finite-strain.md, "F-bar").
    const bool   f_bar  = strain.use_b_bar;
    const double tr_tau = trace(tau);
    double       shift[n];
    for (unsigned int a = 0; a < n; ++a)
      shift[a] = f_bar ? strain.centroid_gradients[a][kernel.component(a)] -
                           kin.gradients[a][kernel.component(a)] :
                         0.;
    const Tensor<1, 2> body_force = body_force_at(props);
    for (unsigned int a = 0; a < n; ++a)
      f[a] += c * (tau_g[a][kernel.component(a)] + tr_tau / 3 * shift[a] -
                   body_force[kernel.component(a)] * N[kernel.vertex(a)]);
    // The zz row of the tangent, for tr(delta tau): (xx, yy, xy) columns,
    // the xy column counted twice, and D_zz : 1.
    Tensor<1, 3> D_zz;
    double       D1_zz = 0;
    if (f_bar)
      {
        for (unsigned int col = 0; col < 3; ++col)
          D_zz[col] = response.tangent[2][2][index[col][0]][index[col][1]] *
                      (col == 2 ? 2. : 1.);
        D1_zz = response.tangent[2][2][0][0] + response.tangent[2][2][1][1] +
                response.tangent[2][2][2][2];
      }
    for (unsigned int b = 0; b < n; ++b)
      {
        // The unit increment of DoF b (component k) gives
        // delta b^tr = 2 sym(e_k (x) h), h = b^tr g_b, and
        // delta eps^tr = L : sym(e_k (x) h) (+ F-bar's volumetric part).
        const unsigned int k = kernel.component(b);
        const Tensor<1, 2> h = kin.trial_b * kin.gradients[b];
        // sym(e_k (x) h) as (xx, yy, xy).
        const Tensor<1, 3> S    = k == 0 ? Tensor<1, 3>({h[0], 0., h[1] / 2}) :
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
        if (f_bar)
          {
            // The derivative of tr(tau) / 3 (g_c - g)_i: delta tr(tau) from
            // the in-plane strain change and the shift, and delta g_a =
            // -g_b (g_a)_k, delta g_c,a likewise with the centroid's.
            const double volumetric =
              (strain.centroid_gradients[b][k] - kin.gradients[b][k]) / 3;
            const double tr_dtau = dtau[0] + dtau[1] +
                                   D_zz * (kin.log_derivative * S) +
                                   volumetric * D1_zz;
            for (unsigned int a = 0; a < n; ++a)
              {
                const unsigned int i = kernel.component(a);
                K(a, b) +=
                  c / 3 *
                  (tr_dtau * shift[a] +
                   tr_tau * (kin.gradients[b][i] * kin.gradients[a][k] -
                             strain.centroid_gradients[b][i] *
                               strain.centroid_gradients[a][k]));
              }
          }
      }
    return true;
  }



  const ConstitutiveUpdate::PointView *
  ConstitutiveUpdate::single_point(const std::vector<PointView> &cell_points,
                                   const CellMoments *exact_moments) const
  {
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
    return single;
  }



  ConstitutiveUpdate::VirtualPoints
  ConstitutiveUpdate::completion_points(const CellMoments *exact_moments,
                                        const double       W,
                                        const double       Ws,
                                        const double       Wt) const
  {
    // Moment completion (doc/finite-strain.md): where the fitted weights
    // miss the exact area or first moments of the cell's part inside the
    // body (a cut cell fitted to its area only), add the one-point rule of
    // the exact moments, weight v at the exact centroid, and subtract that
    // of the points, weight W at their centroid. Both virtual points carry
    // the cell's mean state with their own strain, so a homogeneous
    // deformation gives every point the same stress and the cell's force
    // is that of the exact geometry, while the tangent stays the
    // derivative of the force (and symmetric where the model's is).
    VirtualPoints points;
    if (!completes_moments() || exact_moments == nullptr || !(W > 0))
      return points;
    const CellMoments &m         = *exact_moments;
    const double       tolerance = 1e-10 * std::max(m.v, W);
    if (std::abs(m.v - W) > tolerance || std::abs(m.vs - Ws) > tolerance ||
        std::abs(m.vt - Wt) > tolerance)
      {
        if (m.v > 0)
          points.add(Point<2>(m.vs / m.v, m.vt / m.v), m.v);
        points.add(Point<2>(Ws / W, Wt / W), -W);
      }
    return points;
  }



  std::vector<double>
  ConstitutiveUpdate::mean_state(const std::vector<PointView> &cell_points,
                                 const double                  W) const
  {
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
    // Several bodies: the state is that of the body most of the weight
    // belongs to (of two, the nearer to the mean index).
    if (mean.size() > Property::body)
      mean[Property::body] = std::round(mean[Property::body]);
    return mean;
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
    const bool             symmetric = symmetric_tangents;
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
              G[a][j][r] += M[PointMoments::index[a][b]] * DP[r];
        }
    if (plastic)
      for (unsigned int a = 0; a < 3; ++a)
        for (unsigned int b = 0; b < 3; ++b)
          {
            const double *h = H[PointMoments::index[a][b]];
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
} // namespace bsmpm
