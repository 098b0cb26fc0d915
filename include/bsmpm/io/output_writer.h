#ifndef bsmpm_output_writer_h
#define bsmpm_output_writer_h

#include <deal.II/base/data_out_base.h>
#include <deal.II/base/parameter_handler.h>

#include <functional>
#include <map>
#include <ostream>
#include <string>
#include <vector>

namespace bsmpm
{
  using namespace dealii;

  /**
   * Writes a run's files into its output directory: per load step one file
   * (per process) for each series (grid, points, and later curves ...), a
   * .pvd collection per series and solution.pvd that holds all series as
   * parts, so that ParaView opens the whole load path at once.
   *
   * Every file is written under a temporary name and renamed when complete,
   * so a run that stops never leaves a half-written file behind.
   */
  class OutputWriter
  {
  public:
    explicit OutputWriter(const MPI_Comm communicator);

    static void
    declare_parameters(ParameterHandler &prm);
    void
    parse_parameters(ParameterHandler &prm);

    /** Creates the output directory (collectively). Throws if it cannot. */
    void
    prepare_directory() const;

    /** Whether output is written after load step @p step (of @p n_steps). */
    bool
    writes_step(const unsigned int step, const unsigned int n_steps) const;

    /** Whether any output is written. */
    bool
    enabled() const
    {
      return interval > 0;
    }

    bool
    print_timing() const
    {
      return timing_summary;
    }

    const std::string &
    directory() const
    {
      return output_directory;
    }

    /**
     * Writes series @p series of step @p step: every process its piece, a
     * .vtu file that @p piece writes, then process 0 the .pvtu record that
     * @p record writes for the pieces' file names; and records it in the
     * collections.
     */
    void
    write_series(
      const std::string                                           &series,
      const unsigned int                                           step,
      const double                                                 time,
      const std::function<void(std::ostream &)>                   &piece,
      const std::function<void(std::ostream &,
                               const std::vector<std::string> &)> &record);

    /** The same from a DataOutInterface (such as DataOut) with patches
     * already built. */
    template <int dim>
    void
    write_series(const std::string              &series,
                 const unsigned int              step,
                 const double                    time,
                 const DataOutInterface<dim, 2> &data);

    /**
     * Writes a .vtu file that only process 0 produces (such as the curves)
     * and records it in the collections.
     */
    void
    write_serial_series(const std::string                         &series,
                        const unsigned int                         step,
                        const double                               time,
                        const std::function<void(std::ostream &)> &writer);

    /**
     * The flags of the .vtu files: the compression of Output/Compression.
     * deal.II's default, the best compression, made writing 676 k points
     * take 14 s per step, 98 % of the run, for files 2 % smaller than the
     * fastest setting's (doc/benchmarks.md).
     */
    DataOutBase::VtkFlags
    vtk_flags() const;

    /** Rewrites the .pvd collections (process 0 only). */
    void
    write_collections() const;

    /** Writes @p writer's output to @p file in the output directory
     * atomically (process 0 only). */
    void
    write_root_file(const std::string                         &file,
                    const std::function<void(std::ostream &)> &writer) const;

    /** Writes to @p path through a temporary file renamed at the end. */
    static void
    write_atomically(const std::string                         &path,
                     const std::function<void(std::ostream &)> &writer);

    /** Saves or restores the records of the series written so far (see
     * Checkpoint), so that a resumed run's .pvd files list every step. */
    template <class Archive>
    void
    serialize(Archive &ar, const unsigned int)
    {
      ar &collections;
    }

  private:
    struct Record
    {
      double      time;
      std::string file;

      template <class Archive>
      void
      serialize(Archive &ar, const unsigned int)
      {
        ar &time &file;
      }
    };

    MPI_Comm                                    communicator;
    std::string                                 output_directory = "output";
    unsigned int                                interval         = 1;
    bool                                        timing_summary   = true;
    DataOutBase::VtkFlags::ZlibCompressionLevel compression =
      DataOutBase::VtkFlags::best_speed;

    std::map<std::string, std::vector<Record>> collections;
  };
} // namespace bsmpm

#endif
