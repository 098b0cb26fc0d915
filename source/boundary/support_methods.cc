#include <bsmpm/boundary/support_methods.h>

#include <algorithm>

namespace bsmpm
{
  void
  SupportMethods::declare_parameters(ParameterHandler &prm)
  {
    for (const auto &[name, entry] : registered_support_methods())
      entry.declare_parameters(prm);
  }



  void
  SupportMethods::parse_parameters(ParameterHandler &prm)
  {
    methods.clear();
    for (const auto &[name, entry] : registered_support_methods())
      {
        methods.push_back(entry.create(prm));
        Assert(methods.back()->name() == name,
               ExcMessage("The support method registered as '" + name +
                          "' calls itself '" + methods.back()->name() + "'."));
      }
  }



  bool
  SupportMethods::mark_point_displacement_cells(const BackgroundGrid &grid,
                                                const BoundaryCurves &curves,
                                                std::vector<bool> &cells) const
  {
    bool any = false;
    for (const auto &method : methods)
      if (method->displaces_points() && method->used_by(curves))
        {
          if (!any)
            cells.assign(grid.triangulation().n_active_cells(), false);
          any = true;
          method->mark_cells(grid, curves, false, cells);
        }
    return any;
  }



  double
  SupportMethods::support_displacement(
    const BoundaryCurves                                &curves,
    const BackgroundGrid                                &grid,
    const Point<2>                                      &x,
    const std::function<Tensor<1, 2>(const Point<2> &)> &field,
    Tensor<1, 2>                                        &w) const
  {
    double factor = 1.;
    for (const auto &method : methods)
      if (method->displaces_points())
        factor =
          std::min(factor,
                   method->support_displacement(curves, grid, x, field, w));
    return factor;
  }



  std::vector<SupportMethod::BandPoint>
  SupportMethods::band_points() const
  {
    std::vector<SupportMethod::BandPoint> all;
    for (const auto &method : methods)
      all.insert(all.end(),
                 method->band_points().begin(),
                 method->band_points().end());
    return all;
  }



  const SupportMethod *
  SupportMethods::fitting_prescribed_displacement(
    const BoundaryCurves &curves) const
  {
    const SupportMethod *fitting = nullptr;
    for (const auto &method : methods)
      if (method->fits_prescribed_displacement(curves))
        {
          AssertThrow(fitting == nullptr,
                      ExcMessage("The support methods '" + fitting->name() +
                                 "' and '" + method->name() +
                                 "' both fit prescribed displacements by "
                                 "least squares: one set of nodal values "
                                 "holds only one."));
          fitting = method.get();
        }
    return fitting;
  }
} // namespace bsmpm
