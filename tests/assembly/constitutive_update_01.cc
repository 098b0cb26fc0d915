// ConstitutiveUpdate (doc/newton.md, doc/finite-strain.md): the Newton
// system of one cell of points (cell_system()) against central differences
// of its internal force, for small and finite strain, standard strain and
// B-bar / F-bar, elastic and yielding points of every model, with and
// without a cut cell's moment completion; in small strain against the
// points summed one by one; the supports' stress in finite strain
// (first_piola_stress()) against central differences and the internal
// force; and the elastic cells (elastic_cell_system() from the points'
// moments) against cell_system(). Only counts and yes/no are printed.

#include <deal.II/base/numbers.h>
#include <deal.II/base/symmetric_tensor.h>

#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>

#include <bsmpm/assembly/constitutive_update.h>
#include <bsmpm/materials/constitutive_model.h>
#include <bsmpm/materials/drucker_prager_plasticity.h>
#include <bsmpm/materials/linear_elastic_model.h>
#include <bsmpm/materials/von_mises_plasticity.h>

#include <array>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

// tests.h uses deallog unqualified: the using directive must come first.
using namespace dealii;

#include "../tests.h"

#include "../unit_test.h"

using namespace bsmpm;

namespace
{
  const double E      = 1e7;
  const double nu     = 0.3;
  const double degree = numbers::PI / 180.;



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
            // A body force of (3e3, -2e4) per unit volume: density 2e3.
            update.set_densities({2e3});
            update.set_body_force(1., Tensor<1, 2>({1.5, -10.}));
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



BSMPM_UNIT_TEST("assembly/constitutive_update_01")
{
  initlog();
  deallog << std::setprecision(6);
  // The points' states and increments: Random(12) after its first 21508
  // numbers, Random(14) after its first 9096 (the counts of the reference
  // output hold for these draws).
  Random random(12);
  random.discard(21508);
  test_cell_tangents(random);
  Random elastic_random(14);
  elastic_random.discard(9096);
  deallog.push("cell tangents");
  test_elastic_cells(elastic_random);
  deallog.pop();
}
