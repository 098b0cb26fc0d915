// Checks of the command line of bsmpm and of the parameters it reads:
// (i)   CommandLine: every option in both of its forms, repeated --set,
//       --resume, --help, and the errors of an unknown option, a missing
//       argument, a second --sweep and a second parameter file;
// (ii)  a --set assignment as parameter text and set in a ParameterHandler,
//       with the errors of a malformed assignment, a bad value, a value
//       with a line break;
// (iii) ParameterNames: the declared paths and subsections, the edit
//       distance, and the suggestions for misspelt paths;
// (iv)  CommandLine::read_parameters on parameter files with includes
//       resolved against their own folder, --set on top, the scene named
//       after the file, and the errors of missing, unreadable, binary,
//       cyclic and misspelt files and of bad --set;
// (v)   --resume: the parameters of the latest complete checkpoint, --set
//       of Output only, and the errors;
// (vi)  ParameterSweep: values split by commas or semicolons, each run's
//       value and directory, sweep.json, and the errors;
// (vii) launched_as_first_process from the launcher's environment.
// Messages name files by absolute path: the working directory is printed
// as <dir>.

#include <deal.II/base/parameter_handler.h>

#include <bsmpm/io/command_line.h>
#include <bsmpm/io/error_report.h>
#include <bsmpm/io/mpi_start.h>
#include <bsmpm/io/parameter_names.h>
#include <bsmpm/io/parameter_sweep.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

// tests.h uses deallog unqualified: the using directive must come first.
using namespace dealii;

#include "../tests.h"

#include "../unit_test.h"

using namespace bsmpm;

namespace
{
  /** A few of bsmpm's parameters, declared here so that the test does not
   * depend on the whole scene. */
  void
  declare(ParameterHandler &prm)
  {
    prm.declare_entry("Scene name", "", Patterns::Anything(), "");
    prm.enter_subsection("Loading");
    prm.declare_entry("Load steps", "1", Patterns::Integer(1), "");
    prm.leave_subsection();
    prm.enter_subsection("Material");
    prm.declare_entry("Young's modulus", "1e6", Patterns::Double(0), "");
    prm.declare_entry("Poisson's ratio", "0.3", Patterns::Double(-1, 0.5), "");
    prm.leave_subsection();
    prm.enter_subsection("Boundary curves");
    prm.enter_subsection("Curve 1");
    prm.declare_entry("Points", "0, 0; 1, 0", Patterns::Anything(), "");
    prm.leave_subsection();
    prm.leave_subsection();
    prm.enter_subsection("Output");
    prm.declare_entry("Directory", "output", Patterns::Anything(), "");
    prm.declare_entry("Interval", "1", Patterns::Integer(0), "");
    prm.leave_subsection();
  }

  /** @p message with the working directory replaced by <dir>, the text
   * of --help by <usage>, and every line break by " | ". */
  std::string
  portable(std::string message)
  {
    const std::string usage = CommandLine::usage;
    if (const auto at = message.find(usage); at != std::string::npos)
      message.replace(at, usage.size(), "<usage>");
    while (!message.empty() && message.back() == '\n')
      message.pop_back();
    const std::string here = std::filesystem::current_path().string();
    for (std::size_t at; (at = message.find(here)) != std::string::npos;)
      message.replace(at, here.size(), "<dir>");
    for (std::size_t at; (at = message.find('\n')) != std::string::npos;)
      message.replace(at, 1, " | ");
    return message;
  }

  /** Prints "<label>: error: <message>" if @p f throws, and
   * "<label>: no error" if not. */
  void
  expect_error(const std::string &label, const std::function<void()> &f)
  {
    try
      {
        f();
        deallog << label << ": no error" << std::endl;
      }
    catch (const ExceptionBase &e)
      {
        deallog << label << ": error: " << portable(message_of(e)) << std::endl;
      }
    catch (const std::exception &e)
      {
        deallog << label << ": error: " << portable(e.what()) << std::endl;
      }
  }

