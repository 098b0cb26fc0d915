#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <bsmpm/io/checkpoint.h>
#include <bsmpm/nonlinear/load_stages.h>

#include <boost/archive/binary_iarchive.hpp>
#include <boost/archive/binary_oarchive.hpp>
#include <boost/serialization/map.hpp>
#include <boost/serialization/string.hpp>
#include <boost/serialization/vector.hpp>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>

namespace boost
{
  namespace serialization
  {
    // The summary is plain data: archived member by member, outside it.
    template <class Archive>
    void
    serialize(Archive &ar, bsmpm::RunSummary::Step &s, const unsigned int)
    {
      ar &s.number &s.stage &s.load_factor &s.solver &s.iterations &s
        .refinement_steps &s.relative_residual &s.n_active_cells &s
        .increments &s.n_yielded &s.newton_residuals &s.newton_corrections &s
        .quantities;
    }

    template <class Archive>
    void
    serialize(Archive &ar, bsmpm::RunSummary &s, const unsigned int)
    {
      ar &s.scene &s.n_cells &s.n_dofs &s.n_material_points &s
        .n_tracking_points &s.load_steps &s.steps &s.errors &s.quantities &s
        .timing;
    }
  } // namespace serialization
} // namespace boost

namespace bsmpm
{
  namespace
  {
    namespace fs = std::filesystem;

    /** First line of every archive: what it is and in which format. */
    const std::string  magic = "bsmpm checkpoint";
    const unsigned int version =
      7; // 7: the stage of a step, the collapse detector's stage

    /** What both archives start with, checked before anything else is
     * read. */
    struct Header
    {
      std::string        what;
      unsigned int       format       = 0;
      unsigned int       n_properties = 0;
      unsigned int       step         = 0;
      unsigned int       n_processes  = 0;
      unsigned long long n_particles  = 0;

      template <class Archive>
      void
      serialize(Archive &ar, const unsigned int)
      {
        ar &what &format &n_properties &step &n_processes &n_particles;
      }
    };

    /** The step of a directory named checkpoint-<step>, or -1. */
    long
    step_of(const fs::path &path)
    {
      const std::string name = path.filename().string();
      const std::string head = "checkpoint-";
      if (name.rfind(head, 0) != 0 || name.size() == head.size() ||
          name.find_first_not_of("0123456789", head.size()) !=
            std::string::npos)
        return -1;
      return std::stol(name.substr(head.size()));
    }

    /** Whether @p path holds a complete checkpoint. */
    bool
    complete(const fs::path &path)
    {
      std::error_code code;
      return fs::is_regular_file(path / "state", code) &&
             fs::is_regular_file(path / "points", code) &&
             fs::is_regular_file(path / "parameters.prm", code);
    }

    /** Throws on every process the message of process 0, if any: errors of
     * the files process 0 writes must not leave the others waiting. */
    void
    throw_if_root_failed(const std::string &message, const MPI_Comm comm)
    {
      const std::string text = Utilities::MPI::broadcast(comm, message, 0);
      AssertThrow(text.empty(), ExcMessage(text));
    }

    /** Opens @p file of checkpoint @p directory and checks its header. */
    Header
    read_header(boost::archive::binary_iarchive &archive,
                const std::string               &directory)
    {
      Header header;
      archive >> header;
      AssertThrow(header.what == magic && header.format == version,
                  ExcMessage("Checkpoint '" + directory +
                             "': not a checkpoint of this version of bsmpm "
                             "(format " +
                             std::to_string(header.format) + ", expected " +
                             std::to_string(version) + ")."));
      AssertThrow(
        header.n_properties == MaterialPoints::Property::n_properties ||
          header.n_properties ==
            MaterialPoints::Property::n_properties_inelastic,
        ExcMessage(
          "Checkpoint '" + directory + "': its points carry " +
          std::to_string(header.n_properties) +
          " properties each, this bsmpm " +
          std::to_string(MaterialPoints::Property::n_properties) + " or " +
          std::to_string(MaterialPoints::Property::n_properties_inelastic) +
          ": it was written by another version and cannot be "
          "resumed by this one."));
      return header;
    }
  } // namespace



  Checkpoint::Checkpoint(const MPI_Comm communicator)
    : communicator(communicator)
  {}



