// The compiled unit tests are one executable, unit_tests, built with the
// program (doc/architecture.md, "Tests"): each tests/<subsystem>/<name>.cc
// registers its test as "<subsystem>/<name>" with BSMPM_UNIT_TEST where a
// test of deal.II's kind has its main(), and tests/unit_tests.cc runs the
// test named on its command line. It is linked once; deal.II's test
// macros built and linked an executable per test while the test suite ran
// (tests/CMakeLists.txt).
#ifndef bsmpm_unit_test_h
#define bsmpm_unit_test_h

#include <cstdlib>
#include <iostream>
#include <map>
#include <string>

namespace unit_test
{
  /** A test: what its main() did, with main()'s arguments. */
  using Function = void (*)(int argc, char **argv);

  /** The tests by name. A function's static, so that it exists before the
   * first test registers, whatever the order in which the objects of the
   * executable are initialised. */
  inline std::map<std::string, Function> &
  registry()
  {
    static std::map<std::string, Function> tests;
    return tests;
  }

  /** Registers a test when the executable starts (BSMPM_UNIT_TEST). */
  struct Registrar
  {
    Registrar(const char *name, const Function test)
    {
      if (!registry().emplace(name, test).second)
        {
          std::cerr << "unit_tests: two tests named " << name << std::endl;
          std::abort();
        }
    }
  };
} // namespace unit_test

/** The function body that follows is the test @p name, "<subsystem>/<name>"
 * of its file tests/<subsystem>/<name>.cc, with main()'s argc and argv. */
#define BSMPM_UNIT_TEST(name)                                                    \
  static void                       unit_test_body(int, char **);                \
  static const unit_test::Registrar unit_test_registrar(name, unit_test_body);   \
  static void                       unit_test_body([[maybe_unused]] int    argc, \
                                                   [[maybe_unused]] char **argv)

#endif
