// The D-function of the implicit boundary method (paper eq. 20) and the
// integrals across the band that make its terms what they are: with the
// band's Gauss rule (3 points, as in the paper) they must be exact,
//   int D'^2 = 4 / (3 delta)   (k3: a penalty of order E / delta),
//   int D D' = 1 / 2           (k2: half of Nitsche's consistency term),
//   int D    = 2 delta / 3.
// The inclined patch test is the scene test scenes/square_compression_45.
#ifndef bsmpm_tests_implicit_boundary_01_h
#define bsmpm_tests_implicit_boundary_01_h

#include <deal.II/base/quadrature_lib.h>

#include <bsmpm/boundary/implicit_boundary.h>

#include "../tests.h"

namespace implicit_boundary_01
{
  void
  run()
  {
    using bsmpm::ImplicitBoundary;

    for (const double delta : {1e-1, 1e-6, 1e-12})
      {
        const auto D = [delta](double p) {
          return ImplicitBoundary::d_function(p, delta);
        };
        const auto dD = [delta](double p) {
          return ImplicitBoundary::d_function_derivative(p, delta);
        };
        deallog << "delta = " << delta << std::endl;
        deallog << "D(-delta) = " << D(-delta) << ", D(0) = " << D(0)
                << ", D(delta) = " << D(delta)
                << ", D(2 delta) = " << D(2 * delta) << std::endl;
        deallog << "D'(0) delta = " << dD(0) * delta
                << ", D'(delta) = " << dD(delta) << std::endl;

        // Derivative against a central difference in the band.
        double worst = 0;
        for (const double f : {0.1, 0.3, 0.5, 0.7, 0.9})
          {
            const double p = f * delta, e = 1e-6 * delta;
            worst = std::max(worst,
                             std::abs((D(p + e) - D(p - e)) / (2 * e) - dD(p)) *
                               delta);
          }
        deallog << "D' matches differences: " << (worst < 1e-8 ? "yes" : "no")
                << std::endl;

        const QGauss<1> across(3);
        double          dd = 0, ddd = 0, d = 0;
        for (unsigned int q = 0; q < across.size(); ++q)
          {
            const double p = delta * across.point(q)[0];
            const double w = delta * across.weight(q);
            dd += dD(p) * dD(p) * w;
            ddd += D(p) * dD(p) * w;
            d += D(p) * w;
          }
        deallog << "int D'^2 * 3 delta / 4 = " << dd * 3 * delta / 4
                << std::endl;
        deallog << "int D D' = " << ddd << std::endl;
        deallog << "int D * 3 / (2 delta) = " << d * 3 / (2 * delta)
                << std::endl;
      }
  }
} // namespace implicit_boundary_01

#endif
