// Checks of the closed-form solutions of exact_solution.h at many points:
// - compatibility with the material: C eps(u) = sigma, with eps from
//   fourth-order central differences of displacement();
// - equilibrium: div sigma + b = 0, by central differences of stress();
// - the boundary conditions of each problem;
// - the pressure that doubles the inner radius of the paper's cylinder;
// - Kirsch: the textbook sigma_yy (used by the code) against the paper's
//   eq. 45 as printed, and against the textbook polar form.

#include <deal.II/base/numbers.h>
#include <deal.II/base/parameter_handler.h>

#include <deal.II/lac/vector.h>

#include <bsmpm/materials/material.h>
#include <bsmpm/verification/exact_solution.h>

#include <algorithm>
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

// tests.h uses deallog unqualified: the using directive must come first.
using namespace dealii;

#include "../tests.h"

#include "../unit_test.h"

using namespace bsmpm;

namespace
{
  Voigt
  to_voigt(const SymmetricTensor<2, 2> &s)
  {
    return Voigt({s[0][0], s[1][1], s[0][1]});
  }

  using StressFunction = std::function<SymmetricTensor<2, 2>(const Point<2> &)>;

  // Fourth-order central difference of f along direction d at X.
  template <typename T>
  T
  derivative(const std::function<T(const Point<2> &)> &f,
             const Point<2>                           &X,
             const unsigned int                        d,
             const double                              h)
  {
    Tensor<1, 2> e;
    e[d] = h;
    return (f(X - 2 * e) - 8. * f(X - e) + 8. * f(X + e) - f(X + 2 * e)) /
           (12. * h);
  }

  // Voigt strain (engineering shear) of the displacement at X.
  Voigt
  strain(const ExactSolution &solution, const Point<2> &X, const double h)
  {
    const std::function<Tensor<1, 2>(const Point<2> &)> u =
      [&solution](const Point<2> &Y) { return solution.displacement(Y); };
    const Tensor<1, 2> du_dx = derivative(u, X, 0, h);
    const Tensor<1, 2> du_dy = derivative(u, X, 1, h);
    return Voigt({du_dx[0], du_dy[1], du_dy[0] + du_dx[1]});
  }

  // div sigma at X.
  Tensor<1, 2>
  divergence(const StressFunction &sigma, const Point<2> &X, const double h)
  {
    const std::function<Tensor<2, 2>(const Point<2> &)> s =
      [&sigma](const Point<2> &Y) { return Tensor<2, 2>(sigma(Y)); };
    const Tensor<2, 2> ds_dx = derivative(s, X, 0, h);
    const Tensor<2, 2> ds_dy = derivative(s, X, 1, h);
    return Tensor<1, 2>({ds_dx[0][0] + ds_dy[0][1], ds_dx[1][0] + ds_dy[1][1]});
  }

  // Largest |C eps(u) - sigma| and |div sigma + b| * length over the points,
  // both relative to stress_scale.
  std::pair<double, double>
  field_residuals(const ExactSolution         &solution,
                  const StressFunction        &sigma,
                  const LinearElasticMaterial &material,
                  const Tensor<1, 2>          &body_force,
                  const std::vector<Point<2>> &points,
                  const double                 length,
                  const double                 stress_scale)
  {
    const double h             = 1e-3 * length;
    double       compatibility = 0, equilibrium = 0;
    for (const auto &X : points)
      {
        const Voigt difference =
          material.stiffness() * strain(solution, X, h) - to_voigt(sigma(X));
        for (unsigned int r = 0; r < 3; ++r)
          compatibility = std::max(compatibility, std::abs(difference[r]));
        equilibrium =
          std::max(equilibrium,
                   (divergence(sigma, X, h) + body_force).norm() * length);
      }
    return {compatibility / stress_scale, equilibrium / stress_scale};
  }

