#include <deal.II/base/mpi.h>

#include <bsmpm/io/mpi_start.h>

#include <sys/stat.h>
#include <sys/types.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <system_error>

namespace bsmpm
{
  namespace
  {
#ifdef OMPI_MAJOR_VERSION
    /**
     * The session directory of this process, when it is one of its own;
     * removed at exit.
     */
    std::string own_session_directory;

    void
    remove_own_session_directory()
    {
      std::error_code ignored;
      std::filesystem::remove_all(own_session_directory, ignored);
    }

    /**
     * Gives this singleton a session directory of its own,
     * <tmp>/bsmpm-mpi.<host>.<uid>/<pid>, unless the user has chosen one.
     *
     * Why: Open MPI 4.1 names every isolated singleton 0:1 (job 1 of job
     * family 0, rank 0), so all of them, of every program of the user on
     * this host, share one session directory, <tmp>/ompi.<host>.<uid>/jf.0
     * with jf.0/1 for the job and jf.0/1/0 for the process. Each creates it
     * at MPI_Init and removes it at MPI_Finalize: it rmdirs jf.0/1/0, jf.0/1
     * and jf.0, which are empty, whether or not other singletons still run.
     * The shared-file-pointer component "sm" of MPI-IO keeps its file in
     * jf.0/1: at every MPI_File_open (deal.II opens the checkpoint's
     * triangulation data with it, to load and to save) it first creates and
     * removes a probe file there to be selected, then creates the file it
     * maps. When another serial run ends in between, the second creation
     * fails ("mca_sharedfp_sm_file_open: Error, unable to open file for
     * mmap: .../jf.0/1/triangulation_fixed.data_cid-0-<pid>.sm") and the
     * open with it (MPI_ERR_OTHER): the resume stops. (When it ends before
     * the probe, "sm" is not selected and "lockedfile" is used instead,
     * silently.) The same removal can also break a singleton's MPI_Init
     * between its mkdir of jf.0/1 and of jf.0/1/0. Seen by
     * tests/whole_program/checkpoint/concurrent_resume.py, which holds a resume
     * in that window while another bsmpm process starts and ends.
     *
     * Open MPI's own mpirun avoids it: each job family is named after the
     * mpirun's pid. Here the top of the session tree
     * (orte_top_session_dir) is one per process. Open MPI creates it at
     * MPI_Init and removes all of it at MPI_Finalize, so also after a run
     * that ends with an error message; after MPI_Abort, which calls exit(),
     * an atexit handler removes it. What a process killed by a signal left
     * (SIGKILL, std::abort) is removed by the next serial run: the
     * directories of processes that no longer exist.
     */
    void
    use_own_session_directory()
    {
      for (const char *chosen : {"OMPI_MCA_orte_top_session_dir",
                                 "OMPI_MCA_orte_jobfam_session_dir"})
        if (std::getenv(chosen) != nullptr)
          return;

      // Where Open MPI would put its own: the same order of choices.
      std::string tmp = "/tmp";
      for (const char *name :
           {"OMPI_MCA_orte_tmpdir_base", "TMPDIR", "TEMP", "TMP"})
        if (const char *value = std::getenv(name);
            value != nullptr && *value != '\0')
          {
            tmp = value;
            break;
          }
      char host[256] = {};
      if (gethostname(host, sizeof(host) - 1) != 0)
        host[0] = '\0';
      const std::string parent =
        tmp + "/bsmpm-mpi." + host + "." + std::to_string(getuid());

      // Ours alone, or nothing is changed.
      struct stat status;
      if ((mkdir(parent.c_str(), 0700) != 0 && errno != EEXIST) ||
          lstat(parent.c_str(), &status) != 0 || !S_ISDIR(status.st_mode) ||
          status.st_uid != getuid())
        return;

      // Left by processes killed by a signal.
      std::error_code error;
      for (std::filesystem::directory_iterator entry(parent, error), end;
           !error && entry != end;
           entry.increment(error))
        {
          const std::string name = entry->path().filename().string();
          if (name.empty() ||
              name.find_first_not_of("0123456789") != std::string::npos ||
              name.size() > 9)
            continue;
          const pid_t pid = std::stoi(name);
          if (pid != getpid() && kill(pid, 0) != 0 && errno == ESRCH)
            {
              std::error_code ignored;
              std::filesystem::remove_all(entry->path(), ignored);
            }
        }

      own_session_directory = parent + "/" + std::to_string(getpid());
      setenv("OMPI_MCA_orte_top_session_dir",
             own_session_directory.c_str(),
             /*overwrite=*/0);
      std::atexit(remove_own_session_directory);
    }
#endif
  } // namespace



  void
  start_mpi_quickly()
  {
#ifdef OMPI_MAJOR_VERSION
    // Checkpoints are written by MPI-IO. Open MPI's shared-memory "shared
    // file pointer" component keeps a named POSIX semaphore per file name
    // (/dev/shm/sem.OMPIO_<file name>) that a process killed while writing
    // leaves taken: every later MPI_File_open of a file of that name on the
    // machine then waits for ever, for any user's run. deal.II writes at
    // explicit offsets and needs no shared file pointer; the other
    // components hold no such lock.
    setenv("OMPI_MCA_sharedfp", "^sm", /*overwrite=*/0);

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
    // Independent of other serial runs (see above).
    const std::string isolated = std::getenv("OMPI_MCA_ess_singleton_isolated");
    if (isolated != "0" && isolated != "false" && isolated != "no")
      use_own_session_directory();
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
