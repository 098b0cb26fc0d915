// ContactLaw: the contact law alone, without grid, curve or body
// (doc/contact.md): the normal penalty and the augmented Lagrangian's
// pressure, Coulomb's return map (stick, slip with |t_T| = mu p against the
// slip, rough (smoothed), smooth), and its derivatives against central
// differences in each regime, which a sign or factor error in any of them would
// fail.

#include <bsmpm/contact/contact_law.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

// tests.h uses deallog unqualified: the using directive must come first.
using namespace dealii;

#include "../tests.h"

#include "../unit_test.h"

using namespace bsmpm;

namespace
{
  constexpr double eps       = 100;
  constexpr double mu        = 0.5;
  constexpr double tolerance = 1e-12;

  ContactLaw
  law(const ContactLaw::Friction friction,
      const ContactLaw::Method   method = ContactLaw::Method::penalty)
  {
    return ContactLaw(method, eps, friction, mu, tolerance);
  }

  ContactLaw::State
  state(const double multiplier, const double previous)
  {
    ContactLaw::State s;
    s.multiplier          = multiplier;
    s.previous_tangential = previous;
    return s;
  }

  void
  print(const std::string &name, const ContactLaw::Traction &t)
  {
    deallog << name << ": active " << yes_no(t.active) << ", sliding "
            << yes_no(t.sliding) << ", p " << filter_roundoff(t.pressure)
            << ", t_T " << filter_roundoff(t.tangential) << std::endl;
  }



  void
  test_normal()
  {
    LogStream::Prefix prefix("normal");
    const ContactLaw  penalty = law(ContactLaw::Friction::smooth);
    // p = -eps g where it penetrates, nothing where it is open; touching
    // within round-off counts with zero pressure.
    print("penalty, g = -0.01", penalty.evaluate(-0.01, 0, state(0, 0)));
    print("penalty, g = 0.01", penalty.evaluate(0.01, 0, state(0, 0)));
    print("penalty, g = 1e-13", penalty.evaluate(1e-13, 0, state(0, 0)));
    print("penalty, g = 1e-11", penalty.evaluate(1e-11, 0, state(0, 0)));
    deallog << "penalty: dp/dg = "
            << penalty.evaluate(-0.01, 0, state(0, 0)).d_pressure_d_gap
            << std::endl;
    // The plain penalty ignores a multiplier.
    print("penalty, lambda = 2, g = 0.01",
          penalty.evaluate(0.01, 0, state(2, 0)));

    // p = max(0, lambda - eps g): it acts while g <= lambda / eps = 0.02.
    const ContactLaw augmented = law(ContactLaw::Friction::smooth,
                                     ContactLaw::Method::augmented_lagrangian);
    print("augmented, lambda = 2, g = -0.01",
          augmented.evaluate(-0.01, 0, state(2, 0)));
    print("augmented, lambda = 2, g = 0.01",
          augmented.evaluate(0.01, 0, state(2, 0)));
    print("augmented, lambda = 2, g = 0.03",
          augmented.evaluate(0.03, 0, state(2, 0)));
    print("augmented, lambda = 0, g = -0.01",
          augmented.evaluate(-0.01, 0, state(0, 0)));
    deallog << "augmented: dp/dg = "
            << augmented.evaluate(0.01, 0, state(2, 0)).d_pressure_d_gap
            << std::endl;
  }