  // Prints the field checks of a solution.
  void
  check_fields(const std::string           &name,
               const ExactSolution         &solution,
               const LinearElasticMaterial &material,
               const Tensor<1, 2>          &body_force,
               const std::vector<Point<2>> &points,
               const double                 length,
               const double                 stress_scale)
  {
    const auto residuals = field_residuals(
      solution,
      [&solution](const Point<2> &X) { return solution.stress(X); },
      material,
      body_force,
      points,
      length,
      stress_scale);
    deallog << name << ": C eps(u) = sigma at " << points.size()
            << " points (relative 1e-6): "
            << (residuals.first < 1e-6 ? "pass" : "FAIL") << std::endl;
    deallog << name << ": div sigma + b = 0 (relative 1e-6): "
            << (residuals.second < 1e-6 ? "pass" : "FAIL") << std::endl;

    // The Function<2> interface returns the same five numbers.
    double mismatch = 0;
    for (const auto &X : points)
      {
        Vector<double> values(5);
        solution.vector_value(X, values);
        const auto u = solution.displacement(X);
        const auto s = solution.stress(X);
        mismatch     = std::max({mismatch,
                                 std::abs(values[0] - u[0]),
                                 std::abs(values[1] - u[1]),
                                 std::abs(values[2] - s[0][0]),
                                 std::abs(values[3] - s[1][1]),
                                 std::abs(values[4] - s[0][1]),
                                 std::abs(solution.value(X, 4) - s[0][1])});
      }
    deallog << name << ": vector_value() = (u, v, sxx, syy, sxy): "
            << yes_no(mismatch == 0) << std::endl;
  }

  // Normal and tangential traction on a surface with unit normal n.
  std::pair<double, double>
  traction(const SymmetricTensor<2, 2> &sigma, const Tensor<1, 2> &n)
  {
    const Tensor<1, 2> t = sigma * n;
    return {t * n, t[0] * n[1] - t[1] * n[0]};
  }

  Tensor<1, 2>
  radial(const double beta)
  {
    return Tensor<1, 2>({std::cos(beta), std::sin(beta)});
  }



  void
  check_column()
  {
    deallog.push("column");
    const LinearElasticMaterial material(
      1e6, 0.25, LinearElasticMaterial::Model::plane_strain, 2000.);
    const double                b_y = -2000. * 9.81, base = 0.5, height = 2.;
    const Tensor<1, 2>          body_force({0., b_y});
    const ColumnUnderSelfWeight solution(material, b_y, base, height);

    Random                random;
    std::vector<Point<2>> points(200);
    for (auto &X : points)
      X = Point<2>(random(-1, 1), base + random(0, height));
    const double stress_scale = std::abs(b_y) * height;
    check_fields(
      "column", solution, material, body_force, points, height, stress_scale);

    double top_stress = 0, base_displacement = 0, shear = 0, lateral = 0;
    for (const double x : {-1., 0., 0.3, 1.})
      {
        top_stress =
          std::max(top_stress,
                   std::abs(solution.stress(Point<2>(x, base + height))[1][1]));
        base_displacement =
          std::max(base_displacement,
                   solution.displacement(Point<2>(x, base)).norm());
      }
    for (const auto &X : points)
      {
        shear   = std::max(shear, std::abs(solution.stress(X)[0][1]));
        lateral = std::max(lateral, std::abs(solution.displacement(X)[0]));
      }
    deallog << "sigma_yy(top) = 0: "
            << yes_no(top_stress < 1e-12 * stress_scale)
            << ", u(base) = 0: " << yes_no(base_displacement == 0)
            << ", sigma_xy = 0 and u_x = 0 everywhere: "
            << yes_no(shear == 0 && lateral == 0) << std::endl;
    deallog << "sigma_yy(base) / (rho g H) = "
            << solution.stress(Point<2>(0, base))[1][1] / (b_y * height)
            << ", u_y(top) E_c / (rho g H^2 / 2) = "
            << solution.displacement(Point<2>(0, base + height))[1] *
                 material.constrained_modulus() / (b_y * height * height / 2)
            << std::endl;
    deallog.pop();
  }



