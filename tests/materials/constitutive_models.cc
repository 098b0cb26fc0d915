// Constitutive models (doc/materials.md): linear elastic, von Mises
// (perfectly plastic and hardening) and Drucker-Prager (plane-strain, outer
// and inner matches; associated and non-associated; with and without
// cohesion; without friction).
//
// Trial strains are built backwards from a known answer: a stress on the
// yield surface (or inside it, or the apex) and a plastic multiplier give the
// trial elastic strain whose return must be that stress. Categories: elastic,
// plastic (small to very large steps), near the apex, beyond the apex, equal
// and nearly equal principal values. For every trial strain: the stress and
// equivalent plastic strain recovered, the yield condition after the return
// (|f| <= 1e-10 of the strength when plastic, f <= 0 when elastic), stress =
// D^e : returned elastic strain, the flow rule, the tangent against central
// differences of update() (1e-6), and isotropy (a rotated trial strain gives
// the rotated stress, elastic strain and tangent). Then: linear elasticity
// against LinearElasticMaterial, Drucker-Prager without friction against
// von Mises, plane-strain limits (von Mises: shear strength sigma_y /
// sqrt(3); Drucker-Prager: Mohr-Coulomb's strength in plane-strain flow),
// ln and exp of symmetric tensors with their derivatives, and the
// parameters. Finally the Newton system of one cell of points
// (ConstitutiveUpdate, small and finite strain, standard strain and
// B-bar / F-bar) against central differences of its internal force, and
// the models' plane_strain_update() (what the Newton system's points call)
// against update(), bit for bit. Only counts, yes/no and rounded figures
// are printed.

#include <deal.II/base/numbers.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/symmetric_tensor.h>

#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>

#include <bsmpm/assembly/constitutive_update.h>
#include <bsmpm/materials/constitutive_model.h>
#include <bsmpm/materials/drucker_prager_plasticity.h>
#include <bsmpm/materials/linear_elastic_model.h>
#include <bsmpm/materials/material.h>
#include <bsmpm/materials/von_mises_plasticity.h>

#include <cmath>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

// tests.h uses deallog unqualified: the using directive must come first.
using namespace dealii;

#include "../tests.h"

using namespace bsmpm;

namespace
{
  using Sym2 = SymmetricTensor<2, 3>;
  using Sym4 = SymmetricTensor<4, 3>;

  const double E      = 1e7;
  const double nu     = 0.3;
  const double mu     = E / (2. * (1. + nu));
  const double kappa  = E / (3. * (1. - 2. * nu));
  const double degree = numbers::PI / 180.;

  Sym2
  unit()
  {
    return unit_symmetric_tensor<3>();
  }

  /** Elastic strain of a stress. */
  Sym2
  compliance(const Sym2 &sigma)
  {
    return trace(sigma) / (9. * kappa) * unit() + deviator(sigma) / (2. * mu);
  }

  Tensor<2, 3>
  random_rotation(Random &random)
  {
    // Uniform unit quaternion (Shoemake).
    const double u1 = random(), u2 = 2. * numbers::PI * random(),
                 u3 = 2. * numbers::PI * random();
    const double a  = std::sqrt(1. - u1) * std::sin(u2),
                 b  = std::sqrt(1. - u1) * std::cos(u2),
                 c  = std::sqrt(u1) * std::sin(u3),
                 d  = std::sqrt(u1) * std::cos(u3);
    Tensor<2, 3> R;
    R[0][0] = 1 - 2 * (c * c + d * d);
    R[0][1] = 2 * (b * c - a * d);
    R[0][2] = 2 * (b * d + a * c);
    R[1][0] = 2 * (b * c + a * d);
    R[1][1] = 1 - 2 * (b * b + d * d);
    R[1][2] = 2 * (c * d - a * b);
    R[2][0] = 2 * (b * d - a * c);
    R[2][1] = 2 * (c * d + a * b);
    R[2][2] = 1 - 2 * (b * b + c * c);
    return R;
  }

  Sym2
  rotate(const Sym2 &x, const Tensor<2, 3> &R)
  {
    return symmetrize(Tensor<2, 3>(R * Tensor<2, 3>(x) * transpose(R)));
  }

