#include <bsmpm/boundary/support_method.h>

namespace bsmpm
{
  namespace
  {
    std::map<std::string, SupportMethodEntry> &
    support_method_registry()
    {
      static std::map<std::string, SupportMethodEntry> methods;
      return methods;
    }
  } // namespace



  SupportMethod::SupportMethod(const std::string                   &name,
                               const BoundaryCurve::DirichletMethod method)
    : method_name(name)
    , method(method)
  {}



  void
  SupportMethod::mark_cells(const BackgroundGrid &grid,
                            const BoundaryCurves &curves,
                            const bool            both_components_only,
                            std::vector<bool>    &cells) const
  {
    curves.mark_support_cells(grid, method, both_components_only, cells);
  }



  double
  SupportMethod::support_displacement(
    const BoundaryCurves &,
    const BackgroundGrid &,
    const Point<2> &,
    const std::function<Tensor<1, 2>(const Point<2> &)> &,
    Tensor<1, 2> &) const
  {
    return 1.;
  }



  const std::vector<SupportMethod::BandPoint> &
  SupportMethod::band_points() const
  {
    static const std::vector<BandPoint> none;
    return none;
  }



  bool
  SupportMethod::fits_prescribed_displacement(const BoundaryCurves &) const
  {
    return false;
  }



  double
  SupportMethod::fit_prescribed_displacement(
    const Context &,
    const double,
    TrilinosWrappers::SparseMatrix &,
    LinearAlgebra::distributed::Vector<double> &) const
  {
    Assert(false,
           ExcMessage("Support method '" + method_name +
                      "' fits no prescribed displacement."));
    return 0.;
  }



  bool
  register_support_method(const std::string        &name,
                          const SupportMethodEntry &entry)
  {
    Assert(support_method_registry().count(name) == 0,
           ExcMessage("Two support methods are called '" + name + "'."));
    support_method_registry()[name] = entry;
    return true;
  }



  const std::map<std::string, SupportMethodEntry> &
  registered_support_methods()
  {
    return support_method_registry();
  }
} // namespace bsmpm
