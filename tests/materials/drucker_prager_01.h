// Drucker-Prager plasticity (doc/materials.md): plane-strain, outer and
// inner matches of Mohr-Coulomb; associated and non-associated; with and
// without cohesion; without friction.
//
// Trial strains are built backwards from a known answer: a stress on the
// yield cone (or inside it, or the apex) and a plastic multiplier give the
// trial elastic strain whose return must be that stress. Categories:
// elastic, plastic (small to very large steps), near the apex, beyond the
// apex, equal and nearly equal principal values. For every trial strain
// the checks of constitutive_checks.h (recovered stress, yield condition,
// D^e : elastic strain, flow rule, tangent against central differences,
// isotropy). Then: without friction it is von Mises (sigma_y = sqrt(3) c);
// in steady plane-strain flow the plane-strain match meets Mohr-Coulomb;
// the parameters; plane_strain_update() against update() bit for bit, and
// elastic_reach(). Only counts, yes/no and rounded figures are printed.
#ifndef bsmpm_tests_drucker_prager_01_h
#define bsmpm_tests_drucker_prager_01_h

#include "constitutive_checks.h"

namespace drucker_prager_01
{
  namespace
  {
    void
    test_drucker_prager(const DruckerPragerPlasticity &model,
                        const std::string             &label,
                        Random                        &random)
    {
      const double eta = model.eta(), xi = model.xi(),
                   eta_bar = model.eta_bar(), c = model.cohesion();
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
          const int    shape   = category == 5 ? 1 + (k / 6) % 3 : 0;
          const double gap     = shape == 3 ? std::pow(10., -4. - (k % 7)) : 0.;
          const Tensor<2, 3> R = (k / 6) % 2 == 0 && shape > 0 ?
                                   unit_symmetric_tensor<3>() :
                                   random_rotation(random);
          const Sym2         n = unit_deviator(random, shape, R, gap);

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
              const Sym2 d_eps_p = v / 3. * unit() + dv * n;
              cs.expected_stress = p_apex * unit();
              cs.trial.elastic_strain =
                compliance(cs.expected_stress) + d_eps_p;
              d_bar = std::sqrt(2. / 3.) * d_eps_p.norm();
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
              cs.trial.elastic_strain =
                compliance(cs.expected_stress) + d_eps_p;
              d_bar = std::sqrt(2. / 3.) * d_eps_p.norm();
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
            std::abs(a.equivalent_plastic_strain -
                     b.equivalent_plastic_strain) <=
              1e-12 * b.equivalent_plastic_strain;
        }
      deallog
        << "Drucker-Prager (phi = psi = 0) = von Mises (sigma_y = sqrt(3) "
        << "c): " << same << " of " << n << " (" << yielded
        << " yielded): stress, elastic strain, eq. plastic strain, tangent"
        << std::endl;
    }



    std::pair<double, bool>
    mohr_coulomb(const Sym2 &s, const double c, const double phi)
    {
      const double m  = (s[0][0] + s[1][1]) / 2.,
                   t  = std::hypot((s[0][0] - s[1][1]) / 2., s[0][1]);
      const double s1 = m + t, s3 = m - t;
      return {t + m * std::sin(phi) - c * std::cos(phi),
              s[2][2] <= s1 && s[2][2] >= s3};
    }



    /** Drucker-Prager's strength in plane-strain flow against
     * Mohr-Coulomb's. */
    void
    test_plane_strain_limits()
    {
      {
        // Drucker-Prager in steady plane-strain flow along the dilatant
        // direction (volumetric / maximum shear rate = sin psi): the stress
        // meets Mohr-Coulomb for the plane-strain match; the outer and inner
        // cones' strengths there are printed against Mohr-Coulomb's (the outer
        // cone contains the Mohr-Coulomb pyramid: never below).
        const double c = 1e4;
        for (const std::array<double, 2> &angles :
             std::vector<std::array<double, 2>>{
               {{30., 0.}}, {{30., 10.}}, {{30., 30.}}, {{40., 15.}}})
          {
            const double phi = angles[0] * degree, psi = angles[1] * degree;
            std::string  line;
            for (const auto match :
                 {DruckerPragerPlasticity::Match::plane_strain,
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
                    percent
                      << std::showpos << std::fixed << std::setprecision(1)
                      << 100. * res / (c * std::cos(phi) - m * std::sin(phi))
                      << " %";
                    line += std::string(
                              match == DruckerPragerPlasticity::Match::outer ?
                                "; outer cone " :
                                "; inner cone ") +
                            percent.str();
                  }
              }
            deallog << "Drucker-Prager phi = " << angles[0]
                    << ", psi = " << angles[1] << ": " << line << std::endl;
          }
      }
    }
  } // namespace



  void
  run()
  {
    deallog << std::setprecision(6);

    deallog.push("parameters");
    for (const std::string match : {"plane strain", "outer", "inner"})
      {
        auto prm =
          material_parameters("subsection Material\n"
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
    check_plane_stress_refused("Drucker-Prager");
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

    // The trial strains: Random(12) after its first 4900 numbers (the
    // counts of the reference output hold for these draws).
    Random random(12);
    random.discard(4900);
    deallog.push("returns");
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

    deallog.push("plane strain");
    test_plane_strain_limits();
    deallog.pop();

    deallog.push("returns");
    {
      const DruckerPragerPlasticity dp(E, nu, 1e4, 30. * degree, 10. * degree),
        dp_cohesionless(E, nu, 0., 35. * degree, 5. * degree);
      Random plane_strain_random(13);
      // Past the 1000 numbers of each of the two von Mises models.
      plane_strain_random.discard(2000);
      check_plane_strain_update({{"Drucker-Prager phi 30, psi 10", &dp},
                                 {"Drucker-Prager c 0, phi 35, psi 5",
                                  &dp_cohesionless}},
                                plane_strain_random);
    }
    {
      const DruckerPragerPlasticity frictional(
        E, nu, 1e4, 30 * degree, 10 * degree);
      const DruckerPragerPlasticity cohesionless(
        E, nu, 0., 35 * degree, 5 * degree);
      Random reach_random(14);
      reach_random.discard(5272);
      check_elastic_reach({{"Drucker-Prager phi 30", &frictional},
                           {"Drucker-Prager c 0, phi 35", &cohesionless}},
                          reach_random);
    }
    deallog.pop();
  }
} // namespace drucker_prager_01

#endif