  void
  Checkpoint::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Output");
    prm.declare_entry(
      "Checkpoint interval",
      "0",
      Patterns::Integer(0),
      "Write a checkpoint every this many load steps into "
      "<Directory>/checkpoint-<step> (the last two are kept, and in a "
      "scene in stages also the last step of every stage but the last, "
      "from which a later stage can be resumed with changed parameters); "
      "`bsmpm --resume <Directory>` continues the run from the latest. "
      "0 writes none.");
    prm.leave_subsection();
  }



  void
  Checkpoint::parse_parameters(ParameterHandler &prm)
  {
    std::ostringstream text;
    prm.print_parameters(text, ParameterHandler::ShortPRM);
    parameters = text.str();
    prm.enter_subsection("Output");
    interval         = prm.get_integer("Checkpoint interval");
    output_directory = prm.get("Directory");
    prm.leave_subsection();
  }



  bool
  Checkpoint::writes_step(const unsigned int step,
                          const unsigned int n_steps) const
  {
    return interval > 0 &&
           (step % interval == 0 || stage_ends.count(step) > 0) &&
           step < n_steps;
  }



  void
  Checkpoint::write(const unsigned int         step,
                    const BackgroundGrid      &grid,
                    MaterialPoints            &points,
                    const RunSummary          &summary,
                    const OutputWriter        &output,
                    const std::vector<CellId> &weak_cells,
                    const std::string         &scene_state)
  {
    const bool     root = Utilities::MPI::this_mpi_process(communicator) == 0;
    const fs::path target =
      fs::path(output_directory) / ("checkpoint-" + std::to_string(step));
    const fs::path temporary = target.string() + ".tmp";

    std::string error;
    if (root)
      {
        std::error_code code;
        fs::remove_all(temporary, code);
        fs::create_directories(temporary, code);
        if (code)
          error = "Checkpoint: cannot create '" + temporary.string() +
                  "': " + code.message() + ".";
      }
    throw_if_root_failed(error, communicator);

    // Grid and points, by deal.II (collective, MPI-IO into shared files).
    auto &handler = points.particle_handler();
    handler.prepare_for_serialization();
    grid.triangulation().save((temporary / "triangulation").string());

    std::vector<CellId> all_weak_cells;
    for (const auto &part : Utilities::MPI::gather(communicator, weak_cells, 0))
      all_weak_cells.insert(all_weak_cells.end(), part.begin(), part.end());

    if (root)
      {
        Header header;
        header.what         = magic;
        header.format       = version;
        header.n_properties = handler.n_properties_per_particle();
        header.step         = step;
        header.n_processes  = Utilities::MPI::n_mpi_processes(communicator);
        header.n_particles  = handler.n_global_particles();
        const auto write = [&](const std::string                         &name,
                               const std::function<void(std::ostream &)> &f) {
          std::ofstream out(temporary / name, std::ios::binary);
          f(out);
          out.flush();
          if (!out && error.empty())
            error = "Checkpoint: writing '" + (temporary / name).string() +
                    "' failed (disk full?).";
        };
        write("points", [&](std::ostream &out) {
          boost::archive::binary_oarchive archive(out);
          archive << header << handler;
        });
        write("state", [&](std::ostream &out) {
          boost::archive::binary_oarchive archive(out);
          archive << header << summary << output << all_weak_cells;
        });
        write("parameters.prm", [&](std::ostream &out) { out << parameters; });
        if (!scene_state.empty())
          write("scene", [&](std::ostream &out) { out << scene_state; });

        // Keep only the one before, then publish the new one: removing
        // the older ones first means a run killed at any moment leaves at
        // most two complete checkpoints, the newest of them intact.
        std::error_code code;
        if (error.empty())
          for (const auto &entry :
               fs::directory_iterator(output_directory, code))
            {
              const fs::path    p = entry.path();
              const std::string n = p.filename().string();
              const bool        stale_temporary =
                n.rfind("checkpoint-", 0) == 0 && p.extension() == ".tmp";
              const long at = step_of(p);
              if ((at >= 0 || stale_temporary) && p != temporary &&
                  n != previous &&
                  stage_ends.count(static_cast<unsigned int>(at)) == 0)
                fs::remove_all(p, code);
            }
        if (error.empty())
          {
            fs::remove_all(target, code);
            fs::rename(temporary, target, code);
            if (code)
              error = "Checkpoint: cannot rename '" + temporary.string() +
                      "': " + code.message() + ".";
          }
      }
    throw_if_root_failed(error, communicator);
    previous = target.filename().string();
  }



  std::string
  Checkpoint::find(const std::string &path)
  {
    const fs::path given(path);
    AssertThrow(fs::is_directory(given),
                ExcMessage("--resume '" + path + "': no such directory."));
    if (complete(given))
      return given.string();
    long     best = -1;
    fs::path found;
    for (const auto &entry : fs::directory_iterator(given))
      if (const long s = step_of(entry.path()); s > best && complete(entry))
        {
          best  = s;
          found = entry.path();
        }
    AssertThrow(best >= 0,
                ExcMessage("--resume '" + path +
                           "': neither a checkpoint nor an output directory "
                           "with one (checkpoint-<step>; write them with "
                           "Output/Checkpoint interval)."));
    return found.string();
  }



  void
  Checkpoint::read_parameters(const std::string &directory,
                              ParameterHandler  &prm)
  {
    const std::string file = directory + "/parameters.prm";
    std::ifstream     in(file);
    AssertThrow(in, ExcMessage("Checkpoint: cannot read '" + file + "'."));
    prm.parse_input(in, file);
    fs::path parent = fs::path(directory).lexically_normal();
    if (!parent.has_filename())
      parent = parent.parent_path();
    prm.enter_subsection("Output");
    prm.set("Directory",
            parent.parent_path().empty() ? std::string(".") :
                                           parent.parent_path().string());
    prm.leave_subsection();
  }



  void
  Checkpoint::check_resume_override(const std::string &path,
                                    const std::string &directory,
                                    ParameterHandler  &prm)
  {
    if (path.rfind("Output/", 0) == 0)
      return;
    const std::string refused =
      "--set \"" + path +
      "=...\" with --resume: a resumed run keeps the parameters of its "
      "checkpoint; only those of Output may change, and in a scene in "
      "stages the number of stages, the stages after the checkpoint's and "
      "the materials and points of the bodies they build";
    // A further body that a stage builds belongs to that stage.
    const std::string body_head = "Body ";
    unsigned int      body      = 0;
    if (path.rfind(body_head, 0) == 0)
      body = std::atoi(path.c_str() + body_head.size());
    AssertThrow(path.rfind("Stages/", 0) == 0 || body >= 2,
                ExcMessage(refused + "."));
    // The stage that the checkpoint's step belongs to (the parameters
    // are still the checkpoint's): that stage and those before it have
    // run, the ones after it may change.
    LoadStages stages;
    stages.parse_parameters(prm, false);
    AssertThrow(stages.staged(),
                ExcMessage(refused + "; the checkpoint's scene has one "
                                     "stage (Loading/Load steps)."));
    fs::path where = fs::path(directory).lexically_normal();
    if (!where.has_filename())
      where = where.parent_path();
    const long         step = step_of(where);
    const unsigned int reached =
      step > 0 ? stages.step(static_cast<unsigned int>(step)).stage : 1;
    const std::string head = "Stages/Stage ";
    unsigned int      k    = 0;
    if (path.rfind(head, 0) == 0)
      k = std::atoi(path.c_str() + head.size());
    if (body >= 2)
      {
        const std::string section = body_head + std::to_string(body);
        AssertThrow(path != section + "/Name", ExcMessage(refused + "."));
        prm.enter_subsection(section);
        const std::string name = prm.get("Name");
        prm.leave_subsection();
        for (unsigned int j = 1; j <= stages.n_stages() && !name.empty(); ++j)
          for (const std::string &built : stages.stage(j).construction)
            if (built == name)
              k = j;
        AssertThrow(k > 0,
                    ExcMessage(refused + ": " + section +
                               " is there from the start."));
      }
    AssertThrow(k > reached || path == "Stages/Number of stages",
                ExcMessage(refused + ": the checkpoint (step " +
                           std::to_string(step) + ") is in stage " +
                           std::to_string(reached) + "."));
  }



  void
  Checkpoint::resume_from(const std::string &directory)
  {
    resume_directory = directory;
    fs::path path    = fs::path(directory).lexically_normal();
    if (!path.has_filename())
      path = path.parent_path();
    previous = path.filename().string();
  }



  std::string
  Checkpoint::triangulation_file() const
  {
    return resuming() ? resume_directory + "/triangulation" : "";
  }



  void
  Checkpoint::read_points(MaterialPoints &points) const
  {
    auto         &handler = points.particle_handler();
    std::ifstream in(resume_directory + "/points", std::ios::binary);
    AssertThrow(in,
                ExcMessage("Checkpoint: cannot read '" + resume_directory +
                           "/points'."));
    boost::archive::binary_iarchive archive(in);
    const Header header = read_header(archive, resume_directory);
    AssertThrow(header.n_properties == handler.n_properties_per_particle(),
                ExcMessage("Checkpoint '" + resume_directory +
                           "': its points carry " +
                           std::to_string(header.n_properties) +
                           " properties, the scene's constitutive model " +
                           std::to_string(handler.n_properties_per_particle()) +
                           ": the parameters were changed."));
    archive >> handler;
    handler.deserialize();
    AssertThrow(handler.n_global_particles() == header.n_particles,
                ExcMessage("Checkpoint '" + resume_directory + "': " +
                           std::to_string(handler.n_global_particles()) +
                           " points read, " +
                           std::to_string(header.n_particles) + " written."));
  }



  unsigned int
  Checkpoint::read_state(RunSummary          &summary,
                         OutputWriter        &output,
                         std::vector<CellId> &weak_cells) const
  {
    std::ifstream in(resume_directory + "/state", std::ios::binary);
    AssertThrow(in,
                ExcMessage("Checkpoint: cannot read '" + resume_directory +
                           "/state'."));
    boost::archive::binary_iarchive archive(in);
    const Header header = read_header(archive, resume_directory);
    archive >> summary >> output >> weak_cells;
    return header.step;
  }


  std::string
  Checkpoint::read_scene_state() const
  {
    std::ifstream in(resume_directory + "/scene", std::ios::binary);
    if (!in)
      return std::string();
    return std::string(std::istreambuf_iterator<char>(in),
                       std::istreambuf_iterator<char>());
  }
} // namespace bsmpm
