#include <bsmpm/materials/linear_elastic_model.h>

#include <limits>

namespace bsmpm
{
  LinearElasticModel::LinearElasticModel(const double youngs_modulus,
                                         const double poissons_ratio,
                                         const bool   plane_stress)
    : ConstitutiveModel(youngs_modulus, poissons_ratio)
    , plane_stress(plane_stress)
  {
    stiffness = isotropic_stiffness();
    if (plane_stress)
      {
        // The map P(eps) that replaces eps_zz by -r (eps_xx + eps_yy) has the
        // derivative I - E_zz (x) E_zz - r E_zz (x) (E_xx + E_yy); the
        // tangent is D^e : dP/deps (doc/materials.md, Sec. 2).
        const double          lambda = kappa - 2. * mu / 3.;
        const double          r      = lambda / (lambda + 2. * mu);
        SymmetricTensor<2, 3> e_zz, e_in;
        e_zz[2][2] = 1.;
        e_in[0][0] = e_in[1][1]                = 1.;
        const SymmetricTensor<4, 3> projection = identity_tensor<3>() -
                                                 outer_product(e_zz, e_zz) -
                                                 r * outer_product(e_zz, e_in);
        stiffness = stiffness * projection;
      }
  }



  ConstitutiveResponse
  LinearElasticModel::update(ConstitutiveState &state) const
  {
    if (plane_stress)
      {
        const double lambda = kappa - 2. * mu / 3.;
        state.elastic_strain[2][2] =
          -lambda / (lambda + 2. * mu) *
          (state.elastic_strain[0][0] + state.elastic_strain[1][1]);
      }
    ConstitutiveResponse response;
    response.stress  = elastic_stress(state.elastic_strain);
    response.tangent = stiffness;
    return response;
  }



  SymmetricTensor<4, 3>
  LinearElasticModel::elastic_tangent() const
  {
    return stiffness;
  }



  double
  LinearElasticModel::elastic_reach(const ConstitutiveState &) const
  {
    return std::numeric_limits<double>::infinity();
  }



  bool
  LinearElasticModel::is_linear() const
  {
    return true;
  }



  std::string
  LinearElasticModel::name() const
  {
    return "linear elastic";
  }



  void
  LinearElasticModel::declare_parameters(ParameterHandler &)
  {}



  std::unique_ptr<ConstitutiveModel>
  LinearElasticModel::create(ParameterHandler &,
                             const ElasticConstants &elastic)
  {
    return std::make_unique<LinearElasticModel>(elastic.youngs_modulus,
                                                elastic.poissons_ratio,
                                                elastic.plane_stress);
  }



  BSMPM_REGISTER_CONSTITUTIVE_MODEL(LinearElasticModel,
                                    "linear elastic",
                                    true,
                                    "Young's modulus and Poisson's ratio")
} // namespace bsmpm
