// The constitutive models (doc/materials.md): one compiled test, whose
// parts, one per model, are the numbered files it includes; the checks
// they share are in constitutive_checks.h.

#include "../unit_test.h"
#include "drucker_prager_01.h"
#include "elastic_01.h"
#include "von_mises_01.h"

BSMPM_UNIT_TEST("materials/constitutive_models")
{
  initlog();
  deallog << std::setprecision(8);
  deallog.push("elastic_01");
  elastic_01::run();
  deallog.pop();
  deallog << std::setprecision(8);
  deallog.push("von_mises_01");
  von_mises_01::run();
  deallog.pop();
  deallog << std::setprecision(8);
  deallog.push("drucker_prager_01");
  drucker_prager_01::run();
  deallog.pop();
}
