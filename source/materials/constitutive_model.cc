#include <bsmpm/materials/constitutive_model.h>
#include <bsmpm/materials/material.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

namespace bsmpm
{
  ConstitutiveModel::ConstitutiveModel(const double youngs_modulus,
                                       const double poissons_ratio)
    : E(youngs_modulus)
    , nu(poissons_ratio)
    , mu(youngs_modulus / (2. * (1. + poissons_ratio)))
    , kappa(youngs_modulus / (3. * (1. - 2. * poissons_ratio)))
  {
    AssertThrow(std::isfinite(E) && E > 0.,
                ExcMessage("Material: Young's modulus must be positive, got " +
                           std::to_string(E) + "."));
    AssertThrow(std::isfinite(nu) && nu > -1. && nu < 0.5,
                ExcMessage("Material: Poisson's ratio must lie in (-1, 0.5), "
                           "got " +
                           std::to_string(nu) + "."));
    stiffness_3d = kappa * outer_product(unit_symmetric_tensor<3>(),
                                         unit_symmetric_tensor<3>()) +
                   2. * mu * deviator_tensor<3>();
  }



  void
  ConstitutiveModel::add_deviatoric_terms(SymmetricTensor<4, 3>       &t,
                                          const double                 a,
                                          const double                 b,
                                          const SymmetricTensor<2, 3> &n)
  {
    // On the stored entries: deal.II keeps a symmetric 3x3 tensor as
    // (00, 11, 22, 01, 02, 12) and a rank-4 one as the 6x6 table of these
    // pairs, T_ijkl at (ij, kl). The chained t[i][j][k][l] looks each
    // entry up by its indices, which made this a tenth of the plastic
    // footing's Newton system; the values are the same.
    for (unsigned int c = 0; c < 6; ++c)
      for (unsigned int d = 0; d < 6; ++d)
        t.access_raw_entry(6 * c + d) +=
          a * deviatoric_projector(c, d) +
          b * n.access_raw_entry(c) * n.access_raw_entry(d);
  }



  bool
  ConstitutiveModel::plane_strain_update(ConstitutiveState      &state,
                                         std::array<double, 4>  &stress,
                                         std::array<double, 16> &tangent) const
  {
    const ConstitutiveResponse response = update(state);
    plane_strain_response(response, stress, tangent);
    return response.yielded;
  }



  double
  ConstitutiveModel::elastic_reach(const ConstitutiveState &) const
  {
    return 0;
  }



  void
  ConstitutiveModel::plane_strain_response(const ConstitutiveResponse &response,
                                           std::array<double, 4>      &stress,
                                           std::array<double, 16>     &tangent)
  {
    stress = {{response.stress[0][0],
               response.stress[1][1],
               response.stress[2][2],
               response.stress[0][1]}};
    if (!response.yielded)
      return;
    // deal.II stores the rank-4 tangent as the 6x6 table of the pairs
    // (00, 11, 22, 01, 02, 12): the first four are (xx, yy, zz, xy), and
    // T_ij01 is the factor of the engineering shear 2 eps_01 (see
    // ConstitutiveUpdate::voigt_tangent()).
    for (unsigned int r = 0; r < 4; ++r)
      for (unsigned int c = 0; c < 4; ++c)
        tangent[4 * r + c] = response.tangent.access_raw_entry(6 * r + c);
  }



  double
  ConstitutiveModel::yield_function(const SymmetricTensor<2, 3> &,
                                    const double) const
  {
    return -std::numeric_limits<double>::infinity();
  }



  SymmetricTensor<4, 3>
  ConstitutiveModel::elastic_tangent() const
  {
    return isotropic_stiffness();
  }



  std::unique_ptr<ConstitutiveModel>
  ConstitutiveModel::with_reduced_strength(const double) const
  {
    AssertThrow(false,
                ExcMessage("Strength reduction: the constitutive model '" +
                           name() +
                           "' has no strength to reduce; use a plastic "
                           "model (von Mises, Drucker-Prager)."));
    return nullptr;
  }



  bool
  ConstitutiveModel::is_linear() const
  {
    return false;
  }