  Sym4
  rotate(const Sym4 &t, const Tensor<2, 3> &R)
  {
    Sym4 result;
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = i; j < 3; ++j)
        for (unsigned int k = 0; k < 3; ++k)
          for (unsigned int l = k; l < 3; ++l)
            {
              double sum = 0;
              for (unsigned int a = 0; a < 3; ++a)
                for (unsigned int b = 0; b < 3; ++b)
                  for (unsigned int c = 0; c < 3; ++c)
                    for (unsigned int d = 0; d < 3; ++d)
                      sum +=
                        R[i][a] * R[j][b] * R[k][c] * R[l][d] * t[a][b][c][d];
              result[i][j][k][l] = sum;
            }
    return result;
  }

  /** A random unit deviatoric tensor with the principal shape @p shape:
   * 0 general, 1 and 2 two equal principal values (the lone one largest or
   * smallest), 3 nearly equal ones (relative gap @p gap); rotated by R. */
  Sym2
  unit_deviator(Random             &random,
                const int           shape,
                const Tensor<2, 3> &R,
                const double        gap = 0)
  {
    Sym2 d;
    if (shape == 0)
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int j = i; j < 3; ++j)
          d[i][j] = random(-1., 1.);
    else
      {
        const double sign = shape == 2 ? -1. : 1.;
        d[0][0]           = 2. * sign;
        d[1][1]           = -sign * (1. + gap);
        d[2][2]           = -sign * (1. - gap);
      }
    d = deviator(d);
    d /= d.norm();
    return rotate(d, R);
  }

  /** Central differences of update() with respect to the trial strain. */
  Sym4
  finite_difference_tangent(const ConstitutiveModel &model,
                            const ConstitutiveState &state,
                            const double             h)
  {
    Sym4 result;
    for (unsigned int k = 0; k < 3; ++k)
      for (unsigned int l = k; l < 3; ++l)
        {
          ConstitutiveState plus = state, minus = state;
          plus.elastic_strain[k][l] += h;
          minus.elastic_strain[k][l] -= h;
          const Sym2 d = model.update(plus).stress - model.update(minus).stress;
          // Off the diagonal the entry (k,l) and (l,k) both moved.
          const double scale = (k == l ? 2. : 4.) * h;
          for (unsigned int i = 0; i < 3; ++i)
            for (unsigned int j = i; j < 3; ++j)
              result[i][j][k][l] = d[i][j] / scale;
        }
    return result;
  }

  struct Case
  {
    ConstitutiveState trial;
    Sym2              expected_stress;
    double            expected_eq_plastic_strain;
    bool              plastic;
    bool              apex;
  };

  struct Counts
  {
    unsigned int n = 0, elastic = 0, plastic = 0, apex = 0, equal = 0;
    unsigned int recovered = 0, yield = 0, consistent = 0, flow = 0,
                 tangent = 0, isotropic = 0;
    double max_tangent_error = 0;
  };

  /** All checks of one trial strain. @p flow_ok checks the flow rule of the
   * model on the trial strain, the returned state and the returned stress. */
  template <typename FlowCheck>
  void
  check_case(const ConstitutiveModel &model,
             const Case              &c,
             const double             strength,
             const bool               equal_eigenvalues,
             Random                  &random,
             const FlowCheck         &flow_ok,
             Counts                  &counts)
  {
    const double stress_scale = std::max(c.expected_stress.norm(), strength);
    ConstitutiveState          state    = c.trial;
    const ConstitutiveResponse response = model.update(state);
    ++counts.n;
    counts.elastic += !c.plastic;
    counts.plastic += c.plastic && !c.apex;
    counts.apex += c.apex;
    counts.equal += equal_eigenvalues;

    if (response.yielded == c.plastic &&
        (response.stress - c.expected_stress).norm() <= 1e-10 * stress_scale &&
        std::abs(state.equivalent_plastic_strain -
                 c.expected_eq_plastic_strain) <=
          1e-10 * std::max(c.expected_eq_plastic_strain, strength / E))
      ++counts.recovered;

    const double f =
      model.yield_function(response.stress, state.equivalent_plastic_strain);
    if (c.plastic ? std::abs(f) <= 1e-10 * strength : f <= 1e-12 * strength)
      ++counts.yield;

    const double lambda       = kappa - 2. * mu / 3.;
    const Sym2 elastic_stress = lambda * trace(state.elastic_strain) * unit() +
                                2. * mu * state.elastic_strain;
    if ((elastic_stress - response.stress).norm() <= 1e-12 * stress_scale &&
        (c.plastic || state.elastic_strain == c.trial.elastic_strain))
      ++counts.consistent;

    if (!c.plastic || flow_ok(c.trial, state, response.stress))
      ++counts.flow;

    // Step: small against the scales of the map, |dev eps^tr| on the
    // smooth part of a plastic return (central differences: error ~ h^2),
    // and against the distance to a change of regime (elastic/plastic,
    // cone/apex).
    const double trial_norm = c.trial.elastic_strain.norm();
    double       h          = 1e-6 * std::max(trial_norm, strength / E);
    if (c.plastic && !c.apex)
      h = std::min(3e-5 * deviator(c.trial.elastic_strain).norm(),
                   0.1 * deviator(c.expected_stress).norm() / (2. * mu));
    const Sym4   fd          = finite_difference_tangent(model, c.trial, h);
    const double ref         = response.tangent.norm() > 0. ?
                                 response.tangent.norm() :
                                 model.elastic_tangent().norm();
    const double error       = (fd - response.tangent).norm() / ref;
    counts.max_tangent_error = std::max(counts.max_tangent_error, error);
    if (error <= 1e-6)
      ++counts.tangent;

    const Tensor<2, 3> R         = random_rotation(random);
    ConstitutiveState  rotated   = c.trial;
    rotated.elastic_strain       = rotate(c.trial.elastic_strain, R);
    const ConstitutiveResponse r = model.update(rotated);
    const double tangent_scale = std::max(response.tangent.norm(), 1e-6 * ref);
    // Rounding the trial strain alone moves the stress by ~ eps 2 mu
    // |eps^tr|: that is the scale of the comparisons.
    if ((r.stress - rotate(response.stress, R)).norm() <=
          1e-12 * (stress_scale + 2. * mu * trial_norm) &&
        (rotated.elastic_strain - rotate(state.elastic_strain, R)).norm() <=
          1e-12 * std::max(trial_norm, strength / E) &&
        std::abs(rotated.equivalent_plastic_strain -
                 state.equivalent_plastic_strain) <=
          1e-12 * std::max(state.equivalent_plastic_strain, strength / E) &&
        (r.tangent - rotate(response.tangent, R)).norm() <=
          1e-10 * tangent_scale)
      ++counts.isotropic;
  }

  void
  print_counts(const std::string &label, const Counts &c)
  {
    deallog << label << ": " << c.n << " trial strains (" << c.elastic
            << " elastic, " << c.plastic << " plastic, " << c.apex << " apex; "
            << c.equal << " with equal or nearly equal "
            << "principal values)" << std::endl;
    deallog << label << ": stress and eq. plastic strain recovered to 1e-10 "
            << c.recovered << ", yield condition " << c.yield
            << ", stress = D^e : returned elastic strain " << c.consistent
            << ", flow rule " << c.flow << ", tangent = central differences "
            << "to 1e-6 " << c.tangent
            << " (max below 1e-7: " << yes_no(c.max_tangent_error < 1e-7)
            << "), isotropy " << c.isotropic << std::endl;
  }



  // ---------------------------------------------------------------- von Mises

  void
  test_von_mises(const double H, const std::string &label, Random &random)
  {
    const double             sigma_y = 1e4;
    const VonMisesPlasticity model(E, nu, sigma_y, H);
    Counts                   counts;

    // The flow rule: d eps_p = d eps_bar 3/2 s / q.
    const auto flow_ok = [&](const ConstitutiveState &trial,
                             const ConstitutiveState &state,
                             const Sym2              &stress) {
      const Sym2   d_eps_p = trial.elastic_strain - state.elastic_strain;
      const double d_bar =
        state.equivalent_plastic_strain - trial.equivalent_plastic_strain;
      const double q = std::sqrt(1.5) * deviator(stress).norm();
      // d_eps_p is a difference of strains: rounding ~ eps |eps^tr|.
      const double tol = 1e-12 * trial.elastic_strain.norm();
      return (d_eps_p - d_bar * 1.5 * deviator(stress) / q).norm() <=
               1e-10 * d_eps_p.norm() + tol &&
             std::abs(d_bar - std::sqrt(2. / 3.) * d_eps_p.norm()) <=
               1e-12 * d_bar + tol;
    };

    for (unsigned int k = 0; k < 160; ++k)
      {
        const int          category = k % 4; // elastic, plastic, large, equal
        const int          shape    = category == 3 ? 1 + (k / 4) % 3 : 0;
        const double       gap = shape == 3 ? std::pow(10., -4. - (k % 7)) : 0.;
        const Tensor<2, 3> R   = (k / 4) % 2 == 0 && shape > 0 ?
                                   unit_symmetric_tensor<3>() :
                                   random_rotation(random);
        const Sym2         n   = unit_deviator(random, shape, R, gap);
        const double eps_bar_n = H > 0 ? random(0., 0.05) : random(0., 0.01);
        const double p         = random(-3., 1.) * sigma_y;

        Case c;
        c.trial.equivalent_plastic_strain = eps_bar_n;
        c.plastic                         = category != 0;
        c.apex                            = false;
        const double dgamma =
          !c.plastic    ? 0. :
          category == 2 ? sigma_y / E * std::pow(10., random(1., 3.)) :
                          sigma_y / E * std::pow(10., random(-3., 1.));
        const double q = (sigma_y + H * (eps_bar_n + dgamma)) *
                         (c.plastic ? 1. : random(0., 0.95));
        c.expected_stress            = p * unit() + std::sqrt(2. / 3.) * q * n;
        c.expected_eq_plastic_strain = eps_bar_n + dgamma;
        c.trial.elastic_strain =
          compliance(c.expected_stress) + dgamma * std::sqrt(1.5) * n;
        check_case(model,
                   c,
                   sigma_y + H * c.expected_eq_plastic_strain,
                   shape > 0,
                   random,
                   flow_ok,
                   counts);
      }
    print_counts(label, counts);
  }



  // ----------------------------------------------------------- Drucker-Prager

  void
  test_drucker_prager(const DruckerPragerPlasticity &model,
                      const std::string             &label,
                      Random                        &random)
  {
    const double eta = model.eta(), xi = model.xi(), eta_bar = model.eta_bar(),
                 c = model.cohesion();
    // Stress scale: the cohesion, or for a cohesionless cone 1e4 Pa of
    // compression.
    const double scale  = c > 0 ? c : 1e4;
    const bool   apex   = eta > 0;
    const double p_apex = apex ? model.apex_pressure() : 0.;
    Counts       counts;

    // d eps_p = dgamma (s / (2 sqrt(J2)) + eta_bar/3 1) on the cone; at the
    // apex, within the cone of directions: tr >= sqrt(2) eta_bar |dev|.
    const auto flow_ok = [&](const ConstitutiveState &trial,
                             const ConstitutiveState &state,
                             const Sym2              &stress) {
      const Sym2   d_eps_p = trial.elastic_strain - state.elastic_strain;
      const double d_bar =
        state.equivalent_plastic_strain - trial.equivalent_plastic_strain;
      // d_eps_p is a difference of strains: rounding ~ eps |eps^tr|.
      const double tol = 1e-12 * trial.elastic_strain.norm();
      if (std::abs(d_bar - std::sqrt(2. / 3.) * d_eps_p.norm()) >
          1e-12 * d_bar + tol)
        return false;
      const Sym2   s       = deviator(stress);
      const double sqrt_j2 = s.norm() / std::sqrt(2.);
      if (sqrt_j2 <= 1e-9 * scale) // apex
        return trace(d_eps_p) >=
               std::sqrt(2.) * eta_bar * deviator(d_eps_p).norm() - tol;
      const Sym2 m = s / (2. * sqrt_j2) + eta_bar / 3. * unit();
      const Sym2 r = d_eps_p - (d_eps_p * m) / (m * m) * m;
      return r.norm() <= 1e-10 * d_eps_p.norm() + tol && d_eps_p * m > 0.;
    };

    for (unsigned int k = 0; k < 240; ++k)
      {
        // elastic, plastic, large plastic, near apex, apex, equal values
        const int category = k % 6;
        if (!apex && (category == 3 || category == 4))
          continue;
        const int          shape = category == 5 ? 1 + (k / 6) % 3 : 0;
        const double       gap = shape == 3 ? std::pow(10., -4. - (k % 7)) : 0.;
        const Tensor<2, 3> R   = (k / 6) % 2 == 0 && shape > 0 ?
                                   unit_symmetric_tensor<3>() :
                                   random_rotation(random);
        const Sym2         n   = unit_deviator(random, shape, R, gap);

        Case cs;
        cs.trial.equivalent_plastic_strain = random(0., 0.01);
        cs.plastic                         = category != 0;
        cs.apex                            = category == 4;
        double d_bar                       = 0;
        if (category == 4)
          {
            // Beyond the apex: d eps_p with tr > 0 and |dev| inside the cone
            // of flow directions (any |dev| without dilation). Equal
            // principal values are tried here too (dev = 0 every 4th).
            const double v = scale / E * std::pow(10., random(-2., 2.));
            const double dv =
              k % 4 == 0  ? 0. :
              eta_bar > 0 ? random(0., 0.9) * v / (std::sqrt(2.) * eta_bar) :
                            random(0., 10.) * v;
            const Sym2 d_eps_p      = v / 3. * unit() + dv * n;
            cs.expected_stress      = p_apex * unit();
            cs.trial.elastic_strain = compliance(cs.expected_stress) + d_eps_p;
            d_bar                   = std::sqrt(2. / 3.) * d_eps_p.norm();
          }
        else
          {
            // On (or inside) the cone: sqrt(J2) = a (xi c - eta p).
            const double p = category == 3 ?
                               p_apex - std::pow(10., random(-4., -2.)) *
                                          scale / std::max(eta, 1e-3) :
                               p_apex - random(0.2, 5.) * scale;
            const double sqrt_j2 =
              (xi * c - eta * p) * (cs.plastic ? 1. : random(0., 0.95));
            cs.expected_stress = p * unit() + std::sqrt(2.) * sqrt_j2 * n;
            const double dgamma =
              !cs.plastic   ? 0. :
              category == 2 ? scale / E * std::pow(10., random(1., 3.)) :
                              scale / E * std::pow(10., random(-3., 1.));
            const Sym2 d_eps_p =
              dgamma * (n / std::sqrt(2.) + eta_bar / 3. * unit());
            cs.trial.elastic_strain = compliance(cs.expected_stress) + d_eps_p;
            d_bar                   = std::sqrt(2. / 3.) * d_eps_p.norm();
          }
        cs.expected_eq_plastic_strain =
          cs.trial.equivalent_plastic_strain + d_bar;
        const double strength =
          std::max(xi * c, eta * std::abs(trace(cs.expected_stress)) / 3.);
        check_case(model,
                   cs,
                   strength > 0 ? strength : scale,
                   shape > 0 || (category == 4 && k % 4 == 0),
                   random,
                   flow_ok,
                   counts);
      }
    print_counts(label, counts);
  }



  // ------------------------------------------------------------ cross checks

  void
  test_linear_elastic(Random &random)
  {
    deallog.push("linear elastic");
    for (const bool plane_stress : {false, true})
      {
        const LinearElasticMaterial material(
          E,
          nu,
          plane_stress ? LinearElasticMaterial::Model::plane_stress :
                         LinearElasticMaterial::Model::plane_strain);
        const LinearElasticModel model(E, nu, plane_stress);
        const Tensor<2, 3>      &C       = material.stiffness();
        const unsigned int       v[3][2] = {{0, 0}, {1, 1}, {0, 1}};
        unsigned int stress_ok = 0, tangent_ok = 0, fd_ok = 0, n = 100;
        for (unsigned int k = 0; k < n; ++k)
          {
            ConstitutiveState state;
            Tensor<1, 3>      voigt;
            for (unsigned int i = 0; i < 3; ++i)
              voigt[i] = random(-1e-3, 1e-3);
            state.elastic_strain[0][0] = voigt[0];
            state.elastic_strain[1][1] = voigt[1];
            state.elastic_strain[0][1] = voigt[2] / 2.;
            // The caller's zz: zero in plane strain, anything in plane stress.
            state.elastic_strain[2][2] = plane_stress ? random(-1., 1.) : 0.;
            const ConstitutiveState    trial    = state;
            const ConstitutiveResponse response = model.update(state);
            const Tensor<1, 3>         expected = C * voigt;
            const double lambda = E * nu / ((1. + nu) * (1. - 2. * nu));
            const double zz =
              plane_stress ? 0. : lambda * (voigt[0] + voigt[1]);
            double error = std::abs(response.stress[2][2] - zz) +
                           std::abs(response.stress[0][2]) +
                           std::abs(response.stress[1][2]);
            for (unsigned int i = 0; i < 3; ++i)
              error +=
                std::abs(response.stress[v[i][0]][v[i][1]] - expected[i]);
            stress_ok += error <= 1e-12 * expected.norm();
            double t_error = 0;
            for (unsigned int i = 0; i < 3; ++i)
              for (unsigned int j = 0; j < 3; ++j)
                // sigma_i = D_i,kl eps_kl = D_i,xy gamma_xy for the shear:
                // C_ij = D[v_i][v_j].
                t_error += std::abs(
                  response.tangent[v[i][0]][v[i][1]][v[j][0]][v[j][1]] -
                  C[i][j]);
            tangent_ok += t_error <= 1e-12 * C.norm() &&
                          response.tangent == model.elastic_tangent();
            const Sym4 fd = finite_difference_tangent(model, trial, 1e-6);
            fd_ok +=
              (fd - response.tangent).norm() <= 1e-8 * response.tangent.norm();
          }
        deallog << (plane_stress ? "plane stress" : "plane strain") << ": " << n
                << " random strains, stress = LinearElasticMaterial's "
                << "C eps (and sigma_zz) " << stress_ok
                << ", in-plane tangent = C " << tangent_ok
                << ", tangent = central differences " << fd_ok
                << ", linear: " << yes_no(model.is_linear())
                << ", yield function -inf: "
                << yes_no(std::isinf(model.yield_function(Sym2(), 0.)) &&
                          model.yield_function(Sym2(), 0.) < 0.)
                << std::endl;
      }
    deallog.pop();
  }



  void
  test_frictionless_drucker_prager_is_von_mises(Random &random)
  {
    // phi = psi = 0, plane-strain match: xi = 1, sqrt(J2) = c, i.e. von
    // Mises with sigma_y = sqrt(3) c. The one returns in principal values
    // and assembles the spin terms, the other works on the tensor.
    const double                  c = 1e4;
    const DruckerPragerPlasticity dp(E, nu, c, 0., 0.);
    const VonMisesPlasticity      vm(E, nu, std::sqrt(3.) * c, 0.);
    unsigned int                  same = 0, n = 100, yielded = 0;
    for (unsigned int k = 0; k < n; ++k)
      {
        const int         shape = k % 5 == 4 ? 1 + (k / 5) % 3 : 0;
        const Sym2        dir   = unit_deviator(random,
                                       shape,
                                       random_rotation(random),
                                       shape == 3 ? 1e-8 : 0.);
        ConstitutiveState a;
        a.elastic_strain =
          c / mu * random(0., 20.) * dir + random(-1e-3, 1e-3) * unit();
        ConstitutiveState          b  = a;
        const ConstitutiveResponse ra = dp.update(a), rb = vm.update(b);
        yielded += ra.yielded;
        same +=
          ra.yielded == rb.yielded &&
          (ra.stress - rb.stress).norm() <= 1e-12 * rb.stress.norm() &&
          (ra.tangent - rb.tangent).norm() <= 1e-10 * rb.tangent.norm() &&
          (a.elastic_strain - b.elastic_strain).norm() <=
            1e-12 * b.elastic_strain.norm() &&
          std::abs(a.equivalent_plastic_strain - b.equivalent_plastic_strain) <=
            1e-12 * b.equivalent_plastic_strain;
      }
    deallog << "Drucker-Prager (phi = psi = 0) = von Mises (sigma_y = sqrt(3) "
            << "c): " << same << " of " << n << " (" << yielded
            << " yielded): stress, elastic strain, eq. plastic strain, tangent"
            << std::endl;
  }



  /**
   * ConstitutiveModel::plane_strain_update(), the return of the Newton
   * system's points, against update() on plane-strain trial strains
   * (xz = yz = 0) from well inside the elastic range to far beyond yield:
   * the same yield flag, stress, returned state and, where the step
   * yields, the (xx, yy, zz, xy) block of the tangent, bit for bit (the
   * Newton iterations must not change by its use).
   */
  void
  test_plane_strain_update(Random &random)
  {
    const VonMisesPlasticity perfect(E, nu, 1e4, 0.),
      hardening(E, nu, 1e4, 2e5);
    const DruckerPragerPlasticity dp(E, nu, 1e4, 30. * degree, 10. * degree),
      dp_cohesionless(E, nu, 0., 35. * degree, 5. * degree);
    const LinearElasticModel elastic(E, nu);
    const std::vector<std::pair<std::string, const ConstitutiveModel *>>
      models = {{"von Mises, perfectly plastic", &perfect},
                {"von Mises, hardening", &hardening},
                {"Drucker-Prager phi 30, psi 10", &dp},
                {"Drucker-Prager c 0, phi 35, psi 5", &dp_cohesionless},
                {"linear elastic", &elastic}};
    for (const auto &[label, model] : models)
      {
        unsigned int same = 0, n = 200, yielded = 0;
        for (unsigned int k = 0; k < n; ++k)
          {
            // Strains from 1e-6 to 1e-2 (yield near 1e-3), with a pressure
            // that may reach beyond the cone's apex.
            const double      scale = std::pow(10., random(-6., -2.));
            ConstitutiveState a;
            a.elastic_strain[0][0]       = scale * random(-1., 1.);
            a.elastic_strain[1][1]       = scale * random(-1., 1.);
            a.elastic_strain[2][2]       = scale * random(-1., 1.);
            a.elastic_strain[0][1]       = scale * random(-1., 1.);
            a.equivalent_plastic_strain  = k % 2 == 0 ? 0. : 1e-3 * k / n;
            ConstitutiveState          b = a;
            const ConstitutiveResponse r = model->update(a);
            std::array<double, 4>      stress;
            std::array<double, 16>     tangent;
            tangent.fill(-1.);
            const bool y = model->plane_strain_update(b, stress, tangent);
            yielded += y;
            bool equal =
              y == r.yielded && stress[0] == r.stress[0][0] &&
              stress[1] == r.stress[1][1] && stress[2] == r.stress[2][2] &&
              stress[3] == r.stress[0][1] &&
              a.elastic_strain == b.elastic_strain &&
              a.equivalent_plastic_strain == b.equivalent_plastic_strain;
            // The Voigt tangent: rows and columns (xx, yy, zz, xy), the xy
            // column the factor of the engineering shear.
            static constexpr unsigned int index[4][2] = {{0, 0},
                                                         {1, 1},
                                                         {2, 2},
                                                         {0, 1}};
            for (unsigned int i = 0; i < 4; ++i)
              for (unsigned int j = 0; j < 4; ++j)
                equal = equal && tangent[4 * i + j] ==
                                   (y ? r.tangent[index[i][0]][index[i][1]]
                                                 [index[j][0]][index[j][1]] :
                                        -1.);
            same += equal;
          }
        deallog << "plane_strain_update() = update(), " << label << ": " << same
                << " of " << n << " (" << yielded << " yielded)" << std::endl;
      }
  }



  /** Mohr-Coulomb residual ((s1 - s3) + (s1 + s3) sin(phi)) / 2 - c cos(phi)
   * and whether sigma_zz is the intermediate principal stress, of an
   * in-plane stress with sigma_xz = sigma_yz = 0. */
  std::pair<double, bool>
  mohr_coulomb(const Sym2 &s, const double c, const double phi)
  {
    const double m  = (s[0][0] + s[1][1]) / 2.,
                 t  = std::hypot((s[0][0] - s[1][1]) / 2., s[0][1]);
    const double s1 = m + t, s3 = m - t;
    return {t + m * std::sin(phi) - c * std::cos(phi),
            s[2][2] <= s1 && s[2][2] >= s3};
  }



  void
  test_plane_strain_limits()
  {
    deallog.push("plane strain");
    {
      // von Mises in pure shear: |sigma_xy| = sigma_y / sqrt(3) = c_u.
      const double             sigma_y = 1e4;
      const VonMisesPlasticity model(E, nu, sigma_y, 0.);
      double                   worst = 0, other = 0;
      for (const double gamma : {2e-3, 1e-2, 1e-1, 1.})
        {
          ConstitutiveState state;
          state.elastic_strain[0][1] = gamma / 2.;
          const Sym2 s               = model.update(state).stress;
          worst =
            std::max(worst,
                     std::abs(std::abs(s[0][1]) / (sigma_y / std::sqrt(3.)) -
                              1.));
          other = std::max(
            {other, std::abs(s[0][0]), std::abs(s[1][1]), std::abs(s[2][2])});
        }
      deallog << "von Mises, pure shear gamma = 2e-3 .. 1: |sigma_xy| = "
              << "sigma_y / sqrt(3) to 1e-12: " << yes_no(worst < 1e-12)
              << ", other components zero: " << yes_no(other < 1e-9)
              << std::endl;

      // Isochoric plane-strain compression after a one-dimensional
      // (oedometric) preload that leaves sigma_zz away from the in-plane
      // mean: the flow drives sigma_zz to the mean and the in-plane Mohr
      // circle to the radius sigma_y / sqrt(3).
      ConstitutiveState state;
      for (unsigned int step = 0; step < 40; ++step)
        {
          state.elastic_strain[1][1] -= 1e-4;
          model.update(state);
        }
      Sym2 stress;
      for (unsigned int step = 0; step < 400; ++step)
        {
          state.elastic_strain[0][0] += 1e-4;
          state.elastic_strain[1][1] -= 1e-4;
          stress = model.update(state).stress;
        }
      const double m = (stress[0][0] + stress[1][1]) / 2.,
                   t = std::hypot((stress[0][0] - stress[1][1]) / 2.,
                                  stress[0][1]);
      deallog << "von Mises, isochoric plane-strain compression after an "
              << "oedometric preload: radius / (sigma_y / sqrt(3)) = "
              << t / (sigma_y / std::sqrt(3.))
              << ", (sigma_zz - mean) / sigma_y = "
              << filter_roundoff((stress[2][2] - m) / sigma_y, 1e-10)
              << std::endl;
    }
    {
      // Drucker-Prager in steady plane-strain flow along the dilatant
      // direction (volumetric / maximum shear rate = sin psi): the stress
      // meets Mohr-Coulomb for the plane-strain match; the outer and inner
      // cones' strengths there are printed against Mohr-Coulomb's (the outer
      // cone contains the Mohr-Coulomb pyramid: never below).
      const double c = 1e4;
      for (const std::array<double, 2> &angles :
           std::vector<std::array<double, 2>>{
             {30., 0.}, {30., 10.}, {30., 30.}, {40., 15.}})
        {
          const double phi = angles[0] * degree, psi = angles[1] * degree;
          std::string  line;
          for (const auto match : {DruckerPragerPlasticity::Match::plane_strain,
                                   DruckerPragerPlasticity::Match::outer,
                                   DruckerPragerPlasticity::Match::inner})
            {
              const DruckerPragerPlasticity model(E, nu, c, phi, psi, match);
              ConstitutiveState             state;
              state.elastic_strain = -5. * c / (3. * kappa) * unit();
              Sym2         stress, previous;
              double       change = 0;
              const double rate   = 2e-5;
              for (unsigned int step = 0; step < 3000; ++step)
                {
                  state.elastic_strain[0][0] += rate * (1. + std::sin(psi));
                  state.elastic_strain[1][1] -= rate * (1. - std::sin(psi));
                  previous = stress;
                  stress   = model.update(state).stress;
                }
              change                  = (stress - previous).norm() / c;
              const auto [res, inter] = mohr_coulomb(stress, c, phi);
              if (match == DruckerPragerPlasticity::Match::plane_strain)
                line += "plane strain match: |residual| / c < 1e-8: " +
                        std::string(yes_no(std::abs(res) < 1e-8 * c)) +
                        " (steady: " + yes_no(change < 1e-10) +
                        ", sigma_zz intermediate: " + yes_no(inter) + ")";
              else
                {
                  // Strength against Mohr-Coulomb's at the same mean
                  // in-plane stress m: residual / (c cos(phi) - m sin(phi)).
                  const double       m = (stress[0][0] + stress[1][1]) / 2.;
                  std::ostringstream percent;
                  percent << std::showpos << std::fixed << std::setprecision(1)
                          << 100. * res /
                               (c * std::cos(phi) - m * std::sin(phi))
                          << " %";
                  line +=
                    std::string(match == DruckerPragerPlasticity::Match::outer ?
                                  "; outer cone " :
                                  "; inner cone ") +
                    percent.str();
                }
            }
          deallog << "Drucker-Prager phi = " << angles[0]
                  << ", psi = " << angles[1] << ": " << line << std::endl;
        }
    }
    deallog.pop();
  }



  void
  test_tensor_functions(Random &random)
  {
    deallog.push("tensor functions");
    const auto   ln      = [](const double x) { return std::log(x); };
    const auto   dln     = [](const double x) { return 1. / x; };
    const auto   ex      = [](const double x) { return std::exp(x); };
    unsigned int inverse = 0, fd_ln = 0, fd_exp = 0, n = 0;
    for (unsigned int k = 0; k < 60; ++k)
      {
        // Left Cauchy-Green-like tensors: general, near the identity, with
        // two or three equal eigenvalues, nearly equal (gap 1e-4 .. 1e-12).
        const int          shape = k % 5;
        const Tensor<2, 3> R     = random_rotation(random);
        Sym2               b;
        if (shape == 0)
          {
            Tensor<2, 3> F;
            for (unsigned int i = 0; i < 3; ++i)
              for (unsigned int j = 0; j < 3; ++j)
                F[i][j] = (i == j ? 1. : 0.) + random(-0.5, 0.5);
            b = symmetrize(Tensor<2, 3>(F * transpose(F)));
          }
        else
          {
            const double a = random(0.3, 3.),
                         g = shape == 1 ? 0. :
                             shape == 2 ? std::pow(10., -4. - (k % 9)) :
                             shape == 3 ? random(0.3, 3.) - a :
                                          random(-1e-6, 1e-6);
            b[0][0] = shape == 4 ? 1. + random(-1e-6, 1e-6) : random(0.3, 3.);
            b[1][1] = shape == 4 ? 1. + g : a + g;
            b[2][2] = shape == 4 ? 1. : a;
            if (shape == 1)
              b[0][0] = a;
            b = rotate(b, R);
          }
        ++n;
        const auto [log_b, d_log_b] = isotropic_tensor_function(b, ln, dln);
        const auto [back, d_exp]    = isotropic_tensor_function(log_b, ex, ex);
        inverse += (back - b).norm() <= 1e-13 * b.norm();
        const double h = 1e-6 * b.norm();
        Sym4         fd_l, fd_e;
        for (unsigned int i = 0; i < 3; ++i)
          for (unsigned int j = i; j < 3; ++j)
            {
              Sym2 plus = b, minus = b;
              plus[i][j] += h;
              minus[i][j] -= h;
              const Sym2 dl = isotropic_tensor_function(plus, ln, dln).first -
                              isotropic_tensor_function(minus, ln, dln).first;
              Sym2 lp = log_b, lm = log_b;
              lp[i][j] += h;
              lm[i][j] -= h;
              const Sym2 de = isotropic_tensor_function(lp, ex, ex).first -
                              isotropic_tensor_function(lm, ex, ex).first;
              const double scale = (i == j ? 2. : 4.) * h;
              for (unsigned int p = 0; p < 3; ++p)
                for (unsigned int q = p; q < 3; ++q)
                  {
                    fd_l[p][q][i][j] = dl[p][q] / scale;
                    fd_e[p][q][i][j] = de[p][q] / scale;
                  }
            }
        fd_ln += (fd_l - d_log_b).norm() <= 1e-6 * d_log_b.norm();
        fd_exp += (fd_e - d_exp).norm() <= 1e-6 * d_exp.norm();
      }
    deallog << n << " symmetric positive definite tensors (general, near "
            << "the identity, equal and nearly equal eigenvalues): exp(ln b) "
            << "= b to 1e-13 " << inverse << ", d ln b / d b = central "
            << "differences to 1e-6 " << fd_ln << ", d exp / d x " << fd_exp
            << std::endl;
    deallog.pop();
  }



  void
  test_parameters()
  {
    deallog.push("parameters");
    const auto make = [](const std::string &text) {
      auto prm = std::make_unique<ParameterHandler>();
      LinearElasticMaterial::declare_parameters(*prm);
      prm->parse_input_from_string(text);
      return prm;
    };
    {
      // Every model registers itself; the selection offers exactly those.
      std::string names;
      for (const auto &name : constitutive_model_names())
        names += "'" + name + "' ";
      deallog << "registered: " << names << std::endl;
    }
    {
      auto prm   = make("");
      auto model = create_constitutive_model(*prm);
      deallog << "default: " << model->name()
              << ", linear: " << yes_no(model->is_linear()) << std::endl;
    }
    {
      auto        prm   = make("subsection Material\n"
                               "  set Young's modulus = 2e7\n"
                               "  set Poisson's ratio = 0.2\n"
                               "  set Constitutive model = von Mises\n"
                               "  subsection von Mises\n"
                               "    set Yield stress = 3e4\n"
                               "    set Hardening modulus = 1e5\n"
                               "  end\n"
                               "end\n");
      auto        model = create_constitutive_model(*prm);
      const auto &vm    = dynamic_cast<const VonMisesPlasticity &>(*model);
      deallog << model->name() << ": E " << vm.youngs_modulus() << ", nu "
              << vm.poissons_ratio() << ", yield stress " << vm.yield_stress()
              << ", hardening modulus " << vm.hardening_modulus()
              << ", linear: " << yes_no(model->is_linear()) << std::endl;
    }
    for (const std::string match : {"plane strain", "outer", "inner"})
      {
        auto        prm   = make("subsection Material\n"
                                 "  set Constitutive model = Drucker-Prager\n"
                                 "  subsection Drucker-Prager\n"
                                 "    set Cohesion = 5e3\n"
                                 "    set Friction angle = 30\n"
                                 "    set Dilation angle = 0\n"
                                 "    set Mohr-Coulomb match = " +
                        match +
                        "\n"
                                 "  end\n"
                                 "end\n");
        auto        model = create_constitutive_model(*prm);
        const auto &dp = dynamic_cast<const DruckerPragerPlasticity &>(*model);
        deallog << model->name() << " (phi 30, psi 0, " << match << "): eta "
                << dp.eta() << ", xi " << dp.xi() << ", eta_bar "
                << dp.eta_bar() << ", apex pressure " << dp.apex_pressure()
                << std::endl;
      }
    {
      // Plasticity in plane stress is refused, by create_constitutive_model()
      // and already by LinearElasticMaterial::parse_parameters().
      for (const std::string name : {"von Mises", "Drucker-Prager"})
        {
          const std::string text = "subsection Material\n"
                                   "  set Model = plane stress\n"
                                   "  set Constitutive model = " +
                                   name + "\nend\n";
          bool refused = false, clear = false, refused_by_material = false;
          try
            {
              auto prm = make(text);
              create_constitutive_model(*prm);
            }
          catch (const ExceptionBase &e)
            {
              // The message as bsmpm prints it, lines joined.
              std::ostringstream info;
              e.print_info(info);
              std::string text;
              for (const char ch : info.str())
                if (ch != '\n' &&
                    (ch != ' ' || text.empty() || text.back() != ' '))
                  text += ch;
                else if (ch == '\n' && !text.empty() && text.back() != ' ')
                  text += ' ';
              refused = true;
              clear =
                text.find("needs 'Model = plane strain'") != std::string::npos;
            }
          try
            {
              auto                  prm = make(text);
              LinearElasticMaterial material;
              material.parse_parameters(*prm);
            }
          catch (const std::exception &)
            {
              refused_by_material = true;
            }
          deallog << name << " in plane stress refused: " << yes_no(refused)
                  << ", message names plane strain: " << yes_no(clear)
                  << ", refused by LinearElasticMaterial too: "
                  << yes_no(refused_by_material) << std::endl;
        }
      auto prm = make("subsection Material\n"
                      "  set Model = plane stress\n"
                      "end\n");
      deallog << "linear elastic in plane stress accepted: "
              << yes_no(create_constitutive_model(*prm)->is_linear())
              << std::endl;
    }
    {
      bool refused = false;
      try
        {
          DruckerPragerPlasticity(E, nu, 1e4, 20. * degree, 25. * degree);
        }
      catch (const std::exception &)
        {
          refused = true;
        }
      deallog << "dilation angle above the friction angle refused: "
              << yes_no(refused) << std::endl;
    }
    deallog.pop();
  }
  /**
   * Small strain: the cell's internal force and tangent summed point by
   * point, sum_p w_p Bbar_p^T sigma_p and sum_p w_p Bbar_p^T D_p Bbar_p,
   * with the B-bar columns (xx, yy, zz, engineering xy) written out here:
   * what ConstitutiveUpdate::cell_system() sums through the cell's
   * moments. Returns the largest difference relative to the largest
   * entry of each.
   */
  double
  pointwise_difference(const ConstitutiveModel                          &model,
                       const Q1CellKernel                               &kernel,
                       const std::vector<ConstitutiveUpdate::PointView> &points,
                       const Q1CellKernel::LocalVector                  &d,
                       const bool                                        b_bar,
                       const bool                weights,
                       const FullMatrix<double> &K,
                       const Vector<double>     &f)
  {
    using Property = MaterialPoints::Property;
    // B-bar's mean volumetric strain: at the points' volume centroid.
    double v = 0, vs = 0, vt = 0;
    for (const auto &point : points)
      {
        const double volume = point.props[Property::volume];
        v += volume;
        vs += volume * point.st[0];
        vt += volume * point.st[1];
      }
    const Point<2>     centroid(vs / v, vt / v);
    FullMatrix<double> K_ref(8, 8);
    Vector<double>     f_ref(8);
    for (const auto &point : points)
      {
        const auto  &props = point.props;
        const double w =
          weights ? props[Property::weight] : props[Property::volume];
        if (props[Property::volume] == 0. || w == 0.)
          continue;
        std::array<Tensor<1, 4>, 8> B;
        Tensor<1, 4>                de;
        for (unsigned int i = 0; i < 8; ++i)
          {
            const Voigt  b     = kernel.strain_column(i, point.st);
            const Voigt  c     = kernel.strain_column(i, centroid);
            const double shift = b_bar ? (c[0] + c[1] - b[0] - b[1]) / 3 : 0.;
            B[i] = Tensor<1, 4>({b[0] + shift, b[1] + shift, shift, b[2]});
            de += d[i] * B[i];
          }
        ConstitutiveState state;
        state.elastic_strain[0][0] = props[Property::elastic_strain] + de[0];
        state.elastic_strain[1][1] =
          props[Property::elastic_strain + 1] + de[1];
        state.elastic_strain[2][2] =
          props[Property::elastic_strain + 2] + de[2];
        state.elastic_strain[0][1] =
          props[Property::elastic_strain + 3] + de[3] / 2;
        state.equivalent_plastic_strain     = props[Property::plastic_strain];
        const ConstitutiveResponse response = model.update(state);
        const unsigned int index[4][2]      = {{0, 0}, {1, 1}, {2, 2}, {0, 1}};
        Tensor<1, 4>       sigma;
        Tensor<2, 4>       D;
        for (unsigned int r = 0; r < 4; ++r)
          {
            sigma[r] = response.stress[index[r][0]][index[r][1]];
            for (unsigned int c = 0; c < 4; ++c)
              D[r][c] =
                response
                  .tangent[index[r][0]][index[r][1]][index[c][0]][index[c][1]];
          }
        for (unsigned int i = 0; i < 8; ++i)
          {
            f_ref[i] += w * (B[i] * sigma);
            for (unsigned int j = 0; j < 8; ++j)
              K_ref(i, j) += w * (B[i] * (D * B[j]));
          }
      }
    double largest_K = 0, largest_f = 0, worst_K = 0, worst_f = 0;
    for (unsigned int i = 0; i < 8; ++i)
      {
        largest_f = std::max(largest_f, std::abs(f_ref[i]));
        worst_f   = std::max(worst_f, std::abs(f[i] - f_ref[i]));
        for (unsigned int j = 0; j < 8; ++j)
          {
            largest_K = std::max(largest_K, std::abs(K_ref(i, j)));
            worst_K   = std::max(worst_K, std::abs(K(i, j) - K_ref(i, j)));
          }
      }
    return std::max(worst_K / largest_K, worst_f / largest_f);
  }



  /**
   * The Newton system of one cell (ConstitutiveUpdate::cell_system) against
   * central differences of its internal force, for small and finite strain,
   * elastic and plastic points, with the standard strain and B-bar / F-bar:
   * the consistent tangent of doc/newton.md and doc/finite-strain.md.
   */
  void
  test_cell_tangents(Random &random)
  {
    deallog.push("cell tangents");
    const FESystem<2>  fe(FE_Q<2>(1), 2);
    const Tensor<2, 3> C; // the kernel's stiffness is not used here
    const Q1CellKernel kernel(fe, Tensor<1, 2>({0.7, 0.5}), C);
    using Property   = MaterialPoints::Property;
    using Kinematics = ConstitutiveUpdate::Kinematics;

    const LinearElasticModel      elastic(E, nu);
    const VonMisesPlasticity      von_mises(E, nu, 2e4, 1e5);
    const DruckerPragerPlasticity drucker_prager(
      E,
      nu,
      1e4,
      30 * degree,
      10 * degree,
      DruckerPragerPlasticity::Match::plane_strain);
    const std::vector<std::pair<std::string, const ConstitutiveModel *>>
      models = {{"linear elastic", &elastic},
                {"von Mises", &von_mises},
                {"Drucker-Prager", &drucker_prager}};

    for (const auto kinematics :
         {Kinematics::small_strain, Kinematics::finite_strain})
      for (const auto &[name, model] : models)
        for (const bool b_bar : {false, true})
          {
            ConstitutiveUpdate update(*model, b_bar, kinematics);
            update.set_body_force(Tensor<1, 2>({3e3, -2e4}));
            double       worst = 0, asymmetry = 0, pointwise = 0;
            unsigned int yielded = 0, cases = 0;
            for (unsigned int c = 0; c < 20; ++c)
              {
                // Five points with a random state, one of them without
                // volume (a tracking point: ignored).
                std::vector<std::vector<double>> props(
                  5, std::vector<double>(Property::n_properties_inelastic));
                std::vector<ConstitutiveUpdate::PointView> points;
                for (unsigned int p = 0; p < props.size(); ++p)
                  {
                    auto &q             = props[p];
                    q[Property::volume] = p == 4 ? 0. : 0.05 + 0.02 * p;
                    q[Property::weight] = 0.8 * q[Property::volume];
                    // Compressed, so that the frictional model is not
                    // torn to its apex (zero tangent) by every increment.
                    for (unsigned int k = 0; k < 4; ++k)
                      q[Property::elastic_strain + k] =
                        (k < 3 ? -4e-3 : 0.) + 1e-3 * (random() - 0.5);
                    q[Property::plastic_strain] = 0.01 * random();
                    q[Property::det_F]          = 0.8 + 0.4 * random();
                    points.push_back(
                      {Point<2>(random(), random()),
                       ArrayView<const double>(q.data(), q.size())});
                  }
                // Increments from well inside the elastic range to large
                // deformation (finite strain: stretches of up to 30 %).
                const double scale =
                  (c % 4 + 1) *
                  (kinematics == Kinematics::small_strain ? 0.005 : 0.02);
                Q1CellKernel::LocalVector d;
                for (auto &x : d)
                  x = scale * (random() - 0.5);
                // Every other cell as a cut cell whose points' weights miss
                // its exact area and first moments: the moment completion
                // of cell_system() is part of the force and the tangent.
                std::vector<CellMoments> exact(1);
                const CellMoments       *cut = nullptr;
                update.use_cut_cell_quadrature(nullptr);
                if (c % 2 == 1)
                  {
                    double W = 0, Ws = 0, Wt = 0;
                    for (const auto &point : points)
                      if (point.props[Property::volume] > 0)
                        {
                          const double w = point.props[Property::weight];
                          W += w;
                          Ws += w * point.st[0];
                          Wt += w * point.st[1];
                        }
                    exact[0].v  = 1.3 * W;
                    exact[0].vs = exact[0].v * (Ws / W + 0.15);
                    exact[0].vt = exact[0].v * (Wt / W - 0.1);
                    cut         = &exact[0];
                    update.use_cut_cell_quadrature(&exact);
                  }
                FullMatrix<double> K(8, 8), K_plus(8, 8), K_minus(8, 8);
                Vector<double>     f(8), f_plus(8), f_minus(8);
                yielded += update.cell_system(kernel, points, d, K, f, cut) > 0;
                if (kinematics == Kinematics::small_strain)
                  pointwise = std::max(
                    pointwise,
                    pointwise_difference(
                      *model, kernel, points, d, b_bar, cut != nullptr, K, f));
                double largest = 0;
                for (unsigned int i = 0; i < 8; ++i)
                  for (unsigned int j = 0; j < 8; ++j)
                    largest = std::max(largest, std::abs(K(i, j)));
                const double e = 1e-7;
                for (unsigned int j = 0; j < 8; ++j)
                  {
                    auto plus = d, minus = d;
                    plus[j] += e;
                    minus[j] -= e;
                    update.cell_system(
                      kernel, points, plus, K_plus, f_plus, cut);
                    update.cell_system(
                      kernel, points, minus, K_minus, f_minus, cut);
                    for (unsigned int i = 0; i < 8; ++i)
                      worst =
                        std::max(worst,
                                 std::abs((f_plus[i] - f_minus[i]) / (2 * e) -
                                          K(i, j)) /
                                   largest);
                  }
                for (unsigned int i = 0; i < 8; ++i)
                  for (unsigned int j = 0; j < 8; ++j)
                    asymmetry = std::max(asymmetry,
                                         std::abs(K(i, j) - K(j, i)) / largest);
                ++cases;
              }
            deallog << (kinematics == Kinematics::small_strain ?
                          "small strain, " :
                          "finite strain, ")
                    << name << (b_bar ? ", B-bar" : ", standard") << ": "
                    << cases << " cells, " << yielded
                    << " with yielding points, tangent = central differences "
                       "(1e-6): "
                    << (worst <= 1e-6 ? "yes" : "NO")
                    << ", symmetric: " << (asymmetry <= 1e-10 ? "yes" : "no");
            if (kinematics == Kinematics::small_strain)
              deallog << ", = the points summed one by one (1e-12): "
                      << (pointwise <= 1e-12 ? "yes" : "NO");
            deallog << std::endl;
          }

    // The supports' stress in finite strain (first_piola_stress(): what
    // the band and Nitsche's terms load): A = dP/df against central
    // differences of P, and P : grad N_a times the weight against the
    // internal force that cell_system() gives one point in the same state.
    for (const auto &[name, model] : models)
      {
        ConstitutiveUpdate update(*model, false, Kinematics::finite_strain);
        double             worst_A = 0, worst_force = 0;
        for (unsigned int c = 0; c < 20; ++c)
          {
            std::vector<double> q(Property::n_properties_inelastic);
            q[Property::volume] = q[Property::weight] = 0.07;
            for (unsigned int k = 0; k < 4; ++k)
              q[Property::elastic_strain + k] =
                (k < 3 ? -4e-3 : 0.) + 1e-3 * (random() - 0.5);
            q[Property::plastic_strain] = 0.01 * random();
            q[Property::det_F]          = 0.8 + 0.4 * random();
            const ArrayView<const double> props(q.data(), q.size());
            const Point<2>                st(random(), random());
            Q1CellKernel::LocalVector     d;
            for (auto &x : d)
              x = 0.02 * (c % 4 + 1) * (random() - 0.5);
            const Tensor<2, 2> f =
              unit_symmetric_tensor<2>() + kernel.gradient(d, st);
            Tensor<2, 2> P, P_plus, P_minus;
            Tensor<4, 2> A, A_other;
            update.first_piola_stress(props, f, P, A);
            double largest = 0;
            for (unsigned int i = 0; i < 2; ++i)
              for (unsigned int j = 0; j < 2; ++j)
                for (unsigned int k = 0; k < 2; ++k)
                  for (unsigned int l = 0; l < 2; ++l)
                    largest = std::max(largest, std::abs(A[i][j][k][l]));
            const double e = 1e-7;
            for (unsigned int k = 0; k < 2; ++k)
              for (unsigned int l = 0; l < 2; ++l)
                {
                  Tensor<2, 2> plus = f, minus = f;
                  plus[k][l] += e;
                  minus[k][l] -= e;
                  update.first_piola_stress(props, plus, P_plus, A_other);
                  update.first_piola_stress(props, minus, P_minus, A_other);
                  for (unsigned int i = 0; i < 2; ++i)
                    for (unsigned int j = 0; j < 2; ++j)
                      worst_A =
                        std::max(worst_A,
                                 std::abs((P_plus[i][j] - P_minus[i][j]) /
                                            (2 * e) -
                                          A[i][j][k][l]) /
                                   largest);
                }
            FullMatrix<double>                         K(8, 8);
            Vector<double>                             force(8);
            std::vector<ConstitutiveUpdate::PointView> one = {{st, props}};
            update.use_cut_cell_quadrature(nullptr);
            update.cell_system(kernel, one, d, K, force);
            for (unsigned int a = 0; a < 8; ++a)
              worst_force =
                std::max(worst_force,
                         std::abs(
                           force[a] -
                           q[Property::volume] *
                             scalar_product(P, kernel.shape_gradient(a, st))) /
                           force.linfty_norm());
          }
        deallog << "finite strain, " << name
                << ", supports' stress: 20 states, dP/df = central "
                   "differences (1e-6): "
                << (worst_A <= 1e-6 ? "yes" : "NO")
                << ", w P : grad N = the point's internal force (1e-12): "
                << (worst_force <= 1e-12 ? "yes" : "NO") << std::endl;
      }
    deallog.pop();
  }


  /**
   * ConstitutiveModel::elastic_reach(): within it every trial strain
   * responds elastically with the stress D_e : e, and just beyond it,
   * along the gradient of the yield function in strain space, the step
   * yields (the reach is the distance to the yield surface for von Mises
   * and Drucker-Prager, not a loose bound).
   */
  void
  test_elastic_reach(Random &random)
  {
    const LinearElasticModel      elastic(E, nu);
    const VonMisesPlasticity      perfect(E, nu, 2e4, 0.);
    const VonMisesPlasticity      hardening(E, nu, 2e4, 2e5);
    const DruckerPragerPlasticity frictional(
      E, nu, 1e4, 30 * degree, 10 * degree);
    const DruckerPragerPlasticity cohesionless(
      E, nu, 0., 35 * degree, 5 * degree);
    const std::vector<std::pair<std::string, const ConstitutiveModel *>>
      models = {{"linear elastic", &elastic},
                {"von Mises, perfectly plastic", &perfect},
                {"von Mises, hardening", &hardening},
                {"Drucker-Prager phi 30", &frictional},
                {"Drucker-Prager c 0, phi 35", &cohesionless}};
    // A plane-strain strain tensor from (xx, yy, zz, xy).
    const auto plane =
      [](const double xx, const double yy, const double zz, const double xy) {
        SymmetricTensor<2, 3> e;
        e[0][0] = xx;
        e[1][1] = yy;
        e[2][2] = zz;
        e[0][1] = xy;
        return e;
      };
    for (const auto &[name, model] : models)
      {
        const SymmetricTensor<4, 3> D      = model->elastic_tangent();
        unsigned int                inside = 0, elastic_inside = 0, beyond = 0,
                     yields_beyond = 0, none = 0;
        for (unsigned int c = 0; c < 200; ++c)
          {
            ConstitutiveState state;
            // Compressed states round the yield surface (some of them
            // outside it: no reach).
            const double size    = 8e-3 * random();
            state.elastic_strain = plane(-2e-3 + size * (random() - 0.5),
                                         -2e-3 + size * (random() - 0.5),
                                         -2e-3 + size * (random() - 0.5),
                                         size * (random() - 0.5));
            state.equivalent_plastic_strain = 0.01 * random();
            const double reach              = model->elastic_reach(state);
            if (!(reach > 0))
              {
                ++none;
                continue;
              }
            // A random direction, scaled to just inside the reach.
            SymmetricTensor<2, 3> u = plane(random() - 0.5,
                                            random() - 0.5,
                                            random() - 0.5,
                                            random() - 0.5);
            u /= u.norm();
            const double length = std::isfinite(reach) ? 0.999 * reach : 1e-2;
            ConstitutiveState trial = state;
            trial.elastic_strain += length * u;
            std::array<double, 4>       stress;
            std::array<double, 16>      tangent;
            const SymmetricTensor<2, 3> expected = D * trial.elastic_strain;
            const SymmetricTensor<2, 3> e        = trial.elastic_strain;
            const bool                  yielded =
              model->plane_strain_update(trial, stress, tangent);
            const double difference = std::abs(stress[0] - expected[0][0]) +
                                      std::abs(stress[1] - expected[1][1]) +
                                      std::abs(stress[2] - expected[2][2]) +
                                      std::abs(stress[3] - expected[0][1]);
            ++inside;
            elastic_inside += !yielded &&
                              difference <= 1e-12 * expected.norm() &&
                              trial.elastic_strain == e;
            if (!std::isfinite(reach))
              continue;
            // Along the yield function's gradient in strain space,
            // sqrt(2) mu n + eta K 1 (eta = 0 for von Mises), a millionth
            // beyond the reach.
            const SymmetricTensor<2, 3> deviatoric =
              deviator(state.elastic_strain);
            if (deviatoric.norm() == 0.)
              continue;
            const auto *dp =
              dynamic_cast<const DruckerPragerPlasticity *>(model);
            const double          eta = dp != nullptr ? dp->eta() : 0.;
            SymmetricTensor<2, 3> g =
              std::sqrt(2.) * model->shear_modulus() * deviatoric /
                deviatoric.norm() +
              eta * model->bulk_modulus() * unit_symmetric_tensor<3>();
            g /= g.norm();
            ConstitutiveState outside = state;
            outside.elastic_strain += (1 + 1e-6) * reach * g;
            ++beyond;
            yields_beyond +=
              model->plane_strain_update(outside, stress, tangent);
          }
        deallog << "elastic reach, " << name << ": " << inside
                << " states with a reach (" << none
                << " without), a step within it elastic with D_e : e: "
                << (elastic_inside == inside ? "yes" : "NO");
        if (beyond > 0)
          deallog << "; 1e-6 beyond it along the yield function's gradient "
                     "yields: "
                  << yields_beyond << " of " << beyond;
        deallog << std::endl;
      }
  }



  /**
   * A cell whose points stay elastic (ConstitutiveUpdate::elastic_cell()
   * and elastic_cell_system()): its system from the points' moments equals
   * cell_system()'s point by point, and it is never taken where a point
   * yields.
   */
  void
  test_elastic_cells(Random &random)
  {
    const FESystem<2>  fe(FE_Q<2>(1), 2);
    const Tensor<2, 3> C;
    const Q1CellKernel kernel(fe, Tensor<1, 2>({0.7, 0.5}), C);
    using Property = MaterialPoints::Property;
    const LinearElasticModel      elastic(E, nu);
    const VonMisesPlasticity      von_mises(E, nu, 2e4, 1e5);
    const DruckerPragerPlasticity drucker_prager(
      E, nu, 1e4, 30 * degree, 10 * degree);
    const std::vector<std::pair<std::string, const ConstitutiveModel *>>
      models = {{"linear elastic", &elastic},
                {"von Mises", &von_mises},
                {"Drucker-Prager", &drucker_prager}};
    for (const auto &[name, model] : models)
      for (const bool b_bar : {false, true})
        {
          ConstitutiveUpdate update(
            *model, b_bar, ConstitutiveUpdate::Kinematics::small_strain);
          unsigned int taken = 0, cells = 0, wrong = 0;
          double       worst = 0;
          for (unsigned int c = 0; c < 40; ++c)
            {
              // Six points, one a tracking point without volume; every
              // other cell integrates with fitted weights.
              std::vector<std::vector<double>> props(
                6, std::vector<double>(Property::n_properties_inelastic));
              std::vector<ConstitutiveUpdate::PointView> points;
              for (unsigned int p = 0; p < props.size(); ++p)
                {
                  auto &q             = props[p];
                  q[Property::volume] = p == 5 ? 0. : 0.05 + 0.02 * p;
                  q[Property::weight] = (0.5 + random()) * q[Property::volume];
                  for (unsigned int k = 0; k < 4; ++k)
                    q[Property::elastic_strain + k] =
                      (k < 3 ? -2e-3 : 0.) + 4e-4 * (random() - 0.5);
                  q[Property::plastic_strain] = 0.01 * random();
                  points.push_back(
                    {Point<2>(0.2 + 0.6 * random(), 0.1 + 0.5 * random()),
                     ArrayView<const double>(q.data(), q.size())});
                }
              std::vector<CellMoments> exact(1);
              update.use_cut_cell_quadrature(c % 2 == 1 ? &exact : nullptr);
              // Increments from far inside the elastic range to yielding.
              const double              scale = 1e-5 * std::pow(4., c % 5);
              Q1CellKernel::LocalVector d;
              for (auto &x : d)
                x = scale * (random() - 0.5);
              FullMatrix<double> K(8, 8), K_moments(8, 8);
              Vector<double>     f(8), f_moments(8);
              const unsigned int yielded =
                update.cell_system(kernel, points, d, K, f);
              const ConstitutiveUpdate::ElasticCell cell =
                update.elastic_cell(points);
              ++cells;
              if (!update.elastic_cell_system(
                    kernel, cell, d, K_moments, f_moments))
                continue;
              ++taken;
              wrong += yielded > 0;
              const double largest_K = K.linfty_norm(),
                           largest_f = f.linfty_norm();
              for (unsigned int i = 0; i < 8; ++i)
                {
                  worst =
                    std::max(worst, std::abs(f[i] - f_moments[i]) / largest_f);
                  for (unsigned int j = 0; j < 8; ++j)
                    worst =
                      std::max(worst,
                               std::abs(K(i, j) - K_moments(i, j)) / largest_K);
                }
            }
          deallog << "elastic cells, " << name
                  << (b_bar ? ", B-bar" : ", standard") << ": " << taken
                  << " of " << cells
                  << " cells from moments, = cell_system() (1e-12): "
                  << (worst <= 1e-12 ? "yes" : "NO")
                  << ", taken where a point yields: " << wrong << std::endl;
        }
  }

} // namespace



