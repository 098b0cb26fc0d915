#include <deal.II/base/mpi.h>

#include <bsmpm/verification/error_measures.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

namespace bsmpm
{
  std::map<std::string, double>
  compute_errors(const MaterialPoints &points,
                 const ExactSolution  &exact,
                 const MPI_Comm        communicator,
                 const bool            finite_strain)
  {
    using P                                = MaterialPoints::Property;
    const std::array<std::string, 5> names = {
      {"u", "v", "sigma_xx", "sigma_yy", "sigma_xy"}};

    // Sums over points, reduced over processes at the end.
    std::vector<double> abs_sum(5), rel_sum(5), max_abs(5), max_exact(5);
    std::vector<double> min_exact(5, std::numeric_limits<double>::max());
    double volume = 0, u_err2 = 0, u_norm2 = 0, s_err2 = 0, s_norm2 = 0;

    Vector<double>          a(5);
    std::array<Point<2>, 2> worst; // where max_A_u, max_A_v occur
    for (const auto &particle : points.particle_handler())
      {
        const auto   props = particle.get_properties();
        const double V =
          props[P::volume] / (finite_strain ? props[P::det_F] : 1.);
        if (V == 0.)
          continue;
        exact.vector_value(Point<2>(props[P::initial_position],
                                    props[P::initial_position + 1]),
                           a);
        const std::array<double, 5> h = {{props[P::displacement],
                                          props[P::displacement + 1],
                                          props[P::stress],
                                          props[P::stress + 1],
                                          props[P::stress + 2]}};
        volume += V;
        for (unsigned int c = 0; c < 5; ++c)
          {
            const double e = std::abs(h[c] - a[c]);
            abs_sum[c] += V * e;
            if (a[c] != 0.)
              rel_sum[c] += V * e / std::abs(a[c]);
            if (c < 2 && e > max_abs[c])
              worst[c] = Point<2>(props[P::initial_position],
                                  props[P::initial_position + 1]);
            max_abs[c]   = std::max(max_abs[c], e);
            max_exact[c] = std::max(max_exact[c], std::abs(a[c]));
            min_exact[c] = std::min(min_exact[c], std::abs(a[c]));
          }
        u_err2 += V * (std::pow(h[0] - a[0], 2) + std::pow(h[1] - a[1], 2));
        u_norm2 += V * (a[0] * a[0] + a[1] * a[1]);
        s_err2 += V * (std::pow(h[2] - a[2], 2) + std::pow(h[3] - a[3], 2) +
                       2 * std::pow(h[4] - a[4], 2));
        s_norm2 += V * (a[2] * a[2] + a[3] * a[3] + 2 * a[4] * a[4]);
      }

    // The worst points' places, from the process that holds each.
    for (unsigned int c = 0; c < 2; ++c)
      {
        const auto stats =
          Utilities::MPI::min_max_avg(max_abs[c], communicator);
        worst[c] =
          Utilities::MPI::broadcast(communicator, worst[c], stats.max_index);
      }
    Utilities::MPI::sum(abs_sum, communicator, abs_sum);
    Utilities::MPI::sum(rel_sum, communicator, rel_sum);
    Utilities::MPI::max(max_abs, communicator, max_abs);
    Utilities::MPI::max(max_exact, communicator, max_exact);
    Utilities::MPI::min(min_exact, communicator, min_exact);
    volume  = Utilities::MPI::sum(volume, communicator);
    u_err2  = Utilities::MPI::sum(u_err2, communicator);
    u_norm2 = Utilities::MPI::sum(u_norm2, communicator);
    s_err2  = Utilities::MPI::sum(s_err2, communicator);
    s_norm2 = Utilities::MPI::sum(s_norm2, communicator);

    std::map<std::string, double> errors;
    for (unsigned int c = 0; c < 5; ++c)
      {
        errors["A_" + names[c]] = abs_sum[c] / volume;
        // A relative error needs an exact value that vanishes nowhere.
        if (min_exact[c] > 1e-14 * max_exact[c])
          errors["R_" + names[c]] = rel_sum[c] / volume;
      }
    errors["max_A_u"]      = max_abs[0];
    errors["max_A_v"]      = max_abs[1];
    errors["max_A_u_at_x"] = worst[0][0];
    errors["max_A_u_at_y"] = worst[0][1];
    errors["max_A_v_at_x"] = worst[1][0];
    errors["max_A_v_at_y"] = worst[1][1];
    errors["L2_u"] =
      u_norm2 > 0 ? std::sqrt(u_err2 / u_norm2) : std::sqrt(u_err2 / volume);
    errors["L2_sigma"] =
      s_norm2 > 0 ? std::sqrt(s_err2 / s_norm2) : std::sqrt(s_err2 / volume);
    return errors;
  }



  std::map<std::string, double>
  compute_radius_errors(const std::vector<BoundaryArc> &curves,
                        const LameCylinder             &lame)
  {
    // (initial radius, mean deformed radius, mean relative error) per arc.
    std::vector<std::array<double, 3>> arcs;
    for (const BoundaryArc &curve : curves)
      {
        double r_min = std::numeric_limits<double>::max(), r_max = 0;
        for (const auto &x : curve.initial_points)
          {
            const double r = x.distance(lame.axis());
            r_min          = std::min(r_min, r);
            r_max          = std::max(r_max, r);
          }
        if (r_max - r_min > 1e-9 * r_max)
          continue; // not an arc about the axis
        const double       r0    = (r_min + r_max) / 2;
        const double       exact = r0 + lame.radial_displacement(r0);
        const unsigned int n     = 1000;
        double             mean = 0, error = 0;
        for (unsigned int i = 0; i < n; ++i)
          {
            const double r =
              curve.deformed.value(double(i) / (n - 1)).distance(lame.axis());
            mean += r / n;
            error += std::abs(r - exact) / exact / n;
          }
        arcs.push_back({{r0, mean, error}});
      }

    std::map<std::string, double> quantities;
    if (arcs.empty())
      return quantities;
    std::sort(arcs.begin(), arcs.end());
    quantities["inner_radius"]       = arcs.front()[1];
    quantities["inner_radius_error"] = arcs.front()[2];
    if (arcs.size() > 1)
      {
        quantities["outer_radius"]       = arcs.back()[1];
        quantities["outer_radius_error"] = arcs.back()[2];
      }
    return quantities;
  }
} // namespace bsmpm