  SymmetricTensor<2, 3>
  ConstitutiveModel::elastic_stress(
    const SymmetricTensor<2, 3> &elastic_strain) const
  {
    return kappa * trace(elastic_strain) * unit_symmetric_tensor<3>() +
           2. * mu * deviator(elastic_strain);
  }



  SpectralDecomposition::SpectralDecomposition(const SymmetricTensor<2, 3> &x)
  {
    auto pairs = eigenvectors(x, SymmetricTensorEigenvectorMethod::jacobi);
    std::sort(pairs.begin(), pairs.end(), [](const auto &a, const auto &b) {
      return a.first > b.first;
    });
    for (unsigned int a = 0; a < 3; ++a)
      {
        values[a]  = pairs[a].first;
        vectors[a] = pairs[a].second;
      }
  }



  SymmetricTensor<2, 3>
  SpectralDecomposition::assemble(const std::array<double, 3> &y) const
  {
    SymmetricTensor<2, 3> result;
    for (unsigned int a = 0; a < 3; ++a)
      result += y[a] * symmetrize(outer_product(vectors[a], vectors[a]));
    return result;
  }



  SymmetricTensor<4, 3>
  SpectralDecomposition::assemble_tangent(
    const Tensor<2, 3>          &dy_dx,
    const std::array<double, 3> &rho) const
  {
    // Components of M_A = n_A n_A and W_AB = (n_A n_B + n_B n_A) / sqrt(2)
    // for the six index pairs; the entries are written directly (deal.II's
    // outer_product of symmetric tensors costs ~ 0.4 us each).
    const unsigned int ij[6][2] = {
      {0, 0}, {1, 1}, {2, 2}, {0, 1}, {0, 2}, {1, 2}};
    const unsigned int pair[3][2] = {{0, 1}, {0, 2}, {1, 2}};
    double             m[3][6], dm[3][6], w[3][6];
    for (unsigned int a = 0; a < 3; ++a)
      for (unsigned int c = 0; c < 6; ++c)
        m[a][c] = vectors[a][ij[c][0]] * vectors[a][ij[c][1]];
    for (unsigned int k = 0; k < 3; ++k)
      {
        const Tensor<1, 3> &n_a = vectors[pair[k][0]];
        const Tensor<1, 3> &n_b = vectors[pair[k][1]];
        for (unsigned int c = 0; c < 6; ++c)
          w[k][c] =
            (n_a[ij[c][0]] * n_b[ij[c][1]] + n_b[ij[c][0]] * n_a[ij[c][1]]) /
            std::sqrt(2.);
      }
    // sum_AB D_AB M_A (x) M_B = sum_A M_A (x) (sum_B D_AB M_B)
    for (unsigned int a = 0; a < 3; ++a)
      for (unsigned int c = 0; c < 6; ++c)
        dm[a][c] =
          dy_dx[a][0] * m[0][c] + dy_dx[a][1] * m[1][c] + dy_dx[a][2] * m[2][c];
    SymmetricTensor<4, 3> result;
    for (unsigned int c = 0; c < 6; ++c)
      for (unsigned int d = 0; d < 6; ++d)
        {
          double value = 0;
          for (unsigned int a = 0; a < 3; ++a)
            value += m[a][c] * dm[a][d] + rho[a] * w[a][c] * w[a][d];
          result[ij[c][0]][ij[c][1]][ij[d][0]][ij[d][1]] = value;
        }
    return result;
  }



  double
  SpectralDecomposition::spin_modulus(const double x_a,
                                      const double x_b,
                                      const double y_a,
                                      const double y_b,
                                      const double limit_a,
                                      const double limit_b)
  {
    // Round-off of the quotient ~ eps / gap, error of the limit ~ gap^2:
    // they balance at gap ~ eps^(1/3) (relative).
    static const double tolerance =
      std::cbrt(std::numeric_limits<double>::epsilon());
    const double gap = x_a - x_b;
    if (std::abs(gap) > tolerance * std::max(std::abs(x_a), std::abs(x_b)))
      return (y_a - y_b) / gap;
    return 0.5 * (limit_a + limit_b);
  }