  /** The command line "bsmpm <arguments>". */
  CommandLine
  parse(const std::vector<std::string> &arguments)
  {
    std::vector<const char *> argv = {"bsmpm"};
    for (const auto &a : arguments)
      argv.push_back(a.c_str());
    return CommandLine(argv.size(), argv.data());
  }

  void
  print(const std::string &label, const CommandLine &line)
  {
    deallog << label << ": file '" << line.parameter_file << "', set [";
    for (unsigned int i = 0; i < line.overrides.size(); ++i)
      deallog << (i == 0 ? "" : " | ") << line.overrides[i];
    deallog << "], sweep '" << line.sweep << "', resume '" << line.resume
            << "', help " << yes_no(line.help) << ", print parameters "
            << yes_no(line.print_parameters) << std::endl;
  }

  void
  write(const std::string &file, const std::string &text)
  {
    std::filesystem::create_directories(
      std::filesystem::path(file).parent_path());
    std::ofstream out(file, std::ios::binary);
    out << text;
  }

  /** The values the cases change. */
  void
  print_values(const std::string &label, ParameterHandler &prm)
  {
    deallog << label << ": scene '" << prm.get("Scene name") << "'";
    prm.enter_subsection("Loading");
    deallog << ", load steps " << prm.get("Load steps");
    prm.leave_subsection();
    prm.enter_subsection("Material");
    deallog << ", E " << prm.get("Young's modulus") << ", nu "
            << prm.get("Poisson's ratio");
    prm.leave_subsection();
    prm.enter_subsection("Boundary curves");
    prm.enter_subsection("Curve 1");
    deallog << ", curve 1 '" << prm.get("Points") << "'";
    prm.leave_subsection();
    prm.leave_subsection();
    prm.enter_subsection("Output");
    deallog << ", output '" << portable(prm.get("Directory")) << "' every "
            << prm.get("Interval") << std::endl;
    prm.leave_subsection();
  }



  // (i)
  void
  check_options()
  {
    deallog.push("options");
    print("file only", parse({"scene.prm"}));
    print("every form",
          parse({"--set",
                 "Loading/Load steps=3",
                 "scene.prm",
                 "--set=Material/Young's modulus=2e6",
                 "--sweep",
                 "Material/Poisson's ratio=0.1,0.2"}));
    print("--sweep=", parse({"--sweep=Loading/Load steps=1;2", "scene.prm"}));
    print("--resume", parse({"--resume", "out", "--set", "Output/Interval=0"}));
    print("-h", parse({"-h"}));
    print("--help and --print-parameters",
          parse({"--help", "--print-parameters"}));
    print("nothing", parse({}));

    for (const std::vector<std::string> &arguments :
         std::vector<std::vector<std::string>>{
           {"scene.prm", "--set"},
           {"scene.prm", "--sweep"},
           {"--resume"},
           {"--sweep=A/B=1", "--sweep", "A/C=2", "scene.prm"},
           {"--frobnicate", "scene.prm"},
           {"-x"},
           {"--set-value=1"},
           {"scene.prm", "square.prm"}})
      {
        std::string label;
        for (const auto &a : arguments)
          label += (label.empty() ? "" : " ") + a;
        expect_error(label, [&]() { parse(arguments); });
      }
    deallog.pop();
  }



