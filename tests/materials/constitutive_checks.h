// The checks that the unit tests of the constitutive models share
// (elastic_01.h, von_mises_01.h, drucker_prager_01.h): the material
// constants, trial strains built backwards from a known return, and the
// checks every model undergoes: update() against the known return,
// plane_strain_update() against update(), and elastic_reach().
#ifndef bsmpm_tests_constitutive_checks_h
#define bsmpm_tests_constitutive_checks_h

#include <deal.II/base/numbers.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/symmetric_tensor.h>

#include <bsmpm/materials/constitutive_model.h>
#include <bsmpm/materials/drucker_prager_plasticity.h>
#include <bsmpm/materials/linear_elastic_model.h>
#include <bsmpm/materials/material.h>
#include <bsmpm/materials/von_mises_plasticity.h>

#include <array>
#include <cmath>
#include <memory>
#include <sstream>
#include <string>
#include <utility>
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

  inline Sym2
  unit()
  {
    return unit_symmetric_tensor<3>();
  }

  /** Elastic strain of a stress. */
  inline Sym2
  compliance(const Sym2 &sigma)
  {
    return trace(sigma) / (9. * kappa) * unit() + deviator(sigma) / (2. * mu);
  }

  inline Tensor<2, 3>
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

  inline Sym2
  rotate(const Sym2 &x, const Tensor<2, 3> &R)
  {
    return symmetrize(Tensor<2, 3>(R * Tensor<2, 3>(x) * transpose(R)));
  }

  inline Sym4
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
  inline Sym2
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
  inline Sym4
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
  inline void
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

  inline void
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



  /** Models with the label that the output gives each. */
  using NamedModels =
    std::vector<std::pair<std::string, const ConstitutiveModel *>>;



  /**
   * ConstitutiveModel::plane_strain_update(), the return of the Newton
   * system's points, against update() on plane-strain trial strains
   * (xz = yz = 0) from well inside the elastic range to far beyond yield:
   * the same yield flag, stress, returned state and, where the step
   * yields, the (xx, yy, zz, xy) block of the tangent, bit for bit (the
   * Newton iterations must not change by its use). 1000 random numbers
   * per model.
   */
  inline void
  check_plane_strain_update(const NamedModels &models, Random &random)
  {
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



  /**
   * ConstitutiveModel::elastic_reach(): within it every trial strain
   * responds elastically with the stress D_e : e, and just beyond it,
   * along the gradient of the yield function in strain space, the step
   * yields (the reach is the distance to the yield surface for von Mises
   * and Drucker-Prager, not a loose bound).
   */
  inline void
  check_elastic_reach(const NamedModels &models, Random &random)
  {
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



  /** The parameters of the material section given by @p text. */
  inline std::unique_ptr<ParameterHandler>
  material_parameters(const std::string &text)
  {
    auto prm = std::make_unique<ParameterHandler>();
    LinearElasticMaterial::declare_parameters(*prm);
    prm->parse_input_from_string(text);
    return prm;
  }



  /**
   * Plasticity in plane stress is refused, by create_constitutive_model()
   * and already by LinearElasticMaterial::parse_parameters(): @p name is the
   * model's name in the parameter file.
   */
  inline void
  check_plane_stress_refused(const std::string &name)
  {
    const std::string text = "subsection Material\n"
                             "  set Model = plane stress\n"
                             "  set Constitutive model = " +
                             name + "\nend\n";
    bool refused = false, clear = false, refused_by_material = false;
    try
      {
        auto prm = material_parameters(text);
        create_constitutive_model(*prm);
      }
    catch (const ExceptionBase &e)
      {
        // The message as bsmpm prints it, lines joined.
        std::ostringstream info;
        e.print_info(info);
        std::string text;
        for (const char ch : info.str())
          if (ch != '\n' && (ch != ' ' || text.empty() || text.back() != ' '))
            text += ch;
          else if (ch == '\n' && !text.empty() && text.back() != ' ')
            text += ' ';
        refused = true;
        clear = text.find("needs 'Model = plane strain'") != std::string::npos;
      }
    try
      {
        auto                  prm = material_parameters(text);
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
} // namespace

#endif
