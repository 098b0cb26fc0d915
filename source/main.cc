// bsmpm: the command-line driver. Everything else is in the library.
#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <bsmpm/scene.h>

#include <boost/archive/archive_exception.hpp>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace
{
  const char *usage =
    "Usage: bsmpm [options] scene.prm\n"
    "       mpirun -np N bsmpm [options] scene.prm\n"
    "\n"
    "Runs an implicit quasi-static material point analysis described by a\n"
    "parameter file, with B-spline boundary conditions.\n"
    "\n"
    "Options:\n"
    "  --set \"Section/Subsection/Name=value\"\n"
    "                      override one parameter of the file (repeatable)\n"
    "  --sweep \"Section/Name=v1,v2,...\"\n"
    "                      run the scene once per value in one process (values\n"
    "                      separated by ';' if they contain commas); run k\n"
    "                      writes into <Output/Directory>/sweep-<k>, and\n"
    "                      <Output/Directory>/sweep.json lists the values\n"
    "  --resume DIR        continue a run from its latest checkpoint in the\n"
    "                      output directory DIR (or from the checkpoint DIR),\n"
    "                      with its parameters; only Output/... may be --set\n"
    "                      (checkpoints: Output/Checkpoint interval)\n"
    "  --print-parameters  print every parameter with its documentation and\n"
    "                      default value, then exit\n"
    "  --help              print this message and exit\n";

  struct CommandLine
  {
    std::string              parameter_file;
    std::vector<std::string> overrides;
    std::string              sweep;
    std::string              resume;
    bool                     help             = false;
    bool                     print_parameters = false;
  };

  CommandLine
  parse_command_line(const int argc, char **argv)
  {
    CommandLine line;
    for (int i = 1; i < argc; ++i)
      {
        const std::string arg = argv[i];
        if (arg == "--help" || arg == "-h")
          line.help = true;
        else if (arg == "--print-parameters")
          line.print_parameters = true;
        else if (arg == "--set")
          {
            if (i + 1 >= argc)
              throw std::runtime_error("--set needs an argument "
                                       "\"Section/Name=value\".");
            line.overrides.emplace_back(argv[++i]);
          }
        else if (arg.rfind("--set=", 0) == 0)
          line.overrides.push_back(arg.substr(6));
        else if (arg == "--sweep" || arg.rfind("--sweep=", 0) == 0)
          {
            if (arg == "--sweep" && i + 1 >= argc)
              throw std::runtime_error("--sweep needs an argument "
                                       "\"Section/Name=v1,v2,...\".");
            if (!line.sweep.empty())
              throw std::runtime_error("only one --sweep is allowed.");
            line.sweep = arg == "--sweep" ? argv[++i] : arg.substr(8);
          }
        else if (arg == "--resume")
          {
            if (i + 1 >= argc)
              throw std::runtime_error("--resume needs a directory.");
            line.resume = argv[++i];
          }
        else if (!arg.empty() && arg[0] == '-')
          throw std::runtime_error("unknown option '" + arg +
                                   "' (see bsmpm --help).");
        else if (line.parameter_file.empty())
          line.parameter_file = arg;
        else
          throw std::runtime_error("more than one parameter file given ('" +
                                   line.parameter_file + "' and '" + arg +
                                   "').");
      }
    return line;
  }

  /** Every declared parameter as "Section/Subsection/Name", from the
   * ParameterHandler's own listing. */
  std::vector<std::string>
  declared_paths(const dealii::ParameterHandler &prm)
  {
    std::ostringstream listing;
    prm.print_parameters(listing, dealii::ParameterHandler::PRM);
    std::istringstream       lines(listing.str());
    std::vector<std::string> stack, paths;
    for (std::string line; std::getline(lines, line);)
      {
        line = dealii::Utilities::trim(line);
        if (line.empty() || line[0] == '#')
          continue;
        if (line.rfind("subsection ", 0) == 0)
          stack.push_back(dealii::Utilities::trim(line.substr(11)));
        else if (line == "end" && !stack.empty())
          stack.pop_back();
        else if (line.rfind("set ", 0) == 0)
          {
            std::string path;
            for (const auto &s : stack)
              path += s + "/";
            paths.push_back(path + dealii::Utilities::trim(
                                     line.substr(4, line.find('=') - 4)));
          }
      }
    return paths;
  }

  /** Edit distance (insertions, deletions, substitutions) ignoring case. */
  unsigned int
  edit_distance(const std::string &a, const std::string &b)
  {
    std::vector<unsigned int> row(b.size() + 1);
    for (unsigned int j = 0; j <= b.size(); ++j)
      row[j] = j;
    for (unsigned int i = 1; i <= a.size(); ++i)
      {
        unsigned int diagonal = row[0];
        row[0]                = i;
        for (unsigned int j = 1; j <= b.size(); ++j)
          {
            const unsigned int up = row[j];
            row[j]                = std::min(
              {row[j] + 1,
                              row[j - 1] + 1,
                              diagonal + (std::tolower(a[i - 1]) != std::tolower(b[j - 1]))});
            diagonal = up;
          }
      }
    return row[b.size()];
  }

  /** " Did you mean ...?" with the declared paths closest to @p path (all
   * those within a third of its length, at most three), or nothing. */
  std::string
  suggestion(const std::string &path, const std::vector<std::string> &paths)
  {
    std::vector<std::pair<unsigned int, std::string>> near;
    for (const auto &p : paths)
      near.emplace_back(edit_distance(path, p), p);
    std::sort(near.begin(), near.end());
    std::string text;
    for (unsigned int k = 0; k < near.size() && k < 3; ++k)
      if (near[k].first <= std::max<std::size_t>(2, path.size() / 3))
        text += (text.empty() ? "" : ", ") + ("\"" + near[k].second + "\"");
    return text.empty() ? "" : " Did you mean " + text + "?";
  }

  /** Throws, naming @p what and the closest declared names, unless
   * @p path is a declared parameter. */
  void
  check_declared(const std::string              &path,
                 const std::vector<std::string> &paths,
                 const std::string              &what)
  {
    if (std::find(paths.begin(), paths.end(), path) == paths.end())
      throw std::runtime_error(what + ": there is no parameter \"" + path +
                               "\"." + suggestion(path, paths) +
                               " (bsmpm --print-parameters lists them all.)");
  }

  /** "A/B/Name=value" as parameter-file text. */
  std::string
  override_as_prm(const std::string &assignment)
  {
    const auto equal = assignment.find('=');
    if (equal == std::string::npos)
      throw std::runtime_error("--set \"" + assignment +
                               "\": expected \"Section/Name=value\".");
    const std::string path  = assignment.substr(0, equal);
    const std::string value = assignment.substr(equal + 1);

    std::vector<std::string> parts;
    std::size_t              start = 0, slash;
    while ((slash = path.find('/', start)) != std::string::npos)
      {
        parts.push_back(path.substr(start, slash - start));
        start = slash + 1;
      }
    parts.push_back(path.substr(start));

    std::string text;
    for (unsigned int i = 0; i + 1 < parts.size(); ++i)
      text += "subsection " + parts[i] + "\n";
    text += "set " + parts.back() + " = " + value + "\n";
    for (unsigned int i = 0; i + 1 < parts.size(); ++i)
      text += "end\n";
    return text;
  }

  /** Why @p file, opened as @p in, cannot be read as a text file, or
   * nothing. (An ifstream opens a directory without complaint and reads
   * nothing from it.) */
  std::string
  unreadable(const std::filesystem::path &file, const std::ifstream &in)
  {
    std::error_code code;
    if (!std::filesystem::exists(file, code))
      return "no such file";
    if (std::filesystem::is_directory(file, code))
      return "it is a directory";
    if (!std::filesystem::is_regular_file(file, code))
      return "it is not a regular file";
    if (!in)
      return "it cannot be opened";
    return "";
  }



  /**
   * A parameter file with its "include" lines replaced by the files they
   * name, each resolved against the folder of the file that includes it
   * (deal.II would resolve them against the working directory). Remembers
   * where every line came from, to name it in error messages.
   */
  struct ParameterText
  {
    std::string                                       text;
    std::vector<std::pair<std::string, unsigned int>> origin;
    std::string                                       top; // the file given

    void
    expand(const std::filesystem::path &file,
           const unsigned int           depth       = 0,
           const std::string           &included_by = "")
    {
      if (depth == 0)
        top = file.string();
      if (depth > 16)
        throw std::runtime_error("'" + file.string() +
                                 "': includes nest too deep (a cycle?).");
      std::ifstream     in(file);
      const std::string problem = unreadable(file, in);
      if (!problem.empty())
        throw std::runtime_error(
          "cannot read the parameter file '" + file.string() + "'" +
          (included_by.empty() ? "" : " (included by " + included_by + ")") +
          ": " + problem + ".");
      std::string  line;
      unsigned int number = 0;
      while (std::getline(in, line))
        {
          ++number;
          const auto first = line.find_first_not_of(" \t");
          if (first != std::string::npos &&
              line.compare(first, 8, "include ") == 0)
            {
              std::string name = line.substr(first + 8);
              name.erase(name.find_last_not_of(" \t\r") + 1);
              name.erase(0, name.find_first_not_of(" \t"));
              std::filesystem::path included(name);
              if (included.is_relative())
                included = file.parent_path() / included;
              expand(included,
                     depth + 1,
                     "line " + std::to_string(number) + " of '" +
                       file.string() + "'");
              continue;
            }
          if (line.find('\0') != std::string::npos)
            throw std::runtime_error(
              "'" + file.string() + "' is not a parameter file: line " +
              std::to_string(number) + " holds binary data.");
          text += line + "\n";
          origin.emplace_back(file.string(), number);
        }
    }

    /** Where line @p n (1-based) of the text came from: "line L of 'F'". */
    std::string
    where(const unsigned int n) const
    {
      if (n == 0 || n > origin.size())
        return "the parameter file";
      return "line " + std::to_string(origin[n - 1].second) + " of '" +
             origin[n - 1].first + "'";
    }

    /**
     * The parameter path that line @p n names: "A/B/Name" for a "set Name"
     * line in subsections A, B; "A/B" for a "subsection B" line in A (then
     * @p subsection is set). Empty for other lines.
     */
    std::string
    path_at(const unsigned int n, bool &subsection) const
    {
      std::istringstream       lines(text);
      std::vector<std::string> stack;
      std::string              line;
      for (unsigned int k = 1; k <= n && std::getline(lines, line); ++k)
        {
          line = dealii::Utilities::trim(line.substr(0, line.find('#')));
          const bool enter = line.rfind("subsection ", 0) == 0;
          if (k == n)
            {
              subsection = enter;
              std::string path;
              for (const auto &s : stack)
                path += s + "/";
              if (enter)
                return path + dealii::Utilities::trim(line.substr(11));
              if (line.rfind("set ", 0) == 0)
                return path + dealii::Utilities::trim(
                                line.substr(4, line.find('=') - 4));
              return "";
            }
          if (enter)
            stack.push_back(dealii::Utilities::trim(line.substr(11)));
          else if (line == "end" && !stack.empty())
            stack.pop_back();
        }
      return "";
    }

    /** Replaces "Line <n> of file <<input>>" by the true file and line,
     * and "the parameter file <<input>>" by the file's name. */
    std::string
    locate(const std::string &message) const
    {
      const std::string key   = "Line <";
      const auto        start = message.find(key);
      if (start == std::string::npos)
        {
          const std::string input = "the parameter file <<input>>";
          const auto        at    = message.find(input);
          if (at == std::string::npos)
            return message;
          return message.substr(0, at) + "'" + top +
                 "' (with the files it includes)" +
                 message.substr(at + input.size());
        }
      const auto end = message.find("> of file <<input>>", start);
      if (end == std::string::npos)
        return message;
      const unsigned int n = std::stoul(
        message.substr(start + key.size(), end - start - key.size()));
      if (n == 0 || n > origin.size())
        return message;
      return message.substr(0, start) + "line " +
             std::to_string(origin[n - 1].second) + " of '" +
             origin[n - 1].first + "'" +
             message.substr(end + std::string("> of file <<input>>").size());
    }
  };

  /** The message of a deal.II exception without its source location. */
  std::string
  message_of(const dealii::ExceptionBase &e)
  {
    std::ostringstream info;
    e.print_info(info);
    std::string text = info.str();
    // Trim the indentation deal.II puts in front of each line.
    std::string        trimmed;
    std::istringstream lines(text);
    for (std::string line; std::getline(lines, line);)
      {
        const auto first = line.find_first_not_of(' ');
        if (first == std::string::npos)
          continue;
        trimmed += (trimmed.empty() ? "" : "\n") + line.substr(first);
      }
    return trimmed.empty() ? e.what() : trimmed;
  }

  /**
   * Tells, after an error on this process, whether every process has one,
   * by a barrier on a communicator of its own that a process still at work
   * (or waiting in a collective call for this one) does not enter.
   */
  class ErrorChannel
  {
  public:
    ErrorChannel()
    {
      MPI_Comm_dup(MPI_COMM_WORLD, &communicator);
    }

    ~ErrorChannel()
    {
      if (!pending)
        MPI_Comm_free(&communicator);
    }

    /** Whether all processes arrive here within @p seconds. */
    bool
    all_failed(const double seconds = 5.)
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
          std::this_thread::sleep_for(std::chrono::milliseconds(2));
        }
    }

  private:
    MPI_Comm communicator;
    bool     pending = false;
  };



  /**
   * Parses "A/B/Name=value" given as @p option ("--set", "--sweep") into
   * @p prm. Errors name the option and the assignment as typed, not the
   * text it was turned into.
   */
  void
  apply_override(dealii::ParameterHandler &prm,
                 const std::string        &assignment,
                 const std::string        &option)
  {
    const std::string as_typed = option + " \"" + assignment + "\"";
    // A line break would end the assignment and start a line of its own.
    if (assignment.find_first_of("\n\r") != std::string::npos)
      throw std::runtime_error(as_typed + ": the value must be a single line.");
    const std::string as_prm = override_as_prm(assignment);
    try
      {
        prm.parse_input_from_string(as_prm, option + " " + assignment);
      }
    catch (const dealii::ExceptionBase &e)
      {
        // "Line <n> of file <input string>: ..." names the generated text:
        // drop it, and put deal.II's message on one line.
        std::string message = message_of(e);
        if (message.rfind("Line <", 0) == 0 &&
            message.find(">:") != std::string::npos)
          message = message.substr(message.find(">:") + 2);
        std::string flat;
        for (const char c : message)
          if (!std::isspace(static_cast<unsigned char>(c)))
            flat += c;
          else if (!flat.empty() && flat.back() != ' ')
            flat += ' ';
        throw std::runtime_error(as_typed + ": " +
                                 dealii::Utilities::trim(flat));
      }
  }



  /**
   * A run started without mpirun is an MPI singleton. Open MPI 4 then starts
   * a helper daemon (orted) and probes the network transports (UCX and the
   * others) at MPI_Init: 0.45-0.95 s on the 2-core test machine, more than
   * a small scene's whole run. One process needs neither: it talks only to
   * itself. Open MPI reads its settings from the environment at MPI_Init,
   * so they are set here, each only if the user has not set it. Under
   * mpirun with every process on this node, the processes still need the
   * shared-memory transport, but not the probing of UCX, the network layer
   * of clusters: the point-to-point layer ob1 alone (0.25 s less at
   * np = 2 there, doc/benchmarks.md). Under another launcher nothing is set.
   */
  void
  start_mpi_quickly()
  {
#ifdef OMPI_MAJOR_VERSION
    const char *size  = std::getenv("OMPI_COMM_WORLD_SIZE");
    const char *local = std::getenv("OMPI_COMM_WORLD_LOCAL_SIZE");
    if (size != nullptr)
      {
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
} // namespace



int
main(int argc, char **argv)
{
  using namespace dealii;

  // --help and --print-parameters are answered before MPI starts and before
  // anything is built. Under mpirun only the first rank prints.
  CommandLine line;
  try
    {
      line = parse_command_line(argc, argv);
    }
  catch (const std::exception &e)
    {
      std::cerr << "bsmpm: error: " << e.what() << std::endl;
      return 1;
    }
  if (line.help || line.print_parameters)
    {
      const char *rank = std::getenv("OMPI_COMM_WORLD_RANK");
      if (rank == nullptr)
        rank = std::getenv("PMI_RANK");
      if (rank != nullptr && std::string(rank) != "0")
        return 0;
      if (line.help)
        std::cout << usage;
      else
        {
          ParameterHandler prm;
          bsmpm::Scene::declare_parameters(prm);
          prm.print_parameters(std::cout, ParameterHandler::PRM);
        }
      return 0;
    }

  start_mpi_quickly();
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const bool   root = Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0;
  ErrorChannel errors;

  // An error ends the run with exit code 1. Errors are meant to be found by
  // every process alike (ParameterTools::throw_if_any); one found by a
  // process alone would leave the others waiting for it in their next
  // collective call: then the run is stopped with its message.
  const auto fail = [&](const std::string &message) {
    if (errors.all_failed())
      {
        if (root)
          std::cerr << "bsmpm: error: " << message << std::endl;
        return 1;
      }
    std::cerr << "bsmpm: error: " << message << " (found by process "
              << Utilities::MPI::this_mpi_process(MPI_COMM_WORLD)
              << " alone: stopping the others)" << std::endl;
    MPI_Abort(MPI_COMM_WORLD, 1);
    return 1;
  };

  try
    {
      ParameterHandler prm;
      bsmpm::Scene::declare_parameters(prm);

      if (!line.resume.empty())
        {
          // A resumed run takes the parameters of its checkpoint.
          if (!line.parameter_file.empty() || !line.sweep.empty())
            throw std::runtime_error("--resume takes no parameter file and "
                                     "no --sweep.");
          const std::string from = bsmpm::Checkpoint::find(line.resume);
          bsmpm::Checkpoint::read_parameters(from, prm);
          for (const auto &assignment : line.overrides)
            {
              bsmpm::Checkpoint::check_resume_override(
                assignment.substr(0, assignment.find('=')));
              apply_override(prm, assignment, "--set");
            }
          if (root)
            std::cout << "resuming from " << from << "\n";
          bsmpm::Scene scene(MPI_COMM_WORLD);
          scene.parse_parameters(prm);
          scene.resume_from(from);
          try
            {
              scene.run();
            }
          catch (const boost::archive::archive_exception &e)
            {
              // Reading the checkpoint's archives failed; boost's message
              // ("input stream error") names nothing.
              if (e.code ==
                  boost::archive::archive_exception::output_stream_error)
                throw;
              throw std::runtime_error(
                "Checkpoint '" + from +
                "': its files 'state' and 'points' cannot be read: "
                "truncated or damaged (" +
                e.what() +
                "). Resume from an earlier checkpoint-<step> directory.");
            }
          return 0;
        }
      if (line.parameter_file.empty())
        throw std::runtime_error("no parameter file given.\n" +
                                 std::string(usage));
      ParameterText text;
      text.expand(std::filesystem::absolute(line.parameter_file));
      const std::vector<std::string> paths = declared_paths(prm);
      try
        {
          std::istringstream input(text.text);
          prm.parse_input(input, "<input>");
        }
      catch (const ExceptionBase &e)
        {
          // A misspelt name or subsection: say which and what is near.
          const std::string message = message_of(e);
          const auto        at      = message.find("Line <");
          if (at != std::string::npos)
            {
              const unsigned int       n = std::atoi(message.c_str() + at + 6);
              bool                     sub        = false;
              const std::string        path       = text.path_at(n, sub);
              std::vector<std::string> candidates = paths;
              if (sub)
                {
                  // The declared subsections: every prefix of a path.
                  candidates.clear();
                  for (const auto &p : paths)
                    for (auto slash = p.find('/'); slash != std::string::npos;
                         slash      = p.find('/', slash + 1))
                      candidates.push_back(p.substr(0, slash));
                  std::sort(candidates.begin(), candidates.end());
                  candidates.erase(std::unique(candidates.begin(),
                                               candidates.end()),
                                   candidates.end());
                }
              if (!path.empty() &&
                  std::find(candidates.begin(), candidates.end(), path) ==
                    candidates.end())
                throw std::runtime_error(
                  text.where(n) + ": there is no " +
                  (sub ? "subsection" : "parameter") + " \"" + path + "\"." +
                  suggestion(path, candidates) +
                  " (bsmpm --print-parameters lists them all.)");
            }
          throw std::runtime_error(text.locate(message));
        }
      for (const auto &assignment : line.overrides)
        {
          override_as_prm(assignment); // checks the form
          check_declared(assignment.substr(0, assignment.find('=')),
                         paths,
                         "--set \"" + assignment + "\"");
          apply_override(prm, assignment, "--set");
        }
      if (prm.get("Scene name").empty())
        prm.set("Scene name",
                std::filesystem::path(line.parameter_file).stem().string());

      if (line.sweep.empty())
        {
          bsmpm::Scene scene(MPI_COMM_WORLD);
          scene.parse_parameters(prm);
          scene.run();
          return 0;
        }

      // A sweep: one run per value, one directory per run, in one process.
      const auto equal = line.sweep.find('=');
      if (equal == std::string::npos)
        throw std::runtime_error("--sweep \"" + line.sweep +
                                 "\": expected \"Section/Name=v1,v2,...\".");
      const std::string path = line.sweep.substr(0, equal);
      check_declared(path, paths, "--sweep \"" + line.sweep + "\"");
      const std::string        list   = line.sweep.substr(equal + 1);
      std::vector<std::string> values = Utilities::split_string_list(
        list, list.find(';') != std::string::npos ? ';' : ',');
      values.erase(std::remove(values.begin(), values.end(), ""), values.end());
      if (values.empty())
        throw std::runtime_error("--sweep \"" + line.sweep + "\": no values.");
      // Every value is checked before the first run.
      for (const auto &value : values)
        apply_override(prm, path + "=" + value, "--sweep");
      prm.enter_subsection("Output");
      const std::string base = prm.get("Directory");
      prm.leave_subsection();

      std::ostringstream record;
      record << "{\n  \"parameter\": \"" << path << "\",\n  \"runs\": [";
      for (unsigned int k = 0; k < values.size(); ++k)
        {
          const std::string assignment = path + "=" + values[k];
          apply_override(prm, assignment, "--sweep");
          const std::string directory = base + "/sweep-" + std::to_string(k);
          prm.enter_subsection("Output");
          prm.set("Directory", directory);
          prm.leave_subsection();
          if (root)
            std::cout << "\nsweep " << k + 1 << " of " << values.size() << ": "
                      << assignment << "\n";
          bsmpm::Scene scene(MPI_COMM_WORLD);
          scene.parse_parameters(prm);
          scene.run();
          record << (k == 0 ? "" : ",") << "\n    {\"value\": \"" << values[k]
                 << "\", \"directory\": \"" << directory
                 << "\", \"summary\": \"" << directory << "/summary.json\"}";
        }
      record << "\n  ]\n}\n";
      if (root)
        {
          const std::string file = base + "/sweep.json";
          {
            std::ofstream out(file + ".tmp");
            out << record.str();
            if (!out)
              throw std::runtime_error("cannot write '" + file + "'.");
          }
          std::filesystem::rename(file + ".tmp", file);
        }
    }
  catch (const ExceptionBase &e)
    {
      return fail(message_of(e));
    }
  catch (const std::exception &e)
    {
      return fail(e.what());
    }
  return 0;
}
