#include <bsmpm/materials/von_mises_plasticity.h>

#include <algorithm>
#include <cmath>

namespace bsmpm
{
  VonMisesPlasticity::VonMisesPlasticity(const double youngs_modulus,
                                         const double poissons_ratio,
                                         const double yield_stress,
                                         const double hardening_modulus)
    : ConstitutiveModel(youngs_modulus, poissons_ratio)
    , sigma_y(yield_stress)
    , H(hardening_modulus)
  {
    AssertThrow(std::isfinite(sigma_y) && sigma_y > 0.,
                ExcMessage("Material: von Mises: the yield stress must be "
                           "positive, got " +
                           std::to_string(sigma_y) + "."));
    AssertThrow(std::isfinite(H) && H >= 0.,
                ExcMessage("Material: von Mises: the hardening modulus must "
                           "be non-negative (0: perfectly plastic), got " +
                           std::to_string(H) + "."));
  }



  void
  VonMisesPlasticity::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("von Mises");
    prm.declare_entry("Yield stress",
                      "1e4",
                      Patterns::Double(0.),
                      "Uniaxial yield stress sigma_y in the units of Young's "
                      "modulus (positive). In "
                      "plane strain the shear strength is sigma_y / sqrt(3): "
                      "a Tresca soil of undrained strength c_u needs "
                      "sigma_y = sqrt(3) c_u.");
    prm.declare_entry("Hardening modulus",
                      "0",
                      Patterns::Double(0.),
                      "Linear isotropic hardening: the yield stress grows by "
                      "H times the equivalent plastic strain (units of "
                      "Young's modulus); 0 is "
                      "perfectly plastic.");
    prm.leave_subsection();
  }



  std::unique_ptr<ConstitutiveModel>
  VonMisesPlasticity::create(ParameterHandler       &prm,
                             const ElasticConstants &elastic)
  {
    prm.enter_subsection("von Mises");
    const double yield_stress      = prm.get_double("Yield stress");
    const double hardening_modulus = prm.get_double("Hardening modulus");
    prm.leave_subsection();
    return std::make_unique<VonMisesPlasticity>(elastic.youngs_modulus,
                                                elastic.poissons_ratio,
                                                yield_stress,
                                                hardening_modulus);
  }



  ConstitutiveResponse
  VonMisesPlasticity::update(ConstitutiveState &state) const
  {
    const SymmetricTensor<2, 3> &eps_tr = state.elastic_strain;
    const SymmetricTensor<2, 3>  e_tr   = deviator(eps_tr);
    const double                 norm_e = e_tr.norm();
    // q^tr = sqrt(3/2) |2 mu e| = sqrt(6) mu |e|
    const double q_tr = std::sqrt(6.) * mu * norm_e;
    const double f_tr = q_tr - (sigma_y + H * state.equivalent_plastic_strain);

    if (!(f_tr > 0.))
      // elastic_stress(eps_tr) with the deviator at hand; made in place
      // (a response zeroed first, then assigned, cost a fifth of this
      // function, which every point of every Newton system calls).
      return {kappa * trace(eps_tr) * unit_symmetric_tensor<3>() +
                2. * mu * e_tr,
              isotropic_stiffness(),
              false};

    ConstitutiveResponse response;

    // Radial return (doc/materials.md, Sec. 3).
    const double                dgamma = f_tr / (3. * mu + H);
    const SymmetricTensor<2, 3> n      = e_tr / norm_e;
    // eps_e = eps_tr - dgamma 3/2 s_tr / q_tr = eps_tr - dgamma sqrt(3/2) n
    state.elastic_strain -= dgamma * std::sqrt(1.5) * n;
    state.equivalent_plastic_strain += dgamma;

    response.yielded = true;
    response.stress  = elastic_stress(state.elastic_strain);
    // D = K 1 (x) 1 + 2 mu beta I_d + 6 mu^2 (dgamma / q_tr - 1 / (3 mu +
    // H)) n (x) n, beta = 1 - 3 mu dgamma / q_tr: the elastic stiffness plus
    // its change.
    const double beta = 1. - 3. * mu * dgamma / q_tr;
    response.tangent  = isotropic_stiffness();
    add_deviatoric_terms(response.tangent,
                         2. * mu * (beta - 1.),
                         6. * mu * mu * (dgamma / q_tr - 1. / (3. * mu + H)),
                         n);
    return response;
  }



  bool
  VonMisesPlasticity::plane_strain_update(ConstitutiveState      &state,
                                          std::array<double, 4>  &stress,
                                          std::array<double, 16> &tangent) const
  {
    // update() step by step, on the four components of plane strain and in
    // the order of deal.II's deviator() and norm() (the same numbers: the
    // norm's terms of xz and yz add zero), without the rank-4 tangent of
    // the elastic branch and with the 4 x 4 block of the plastic one.
    const SymmetricTensor<2, 3> &eps_tr = state.elastic_strain;
    Assert(eps_tr[0][2] == 0. && eps_tr[1][2] == 0.,
           ExcMessage("plane_strain_update() needs xz = yz = 0."));
    const double tr   = eps_tr[0][0] + eps_tr[1][1] + eps_tr[2][2];
    const double mean = tr / 3;
    const double e_xx = eps_tr[0][0] - mean, e_yy = eps_tr[1][1] - mean,
                 e_zz = eps_tr[2][2] - mean, e_xy = eps_tr[0][1];
    const double norm_e =
      std::sqrt(e_xx * e_xx + e_yy * e_yy + e_zz * e_zz + 2. * (e_xy * e_xy));
    const double q_tr = std::sqrt(6.) * mu * norm_e;
    const double f_tr = q_tr - (sigma_y + H * state.equivalent_plastic_strain);
    if (!(f_tr > 0.))
      {
        // elastic_stress(eps_tr): K tr 1 + 2 mu e.
        const double p = kappa * tr;
        stress[0]      = p + 2. * mu * e_xx;
        stress[1]      = p + 2. * mu * e_yy;
        stress[2]      = p + 2. * mu * e_zz;
        stress[3]      = 2. * mu * e_xy;
        return false;
      }

    SymmetricTensor<2, 3> e_tr;
    e_tr[0][0]                         = e_xx;
    e_tr[1][1]                         = e_yy;
    e_tr[2][2]                         = e_zz;
    e_tr[0][1]                         = e_xy;
    const double                dgamma = f_tr / (3. * mu + H);
    const SymmetricTensor<2, 3> n      = e_tr / norm_e;
    state.elastic_strain -= dgamma * std::sqrt(1.5) * n;
    state.equivalent_plastic_strain += dgamma;
    plane_strain_elastic_stress(state.elastic_strain,
                                deviator(state.elastic_strain),
                                stress);
    // The (xx, yy, zz, xy) block of isotropic_stiffness() plus
    // add_deviatoric_terms() (the first four of deal.II's stored pairs);
    // n (x) n takes n's stored entries.
    const double beta = 1. - 3. * mu * dgamma / q_tr;
    const double a    = 2. * mu * (beta - 1.);
    const double b    = 6. * mu * mu * (dgamma / q_tr - 1. / (3. * mu + H));
    const double n_voigt[4] = {n[0][0], n[1][1], n[2][2], n[0][1]};
    for (unsigned int r = 0; r < 4; ++r)
      for (unsigned int c = 0; c < 4; ++c)
        tangent[4 * r + c] =
          isotropic_stiffness().access_raw_entry(6 * r + c) +
          (a * deviatoric_projector(r, c) + b * n_voigt[r] * n_voigt[c]);
    return true;
  }



  double
  VonMisesPlasticity::elastic_reach(const ConstitutiveState &state) const
  {
    // f(e) = sqrt(6) mu |dev e| - (sigma_y + H eps_bar), and
    // |dev(e_n + de)| <= |dev e_n| + |de|: the step stays elastic while
    // |de| <= Y / (sqrt(6) mu) - |dev e_n|. A millionth of a millionth of
    // the yield strain is kept back for the round-off of the two sides.
    const double yield_strain =
      (sigma_y + H * state.equivalent_plastic_strain) / (std::sqrt(6.) * mu);
    // |dev e| on the four plane-strain components (xz = yz = 0).
    const SymmetricTensor<2, 3> &e    = state.elastic_strain;
    const double                 mean = (e[0][0] + e[1][1] + e[2][2]) / 3;
    const double                 e_xx = e[0][0] - mean, e_yy = e[1][1] - mean,
                 e_zz = e[2][2] - mean, e_xy = e[0][1];
    const double norm =
      std::sqrt(e_xx * e_xx + e_yy * e_yy + e_zz * e_zz + 2. * e_xy * e_xy);
    return std::max(0., (1. - 1e-12) * yield_strain - norm);
  }



  double
  VonMisesPlasticity::yield_function(const SymmetricTensor<2, 3> &stress,
                                     const double eq_plastic_strain) const
  {
    return std::sqrt(1.5) * deviator(stress).norm() -
           (sigma_y + H * eq_plastic_strain);
  }



  std::string
  VonMisesPlasticity::name() const
  {
    return "von Mises";
  }



  std::unique_ptr<ConstitutiveModel>
  VonMisesPlasticity::with_reduced_strength(const double factor) const
  {
    AssertThrow(factor > 0,
                ExcMessage("Strength reduction: the factor must be positive."));
    // The yield stress sigma_y + H eps_bar is the strength at every plastic
    // strain: both parts are divided.
    return std::make_unique<VonMisesPlasticity>(E,
                                                nu,
                                                sigma_y / factor,
                                                H / factor);
  }



  BSMPM_REGISTER_CONSTITUTIVE_MODEL(
    VonMisesPlasticity,
    "von Mises",
    false,
    "plasticity with linear hardening, subsection 'von Mises'")
} // namespace bsmpm
