// The registry of support methods (SupportMethod, SupportMethods): every
// method registered under the value of "Boundary curves/Curve k/Dirichlet
// method" that selects it, in the order of the names, with its own
// parameter subsection, whose entries and defaults users write in their
// .prm files and must not change.
#ifndef bsmpm_tests_support_method_registry_01_h
#define bsmpm_tests_support_method_registry_01_h

#include <deal.II/base/parameter_handler.h>

#include <bsmpm/boundary/support_methods.h>

#include <sstream>
#include <string>

#include "../tests.h"

namespace support_method_registry_01
{
  void
  run()
  {
    using namespace bsmpm;

    for (const auto &[name, entry] : registered_support_methods())
      deallog << "registered: " << name << std::endl;

    ParameterHandler prm;
    SupportMethods::declare_parameters(prm);
    std::ostringstream declared;
    prm.print_parameters(declared, ParameterHandler::ShortPRM);
    std::istringstream lines(declared.str());
    for (std::string line; std::getline(lines, line);)
      deallog << line << std::endl;

    SupportMethods       supports;
    const BoundaryCurves no_curves;
    supports.parse_parameters(prm);
    for (const auto &method : supports)
      deallog << method->name()
              << ": displaces points = " << yes_no(method->displaces_points())
              << ", used without curves = "
              << yes_no(method->used_by(no_curves))
              << ", fits prescribed displacements without curves = "
              << yes_no(method->fits_prescribed_displacement(no_curves))
              << std::endl;
    deallog << "a method fits prescribed displacements: "
            << yes_no(supports.fitting_prescribed_displacement(no_curves) !=
                      nullptr)
            << std::endl;
  }
} // namespace support_method_registry_01

#endif
