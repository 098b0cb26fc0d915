// The unit tests' executable (tests/unit_test.h): `unit_tests
// <subsystem>/<name>` runs the test of tests/<subsystem>/<name>.cc,
// `unit_tests --list` lists the tests. ctest runs each test through
// tests/run_unit_test.sh, which compares its deallog output with the
// reference.

#include <iostream>
#include <string>

#include "unit_test.h"

int
main(int argc, char **argv)
{
  const auto       &tests    = unit_test::registry();
  const std::string argument = argc > 1 ? argv[1] : "";
  const auto        test     = tests.find(argument);
  if (test != tests.end())
    {
      test->second(argc, argv);
      return 0;
    }

  const bool    list = argument == "--list";
  std::ostream &out  = list ? std::cout : std::cerr;
  if (!list)
    out << (argument.empty() ? "" : "unit_tests: no test " + argument + "\n")
        << "usage: unit_tests <subsystem>/<name> | --list\n"
        << "the tests:\n";
  for (const auto &named_test : tests)
    out << named_test.first << '\n';
  return list ? 0 : 1;
}
