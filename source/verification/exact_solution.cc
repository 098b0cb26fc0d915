#include <deal.II/base/numbers.h>

#include <bsmpm/base/parameter_tools.h>
#include <bsmpm/verification/exact_solution.h>

#include <boost/math/special_functions/lambert_w.hpp>

#include <array>
#include <cmath>
#include <sstream>

namespace bsmpm
{
  namespace
  {
    /** Voigt stress (engineering shear strain) to a symmetric tensor. */
    SymmetricTensor<2, 2>
    tensor_from_voigt(const Voigt &v, const bool engineering_shear)
    {
      SymmetricTensor<2, 2> t;
      t[0][0] = v[0];
      t[1][1] = v[1];
      t[0][1] = engineering_shear ? v[2] / 2 : v[2];
      return t;
    }
  } // namespace



  double
  ExactSolution::value(const Point<2> &X, const unsigned int component) const
  {
    Vector<double> values(5);
    vector_value(X, values);
    return values[component];
  }



  void
  ExactSolution::vector_value(const Point<2> &X, Vector<double> &values) const
  {
    const auto u     = displacement(X);
    const auto sigma = stress(X);
    values[0]        = u[0];
    values[1]        = u[1];
    values[2]        = sigma[0][0];
    values[3]        = sigma[1][1];
    values[4]        = sigma[0][1];
  }



