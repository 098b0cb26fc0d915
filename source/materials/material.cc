#include <bsmpm/materials/constitutive_model.h>
#include <bsmpm/materials/material.h>

namespace bsmpm
{
  LinearElasticMaterial::LinearElasticMaterial(const double youngs_modulus,
                                               const double poissons_ratio,
                                               const Model  model,
                                               const double density)
    : E(youngs_modulus)
    , nu(poissons_ratio)
    , rho(density)
    , plane_model(model)
  {
    check_and_build();
  }



  void
  LinearElasticMaterial::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Material");
    prm.declare_entry("Young's modulus",
                      "1e6",
                      Patterns::Double(),
                      "Young's modulus E; must be positive. bsmpm has no "
                      "units of its own: any consistent set works, e.g. Pa, "
                      "kg/m^3, m/s^2 and m, or kPa, t/m^3, m/s^2 and m (the "
                      "plastic scenes in prm/); the stresses and forces it "
                      "reports are in the same set.");
    prm.declare_entry("Poisson's ratio",
                      "0.25",
                      Patterns::Double(),
                      "Poisson's ratio nu; must lie in (-1, 0.5).");
    prm.declare_entry("Model",
                      "plane strain",
                      Patterns::Selection("plane strain|plane stress"),
                      "Two-dimensional idealisation of the body: plane strain "
                      "(the default; needed by the plastic models and by "
                      "finite strain) or plane stress (linear elasticity in "
                      "small strain only).");
    prm.declare_entry(
      "Density",
      "0",
      Patterns::Double(0.),
      "Mass density (kg/m^3 with Pa, t/m^3 with kPa); with the gravity of the "
      "Loading section it gives the body force.");
    prm.leave_subsection();
    // "Constitutive model" and the subsections of the models.
    declare_constitutive_parameters(prm);
  }



  void
  LinearElasticMaterial::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Material");
    E           = prm.get_double("Young's modulus");
    nu          = prm.get_double("Poisson's ratio");
    plane_model = prm.get("Model") == "plane strain" ? Model::plane_strain :
                                                       Model::plane_stress;
    rho         = prm.get_double("Density");
    const std::string constitutive_model = prm.get("Constitutive model");
    prm.leave_subsection();
    check_and_build();
    check_constitutive_model_compatibility(constitutive_model,
                                           plane_model == Model::plane_stress);
  }



  void
  LinearElasticMaterial::check_and_build()
  {
    AssertThrow(std::isfinite(E) && E > 0.,
                ExcMessage("Material: Young's modulus must be positive, got " +
                           std::to_string(E) + "."));
    AssertThrow(std::isfinite(nu) && nu > -1. && nu < 0.5,
                ExcMessage("Material: Poisson's ratio must lie in (-1, 0.5), "
                           "got " +
                           std::to_string(nu) + "."));
    AssertThrow(std::isfinite(rho) && rho >= 0.,
                ExcMessage("Material: density must be non-negative."));

    C = 0;
    if (plane_model == Model::plane_strain)
      {
        const double f = E / ((1. + nu) * (1. - 2. * nu));
        C[0][0] = C[1][1] = f * (1. - nu);
        C[0][1] = C[1][0] = f * nu;
        C[2][2]           = f * (1. - 2. * nu) / 2.;
      }
    else
      {
        const double f = E / (1. - nu * nu);
        C[0][0] = C[1][1] = f;
        C[0][1] = C[1][0] = f * nu;
        C[2][2]           = f * (1. - nu) / 2.;
      }
  }



  double
  LinearElasticMaterial::constrained_modulus() const
  {
    return C[1][1];
  }



  double
  LinearElasticMaterial::kolosov_constant() const
  {
    return plane_model == Model::plane_strain ? 3. - 4. * nu :
                                                (3. - nu) / (1. + nu);
  }
} // namespace bsmpm
