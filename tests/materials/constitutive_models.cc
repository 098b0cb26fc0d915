// The constitutive models (doc/materials.md), each in its own part: the
// linear elastic model with the tensor functions of finite strain and the
// registry, von Mises and Drucker-Prager with their returns, tangents and
// limits. The checks they share are in constitutive_checks.h.

// tests.h uses deallog unqualified: the using directive must come first.
using namespace dealii;

#include "../tests.h"

#include "constitutive_checks.h"

using namespace bsmpm;

// Elasticity (doc/materials.md): the linear elastic model against
// LinearElasticMaterial's stiffness in plane strain and plane stress (the
// stress, the tangent, central differences); ln and exp of symmetric
// tensors with their derivatives (isotropic_tensor_function(), the Hencky
// strain of finite strain); the registry of constitutive models and the
// default; plane_strain_update() against update() bit for bit, and
// elastic_reach() (infinite). Only counts, yes/no and rounded figures are
// printed.
namespace elastic_checks
{
  namespace
  {
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
              // The caller's zz: zero in plane strain, anything in plane
              // stress.
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
              fd_ok += (fd - response.tangent).norm() <=
                       1e-8 * response.tangent.norm();
            }
          deallog << (plane_stress ? "plane stress" : "plane strain") << ": "
                  << n << " random strains, stress = LinearElasticMaterial's "
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
          const auto [back, d_exp] = isotropic_tensor_function(log_b, ex, ex);
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
  } // namespace



  void
  run()
  {
    deallog << std::setprecision(6);

    deallog.push("parameters");
    {
      // Every model registers itself; the selection offers exactly those.
      std::string names;
      for (const auto &name : constitutive_model_names())
        names += "'" + name + "' ";
      deallog << "registered: " << names << std::endl;
    }
    {
      auto prm   = material_parameters("");
      auto model = create_constitutive_model(*prm);
      deallog << "default: " << model->name()
              << ", linear: " << yes_no(model->is_linear()) << std::endl;
    }
    {
      auto prm = material_parameters("subsection Material\n"
                                     "  set Model = plane stress\n"
                                     "end\n");
      deallog << "linear elastic in plane stress accepted: "
              << yes_no(create_constitutive_model(*prm)->is_linear())
              << std::endl;
    }
    deallog.pop();

    // The random strains and tensors: Random(12) from its start and after
    // its first 21100 numbers (the counts of the reference output hold for
    // these draws).
    Random random(12);
    test_linear_elastic(random);
    Random tensor_random(12);
    tensor_random.discard(21100);
    test_tensor_functions(tensor_random);

    deallog.push("returns");
    const LinearElasticModel elastic(E, nu);
    Random                   plane_strain_random(13);
    // Past the 1000 numbers of each of the four plastic models.
    plane_strain_random.discard(4000);
    check_plane_strain_update({{"linear elastic", &elastic}},
                              plane_strain_random);
    Random reach_random(14);
    check_elastic_reach({{"linear elastic", &elastic}}, reach_random);
    deallog.pop();
  }
} // namespace elastic_checks



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
namespace von_mises_checks
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
} // namespace von_mises_checks



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
namespace drucker_prager_checks
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
               {30., 0.}, {30., 10.}, {30., 30.}, {40., 15.}})
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
} // namespace drucker_prager_checks



int
main()
{
  initlog();
  elastic_checks::run();
  deallog << std::setprecision(8);
  von_mises_checks::run();
  deallog << std::setprecision(8);
  drucker_prager_checks::run();
}
