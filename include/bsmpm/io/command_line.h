#ifndef bsmpm_command_line_h
#define bsmpm_command_line_h

#include <deal.II/base/parameter_handler.h>

#include <string>
#include <vector>

namespace bsmpm
{
  using namespace dealii;

  /**
   * The command line of bsmpm (CommandLine::usage) and the parameters it
   * asks for.
   *
   * Parsing only records what was typed: whether the options make sense
   * together, the parameter file and the names given to --set are checked
   * when the parameters are read (read_parameters() for a new run,
   * read_checkpoint_parameters() for --resume), after MPI has started, so
   * that every process finds the same errors and they are reported once.
   */
  class CommandLine
  {
  public:
    /** The text of bsmpm --help. */
    static const char *const usage;

    /** Nothing given. */
    CommandLine() = default;

    /**
     * Parses the options and the parameter file of @p argv. Throws with a
     * message on an unknown option, an option without its argument, a
     * second --sweep or a second parameter file.
     */
    CommandLine(const int argc, const char *const *argv);

    /** The parameter file; empty if none was given. */
    std::string parameter_file;
    /** The arguments of --set, "Section/Name=value", in their order. */
    std::vector<std::string> overrides;
    /** The argument of --sweep, "Section/Name=v1,v2,..."; empty if none
     * (ParameterSweep). */
    std::string sweep;
    /** The argument of --resume, a checkpoint or output directory; empty if
     * none. */
    std::string resume;
    /** --help or -h. */
    bool help = false;
    /** --print-parameters. */
    bool print_parameters = false;

    /**
     * Reads the parameters of a new run into @p prm, in which they are
     * declared: the parameter file with the files it includes
     * (ParameterFile), then every --set, each checked to name a declared
     * parameter. The scene is named after the file unless the parameters
     * name it ("Scene name").
     */
    void
    read_parameters(ParameterHandler &prm) const;

    /**
     * For --resume: reads the parameters of the checkpoint to resume from
     * into @p prm (Checkpoint::read_parameters()), then every --set, each
     * checked to be one that may change on resuming. Returns the
     * checkpoint's directory. Throws if a parameter file or --sweep was
     * given too.
     */
    std::string
    read_checkpoint_parameters(ParameterHandler &prm) const;

    /**
     * Sets the parameter that @p assignment "A/B/Name=value", given with
     * the command-line option @p option ("--set", "--sweep"), names in
     * @p prm, with deal.II's checks of the value. Errors name the option
     * and the assignment as typed, not the text it is turned into
     * (as_parameter_text()).
     */
    static void
    apply(ParameterHandler  &prm,
          const std::string &assignment,
          const std::string &option);

    /** "A/B/Name=value" as parameter-file text: "subsection A",
     * "subsection B", "set Name = value", "end", "end". Throws unless
     * @p assignment has the form. */
    static std::string
    as_parameter_text(const std::string &assignment);
  };
} // namespace bsmpm

#endif
