#include <deal.II/base/mpi.h>

#include <bsmpm/io/mpi_start.h>

#include <cstdlib>
#include <string>

namespace bsmpm
{
  void
  start_mpi_quickly()
  {
#ifdef OMPI_MAJOR_VERSION
    const char *size  = std::getenv("OMPI_COMM_WORLD_SIZE");
    const char *local = std::getenv("OMPI_COMM_WORLD_LOCAL_SIZE");
    if (size != nullptr)
      {
        // Started by Open MPI's mpirun: all processes on this node?
        if (local != nullptr && std::string(size) == local)
          setenv("OMPI_MCA_pml", "ob1", /*overwrite=*/0);
        return;
      }
    for (const char *launched :
         {"PMIX_RANK", "PMI_RANK", "PMI_SIZE", "SLURM_PROCID"})
      if (std::getenv(launched) != nullptr)
        return;
    // No daemon; the point-to-point layer over the self transport only.
    setenv("OMPI_MCA_ess_singleton_isolated", "1", /*overwrite=*/0);
    setenv("OMPI_MCA_pml", "ob1", 0);
    setenv("OMPI_MCA_btl", "self", 0);
#endif
  }



  bool
  launched_as_first_process()
  {
    const char *rank = std::getenv("OMPI_COMM_WORLD_RANK");
    if (rank == nullptr)
      rank = std::getenv("PMI_RANK");
    return rank == nullptr || std::string(rank) == "0";
  }
} // namespace bsmpm
