// bsmpm: the command-line driver. Everything else is in the library.
#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <bsmpm/scene.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
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
    "  --print-parameters  print every parameter with its documentation and\n"
    "                      default value, then exit\n"
    "  --help              print this message and exit\n";

  struct CommandLine
  {
    std::string              parameter_file;
    std::vector<std::string> overrides;
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

    void
    expand(const std::filesystem::path &file, const unsigned int depth = 0)
    {
      if (depth > 16)
        throw std::runtime_error("'" + file.string() +
                                 "': includes nest too deep (a cycle?).");
      std::ifstream in(file);
      if (!in)
        throw std::runtime_error("cannot read the parameter file '" +
                                 file.string() + "'.");
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
              expand(included, depth + 1);
              continue;
            }
          text += line + "\n";
          origin.emplace_back(file.string(), number);
        }
    }

    /** Replaces "Line <n> of file <<input>>" by the true file and line. */
    std::string
    locate(const std::string &message) const
    {
      const std::string key   = "Line <";
      const auto        start = message.find(key);
      if (start == std::string::npos)
        return message;
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
} // namespace



int
main(int argc, char **argv)
{
  using namespace dealii;
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const bool root = Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0;

  try
    {
      const CommandLine line = parse_command_line(argc, argv);
      ParameterHandler  prm;
      bsmpm::Scene::declare_parameters(prm);

      if (line.help)
        {
          if (root)
            std::cout << usage;
          return 0;
        }
      if (line.print_parameters)
        {
          if (root)
            prm.print_parameters(std::cout, ParameterHandler::PRM);
          return 0;
        }
      if (line.parameter_file.empty())
        throw std::runtime_error("no parameter file given.\n" +
                                 std::string(usage));
      if (!std::filesystem::is_regular_file(line.parameter_file))
        throw std::runtime_error("cannot read the parameter file '" +
                                 line.parameter_file + "'.");

      ParameterText text;
      text.expand(std::filesystem::absolute(line.parameter_file));
      try
        {
          std::istringstream input(text.text);
          prm.parse_input(input, "<input>");
        }
      catch (const ExceptionBase &e)
        {
          throw std::runtime_error(text.locate(message_of(e)));
        }
      for (const auto &assignment : line.overrides)
        prm.parse_input_from_string(override_as_prm(assignment),
                                    "--set " + assignment);
      if (prm.get("Scene name").empty())
        prm.set("Scene name",
                std::filesystem::path(line.parameter_file).stem().string());

      bsmpm::Scene scene(MPI_COMM_WORLD);
      scene.parse_parameters(prm);
      scene.run();
    }
  catch (const ExceptionBase &e)
    {
      if (root)
        std::cerr << "bsmpm: error: " << message_of(e) << std::endl;
      return 1;
    }
  catch (const std::exception &e)
    {
      if (root)
        std::cerr << "bsmpm: error: " << e.what() << std::endl;
      return 1;
    }
  return 0;
}