  void
  check_constant_stress()
  {
    deallog.push("constant stress");
    const LinearElasticMaterial material(
      1e7, 0.3, LinearElasticMaterial::Model::plane_strain);
    const Voigt           frame_stress({-2e3, -6e3, 1e3});
    const Point<2>        fixed_point(0.3, 0.2);
    Random                random;
    std::vector<Point<2>> points(100);
    for (auto &X : points)
      X = Point<2>(random(-1, 2), random(-1, 2));

    for (const double degrees : {0., 30., 60.})
      {
        const double         angle = degrees * numbers::PI / 180.;
        const ConstantStress solution(material,
                                      frame_stress,
                                      angle,
                                      fixed_point);
        const std::string    name = "angle " + std::to_string(int(degrees));
        check_fields(name, solution, material, Tensor<1, 2>(), points, 1., 6e3);

        // The stress seen in the rotated frame is the one given.
        const Tensor<1, 2> n1({std::cos(angle), std::sin(angle)});
        const Tensor<1, 2> n2({-std::sin(angle), std::cos(angle)});
        const auto         sigma = solution.stress(Point<2>(1, 1));
        const Voigt        in_frame(
          {n1 * (sigma * n1), n2 * (sigma * n2), n1 * (sigma * n2)});
        deallog << name << ": stress in the rotated frame is the given one: "
                << yes_no((in_frame - frame_stress).norm() < 1e-12 * 6e3)
                << std::endl;

        // Zero displacement at the fixed point and no rigid rotation.
        double                                              rotation = 0;
        const std::function<Tensor<1, 2>(const Point<2> &)> u =
          [&solution](const Point<2> &Y) { return solution.displacement(Y); };
        for (const auto &X : points)
          rotation = std::max(rotation,
                              std::abs(derivative(u, X, 1, 1e-3)[0] -
                                       derivative(u, X, 0, 1e-3)[1]));
        deallog << name << ": u(fixed point) = 0: "
                << yes_no(solution.displacement(fixed_point).norm() == 0)
                << ", no rigid rotation: "
                << yes_no(rotation < 1e-12 * 6e3 / material.youngs_modulus())
                << std::endl;
      }
    deallog.pop();
  }



