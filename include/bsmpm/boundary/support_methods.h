#ifndef bsmpm_support_methods_h
#define bsmpm_support_methods_h

#include <deal.II/base/parameter_handler.h>

#include <bsmpm/boundary/support_method.h>

#include <memory>
#include <vector>

namespace bsmpm
{
  using namespace dealii;

  /**
   * Every registered SupportMethod, made from its parameters, in the order
   * of their names: the list that SystemAssembly and Scene call in turn.
   * What concerns all methods at once (the cells where one displaces the
   * points, the band points of all) is here; what one method does, in it.
   */
  class SupportMethods
  {
  public:
    /** Declares the parameters of every registered method. */
    static void
    declare_parameters(ParameterHandler &prm);

    /** Makes every registered method from its parameters. */
    void
    parse_parameters(ParameterHandler &prm);

    using const_iterator =
      std::vector<std::unique_ptr<SupportMethod>>::const_iterator;

    const_iterator
    begin() const
    {
      return methods.begin();
    }
    const_iterator
    end() const
    {
      return methods.end();
    }

    /**
     * Marks in @p cells (by active_cell_index(), resized to the active
     * cells) the locally owned cells where a method displaces the points
     * (SupportMethod::displaces_points()) of @p curves. Returns whether any
     * method does that in this scene; @p cells is left alone if none does.
     */
    bool
    mark_point_displacement_cells(const BackgroundGrid &grid,
                                  const BoundaryCurves &curves,
                                  std::vector<bool>    &cells) const;

    /** The displacement increment @p w of a point at @p x near a support
     * (SupportMethod::support_displacement()), of every method that
     * displaces points in turn; the smallest factor they return. */
    double
    support_displacement(
      const BoundaryCurves                                &curves,
      const BackgroundGrid                                &grid,
      const Point<2>                                      &x,
      const std::function<Tensor<1, 2>(const Point<2> &)> &field,
      Tensor<1, 2>                                        &w) const;

    /** The band points of every method's last assemble(). */
    std::vector<SupportMethod::BandPoint>
    band_points() const;

    /** The method that fits prescribed displacements of @p curves by
     * least squares (SupportMethod::fits_prescribed_displacement()), or
     * nullptr. At most one may. */
    const SupportMethod *
    fitting_prescribed_displacement(const BoundaryCurves &curves) const;

  private:
    std::vector<std::unique_ptr<SupportMethod>> methods;
  };
} // namespace bsmpm

#endif
