#ifndef bsmpm_drucker_prager_plasticity_h
#define bsmpm_drucker_prager_plasticity_h

#include <bsmpm/materials/constitutive_model.h>

namespace bsmpm
{
  /**
   * Perfectly plastic Drucker-Prager cone f = sqrt(J2) + eta p - xi c with
   * the flow potential g = sqrt(J2) + eta_bar p (non-associated when the
   * dilation angle is below the friction angle), matched to Mohr-Coulomb in
   * plane strain (default), on the outer or on the inner edges. The return
   * map works on the principal values of the trial elastic strain (smooth
   * part and apex) and reassembles the consistent tangent with the spin
   * terms (doc/materials.md, Sec. 4 and 5). Parameters in
   * "Material/Drucker-Prager".
   */
  class DruckerPragerPlasticity : public ConstitutiveModel
  {
  public:
    enum class Match
    {
      plane_strain,
      outer,
      inner
    };

    /** Angles in radians. */
    DruckerPragerPlasticity(const double youngs_modulus,
                            const double poissons_ratio,
                            const double cohesion,
                            const double friction_angle,
                            const double dilation_angle,
                            const Match  match = Match::plane_strain);

    /** Declares "Drucker-Prager" inside the current subsection. */
    static void
    declare_parameters(ParameterHandler &prm);
    /** Reads "Drucker-Prager" inside the current subsection. */
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
    /** sqrt(J2) + eta p - xi c. */
    double
    yield_function(const SymmetricTensor<2, 3> &stress,
                   const double eq_plastic_strain) const override;
    /** Jaky's 1 - sin(phi) for normally consolidated ground. */
    double
    at_rest_coefficient() const override;
    std::string
    name() const override;
    /** c / F, tan(phi) / F and tan(psi) / F, the same match. */
    std::unique_ptr<ConstitutiveModel>
    with_reduced_strength(const double factor) const override;

    /** Coefficients of the cone: f = sqrt(J2) + eta p - xi c,
     * g = sqrt(J2) + eta_bar p. */
    double
    eta() const
    {
      return eta_f;
    }
    double
    xi() const
    {
      return xi_f;
    }
    double
    eta_bar() const
    {
      return eta_g;
    }
    double
    cohesion() const
    {
      return c;
    }
    bool
    symmetric_tangent() const override
    {
      return eta_g == eta_f;
    }
    /** Mean stress of the apex, xi c / eta (infinite for eta = 0). */
    double
    apex_pressure() const;

  private:
    double c;
    double phi;
    double psi;
    double eta_f;
    double xi_f;
    double eta_g;
    Match  match;
  };
} // namespace bsmpm

#endif
