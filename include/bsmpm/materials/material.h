#ifndef bsmpm_material_h
#define bsmpm_material_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/tensor.h>

#include <algorithm>

namespace bsmpm
{
  using namespace dealii;

  /**
   * In-plane stress or strain in Voigt order (xx, yy, xy). Strains carry the
   * engineering shear gamma_xy = 2 eps_xy, so that sigma = C eps.
   */
  using Voigt = Tensor<1, 3>;

  /**
   * Isotropic linear elasticity in two dimensions, plane strain or plane
   * stress (paper Sec. 2, method-notes Sec. 1).
   */
  class LinearElasticMaterial
  {
  public:
    enum class Model
    {
      plane_strain,
      plane_stress
    };

    LinearElasticMaterial() = default;
    LinearElasticMaterial(const double youngs_modulus,
                          const double poissons_ratio,
                          const Model  model,
                          const double density = 0.);

    static void
    declare_parameters(ParameterHandler &prm);
    void
    parse_parameters(ParameterHandler &prm);

    /** Voigt stiffness: sigma = C eps with engineering shear strain. */
    const Tensor<2, 3> &
    stiffness() const
    {
      return C;
    }

    /** Modulus of uniaxial strain in the plane (sigma_yy / eps_yy when
     * eps_xx = 0): E (1 - nu) / ((1 + nu)(1 - 2 nu)) in plane strain,
     * E / (1 - nu^2) in plane stress. */
    double
    constrained_modulus() const;

    double
    youngs_modulus() const
    {
      return E;
    }

    /**
     * The scale of a boundary penalty (Nitsche, contact): max(E, kappa)
     * with the in-plane bulk modulus kappa = (C_00 + C_01) / 2 = lambda +
     * mu, the stiffness of the material's stiffest mode. It is E up to
     * nu = 0.3 in plane strain and for every nu in plane stress, and grows
     * without bound as nu -> 0.5 in plane strain (167 E at nu = 0.499).
     */
    double
    penalty_modulus() const
    {
      return std::max(E, (C[0][0] + C[0][1]) / 2);
    }
    double
    poissons_ratio() const
    {
      return nu;
    }
    double
    shear_modulus() const
    {
      return E / (2. * (1. + nu));
    }
    /** Kolosov's constant: 3 - 4 nu in plane strain, (3 - nu)/(1 + nu) in
     * plane stress. */
    double
    kolosov_constant() const;
    double
    density() const
    {
      return rho;
    }
    Model
    model() const
    {
      return plane_model;
    }

  private:
    void
    check_and_build();

    double       E           = 1.;
    double       nu          = 0.;
    double       rho         = 0.;
    Model        plane_model = Model::plane_strain;
    Tensor<2, 3> C;
  };
} // namespace bsmpm

#endif