int
main()
{
  initlog();
  deallog << std::setprecision(6);
  Random random(12);

  test_parameters();
  test_linear_elastic(random);

  deallog.push("returns");
  test_von_mises(0., "von Mises, perfectly plastic", random);
  test_von_mises(2e5, "von Mises, hardening H = E/50", random);
  using Match = DruckerPragerPlasticity::Match;
  test_drucker_prager(
    DruckerPragerPlasticity(E, nu, 1e4, 30. * degree, 10. * degree),
    "Drucker-Prager phi 30, psi 10, plane strain",
    random);
  test_drucker_prager(DruckerPragerPlasticity(
                        E, nu, 1e4, 30. * degree, 30. * degree, Match::outer),
                      "Drucker-Prager phi 30, psi 30, outer",
                      random);
  test_drucker_prager(
    DruckerPragerPlasticity(E, nu, 5e3, 20. * degree, 0., Match::inner),
    "Drucker-Prager phi 20, psi 0, inner",
    random);
  test_drucker_prager(
    DruckerPragerPlasticity(E, nu, 0., 35. * degree, 5. * degree),
    "Drucker-Prager c 0, phi 35, psi 5, plane strain",
    random);
  test_drucker_prager(DruckerPragerPlasticity(E, nu, 1e4, 0., 0.),
                      "Drucker-Prager phi 0, plane strain",
                      random);
  test_frictionless_drucker_prager_is_von_mises(random);
  deallog.pop();

  test_plane_strain_limits();
  test_tensor_functions(random);
  test_cell_tangents(random);
  // Its own random numbers: the checks above keep theirs.
  Random plane_strain_random(13);
  deallog.push("returns");
  test_plane_strain_update(plane_strain_random);
  deallog.pop();
  Random reach_random(14);
  deallog.push("returns");
  test_elastic_reach(reach_random);
  deallog.pop();
  deallog.push("cell tangents");
  test_elastic_cells(reach_random);
  deallog.pop();
}
