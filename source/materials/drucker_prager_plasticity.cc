#include <deal.II/base/numbers.h>

#include <bsmpm/materials/drucker_prager_plasticity.h>

#include <cmath>
#include <limits>

namespace bsmpm
{
  DruckerPragerPlasticity::DruckerPragerPlasticity(const double youngs_modulus,
                                                   const double poissons_ratio,
                                                   const double cohesion,
                                                   const double friction_angle,
                                                   const double dilation_angle,
                                                   const Match  match)
    : ConstitutiveModel(youngs_modulus, poissons_ratio)
    , c(cohesion)
    , phi(friction_angle)
    , psi(dilation_angle)
    , match(match)
  {
    const double to_degrees = 180. / numbers::PI;
    AssertThrow(std::isfinite(c) && c >= 0.,
                ExcMessage("Material: Drucker-Prager: the cohesion must be "
                           "non-negative, got " +
                           std::to_string(c) + "."));
    AssertThrow(std::isfinite(phi) && phi >= 0. && phi < numbers::PI / 2.,
                ExcMessage("Material: Drucker-Prager: the friction angle must "
                           "lie in [0, 90) degrees, got " +
                           std::to_string(phi * to_degrees) + "."));
    AssertThrow(std::isfinite(psi) && psi >= 0. && psi <= phi,
                ExcMessage("Material: Drucker-Prager: the dilation angle must "
                           "lie in [0, friction angle = " +
                           std::to_string(phi * to_degrees) +
                           "] degrees, got " +
                           std::to_string(psi * to_degrees) + "."));
    AssertThrow(c > 0. || phi > 0.,
                ExcMessage("Material: Drucker-Prager: cohesion and friction "
                           "angle are both zero: the material has no "
                           "strength."));

    // doc/materials.md, Sec. 4.2.
    const double s_phi = std::sin(phi), c_phi = std::cos(phi),
                 s_psi = std::sin(psi);
    const double root3 = std::sqrt(3.);
    switch (match)
      {
        case Match::plane_strain:
          {
            const double r = std::sqrt(3. + s_psi * s_psi);
            eta_g          = root3 * s_psi / r;
            eta_f          = root3 * s_phi * r / (3. + s_phi * s_psi);
            xi_f           = root3 * c_phi * r / (3. + s_phi * s_psi);
            break;
          }
        case Match::outer:
          eta_f = 6. * s_phi / (root3 * (3. - s_phi));
          xi_f  = 6. * c_phi / (root3 * (3. - s_phi));
          eta_g = 6. * s_psi / (root3 * (3. - s_psi));
          break;
        case Match::inner:
          eta_f = 6. * s_phi / (root3 * (3. + s_phi));
          xi_f  = 6. * c_phi / (root3 * (3. + s_phi));
          eta_g = 6. * s_psi / (root3 * (3. + s_psi));
          break;
      }
  }