  void
  test_coulomb()
  {
    LogStream::Prefix prefix("coulomb");
    const ContactLaw  coulomb = law(ContactLaw::Friction::frictional);
    // p = 2, so mu p = 1. t_trial = t_prev - eps s.
    const double g = -0.02;
    // Stick: t_trial = 0.3 - 0.5 = -0.2, inside the cone.
    const ContactLaw::Traction stick =
      coulomb.evaluate(g, 0.005, state(0, 0.3));
    print("stick, t_prev = 0.3, s = 0.005", stick);
    deallog << "stick: t_T = t_trial: "
            << yes_no(std::abs(stick.tangential - (0.3 - eps * 0.005)) < 1e-14)
            << std::endl;
    // Slip: the trial leaves the cone; t_T is its projection back onto it,
    // |t_T| = mu p, in the direction of the trial: against the slip.
    for (const double s : {0.02, -0.02, 0.5, -0.5})
      {
        const ContactLaw::Traction slip = coulomb.evaluate(g, s, state(0, 0));
        print("slip, t_prev = 0, s = " + std::to_string(s), slip);
        deallog << "  |t_T| = mu p: "
                << yes_no(std::abs(std::abs(slip.tangential) -
                                   mu * slip.pressure) < 1e-14)
                << ", against the slip: " << yes_no(slip.tangential * s < 0)
                << std::endl;
      }
    // With a history the direction is that of t_trial: from a traction of
    // 0.8 held in the last increment, slips of -0.001, -0.005, 0.015, 0.02
    // give trials 0.9 (sticks), 1.3 (slides, t_T = mu p), -0.7 (sticks on
    // the other side) and -1.2 (slides back, t_T = -mu p).
    for (const double s : {-0.001, -0.005, 0.015, 0.02})
      print("t_prev = 0.8, s = " + std::to_string(s),
            coulomb.evaluate(g, s, state(0, 0.8)));
    // The map is continuous where stick turns into slip: |t_trial| = mu p.
    const double s_edge = (0.3 + 1) / eps;
    const double below =
      coulomb.evaluate(g, s_edge * (1 - 1e-9), state(0, 0.3)).tangential;
    const double above =
      coulomb.evaluate(g, s_edge * (1 + 1e-9), state(0, 0.3)).tangential;
    deallog << "continuous at |t_trial| = mu p: "
            << yes_no(std::abs(below - above) < 1e-6) << std::endl;
    // Open: no traction at all.
    print("open, g = 0.01", coulomb.evaluate(0.01, 0.5, state(0, 0.3)));
  }



  void
  test_rough_and_smooth()
  {
    const ContactLaw rough  = law(ContactLaw::Friction::rough);
    const ContactLaw smooth = law(ContactLaw::Friction::smooth);
    {
      LogStream::Prefix prefix("rough");
      // Coulomb with mu = 10 smoothed: t_T = 10 p tanh(t_trial / (10 p)),
      // t_trial = t_prev - eps s.
      const auto smoothed = [](const ContactLaw::Traction &t,
                               const double                trial) {
        const double limit =
          ContactLaw::rough_friction_coefficient * t.pressure;
        return limit * std::tanh(trial / limit);
      };
      // Where it presses hard, t_T is the penalty's stick traction to
      // within (x^2 / 3), x = t_trial / (10 p).
      const ContactLaw::Traction hard =
        rough.evaluate(-0.2, 0.005, state(0, 0.3));
      print("g = -0.2, s = 0.005", hard);
      const double trial_hard = 0.3 - eps * 0.005;
      deallog << "t_T = t_prev - eps s within 1e-4: "
              << yes_no(std::abs(hard.tangential - trial_hard) <
                        1e-4 * std::abs(trial_hard))
              << std::endl;
      const ContactLaw::Traction t = rough.evaluate(-0.02, 0.15, state(0, 0.3));
      print("s = 0.15", t);
      deallog << "t_T = 10 p tanh(t_trial / 10 p): "
              << yes_no(std::abs(t.tangential - smoothed(t, 0.3 - eps * 0.15)) <
                        1e-12)
              << std::endl;
      // Far beyond, |t_T| -> 10 p: the traction vanishes with the pressure,
      // as a place starts or stops touching, instead of jumping there.
      const ContactLaw::Traction u = rough.evaluate(-0.02, 5, state(0, 0.3));
      print("s = 5", u);
      deallog << "t_T = -10 p: "
              << yes_no(std::abs(u.tangential +
                                 ContactLaw::rough_friction_coefficient *
                                   u.pressure) < 1e-12)
              << std::endl;
    }
    {
      LogStream::Prefix prefix("smooth");
      // No tangential traction whatever the slip.
      print("s = 0.5", smooth.evaluate(-0.02, 0.5, state(0, 0.3)));
    }
    deallog << "has friction: smooth " << yes_no(smooth.has_friction())
            << ", rough " << yes_no(rough.has_friction()) << std::endl;
  }



