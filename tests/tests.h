// Shared set-up for the unit tests, in the manner of deal.II's tests/tests.h:
// deallog writes to the file "output" that the test harness compares.
#ifndef bsmpm_tests_h
#define bsmpm_tests_h

#include <deal.II/base/logstream.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <cmath>
#include <cstdint>
#include <fstream>
#include <iomanip>
#include <string>

using namespace dealii;

// inline: the unit tests are linked into one executable (unit_test.h).
inline std::ofstream deallogfile;

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

/** "yes" or "no", to print the outcome of a check. */
inline const char *
yes_no(const bool condition)
{
  return condition ? "yes" : "no";
}

/** Random numbers whose sequence is the same on every platform
 * (std::uniform_real_distribution is not specified bit for bit). */
class Random
{
public:
  explicit Random(const std::uint64_t seed = 7)
    : state(seed)
  {}

  double
  operator()(const double a = 0., const double b = 1.)
  {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return a + (b - a) * double(state >> 11) / double(1ULL << 53);
  }

  /** Skips @p n numbers, as std::mt19937::discard(): a test that makes one
   * part of a longer sequence of checks draws that part's numbers. */
  void
  discard(const std::uint64_t n)
  {
    for (std::uint64_t i = 0; i < n; ++i)
      (*this)();
  }

private:
  std::uint64_t state;
};

#endif
