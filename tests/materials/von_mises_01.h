// von Mises plasticity, perfectly plastic and with linear hardening
// (doc/materials.md).
//
// Trial strains are built backwards from a known answer: a stress on the
// yield surface (or inside it) and a plastic multiplier give the trial
// elastic strain whose return must be that stress. Categories: elastic,
// plastic (small to very large steps), equal and nearly equal principal
// values. For every trial strain the checks of constitutive_checks.h: the
// stress and equivalent plastic strain recovered, the yield condition
// after the return, stress = D^e : returned elastic strain, the flow rule,
// the tangent against central differences of update() (1e-6), isotropy.
// Then the parameters, the plane-strain limits (pure shear at sigma_y /
// sqrt(3); an isochoric compression after an oedometric preload ends on
// the radius sigma_y / sqrt(3) with sigma_zz at the in-plane mean),
// plane_strain_update() against update() bit for bit, and elastic_reach().
// Only counts, yes/no and rounded figures are printed.
#ifndef bsmpm_tests_von_mises_01_h
#define bsmpm_tests_von_mises_01_h

#include "constitutive_checks.h"

namespace von_mises_01
{
  namespace
  {
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
          const int    category = k % 4; // elastic, plastic, large, equal
          const int    shape    = category == 3 ? 1 + (k / 4) % 3 : 0;
          const double gap     = shape == 3 ? std::pow(10., -4. - (k % 7)) : 0.;
          const Tensor<2, 3> R = (k / 4) % 2 == 0 && shape > 0 ?
                                   unit_symmetric_tensor<3>() :
                                   random_rotation(random);
          const Sym2         n = unit_deviator(random, shape, R, gap);
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
          c.expected_stress = p * unit() + std::sqrt(2. / 3.) * q * n;
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



    /** The plane-strain limits of von Mises. */
    void
    test_plane_strain_limits()
    {
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
    }
  } // namespace



  void
  run()
  {
    deallog << std::setprecision(6);

    deallog.push("parameters");
    {
      auto        prm   = material_parameters("subsection Material\n"
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
    check_plane_stress_refused("von Mises");
    deallog.pop();

    // The trial strains: Random(12) after its first 700 numbers (the
    // counts of the reference output hold for these draws).
    Random random(12);
    random.discard(700);
    deallog.push("returns");
    test_von_mises(0., "von Mises, perfectly plastic", random);
    test_von_mises(2e5, "von Mises, hardening H = E/50", random);
    deallog.pop();

    deallog.push("plane strain");
    test_plane_strain_limits();
    deallog.pop();

    deallog.push("returns");
    {
      const VonMisesPlasticity perfect(E, nu, 1e4, 0.),
        hardening(E, nu, 1e4, 2e5);
      Random plane_strain_random(13);
      check_plane_strain_update({{"von Mises, perfectly plastic", &perfect},
                                 {"von Mises, hardening", &hardening}},
                                plane_strain_random);
    }
    {
      const VonMisesPlasticity perfect(E, nu, 2e4, 0.),
        hardening(E, nu, 2e4, 2e5);
      Random reach_random(14);
      reach_random.discard(2000);
      check_elastic_reach({{"von Mises, perfectly plastic", &perfect},
                           {"von Mises, hardening", &hardening}},
                          reach_random);
    }
    deallog.pop();
  }
} // namespace von_mises_01

#endif
