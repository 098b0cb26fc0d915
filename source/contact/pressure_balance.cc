#include <deal.II/base/numbers.h>

#include <bsmpm/contact/pressure_balance.h>

#include <cmath>
#include <limits>

namespace bsmpm
{
  bool
  pressures_can_balance(const Tensor<1, 2>              &force,
                        const std::vector<Tensor<1, 2>> &normals,
                        const std::array<bool, 2>       &free)
  {
    const auto in_free = [&](const Tensor<1, 2> &v) {
      return Tensor<1, 2>({free[0] ? v[0] : 0., free[1] ? v[1] : 0.});
    };
    const Tensor<1, 2> f = in_free(force);
    if (f.norm() <= 1e-12 * force.norm() || f.norm() == 0.)
      return true;
    // In 2D the cone of the normals holds f if one normal points along f,
    // or if the nearest normals on either side of f are less than half a
    // turn apart (f is then a non-negative combination of the two).
    constexpr double angle_tolerance = 1e-6;
    double           left            = std::numeric_limits<double>::infinity();
    double           right           = -left;
    for (const Tensor<1, 2> &normal : normals)
      {
        const Tensor<1, 2> m = in_free(normal);
        if (m.norm() <= 1e-12)
          continue;
        const double angle =
          std::atan2(f[0] * m[1] - f[1] * m[0], f[0] * m[0] + f[1] * m[1]);
        if (std::abs(angle) <= angle_tolerance)
          return true;
        if (angle > 0)
          left = std::min(left, angle);
        else
          right = std::max(right, angle);
      }
    return std::isfinite(left) && std::isfinite(right) &&
           left - right < numbers::PI - angle_tolerance;
  }
} // namespace bsmpm
