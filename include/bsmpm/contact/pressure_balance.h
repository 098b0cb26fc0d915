#ifndef bsmpm_pressure_balance_h
#define bsmpm_pressure_balance_h

#include <deal.II/base/tensor.h>

#include <array>
#include <vector>

namespace bsmpm
{
  using namespace dealii;

  /**
   * Whether contact pressures alone, forces p_i n_i with p_i >= 0 along
   * the unit normals @p normals of the places that touch, can balance the
   * force @p force in the components @p free (0: x, 1: y; the others are
   * held otherwise, by a prescribed motion): whether that part of the force
   * lies in the cone of those parts of the normals. Where it does not, only
   * friction can hold the body in some direction, and it holds at most mu
   * times the pressure: a force beyond that leaves no quasi-static
   * equilibrium (the hint of a failed load increment, CurveContact::
   * friction_hint()).
   *
   * A force with nothing in the free components needs nothing. Directions
   * are compared to 1e-6 rad: a flat base holds a force along its normal
   * that round-off tilts.
   */
  bool
  pressures_can_balance(const Tensor<1, 2>              &force,
                        const std::vector<Tensor<1, 2>> &normals,
                        const std::array<bool, 2>       &free = {{true, true}});
} // namespace bsmpm

#endif