  // (ii)
  void
  check_assignments()
  {
    deallog.push("set");
    for (const std::string assignment :
         {"Material/Young's modulus=2e6",
          "Scene name=column",
          "Boundary curves/Curve 1/Points=0, 0; 2, 1",
          "Output/Directory="})
      deallog << assignment << " as text: "
              << portable(CommandLine::as_parameter_text(assignment))
              << std::endl;
    expect_error("without '='", []() {
      CommandLine::as_parameter_text("Material/Young's modulus");
    });

    ParameterHandler prm;
    declare(prm);
    CommandLine::apply(prm, "Material/Young's modulus=2e6", "--set");
    CommandLine::apply(prm,
                       "Boundary curves/Curve 1/Points=0, 0; 2, 1",
                       "--set");
    CommandLine::apply(prm, "Scene name=column", "--set");
    print_values("applied", prm);
    expect_error("bad value", [&]() {
      CommandLine::apply(prm, "Loading/Load steps=two", "--set");
    });
    expect_error("bad value in a sweep", [&]() {
      CommandLine::apply(prm, "Loading/Load steps=0", "--sweep");
    });
    expect_error("line break", [&]() {
      CommandLine::apply(prm, "Loading/Load steps=1\nend\nend", "--set");
    });
    expect_error("undeclared", [&]() {
      CommandLine::apply(prm, "Material/Youngs modulus=1", "--set");
    });
    print_values("unchanged", prm);
    deallog.pop();
  }



  // (iii)
  void
  check_names()
  {
    deallog.push("names");
    ParameterHandler prm;
    declare(prm);
    const ParameterNames names(prm);
    for (const auto &p : names.parameters())
      deallog << "parameter \"" << p << "\"" << std::endl;
    for (const auto &s : names.subsections())
      deallog << "subsection \"" << s << "\"" << std::endl;

    for (const auto &[a, b] : std::vector<std::pair<std::string, std::string>>{
           {"kitten", "sitting"},
           {"Material", "material"},
           {"", "abc"},
           {"abc", ""},
           {"Load steps", "Load step"},
           {"flaw", "lawn"}})
      deallog << "edit distance '" << a << "' '" << b
              << "' = " << ParameterNames::edit_distance(a, b) << std::endl;

    for (const std::string path : {"Material/Young's modulos",
                                   "material/young's modulus",
                                   "Materials/Poisson ratio",
                                   "Loading/Load step",
                                   "Output/Intervals",
                                   "Load steps",
                                   "Nothing like it"})
      deallog << "suggestion for \"" << path
              << "\":" << ParameterNames::suggestion(path, names.parameters())
              << std::endl;
    deallog << "suggestion for \"Boundary curve/Curve1\":"
            << ParameterNames::suggestion("Boundary curve/Curve1",
                                          names.subsections())
            << std::endl;

    expect_error("declared", [&]() {
      names.check_declared("Loading/Load steps", "--set \"...\"");
    });
    expect_error("misspelt", [&]() {
      names.check_declared("Loading/Loadsteps", "--set \"...\"");
    });
    expect_error("a subsection",
                 [&]() { names.check_declared("Loading", "--set \"...\""); });
    deallog.pop();
  }



