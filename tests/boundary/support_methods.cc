// The support methods: one compiled test, whose parts are the numbered
// files it includes (the registry, the implicit boundary method's band
// integrals).

#include "../unit_test.h"
#include "implicit_boundary_01.h"
#include "support_method_registry_01.h"

BSMPM_UNIT_TEST("boundary/support_methods")
{
  initlog();
  deallog << std::setprecision(8);
  deallog.push("support_method_registry_01");
  support_method_registry_01::run();
  deallog.pop();
  deallog << std::setprecision(8);
  deallog.push("implicit_boundary_01");
  implicit_boundary_01::run();
  deallog.pop();
}
