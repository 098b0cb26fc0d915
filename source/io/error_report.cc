#include <bsmpm/io/error_report.h>

#include <chrono>
#include <iostream>
#include <sstream>
#include <thread>

namespace bsmpm
{
  ErrorReport::ErrorReport()
  {
    MPI_Comm_dup(MPI_COMM_WORLD, &communicator);
  }



  ErrorReport::~ErrorReport()
  {
    if (!pending)
      MPI_Comm_free(&communicator);
  }



  int
  ErrorReport::fail(const std::string &message)
  {
    const unsigned int process =
      Utilities::MPI::this_mpi_process(MPI_COMM_WORLD);
    if (all_failed())
      {
        if (process == 0)
          std::cerr << "bsmpm: error: " << message << std::endl;
        return 1;
      }
    std::cerr << "bsmpm: error: " << message << " (found by process " << process
              << " alone: stopping the others)" << std::endl;
    MPI_Abort(MPI_COMM_WORLD, 1);
    return 1;
  }



  bool
  ErrorReport::all_failed(const double seconds)
  {
    int n_processes = 1;
    MPI_Comm_size(communicator, &n_processes);
    if (n_processes == 1)
      return true;
    MPI_Request request;
    MPI_Ibarrier(communicator, &request);
    pending          = true;
    const auto start = std::chrono::steady_clock::now();
    for (;;)
      {
        int done = 0;
        MPI_Test(&request, &done, MPI_STATUS_IGNORE);
        if (done)
          {
            pending = false;
            return true;
          }
        if (std::chrono::duration<double>(std::chrono::steady_clock::now() -
                                          start)
              .count() > seconds)
          return false;
        // Poll, rather than wait in MPI_Wait, to give up after seconds.
        std::this_thread::sleep_for(std::chrono::milliseconds(2));
      }
  }
} // namespace bsmpm
