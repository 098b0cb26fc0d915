#ifndef bsmpm_von_mises_plasticity_h
#define bsmpm_von_mises_plasticity_h

#include <bsmpm/materials/constitutive_model.h>

namespace bsmpm
{
  /**
   * von Mises plasticity with linear isotropic hardening (H = 0: perfectly
   * plastic), associated flow, radial return and its consistent tangent
   * (doc/materials.md, Sec. 3). Parameters in "Material/von Mises".
   */
  class VonMisesPlasticity : public ConstitutiveModel
  {
  public:
    VonMisesPlasticity(const double youngs_modulus,
                       const double poissons_ratio,
                       const double yield_stress,
                       const double hardening_modulus);

    /** Declares "von Mises" inside the current subsection. */
    static void
    declare_parameters(ParameterHandler &prm);
    /** Reads "von Mises" inside the current subsection. */
    static std::unique_ptr<ConstitutiveModel>
    create(ParameterHandler &prm, const ElasticConstants &elastic);

    ConstitutiveResponse
    update(ConstitutiveState &state) const override;
    bool
    plane_strain_update(ConstitutiveState      &state,
                        std::array<double, 4>  &stress,
                        std::array<double, 16> &tangent) const override;

    double
    elastic_reach(const ConstitutiveState &state) const override;
    /** q(sigma) - (sigma_y + H eps_bar). */
    double
    yield_function(const SymmetricTensor<2, 3> &stress,
                   const double eq_plastic_strain) const override;
    std::string
    name() const override;
    std::unique_ptr<ConstitutiveModel>
    with_reduced_strength(const double factor) const override;

    double
    yield_stress() const
    {
      return sigma_y;
    }
    double
    hardening_modulus() const
    {
      return H;
    }

  private:
    double sigma_y;
    double H;
  };
} // namespace bsmpm

#endif