  // (iv)
  void
  check_parameter_files()
  {
    deallog.push("files");
    // The included file lies next to the scene, not in the working
    // directory; it includes one further down.
    write("scenes/common.prm",
          "subsection Material\n"
          "  set Young's modulus = 3e6\n"
          "end\n"
          "include deeper/curve.prm\n");
    write("scenes/deeper/curve.prm",
          "subsection Boundary curves\n"
          "  subsection Curve 1\n"
          "    set Points = 0, 0; 3, 0 # a comment\n"
          "  end\n"
          "end\n");
    write("scenes/column.prm",
          "# A scene.\n"
          "include common.prm\n"
          "subsection Loading\n"
          "  set Load steps = 4\n"
          "end\n");
    write("scenes/named.prm",
          "set Scene name = my scene\n"
          "  include   " +
            (std::filesystem::current_path() / "scenes/common.prm").string() +
            "  \n");

    const auto read = [](const std::string              &label,
                         const std::vector<std::string> &arguments) {
      ParameterHandler prm;
      declare(prm);
      parse(arguments).read_parameters(prm);
      print_values(label, prm);
    };
    read("column", {"scenes/column.prm"});
    read("column with --set",
         {"scenes/column.prm",
          "--set",
          "Loading/Load steps=5",
          "--set=Material/Poisson's ratio=0.25",
          "--set",
          "Loading/Load steps=6"});
    read("named", {"scenes/named.prm"});
    read("named by --set", {"--set", "Scene name=set", "scenes/column.prm"});

    write("scenes/misspelt.prm",
          "subsection Material\n"
          "  set Young's modulos = 1\n"
          "end\n");
    write("scenes/misspelt-subsection.prm",
          "\n"
          "subsection Materials\n"
          "  set Young's modulus = 1\n"
          "end\n");
    write("scenes/includes-misspelt.prm",
          "set Scene name = x\n"
          "include misspelt.prm\n");
    write("scenes/bad-value.prm",
          "subsection Loading\n"
          "  set Load steps = 0\n"
          "end\n");
    const char binary[] = "set Scene name = a\nset \0\n";
    write("scenes/binary.prm", std::string(binary, sizeof(binary) - 1));
    write("scenes/cycle.prm", "include cycle.prm\n");
    write("scenes/includes-missing.prm", "\ninclude nowhere.prm\n");
    write("scenes/unclosed.prm", "subsection Loading\n");

    for (const std::vector<std::string> &arguments :
         std::vector<std::vector<std::string>>{
           {},
           {"--set", "Loading/Load steps=2"},
           {"does-not-exist.prm"},
           {"scenes"},
           {"scenes/misspelt.prm"},
           {"scenes/misspelt-subsection.prm"},
           {"scenes/includes-misspelt.prm"},
           {"scenes/bad-value.prm"},
           {"scenes/binary.prm"},
           {"scenes/cycle.prm"},
           {"scenes/includes-missing.prm"},
           {"scenes/unclosed.prm"},
           {"scenes/column.prm", "--set", "Material/Young's modulos=1"},
           {"scenes/column.prm", "--set", "Materials/Young's modulus=1"},
           {"scenes/column.prm", "--set", "Loading"},
           {"scenes/column.prm", "--set", "Loading/Load steps"},
           {"scenes/column.prm", "--set", "Loading/Load steps=two"},
           {"scenes/column.prm", "--set", "Loading/Load steps=1\nend"}})
      {
        std::string label;
        for (const auto &a : arguments)
          label += (label.empty() ? "" : " ") + a;
        expect_error(portable(label), [&]() {
          ParameterHandler prm;
          declare(prm);
          parse(arguments).read_parameters(prm);
        });
      }
    deallog.pop();
  }



  // (v)
  void
  check_resume()
  {
    deallog.push("resume");
    const std::string parameters = "subsection Loading\n"
                                   "  set Load steps = 7\n"
                                   "end\n"
                                   "subsection Output\n"
                                   "  set Directory = elsewhere\n"
                                   "  set Interval = 3\n"
                                   "end\n";
    for (const std::string step : {"checkpoint-2", "checkpoint-10"})
      for (const std::string file : {"state", "points", "parameters.prm"})
        write("run/" + step + "/" + file, file == "state" ? "" : parameters);
    // Not complete: neither is the latest.
    write("run/checkpoint-11/parameters.prm", parameters);
    write("run/checkpoint-12.tmp/state", "");

    for (const std::vector<std::string> &arguments :
         std::vector<std::vector<std::string>>{
           {"--resume", "run"},
           {"--resume", "run/checkpoint-2/", "--set", "Output/Interval=0"}})
      {
        ParameterHandler prm;
        declare(prm);
        const std::string from =
          parse(arguments).read_checkpoint_parameters(prm);
        print_values("from " + from, prm);
      }
    for (const std::vector<std::string> &arguments :
         std::vector<std::vector<std::string>>{
           {"--resume", "run", "scene.prm"},
           {"--resume", "run", "--sweep", "Loading/Load steps=1,2"},
           {"--resume", "nowhere"},
           {"--resume", "scenes"},
           {"--resume", "run", "--set", "Loading/Load steps=2"},
           {"--resume", "run", "--set", "Output/Interval=-1"}})
      {
        std::string label;
        for (const auto &a : arguments)
          label += (label.empty() ? "" : " ") + a;
        expect_error(label, [&]() {
          ParameterHandler prm;
          declare(prm);
          parse(arguments).read_checkpoint_parameters(prm);
        });
      }
    deallog.pop();
  }



