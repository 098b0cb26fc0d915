// Shared set-up for the unit tests, in the manner of deal.II's tests/tests.h:
// deallog writes to the file "output" that the test harness compares.
#ifndef bsmpm_tests_h
#define bsmpm_tests_h

#include <deal.II/base/logstream.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <cmath>
#include <fstream>
#include <iomanip>
#include <string>

using namespace dealii;

std::ofstream deallogfile;

inline void
initlog(const unsigned int precision = 8)
{
  deallogfile.open("output");
  deallog.attach(deallogfile, false);
  deallog.depth_console(0);
  deallog << std::setprecision(precision);
}

// Prints a number rounded to the given relative precision so that numdiff's
// tolerances compare what the test means to compare.
inline double
filter_roundoff(const double value, const double tolerance = 1e-12)
{
  return std::abs(value) < tolerance ? 0. : value;
}

#endif
