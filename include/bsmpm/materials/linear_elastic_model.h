#ifndef bsmpm_linear_elastic_model_h
#define bsmpm_linear_elastic_model_h

#include <bsmpm/materials/constitutive_model.h>

namespace bsmpm
{
  /**
   * Isotropic linear elasticity. In plane strain the in-plane block of the
   * tangent is LinearElasticMaterial::stiffness(); in plane stress update()
   * replaces the zz elastic strain by the one that makes sigma_zz = 0 and
   * the tangent is that of the condensed map.
   */
  class LinearElasticModel : public ConstitutiveModel
  {
  public:
    LinearElasticModel(const double youngs_modulus,
                       const double poissons_ratio,
                       const bool   plane_stress = false);

    /** Its constants are those of "Material": nothing to declare. */
    static void
    declare_parameters(ParameterHandler &prm);
    static std::unique_ptr<ConstitutiveModel>
    create(ParameterHandler &prm, const ElasticConstants &elastic);

    ConstitutiveResponse
    update(ConstitutiveState &state) const override;
    SymmetricTensor<4, 3>
    elastic_tangent() const override;
    /** Infinity: every step is elastic. */
    double
    elastic_reach(const ConstitutiveState &state) const override;
    bool
    is_linear() const override;
    std::string
    name() const override;

  private:
    bool                  plane_stress;
    SymmetricTensor<4, 3> stiffness;
  };
} // namespace bsmpm

#endif
