#include <bsmpm/assembly/constitutive_update.h>
#include <bsmpm/assembly/plane_strain_kinematics.h>

#include <cmath>

// ConstitutiveUpdate, part 2: the kinematics of a cell's points. The strain
// of a cell (small strain, B-bar), the trial state of a point in finite
// strain (F-bar) and the first Piola stress of the supports' points.

namespace bsmpm
{
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

    point.trial_b =
      PlaneStrainKinematics::as_tensor(PlaneStrainKinematics::trial_state(
        props, point.f, state, point.log_derivative));
    // F-bar: f scaled by (det f_c / det f)^(1/3) (zz included), so that
    // ln det f is that of the centroid; in small strain this is B-bar.
    if (strain.use_b_bar)
      state.elastic_strain +=
        (strain.log_det_centroid - std::log(point.det_f)) / 3 *
        unit_symmetric_tensor<3>();
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
    ConstitutiveState  state;
    Tensor<2, 3>       log_derivative;
    const Tensor<1, 3> b_trial =
      PlaneStrainKinematics::trial_state(props, f, state, log_derivative);
    const auto response = model_of(props).update(state);

    // d tau / d eps^tr on (xx, yy, xy), as in cell_system().
    const Tensor<2, 3> DL =
      PlaneStrainKinematics::in_plane_tangent(response.tangent) *
      log_derivative;
    const Tensor<2, 2> tau({{response.stress[0][0], response.stress[0][1]},
                            {response.stress[0][1], response.stress[1][1]}});
    const Tensor<2, 2> b       = PlaneStrainKinematics::as_tensor(b_trial);
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
          const Tensor<2, 2> dP =
            c * (PlaneStrainKinematics::as_tensor(dtau) * f_inv_T -
                 tau * f_inv_T * transpose(df) * f_inv_T);
          for (unsigned int i = 0; i < 2; ++i)
            for (unsigned int j = 0; j < 2; ++j)
              A[i][j][k][l] = dP[i][j];
        }
    return true;
  }
} // namespace bsmpm