  // The largest difference of the law's derivatives by the gap, the slip
  // and the previous traction from central differences of its pressure and
  // traction, relative to the larger of the two (1 where one of them is
  // zero and the other is not).
  double
  difference_error(const ContactLaw &law,
                   const double      g,
                   const double      s,
                   const double      lambda,
                   const double      t_prev,
                   std::string      &report)
  {
    const ContactLaw::Traction t = law.evaluate(g, s, state(lambda, t_prev));
    const double               h = 1e-7;
    const auto at = [&](const double dg, const double ds, const double dt) {
      return law.evaluate(g + dg, s + ds, state(lambda, t_prev + dt));
    };
    // {name, exact, central difference}
    const double pairs[6][3] = {
      {0,
       t.d_pressure_d_gap,
       (at(h, 0, 0).pressure - at(-h, 0, 0).pressure) / (2 * h)},
      {1, 0., (at(0, h, 0).pressure - at(0, -h, 0).pressure) / (2 * h)},
      {2, 0., (at(0, 0, h).pressure - at(0, 0, -h).pressure) / (2 * h)},
      {3,
       t.d_tangential_d_gap(),
       (at(h, 0, 0).tangential - at(-h, 0, 0).tangential) / (2 * h)},
      {4,
       t.d_tangential_d_slip,
       (at(0, h, 0).tangential - at(0, -h, 0).tangential) / (2 * h)},
      {5,
       t.d_tangential_d_previous,
       (at(0, 0, h).tangential - at(0, 0, -h).tangential) / (2 * h)}};
    const char *names[] = {
      "dp/dg", "dp/ds", "dp/dt_prev", "dt_T/dg", "dt_T/ds", "dt_T/dt_prev"};
    double error = 0;
    report.clear();
    for (const auto &[k, exact, difference] : pairs)
      {
        const double scale = std::max(std::abs(exact), std::abs(difference));
        if (scale > 0)
          error = std::max(error, std::abs(exact - difference) / scale);
        report += std::string(" ") + names[int(k)] + " " +
                  std::to_string(int(std::round(exact)));
      }
    return error;
  }



  void
  test_derivatives()
  {
    LogStream::Prefix prefix("derivatives");
    struct Case
    {
      std::string          name;
      ContactLaw::Friction friction;
      ContactLaw::Method   method;
      double               g, s, lambda, t_prev;
    };
    const std::vector<Case> cases = {{"stick",
                                      ContactLaw::Friction::frictional,
                                      ContactLaw::Method::penalty,
                                      -0.02,
                                      0.005,
                                      0,
                                      0.3},
                                     {"slip forwards",
                                      ContactLaw::Friction::frictional,
                                      ContactLaw::Method::penalty,
                                      -0.02,
                                      0.02,
                                      0,
                                      0.3},
                                     {"slip backwards",
                                      ContactLaw::Friction::frictional,
                                      ContactLaw::Method::penalty,
                                      -0.02,
                                      -0.03,
                                      0,
                                      0.3},
                                     {"separation",
                                      ContactLaw::Friction::frictional,
                                      ContactLaw::Method::penalty,
                                      0.01,
                                      0.02,
                                      0,
                                      0.3},
                                     {"augmented, stick",
                                      ContactLaw::Friction::frictional,
                                      ContactLaw::Method::augmented_lagrangian,
                                      0.01,
                                      0.002,
                                      2,
                                      0.1},
                                     {"augmented, slip",
                                      ContactLaw::Friction::frictional,
                                      ContactLaw::Method::augmented_lagrangian,
                                      0.01,
                                      -0.02,
                                      2,
                                      0.1},
                                     {"augmented, separation",
                                      ContactLaw::Friction::frictional,
                                      ContactLaw::Method::augmented_lagrangian,
                                      0.03,
                                      0.02,
                                      2,
                                      0.1},
                                     {"rough",
                                      ContactLaw::Friction::rough,
                                      ContactLaw::Method::penalty,
                                      -0.02,
                                      0.5,
                                      0,
                                      0.3},
                                     {"rough, between sticking and sliding",
                                      ContactLaw::Friction::rough,
                                      ContactLaw::Method::penalty,
                                      -0.02,
                                      0.15,
                                      0,
                                      0.3},
                                     {"smooth",
                                      ContactLaw::Friction::smooth,
                                      ContactLaw::Method::penalty,
                                      -0.02,
                                      0.5,
                                      0,
                                      0.3}};
    for (const Case &c : cases)
      {
        std::string  report;
        const double error = difference_error(
          law(c.friction, c.method), c.g, c.s, c.lambda, c.t_prev, report);
        deallog << c.name << ":" << report
                << "; against central differences to 1e-6: "
                << yes_no(error < 1e-6) << std::endl;
      }
  }
} // namespace



BSMPM_UNIT_TEST("contact/contact_law")
{
  initlog();
  test_normal();
  test_coulomb();
  test_rough_and_smooth();
  test_derivatives();
}
