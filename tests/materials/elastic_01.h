// Elasticity (doc/materials.md): the linear elastic model against
// LinearElasticMaterial's stiffness in plane strain and plane stress (the
// stress, the tangent, central differences); ln and exp of symmetric
// tensors with their derivatives (isotropic_tensor_function(), the Hencky
// strain of finite strain); the registry of constitutive models and the
// default; plane_strain_update() against update() bit for bit, and
// elastic_reach() (infinite). Only counts, yes/no and rounded figures are
// printed.
#ifndef bsmpm_tests_elastic_01_h
#define bsmpm_tests_elastic_01_h

#include "constitutive_checks.h"

namespace elastic_01
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
} // namespace elastic_01

#endif