  // (vi)
  void
  check_sweep()
  {
    deallog.push("sweep");
    for (const std::string list :
         {"1,2,3", "1, 2 ,3", "0, 0; 1, 1; 2, 0", "1;2", "1,,2,", "", " , ; "})
      {
        deallog << "split '" << list << "':";
        for (const auto &v : ParameterSweep::split_values(list))
          deallog << " '" << v << "'";
        deallog << std::endl;
      }

    ParameterHandler prm;
    declare(prm);
    prm.enter_subsection("Output");
    prm.set("Directory", "study");
    prm.leave_subsection();
    // Values that hold commas are separated by semicolons.
    const ParameterSweep sweep(
      "Boundary curves/Curve 1/Points=0, 0, 1, 0;0, 0, 2, 0; 0, 0, 3, 0", prm);
    deallog << "parameter \"" << sweep.parameter() << "\", "
            << sweep.values().size() << " runs" << std::endl;
    print_values("after the checks", prm);
    for (unsigned int k = 0; k < sweep.values().size(); ++k)
      {
        deallog << "run " << k << ": " << sweep.set_run(k, prm) << std::endl;
        print_values("run " + std::to_string(k), prm);
      }
    deallog << "sweep.json: " << portable(sweep.record()) << std::endl;
    std::filesystem::create_directories("study");
    sweep.write_record();
    std::ifstream      in("study/sweep.json");
    std::ostringstream written;
    written << in.rdbuf();
    deallog << "written as the record: "
            << yes_no(written.str() == sweep.record())
            << ", no temporary left: "
            << yes_no(!std::filesystem::exists("study/sweep.json.tmp"))
            << std::endl;

    // A sweep of the output directory writes into its last value.
    {
      ParameterHandler prm;
      declare(prm);
      const ParameterSweep directories("Output/Directory=a,b", prm);
      deallog << "sweep of the directory: " << directories.directory(0) << ", "
              << directories.directory(1) << std::endl;
    }

    for (const std::string argument : {"Loading/Load steps",
                                       "Loading/Load step=1,2",
                                       "Loading/Load steps=",
                                       "Loading/Load steps= , ",
                                       "Loading/Load steps=1,0",
                                       "Loading/Load steps=1\n2"})
      expect_error("--sweep " + portable(argument), [&]() {
        ParameterHandler prm;
        declare(prm);
        ParameterSweep(argument, prm);
      });
    deallog.pop();
  }



  // (vii)
  void
  check_first_process()
  {
    deallog.push("launched");
    unsetenv("OMPI_COMM_WORLD_RANK");
    unsetenv("PMI_RANK");
    deallog << "alone: " << yes_no(launched_as_first_process()) << std::endl;
    setenv("OMPI_COMM_WORLD_RANK", "0", 1);
    deallog << "Open MPI rank 0: " << yes_no(launched_as_first_process())
            << std::endl;
    setenv("OMPI_COMM_WORLD_RANK", "1", 1);
    deallog << "Open MPI rank 1: " << yes_no(launched_as_first_process())
            << std::endl;
    unsetenv("OMPI_COMM_WORLD_RANK");
    setenv("PMI_RANK", "2", 1);
    deallog << "PMI rank 2: " << yes_no(launched_as_first_process())
            << std::endl;
    unsetenv("PMI_RANK");
    deallog.pop();
  }
} // namespace



BSMPM_UNIT_TEST("io/command_line")
{
  initlog();
  check_options();
  check_assignments();
  check_names();
  check_parameter_files();
  check_resume();
  check_sweep();
  check_first_process();
}