  void
  check_lame()
  {
    deallog.push("lame");
    const double   a = 1., b = 5.;
    const Point<2> center(0.5, -0.25);
    for (const auto model : {LinearElasticMaterial::Model::plane_strain,
                             LinearElasticMaterial::Model::plane_stress})
      {
        const std::string name =
          model == LinearElasticMaterial::Model::plane_strain ? "plane strain" :
                                                                "plane stress";
        const LinearElasticMaterial material(1e6, 0.25, model);
        // The pressure that doubles the inner radius (u_r(r_i) = r_i).
        const LameCylinder solution(material, center, a, b, 0., a);
        const double       p = solution.pressure();
        deallog << name
                << ": pressure that doubles r_i = 1 (r_o = 5, E = 1 MPa, "
                   "nu = 0.25): "
                << p / 1e6 << " MPa" << std::endl;
        deallog << name
                << ": u_r(r_i) / r_i = " << solution.radial_displacement(a) / a
                << ", u_r(r_o) / r_i = " << solution.radial_displacement(b) / a
                << std::endl;

        Random                random;
        std::vector<Point<2>> points(200);
        for (auto &X : points)
          X = center + random(a, b) * radial(random(0, 2 * numbers::PI));
        check_fields(name, solution, material, Tensor<1, 2>(), points, a, p);

        // Boundary conditions, and u radial with |u| = u_r.
        double inner = 0, outer = 0, direction = 0;
        for (unsigned int k = 0; k < 72; ++k)
          {
            const double       beta = 2 * numbers::PI * (k + 0.25) / 72;
            const Tensor<1, 2> n    = radial(beta);
            const auto t_in  = traction(solution.stress(center + a * n), n);
            const auto t_out = traction(solution.stress(center + b * n), n);
            inner            = std::max(
              {inner, std::abs(t_in.first + p), std::abs(t_in.second)});
            outer =
              std::max({outer, std::abs(t_out.first), std::abs(t_out.second)});
            const Tensor<1, 2> u = solution.displacement(center + 2.5 * n);
            direction =
              std::max(direction,
                       (u - solution.radial_displacement(2.5) * n).norm());
          }
        deallog << name << ": sigma_rr(r_i) = -p, tau(r_i) = 0: "
                << yes_no(inner < 1e-12 * p)
                << ", sigma_rr(r_o) = 0, tau(r_o) = 0: "
                << yes_no(outer < 1e-12 * p)
                << ", u = u_r(r) e_r: " << yes_no(direction < 1e-14 * a)
                << std::endl;
      }

    // The same solution through the parameter file.
    {
      ParameterHandler prm;
      ExactSolution::declare_parameters(prm);
      prm.parse_input_from_string("subsection Exact solution\n"
                                  "  set Name = lame cylinder\n"
                                  "  subsection Lame cylinder\n"
                                  "    set Inner radius = 1\n"
                                  "    set Outer radius = 5\n"
                                  "    set Inner displacement = 1\n"
                                  "  end\n"
                                  "end\n");
      const LinearElasticMaterial material(
        1e6, 0.25, LinearElasticMaterial::Model::plane_strain);
      const auto solution =
        ExactSolution::create(prm, material, Tensor<1, 2>());
      const auto *lame = dynamic_cast<const LameCylinder *>(solution.get());
      deallog << "created from parameters: "
              << (lame != nullptr ? "lame cylinder" : "WRONG TYPE")
              << ", pressure " << (lame ? lame->pressure() / 1e6 : 0.) << " MPa"
              << std::endl;
    }
    deallog.pop();
  }



  // Kirsch's sigma_yy as printed in the paper's eq. 45 (+ cos 4 beta inside
  // the bracket) and the polar textbook form, for comparison.
  SymmetricTensor<2, 2>
  kirsch_paper_eq45(const KirschPlate &solution,
                    const Point<2>    &X,
                    const Point<2>    &center,
                    const double       a,
                    const double       S)
  {
    SymmetricTensor<2, 2> sigma = solution.stress(X);
    const Tensor<1, 2>    d     = X - center;
    const double          beta  = std::atan2(d[1], d[0]);
    const double          q2    = a * a / d.norm_square();
    // Paper: -S q2 (cos(2b)/2 + cos(4b)); textbook: -S q2 (cos(2b)/2 -
    // cos(4b)). The difference is -2 S q2 cos(4b).
    sigma[1][1] += -2 * S * q2 * std::cos(4 * beta);
    return sigma;
  }

