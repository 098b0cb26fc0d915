#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <bsmpm/io/output_writer.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

namespace bsmpm
{
  OutputWriter::OutputWriter(const MPI_Comm communicator)
    : communicator(communicator)
  {}



  void
  OutputWriter::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Output");
    prm.declare_entry("Directory",
                      "output",
                      Patterns::DirectoryName(),
                      "Where the run writes its files and summary.json "
                      "(relative to the working directory).");
    prm.declare_entry("Interval",
                      "1",
                      Patterns::Integer(0),
                      "Write ParaView files every this many load steps (and "
                      "after the last); 0 writes none and costs nothing, for "
                      "runs of which only summary.json is wanted (studies, "
                      "benchmarks).");
    prm.declare_entry("Compression",
                      "fast",
                      Patterns::Selection("fast|best|none"),
                      "zlib compression of the ParaView (.vtu) files: fast "
                      "(the default) writes quickly, files nearly as small as "
                      "best's; best, the smallest files, many times slower to "
                      "write; none, the fastest to write and the largest "
                      "files. Choose best for files to keep, none when disk "
                      "space does not matter (doc/benchmarks.md).");
    prm.declare_entry("Timing summary",
                      "true",
                      Patterns::Bool(),
                      "Print the time spent in each phase at the end.");
    prm.leave_subsection();
  }



  void
  OutputWriter::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Output");
    output_directory        = prm.get("Directory");
    interval                = prm.get_integer("Interval");
    timing_summary          = prm.get_bool("Timing summary");
    const std::string level = prm.get("Compression");
    compression = level == "fast" ? DataOutBase::VtkFlags::best_speed :
                  level == "best" ? DataOutBase::VtkFlags::best_compression :
                                    DataOutBase::VtkFlags::no_compression;
    prm.leave_subsection();
    AssertThrow(!output_directory.empty(),
                ExcMessage("Output: the directory must not be empty."));
  }



  void
  OutputWriter::prepare_directory() const
  {
    std::string error;
    if (Utilities::MPI::this_mpi_process(communicator) == 0)
      {
        std::error_code code;
        std::filesystem::create_directories(output_directory, code);
        const std::string probe = output_directory + "/.bsmpm-write-test";
        if (code)
          error = code.message();
        else if (!std::ofstream(probe))
          error = "it is not writable";
        std::remove(probe.c_str());
      }
    error = Utilities::MPI::broadcast(communicator, error, 0);
    AssertThrow(error.empty(),
                ExcMessage("Output: cannot use the output directory '" +
                           output_directory + "': " + error + "."));
  }



  bool
  OutputWriter::writes_step(const unsigned int step,
                            const unsigned int n_steps) const
  {
    return interval > 0 && (step % interval == 0 || step == n_steps);
  }



  void
  OutputWriter::write_atomically(
    const std::string                         &path,
    const std::function<void(std::ostream &)> &writer)
  {
    const std::string temporary = path + ".tmp";
    {
      std::ofstream out(temporary);
      AssertThrow(out,
                  ExcMessage("Output: cannot write the file '" + path + "'."));
      writer(out);
      out.flush();
      AssertThrow(out,
                  ExcMessage("Output: writing the file '" + path +
                             "' failed (disk full?)."));
    }
    AssertThrow(std::rename(temporary.c_str(), path.c_str()) == 0,
                ExcMessage("Output: cannot rename '" + temporary + "' to '" +
                           path + "'."));
  }



  DataOutBase::VtkFlags
  OutputWriter::vtk_flags() const
  {
    DataOutBase::VtkFlags flags;
    flags.compression_level = compression;
    return flags;
  }



  void
  OutputWriter::write_root_file(
    const std::string                         &file,
    const std::function<void(std::ostream &)> &writer) const
  {
    if (Utilities::MPI::this_mpi_process(communicator) == 0)
      write_atomically(output_directory + "/" + file, writer);
  }



  void
  OutputWriter::write_series(
    const std::string                         &series,
    const unsigned int                         step,
    const double                               time,
    const std::function<void(std::ostream &)> &piece,
    const std::function<void(std::ostream &, const std::vector<std::string> &)>
      &record)
  {
    const unsigned int rank    = Utilities::MPI::this_mpi_process(communicator);
    const unsigned int n_ranks = Utilities::MPI::n_mpi_processes(communicator);
    const std::string  base = series + "-" + Utilities::int_to_string(step, 4);

    const auto piece_name = [&base](const unsigned int r) {
      return base + "." + Utilities::int_to_string(r) + ".vtu";
    };
    write_atomically(output_directory + "/" + piece_name(rank), piece);

    std::vector<std::string> pieces;
    for (unsigned int r = 0; r < n_ranks; ++r)
      pieces.push_back(piece_name(r));
    // The record must name pieces that exist: wait for all of them.
    MPI_Barrier(communicator);
    write_root_file(base + ".pvtu",
                    [&](std::ostream &out) { record(out, pieces); });
    collections[series].push_back({time, base + ".pvtu"});
  }



  template <int dim>
  void
  OutputWriter::write_series(const std::string              &series,
                             const unsigned int              step,
                             const double                    time,
                             const DataOutInterface<dim, 2> &data)
  {
    write_series(
      series,
      step,
      time,
      [&data](std::ostream &out) { data.write_vtu(out); },
      [&data](std::ostream &out, const std::vector<std::string> &pieces) {
        data.write_pvtu_record(out, pieces);
      });
  }



  void
  OutputWriter::write_serial_series(
    const std::string                         &series,
    const unsigned int                         step,
    const double                               time,
    const std::function<void(std::ostream &)> &writer)
  {
    const std::string file =
      series + "-" + Utilities::int_to_string(step, 4) + ".vtu";
    write_root_file(file, writer);
    collections[series].push_back({time, file});
  }



  void
  OutputWriter::write_collections() const
  {
    const auto write_pvd = [](std::ostream &out, const auto &datasets) {
      out << "<?xml version=\"1.0\"?>\n"
          << "<VTKFile type=\"Collection\" version=\"0.1\">\n"
          << "  <Collection>\n";
      for (const auto &d : datasets)
        out << "    <DataSet timestep=\"" << std::get<0>(d) << "\" part=\""
            << std::get<1>(d) << "\" file=\"" << std::get<2>(d) << "\"/>\n";
      out << "  </Collection>\n</VTKFile>\n";
    };

    std::vector<std::tuple<double, unsigned int, std::string>> all;
    unsigned int                                               part = 0;
    for (const auto &[series, records] : collections)
      {
        std::vector<std::tuple<double, unsigned int, std::string>> one;
        for (const auto &r : records)
          {
            one.emplace_back(r.time, 0, r.file);
            all.emplace_back(r.time, part, r.file);
          }
        write_root_file(series + ".pvd",
                        [&](std::ostream &out) { write_pvd(out, one); });
        ++part;
      }
    std::stable_sort(all.begin(), all.end(), [](const auto &a, const auto &b) {
      return std::get<0>(a) < std::get<0>(b);
    });
    write_root_file("solution.pvd",
                    [&](std::ostream &out) { write_pvd(out, all); });
  }



  template void
  OutputWriter::write_series<2>(const std::string &,
                                const unsigned int,
                                const double,
                                const DataOutInterface<2, 2> &);
} // namespace bsmpm
