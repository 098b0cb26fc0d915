#ifndef bsmpm_support_stress_h
#define bsmpm_support_stress_h

#include <deal.II/base/array_view.h>
#include <deal.II/base/tensor.h>

#include <functional>

namespace bsmpm
{
  using namespace dealii;

  /**
   * Finite strain: the material's response where the terms of a support
   * (ImplicitBoundary's band, NitscheBoundary's curve points) evaluate it,
   * given by the solver (ConstitutiveUpdate::first_piola_stress()), which
   * lies above the boundaries. Arguments: the state as the properties of
   * a material point (BoundaryCurve::state_at()), the relative deformation
   * gradient f of the step; results: the first Piola stress P of the
   * configuration at the step's start and A = dP/df. Returns false if
   * det f <= 0: the support then leaves the point out, and the solver,
   * which counts such points in the function it gives, rejects the
   * increment (SystemAssembly::newton_system()).
   */
  using SupportStress = std::function<bool(const ArrayView<const double> &,
                                           const Tensor<2, 2> &,
                                           Tensor<2, 2> &,
                                           Tensor<4, 2> &)>;

  /** A : T, (A : T)_ij = A_ijkl T_kl. */
  inline Tensor<2, 2>
  contract(const Tensor<4, 2> &A, const Tensor<2, 2> &T)
  {
    Tensor<2, 2> result;
    for (unsigned int i = 0; i < 2; ++i)
      for (unsigned int j = 0; j < 2; ++j)
        for (unsigned int k = 0; k < 2; ++k)
          for (unsigned int l = 0; l < 2; ++l)
            result[i][j] += A[i][j][k][l] * T[k][l];
    return result;
  }
} // namespace bsmpm

#endif
