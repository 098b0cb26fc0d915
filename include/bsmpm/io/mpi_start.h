#ifndef bsmpm_mpi_start_h
#define bsmpm_mpi_start_h

namespace bsmpm
{
  /**
   * Sets Open MPI's settings for a fast MPI_Init; call before it.
   *
   * A run started without mpirun is an MPI singleton. Open MPI 4 then
   * starts a helper daemon (orted) and probes the network transports (UCX
   * and the others) at MPI_Init: 0.45-0.95 s on the 2-core test machine,
   * more than a small scene's whole run. One process needs neither: it
   * talks only to itself. Open MPI reads its settings from the environment
   * at MPI_Init, so they are set here, each only if the user has not set
   * it. Under mpirun with every process on this node, the processes still
   * need the shared-memory transport, but not the probing of UCX, the
   * network layer of clusters: the point-to-point layer ob1 alone (0.25 s
   * less at np = 2 there, doc/benchmarks.md). Under another launcher, and
   * with another MPI, nothing is set.
   *
   * Every run started by Open MPI leaves out its shared-memory shared file
   * pointer (OMPI_MCA_sharedfp = ^sm): its lock, left taken by a run killed
   * while writing a checkpoint, would make every later checkpoint of every
   * run on the machine wait for ever (the reason in
   * source/io/mpi_start.cc).
   *
   * A serial run also gets a session directory of its own
   * (OMPI_MCA_orte_top_session_dir = <tmp>/bsmpm-mpi.<host>.<uid>/<pid>):
   * Open MPI gives every isolated singleton the same one, which each
   * removes at its end while others may still use it (the reason in
   * source/io/mpi_start.cc).
   */
  void
  start_mpi_quickly();

  /**
   * Whether this process is the first of those a launcher started, or was
   * started alone; known before MPI_Init from the launcher's environment
   * (Open MPI's OMPI_COMM_WORLD_RANK, or PMI_RANK). Under mpirun only the
   * first process answers --help and --print-parameters, which are
   * answered without starting MPI.
   */
  bool
  launched_as_first_process();
} // namespace bsmpm

#endif