  void
  DruckerPragerPlasticity::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Drucker-Prager");
    prm.declare_entry(
      "Cohesion",
      "1e4",
      Patterns::Double(0.),
      "Cohesion c in the units of Young's modulus (non-negative; positive when the "
      "friction angle is 0).");
    prm.declare_entry("Friction angle",
                      "30",
                      Patterns::Double(0., 90.),
                      "Friction angle phi in degrees, in [0, 90).");
    prm.declare_entry("Dilation angle",
                      "0",
                      Patterns::Double(0., 90.),
                      "Dilation angle psi in degrees, in [0, phi]; psi = phi "
                      "is associated flow, psi < phi non-associated.");
    prm.declare_entry(
      "Mohr-Coulomb match",
      "plane strain",
      Patterns::Selection("plane strain|outer|inner"),
      "How the cone is fitted to Mohr-Coulomb with the same c, phi, psi: "
      "'plane strain' gives Mohr-Coulomb's strength in plane-strain plastic "
      "flow (for the given dilation angle), 'outer' passes through the outer "
      "edges of the Mohr-Coulomb pyramid (compressive meridian), 'inner' "
      "through the inner ones (tensile meridian).");
    prm.leave_subsection();
  }



  std::unique_ptr<ConstitutiveModel>
  DruckerPragerPlasticity::create(ParameterHandler       &prm,
                                  const ElasticConstants &elastic)
  {
    prm.enter_subsection("Drucker-Prager");
    const double      to_radians = numbers::PI / 180.;
    const double      cohesion   = prm.get_double("Cohesion");
    const double      friction   = prm.get_double("Friction angle");
    const double      dilation   = prm.get_double("Dilation angle");
    const std::string match      = prm.get("Mohr-Coulomb match");
    prm.leave_subsection();
    return std::make_unique<DruckerPragerPlasticity>(elastic.youngs_modulus,
                                                     elastic.poissons_ratio,
                                                     cohesion,
                                                     friction * to_radians,
                                                     dilation * to_radians,
                                                     match == "outer" ?
                                                       Match::outer :
                                                     match == "inner" ?
                                                       Match::inner :
                                                       Match::plane_strain);
  }



  double
  DruckerPragerPlasticity::apex_pressure() const
  {
    return eta_f > 0. ? xi_f * c / eta_f :
                        std::numeric_limits<double>::infinity();
  }



  ConstitutiveResponse
  DruckerPragerPlasticity::update(ConstitutiveState &state) const
  {
    ConstitutiveResponse response;
    {
      // Elastic check on the invariants of the trial strain.
      const SymmetricTensor<2, 3> &eps_tr = state.elastic_strain;
      const double S    = std::sqrt(2.) * mu * deviator(eps_tr).norm();
      const double f_tr = S + eta_f * kappa * trace(eps_tr) - xi_f * c;
      if (!(f_tr > 0.))
        {
          response.stress  = elastic_stress(eps_tr);
          response.tangent = isotropic_stiffness();
          return response;
        }
    }

    // Return in principal values (doc/materials.md, Sec. 4.3).
    const SpectralDecomposition  spectral(state.elastic_strain);
    const std::array<double, 3> &eps   = spectral.values;
    const double                 eps_v = eps[0] + eps[1] + eps[2];
    std::array<double, 3>        e;
    for (unsigned int a = 0; a < 3; ++a)
      e[a] = eps[a] - eps_v / 3.;
    const double norm_e = std::sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]);
    const double S      = std::sqrt(2.) * mu * norm_e;
    const double p_tr   = kappa * eps_v;
    const double f_tr   = S + eta_f * p_tr - xi_f * c;
    const double alpha  = 1. / (mu + kappa * eta_f * eta_g);
    const double dgamma = f_tr * alpha;

    std::array<double, 3> sigma, eps_e, rho;
    Tensor<2, 3>          d_sigma;
    if (S - mu * dgamma >= 0. && norm_e > 0.)
      {
        // Smooth part of the cone: s = beta s_tr, p = p_tr - K eta_bar dgamma.
        const double          beta = 1. - mu * dgamma / S;
        const double          p    = p_tr - kappa * eta_g * dgamma;
        std::array<double, 3> n;
        for (unsigned int a = 0; a < 3; ++a)
          {
            n[a]     = e[a] / norm_e;
            sigma[a] = p + 2. * mu * beta * e[a];
            eps_e[a] = p / (3. * kappa) + beta * e[a];
          }
        for (unsigned int a = 0; a < 3; ++a)
          for (unsigned int b = 0; b < 3; ++b)
            d_sigma[a][b] =
              kappa * (1. - kappa * eta_f * eta_g * alpha) +
              2. * mu * beta * ((a == b ? 1. : 0.) - 1. / 3.) +
              2. * mu * (mu * dgamma / S - mu * alpha) * n[a] * n[b] -
              std::sqrt(2.) * mu * kappa * alpha *
                (eta_f * n[a] + eta_g * n[b]);
        rho.fill(2. * mu * beta);
      }
    else
      {
        // Apex: sigma = p_apex 1, no stiffness (perfect plasticity).
        const double p_apex = apex_pressure();
        sigma.fill(p_apex);
        eps_e.fill(p_apex / (3. * kappa));
        rho.fill(0.);
      }

    double plastic_norm2 = 0;
    for (unsigned int a = 0; a < 3; ++a)
      plastic_norm2 += (eps[a] - eps_e[a]) * (eps[a] - eps_e[a]);
    state.equivalent_plastic_strain += std::sqrt(2. / 3. * plastic_norm2);
    state.elastic_strain = spectral.assemble(eps_e);

    response.yielded = true;
    response.stress  = spectral.assemble(sigma);
    response.tangent = spectral.assemble_tangent(d_sigma, rho);
    return response;
  }



  bool
  DruckerPragerPlasticity::plane_strain_update(
    ConstitutiveState      &state,
    std::array<double, 4>  &stress,
    std::array<double, 16> &tangent) const
  {
    // update()'s elastic check, without the rank-4 tangent; a step that
    // yields takes update() itself.
    const SymmetricTensor<2, 3> &eps_tr = state.elastic_strain;
    const SymmetricTensor<2, 3>  e_tr   = deviator(eps_tr);
    const double                 S      = std::sqrt(2.) * mu * e_tr.norm();
    const double f_tr = S + eta_f * kappa * trace(eps_tr) - xi_f * c;
    if (!(f_tr > 0.))
      {
        plane_strain_elastic_stress(eps_tr, e_tr, stress);
        return false;
      }
    const ConstitutiveResponse response = update(state);
    plane_strain_response(response, stress, tangent);
    return response.yielded;
  }



  double
  DruckerPragerPlasticity::elastic_reach(const ConstitutiveState &state) const
  {
    // f(e) = sqrt(2) mu |dev e| + eta K tr e - xi c. With
    // |de|^2 = |dev de|^2 + (tr de)^2 / 3, the change of f over a step de is
    // at most sqrt(2 mu^2 + 3 eta^2 K^2) |de| (Cauchy-Schwarz): the step
    // stays elastic while |de| <= -f(e_n) / that. A millionth of a
    // millionth of the terms' size is kept back for round-off.
    const SymmetricTensor<2, 3> &e = state.elastic_strain;
    const double shear             = std::sqrt(2.) * mu * deviator(e).norm();
    const double mean              = eta_f * kappa * trace(e);
    const double f                 = shear + mean - xi_f * c;
    const double scale = shear + std::abs(mean) + std::abs(xi_f * c);
    const double slope =
      std::sqrt(2. * mu * mu + 3. * eta_f * eta_f * kappa * kappa);
    return std::max(0., (-f - 1e-12 * scale) / slope);
  }



  double
  DruckerPragerPlasticity::yield_function(const SymmetricTensor<2, 3> &stress,
                                          const double) const
  {
    return deviator(stress).norm() / std::sqrt(2.) +
           eta_f * trace(stress) / 3. - xi_f * c;
  }



  double
  DruckerPragerPlasticity::at_rest_coefficient() const
  {
    return 1. - std::sin(phi);
  }



  std::string
  DruckerPragerPlasticity::name() const
  {
    return "Drucker-Prager";
  }



  std::unique_ptr<ConstitutiveModel>
  DruckerPragerPlasticity::with_reduced_strength(const double factor) const
  {
    AssertThrow(factor > 0,
                ExcMessage("Strength reduction: the factor must be positive."));
    // Mohr-Coulomb's strength c + sigma_n tan(phi) divided by F; the
    // dilation angle is reduced alike, so that psi <= phi stays true and
    // associated flow stays associated.
    return std::make_unique<DruckerPragerPlasticity>(
      E,
      nu,
      c / factor,
      std::atan(std::tan(phi) / factor),
      std::atan(std::tan(psi) / factor),
      match);
  }



  BSMPM_REGISTER_CONSTITUTIVE_MODEL(
    DruckerPragerPlasticity,
    "Drucker-Prager",
    false,
    "a frictional cone, subsection 'Drucker-Prager'")
} // namespace bsmpm