  std::pair<SymmetricTensor<2, 3>, SymmetricTensor<4, 3>>
  isotropic_tensor_function(const SymmetricTensor<2, 3>         &x,
                            const std::function<double(double)> &f,
                            const std::function<double(double)> &df)
  {
    const SpectralDecomposition spectral(x);
    std::array<double, 3>       y, dy;
    Tensor<2, 3>                dy_dx;
    for (unsigned int a = 0; a < 3; ++a)
      {
        y[a]        = f(spectral.values[a]);
        dy[a]       = df(spectral.values[a]);
        dy_dx[a][a] = dy[a];
      }
    const unsigned int    pair[3][2] = {{0, 1}, {0, 2}, {1, 2}};
    std::array<double, 3> rho;
    for (unsigned int k = 0; k < 3; ++k)
      {
        const unsigned int a = pair[k][0], b = pair[k][1];
        rho[k] = SpectralDecomposition::spin_modulus(
          spectral.values[a], spectral.values[b], y[a], y[b], dy[a], dy[b]);
      }
    return {spectral.assemble(y), spectral.assemble_tangent(dy_dx, rho)};
  }



  namespace
  {
    /** The registered models by name. A function-local static: the
     * registrations run during static initialisation, in an order that
     * the language leaves open. */
    std::map<std::string, ConstitutiveModelEntry> &
    registry()
    {
      static std::map<std::string, ConstitutiveModelEntry> models;
      return models;
    }

    const ConstitutiveModelEntry &
    registered_model(const std::string &name)
    {
      const auto model = registry().find(name);
      AssertThrow(model != registry().end(),
                  ExcMessage("Material: no constitutive model is called '" +
                             name + "'."));
      return model->second;
    }
  } // namespace



  bool
  register_constitutive_model(const std::string            &name,
                              const ConstitutiveModelEntry &entry)
  {
    Assert(registry().count(name) == 0,
           ExcMessage("Two constitutive models are called '" + name + "'."));
    registry()[name] = entry;
    return true;
  }



  std::vector<std::string>
  constitutive_model_names()
  {
    std::vector<std::string> names;
    for (const auto &[name, entry] : registry())
      names.push_back(name);
    return names;
  }



  void
  declare_constitutive_parameters(ParameterHandler &prm)
  {
    std::string selection, documentation;
    const auto  names = constitutive_model_names();
    for (unsigned int i = 0; i < names.size(); ++i)
      {
        const auto &entry = registry().at(names[i]);
        selection += (i == 0 ? "" : "|") + names[i];
        documentation += std::string(i == 0               ? "" :
                                     i + 1 < names.size() ? ", " :
                                                            " or ") +
                         "'" + names[i] + "' (" + entry.description +
                         (entry.plane_stress ? "" : "; plane strain only") +
                         ")";
      }
    prm.enter_subsection("Material");
    prm.declare_entry("Constitutive model",
                      "linear elastic",
                      Patterns::Selection(selection),
                      "Stress-strain law of the body (doc/materials.md): " +
                        documentation + ".");
    for (const auto &name : names)
      registry().at(name).declare_parameters(prm);
    prm.leave_subsection();
  }



  void
  check_constitutive_model_compatibility(const std::string &name,
                                         const bool         plane_stress)
  {
    AssertThrow(!plane_stress || registered_model(name).plane_stress,
                ExcMessage("Material: the constitutive model '" + name +
                           "' needs 'Model = plane strain'; plasticity in "
                           "plane stress is not implemented (the return map "
                           "would have to keep sigma_zz = 0)."));
  }



  std::unique_ptr<ConstitutiveModel>
  create_constitutive_model(ParameterHandler &prm)
  {
    LinearElasticMaterial elastic;
    elastic.parse_parameters(prm);
    const bool plane_stress =
      elastic.model() == LinearElasticMaterial::Model::plane_stress;

    prm.enter_subsection("Material");
    const std::string                  name = prm.get("Constitutive model");
    std::unique_ptr<ConstitutiveModel> model;
    try
      {
        check_constitutive_model_compatibility(name, plane_stress);
        model = registered_model(name).create(prm,
                                              {elastic.youngs_modulus(),
                                               elastic.poissons_ratio(),
                                               plane_stress});
      }
    catch (...)
      {
        prm.leave_subsection();
        throw;
      }
    prm.leave_subsection();
    return model;
  }
} // namespace bsmpm