  void
  check_kirsch()
  {
    deallog.push("kirsch");
    const double   a = 0.5, S = 1e7;
    const Point<2> center(0.25, -0.5);
    for (const auto model : {LinearElasticMaterial::Model::plane_stress,
                             LinearElasticMaterial::Model::plane_strain})
      {
        const std::string name =
          model == LinearElasticMaterial::Model::plane_strain ? "plane strain" :
                                                                "plane stress";
        const LinearElasticMaterial material(1e7, 0.2, model);
        const KirschPlate           solution(material, center, a, S);

        Random                random;
        std::vector<Point<2>> points(300);
        for (auto &X : points)
          X = center + random(a, 6 * a) * radial(random(0, 2 * numbers::PI));
        check_fields(name, solution, material, Tensor<1, 2>(), points, a, S);

        // Traction-free hole, and the polar textbook form.
        double hole = 0, polar = 0;
        for (unsigned int k = 0; k < 360; ++k)
          {
            const double       beta = 2 * numbers::PI * (k + 0.5) / 360;
            const Tensor<1, 2> n    = radial(beta);
            const Tensor<1, 2> t    = solution.stress(center + a * n) * n;
            hole                    = std::max(hole, t.norm());

            for (const double r : {a, 1.7 * a, 4 * a})
              {
                const Tensor<1, 2> m({-n[1], n[0]});
                const auto         sigma = solution.stress(center + r * n);
                const double       q2 = a * a / (r * r), q4 = q2 * q2;
                const double c2 = std::cos(2 * beta), s2 = std::sin(2 * beta);
                const double srr =
                  S / 2 * (1 - q2) + S / 2 * (1 - 4 * q2 + 3 * q4) * c2;
                const double stt = S / 2 * (1 + q2) - S / 2 * (1 + 3 * q4) * c2;
                const double srt = -S / 2 * (1 + 2 * q2 - 3 * q4) * s2;
                polar            = std::max({polar,
                                             std::abs(n * (sigma * n) - srr),
                                             std::abs(m * (sigma * m) - stt),
                                             std::abs(n * (sigma * m) - srt)});
              }
          }
        deallog << name << ": traction-free hole (|sigma n| < 1e-12 S): "
                << yes_no(hole < 1e-12 * S) << std::endl;
        deallog << name << ": equals the polar textbook form (1e-12 S): "
                << yes_no(polar < 1e-12 * S) << std::endl;

        // Far field: sigma -> (S, 0, 0), error of order (a/r)^2.
        double far = 0;
        for (unsigned int k = 0; k < 36; ++k)
          {
            const auto sigma = solution.stress(
              center + 1e4 * a * radial(2 * numbers::PI * k / 36));
            far =
              std::max(far, (to_voigt(sigma) - Voigt({S, 0., 0.})).norm() / S);
          }
        deallog << name << ": sigma at r = 1e4 r_i equals (S, 0, 0) to 1e-7 S: "
                << yes_no(far < 1e-7) << std::endl;
        deallog << name << ": stress concentration sigma_xx(0, r_i) / S = "
                << solution.stress(center + Tensor<1, 2>({0., a}))[0][0] / S
                << ", sigma_xx(r_i, 0) / S = "
                << filter_roundoff(
                     solution.stress(center + Tensor<1, 2>({a, 0.}))[0][0] / S)
                << ", sigma_yy(r_i, 0) / S = "
                << solution.stress(center + Tensor<1, 2>({a, 0.}))[1][1] / S
                << std::endl;

        if (model == LinearElasticMaterial::Model::plane_stress)
          {
            // The paper's eq. 45 as printed.
            double paper_hole = 0;
            for (unsigned int k = 0; k < 360; ++k)
              {
                const Tensor<1, 2> n =
                  radial(2 * numbers::PI * (k + 0.5) / 360);
                paper_hole = std::max(
                  paper_hole,
                  (kirsch_paper_eq45(solution, center + a * n, center, a, S) *
                   n)
                      .norm() /
                    S);
              }
            const auto residuals = field_residuals(
              solution,
              [&](const Point<2> &X) {
                return kirsch_paper_eq45(solution, X, center, a, S);
              },
              material,
              Tensor<1, 2>(),
              points,
              a,
              S);
            deallog << "paper's eq. 45 as printed: traction-free hole: "
                    << yes_no(paper_hole < 1e-12)
                    << ", max |sigma n| / S on the hole = "
                    << std::round(paper_hole * 1000) / 1000 << std::endl;
            deallog << "paper's eq. 45 as printed: C eps(u) = sigma: "
                    << (residuals.first < 1e-6 ? "pass" : "fail")
                    << ", div sigma = 0: "
                    << (residuals.second < 1e-6 ? "pass" : "fail") << std::endl;
          }
      }
    deallog.pop();
  }
} // namespace



BSMPM_UNIT_TEST("verification/exact_solution")
{
  initlog();
  check_column();
  check_constant_stress();
  check_lame();
  check_kirsch();
  deallog << "OK" << std::endl;
}