  void
  ExactSolution::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Exact solution");
    prm.declare_entry("Name",
                      "none",
                      Patterns::Selection("none|column under self weight|"
                                          "constant stress|lame cylinder|"
                                          "kirsch plate"),
                      "Closed-form solution to measure the errors against "
                      "(none: no error evaluation).");
    prm.enter_subsection("Column");
    prm.declare_entry("Base", "0", Patterns::Double(), "y of the fixed base.");
    prm.declare_entry("Height",
                      "1",
                      Patterns::Double(0.),
                      "Height of the column above its base.");
    prm.leave_subsection();
    prm.enter_subsection("Constant stress");
    prm.declare_entry("Stress",
                      "0, 0, 0",
                      Patterns::List(Patterns::Double(), 3, 3, ","),
                      "sigma_xx, sigma_yy, sigma_xy in Pa, in the frame "
                      "rotated by Angle.");
    prm.declare_entry("Angle",
                      "0",
                      Patterns::Double(),
                      "Counter-clockwise rotation of the stress frame, in "
                      "degrees, in [-360, 360].");
    prm.declare_entry("Fixed point",
                      "0, 0",
                      ParameterTools::point_pattern(),
                      "Initial position where the displacement is zero.");
    prm.leave_subsection();
    prm.enter_subsection("Lame cylinder");
    prm.declare_entry("Center",
                      "0, 0",
                      ParameterTools::point_pattern(),
                      "Axis of the cylinder.");
    prm.declare_entry("Inner radius", "1", Patterns::Double(0.), "r_i in m.");
    prm.declare_entry("Outer radius", "5", Patterns::Double(0.), "r_o in m.");
    prm.declare_entry("Inner pressure",
                      "0",
                      Patterns::Double(),
                      "Pressure on the inner surface, in Pa. Ignored when "
                      "'Inner displacement' is positive.");
    prm.declare_entry("Inner displacement",
                      "0",
                      Patterns::Double(0.),
                      "If positive: the pressure is the one whose Lame "
                      "solution moves the inner radius outwards by this "
                      "much (in m).");
    prm.leave_subsection();
    prm.enter_subsection("Kirsch plate");
    prm.declare_entry("Center",
                      "0, 0",
                      ParameterTools::point_pattern(),
                      "Centre of the hole.");
    prm.declare_entry("Hole radius", "0.5", Patterns::Double(0.), "r_i in m.");
    prm.declare_entry("Far-field stress",
                      "1e7",
                      Patterns::Double(),
                      "Tension S along x far from the hole, in Pa.");
    prm.leave_subsection();
    prm.leave_subsection();
  }



  std::unique_ptr<ExactSolution>
  ExactSolution::create(ParameterHandler            &prm,
                        const LinearElasticMaterial &material,
                        const Tensor<1, 2>          &gravity,
                        const bool                   finite_strain)
  {
    std::unique_ptr<ExactSolution> solution;
    prm.enter_subsection("Exact solution");
    const std::string name = prm.get("Name");
    if (name == "column under self weight")
      {
        prm.enter_subsection("Column");
        solution =
          std::make_unique<ColumnUnderSelfWeight>(material,
                                                  material.density() *
                                                    gravity[1],
                                                  prm.get_double("Base"),
                                                  prm.get_double("Height"),
                                                  finite_strain);
        prm.leave_subsection();
      }
    else if (name == "constant stress")
      {
        prm.enter_subsection("Constant stress");
        const auto   s     = ParameterTools::get_doubles(prm, "Stress");
        const double angle = prm.get_double("Angle");
        ParameterTools::require_finite(angle,
                                       "Exact solution/Constant stress/Angle");
        std::ostringstream value;
        value << angle;
        AssertThrow(std::abs(angle) <= 360,
                    ExcMessage(
                      "Exact solution/Constant stress/Angle: " + value.str() +
                      " degrees is more than a full turn; give the "
                      "counter-clockwise rotation of the stress frame "
                      "in degrees in [-360, 360]."));
        solution = std::make_unique<ConstantStress>(
          material,
          Voigt({s[0], s[1], s[2]}),
          angle * numbers::PI / 180.,
          ParameterTools::get_point(prm, "Fixed point"));
        prm.leave_subsection();
      }
    else if (name == "lame cylinder")
      {
        prm.enter_subsection("Lame cylinder");
        solution =
          std::make_unique<LameCylinder>(material,
                                         ParameterTools::get_point(prm,
                                                                   "Center"),
                                         prm.get_double("Inner radius"),
                                         prm.get_double("Outer radius"),
                                         prm.get_double("Inner pressure"),
                                         prm.get_double("Inner displacement"));
        prm.leave_subsection();
      }
    else if (name == "kirsch plate")
      {
        prm.enter_subsection("Kirsch plate");
        solution =
          std::make_unique<KirschPlate>(material,
                                        ParameterTools::get_point(prm,
                                                                  "Center"),
                                        prm.get_double("Hole radius"),
                                        prm.get_double("Far-field stress"));
        prm.leave_subsection();
      }
    prm.leave_subsection();
    return solution;
  }



  // ---------------------------------------------------------------------

  ColumnUnderSelfWeight::ColumnUnderSelfWeight(
    const LinearElasticMaterial &material,
    const double                 unit_weight_y,
    const double                 base,
    const double                 height,
    const bool                   finite_strain)
    : b_y(unit_weight_y)
    , base(base)
    , height(height)
    , constrained_modulus(material.constrained_modulus())
    , lateral_ratio(material.stiffness()[0][1] / material.stiffness()[1][1])
    , finite_strain(finite_strain)
  {
    AssertThrow(height > 0,
                ExcMessage("Exact solution: the column height must be "
                           "positive."));
  }



  Tensor<1, 2>
  ColumnUnderSelfWeight::displacement(const Point<2> &X) const
  {
    // sigma_yy' = -b_y with sigma_yy(H) = 0, and eps_yy = sigma_yy / E_c.
    const double y = X[1] - base;
    if (!finite_strain || b_y == 0.)
      return Tensor<1, 2>(
        {0., b_y * (height * y - y * y / 2) / constrained_modulus});
    // Finite strain: the weight above the initial height Y is unchanged,
    // so sigma_yy(Y) = b_y (H - Y) as in small strain, and with the stretch
    // s = dy/dY, tau_yy = E_c ln s = s sigma_yy: ln(s) / s = -q,
    // q = -b_y (H - Y) / E_c, i.e. s = exp(-W(q)) (Lambert's W, principal
    // branch). u(Y) = int_0^Y (s - 1) dY and int exp(-W(q)) dq = W + W^2/2
    // (q = W e^W) give u = E_c / b_y (G(q(Y)) - G(q(0))),
    // G(q) = W(q) + W(q)^2 / 2 - q.
    const auto G = [](const double q) {
      const double W = boost::math::lambert_w0(q);
      return W + W * W / 2 - q;
    };
    const double q  = -b_y * (height - y) / constrained_modulus;
    const double q0 = -b_y * height / constrained_modulus;
    return Tensor<1, 2>({0., constrained_modulus / b_y * (G(q) - G(q0))});
  }



  SymmetricTensor<2, 2>
  ColumnUnderSelfWeight::stress(const Point<2> &X) const
  {
    const double          y = X[1] - base;
    SymmetricTensor<2, 2> sigma;
    sigma[1][1] = b_y * (height - y);
    sigma[0][0] = lateral_ratio * sigma[1][1];
    return sigma;
  }



  std::string
  ColumnUnderSelfWeight::description() const
  {
    std::ostringstream s;
    s << (finite_strain ? "column under self weight (finite strain)" :
                          "column under self weight")
      << ": unit weight " << -b_y << " N/m^3, height " << height
      << " m, constrained modulus " << constrained_modulus
      << " Pa, top displacement " << displacement(Point<2>(0, base + height))[1]
      << " m";
    return s.str();
  }



  // ---------------------------------------------------------------------

  ConstantStress::ConstantStress(const LinearElasticMaterial &material,
                                 const Voigt                 &stress_in_frame,
                                 const double                 angle,
                                 const Point<2>              &fixed_point)
    : fixed_point(fixed_point)
  {
    const Voigt  eps_in_frame = invert(material.stiffness()) * stress_in_frame;
    Tensor<2, 2> R;
    R[0][0] = R[1][1] = std::cos(angle);
    R[1][0]           = std::sin(angle);
    R[0][1]           = -R[1][0];
    const auto rotate = [&R](const SymmetricTensor<2, 2> &t) {
      return symmetrize(Tensor<2, 2>(R * Tensor<2, 2>(t) * transpose(R)));
    };
    sigma   = rotate(tensor_from_voigt(stress_in_frame, false));
    epsilon = rotate(tensor_from_voigt(eps_in_frame, true));
  }



  Tensor<1, 2>
  ConstantStress::displacement(const Point<2> &X) const
  {
    return epsilon * (X - fixed_point);
  }



  SymmetricTensor<2, 2>
  ConstantStress::stress(const Point<2> &) const
  {
    return sigma;
  }



  std::string
  ConstantStress::description() const
  {
    std::ostringstream s;
    s << "constant stress: sigma = (" << sigma[0][0] << ", " << sigma[1][1]
      << ", " << sigma[0][1] << ") Pa, strain = (" << epsilon[0][0] << ", "
      << epsilon[1][1] << ", " << epsilon[0][1] << ")";
    return s.str();
  }



  // ---------------------------------------------------------------------

  LameCylinder::LameCylinder(const LinearElasticMaterial &material,
                             const Point<2>              &center,
                             const double                 inner_radius,
                             const double                 outer_radius,
                             const double                 pressure,
                             const double                 inner_displacement)
    : center(center)
    , a(inner_radius)
    , b(outer_radius)
    , p(pressure)
    , E(material.youngs_modulus())
    , nu(material.poissons_ratio())
    , plane_strain(material.model() ==
                   LinearElasticMaterial::Model::plane_strain)
  {
    AssertThrow(a > 0 && b > a,
                ExcMessage("Exact solution: the Lame cylinder needs "
                           "0 < inner radius < outer radius."));
    if (inner_displacement > 0)
      {
        // u_r is linear in p: scale the displacement of a unit pressure.
        p = 1.;
        p = inner_displacement / radial_displacement(a);
      }
  }



  double
  LameCylinder::radial_displacement(const double r) const
  {
    const double k = p * a * a / (b * b - a * a);
    if (plane_strain)
      return (1 + nu) * k / E * ((1 - 2 * nu) * r + b * b / r);
    return k / E * ((1 - nu) * r + (1 + nu) * b * b / r);
  }



  Tensor<1, 2>
  LameCylinder::displacement(const Point<2> &X) const
  {
    const Tensor<1, 2> d = X - center;
    const double       r = d.norm();
    return radial_displacement(r) / r * d;
  }



  SymmetricTensor<2, 2>
  LameCylinder::stress(const Point<2> &X) const
  {
    const Tensor<1, 2> d   = X - center;
    const double       r2  = d.norm_square();
    const double       k   = p * a * a / (b * b - a * a);
    const double       srr = k * (1 - b * b / r2), stt = k * (1 + b * b / r2);
    const double       c2 = d[0] * d[0] / r2, s2 = d[1] * d[1] / r2,
                 cs = d[0] * d[1] / r2;
    SymmetricTensor<2, 2> sigma;
    sigma[0][0] = srr * c2 + stt * s2;
    sigma[1][1] = srr * s2 + stt * c2;
    sigma[0][1] = (srr - stt) * cs;
    return sigma;
  }



  std::string
  LameCylinder::description() const
  {
    std::ostringstream s;
    s << "lame cylinder: r_i = " << a << " m, r_o = " << b
      << " m, inner pressure " << p
      << " Pa, u_r(r_i) = " << radial_displacement(a)
      << " m, u_r(r_o) = " << radial_displacement(b) << " m";
    return s.str();
  }



  // ---------------------------------------------------------------------

  KirschPlate::KirschPlate(const LinearElasticMaterial &material,
                           const Point<2>              &center,
                           const double                 hole_radius,
                           const double                 far_field_stress)
    : center(center)
    , a(hole_radius)
    , S(far_field_stress)
    , mu(material.shear_modulus())
    , kappa(material.kolosov_constant())
  {
    AssertThrow(a > 0,
                ExcMessage("Exact solution: the hole radius must be "
                           "positive."));
  }



  namespace
  {
    // cos(k beta) and sin(k beta), k = 1 .. 4, of the polar angle beta of d,
    // by the multiple-angle formulas: no atan2, sin or cos per point.
    std::array<std::array<double, 2>, 5>
    multiple_angles(const Tensor<1, 2> &d)
    {
      const double                         r = d.norm();
      std::array<std::array<double, 2>, 5> cs;
      cs[0] = {{1., 0.}};
      cs[1] = {{d[0] / r, d[1] / r}};
      for (unsigned int k = 2; k < 5; ++k) // cos/sin of (k - 1) beta + beta
        cs[k] = {{cs[k - 1][0] * cs[1][0] - cs[k - 1][1] * cs[1][1],
                  cs[k - 1][1] * cs[1][0] + cs[k - 1][0] * cs[1][1]}};
      return cs;
    }
  } // namespace



  Tensor<1, 2>
  KirschPlate::displacement(const Point<2> &X) const
  {
    const Tensor<1, 2> d  = X - center;
    const auto         cs = multiple_angles(d);
    const double       f  = S * a / (8 * mu);
    const double       q = a / d.norm(), q3 = q * q * q;
    return Tensor<1, 2>(
      {f * ((kappa + 1) * cs[1][0] / q +
            2 * q * ((1 + kappa) * cs[1][0] + cs[3][0]) - 2 * q3 * cs[3][0]),
       f * ((kappa - 3) * cs[1][1] / q +
            2 * q * ((1 - kappa) * cs[1][1] + cs[3][1]) - 2 * q3 * cs[3][1])});
  }



  SymmetricTensor<2, 2>
  KirschPlate::stress(const Point<2> &X) const
  {
    const Tensor<1, 2>    d  = X - center;
    const auto            cs = multiple_angles(d);
    const double          q2 = a * a / d.norm_square(), q4 = 1.5 * q2 * q2;
    SymmetricTensor<2, 2> sigma;
    sigma[0][0] = S - S * q2 * (1.5 * cs[2][0] + cs[4][0]) + S * q4 * cs[4][0];
    sigma[1][1] = -S * q2 * (0.5 * cs[2][0] - cs[4][0]) - S * q4 * cs[4][0];
    sigma[0][1] = -S * q2 * (0.5 * cs[2][1] + cs[4][1]) + S * q4 * cs[4][1];
    return sigma;
  }



  std::string
  KirschPlate::description() const
  {
    std::ostringstream s;
    s << "kirsch plate: hole radius " << a << " m, far-field stress " << S
      << " Pa, shear modulus " << mu << " Pa, kappa " << kappa;
    return s.str();
  }
} // namespace bsmpm
