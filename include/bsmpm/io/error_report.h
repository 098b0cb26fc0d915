#ifndef bsmpm_error_report_h
#define bsmpm_error_report_h

#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>

#include <bsmpm/base/exception_message.h>

#include <string>

namespace bsmpm
{
  using namespace dealii;

  /**
   * How a run that failed tells so: "bsmpm: error: <message>" on the
   * standard error and exit code 1.
   *
   * Errors are meant to be found by every process alike
   * (ParameterTools::throw_if_any); then the first process prints the
   * message once. One found by a process alone would leave the others
   * waiting for it in their next collective call: then that process prints
   * it, with its number, and stops the run (MPI_Abort). Which of the two it
   * is, the processes tell by a barrier on a communicator of their own that
   * a process still at work (or waiting in a collective call for this one)
   * does not enter.
   */
  class ErrorReport
  {
  public:
    /** Call after MPI_Init: duplicates MPI_COMM_WORLD. */
    ErrorReport();

    ~ErrorReport();

    ErrorReport(const ErrorReport &) = delete;
    ErrorReport &
    operator=(const ErrorReport &) = delete;

    /** Reports @p message as above and returns the exit code, 1 (unless
     * the run is stopped). */
    int
    fail(const std::string &message);

  private:
    /** Whether all processes arrive here within @p seconds. */
    bool
    all_failed(const double seconds = 5.);

    MPI_Comm communicator;
    /** A barrier was entered and not completed: the communicator cannot
     * be freed. */
    bool pending = false;
  };
} // namespace bsmpm

#endif
