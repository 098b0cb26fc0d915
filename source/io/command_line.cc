#include <deal.II/base/utilities.h>

#include <bsmpm/io/checkpoint.h>
#include <bsmpm/io/command_line.h>
#include <bsmpm/io/error_report.h>
#include <bsmpm/io/parameter_file.h>
#include <bsmpm/io/parameter_names.h>

#include <cctype>
#include <filesystem>
#include <stdexcept>

namespace bsmpm
{
  const char *const CommandLine::usage =
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



  CommandLine::CommandLine(const int argc, const char *const *argv)
  {
    for (int i = 1; i < argc; ++i)
      {
        const std::string arg = argv[i];
        if (arg == "--help" || arg == "-h")
          help = true;
        else if (arg == "--print-parameters")
          print_parameters = true;
        else if (arg == "--set")
          {
            if (i + 1 >= argc)
              throw std::runtime_error("--set needs an argument "
                                       "\"Section/Name=value\".");
            overrides.emplace_back(argv[++i]);
          }
        else if (arg.rfind("--set=", 0) == 0)
          overrides.push_back(arg.substr(6));
        else if (arg == "--sweep" || arg.rfind("--sweep=", 0) == 0)
          {
            if (arg == "--sweep" && i + 1 >= argc)
              throw std::runtime_error("--sweep needs an argument "
                                       "\"Section/Name=v1,v2,...\".");
            if (!sweep.empty())
              throw std::runtime_error("only one --sweep is allowed.");
            sweep = arg == "--sweep" ? argv[++i] : arg.substr(8);
          }
        else if (arg == "--resume")
          {
            if (i + 1 >= argc)
              throw std::runtime_error("--resume needs a directory.");
            resume = argv[++i];
          }
        else if (!arg.empty() && arg[0] == '-')
          throw std::runtime_error("unknown option '" + arg +
                                   "' (see bsmpm --help).");
        else if (parameter_file.empty())
          parameter_file = arg;
        else
          throw std::runtime_error("more than one parameter file given ('" +
                                   parameter_file + "' and '" + arg + "').");
      }
  }



  void
  CommandLine::read_parameters(ParameterHandler &prm) const
  {
    if (parameter_file.empty())
      throw std::runtime_error("no parameter file given.\n" +
                               std::string(usage));
    const ParameterFile file(std::filesystem::absolute(parameter_file));
    // Listed before parsing: the names declared, whatever the values.
    const ParameterNames declared(prm);
    file.parse_into(prm, declared);
    for (const auto &assignment : overrides)
      {
        as_parameter_text(assignment); // checks the form
        declared.check_declared(assignment.substr(0, assignment.find('=')),
                                "--set \"" + assignment + "\"");
        apply(prm, assignment, "--set");
      }
    if (prm.get("Scene name").empty())
      prm.set("Scene name",
              std::filesystem::path(parameter_file).stem().string());
  }



  std::string
  CommandLine::read_checkpoint_parameters(ParameterHandler &prm) const
  {
    if (!parameter_file.empty() || !sweep.empty())
      throw std::runtime_error("--resume takes no parameter file and "
                               "no --sweep.");
    const std::string from = Checkpoint::find(resume);
    Checkpoint::read_parameters(from, prm);
    for (const auto &assignment : overrides)
      {
        Checkpoint::check_resume_override(
          assignment.substr(0, assignment.find('=')), from, prm);
        apply(prm, assignment, "--set");
      }
    return from;
  }



  void
  CommandLine::apply(ParameterHandler  &prm,
                     const std::string &assignment,
                     const std::string &option)
  {
    const std::string as_typed = option + " \"" + assignment + "\"";
    // A line break would end the assignment and start a line of its own.
    if (assignment.find_first_of("\n\r") != std::string::npos)
      throw std::runtime_error(as_typed + ": the value must be a single line.");
    const std::string text = as_parameter_text(assignment);
    try
      {
        prm.parse_input_from_string(text, option + " " + assignment);
      }
    catch (const ExceptionBase &e)
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
        throw std::runtime_error(as_typed + ": " + Utilities::trim(flat));
      }
  }



  std::string
  CommandLine::as_parameter_text(const std::string &assignment)
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
} // namespace bsmpm
