#ifndef bsmpm_parameter_file_h
#define bsmpm_parameter_file_h

#include <deal.II/base/parameter_handler.h>

#include <bsmpm/io/parameter_names.h>

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace bsmpm
{
  using namespace dealii;

  /**
   * A parameter file read for a ParameterHandler, with errors that name
   * the file and line they are in.
   *
   * Its "include" lines are replaced by the files they name, each resolved
   * against the folder of the file that includes it (deal.II would resolve
   * them against the working directory, so that a scene could only be run
   * from one folder). The text remembers where each of its lines came from:
   * deal.II's messages name a line of the text it was given, the user wants
   * the line of the file it is in.
   */
  class ParameterFile
  {
  public:
    /** Reads @p file and the files it includes. Throws, saying why, if one
     * of them cannot be read as a text file (missing, a directory, binary
     * data) or if includes nest more than 16 deep (a cycle?). */
    explicit ParameterFile(const std::filesystem::path &file);

    /** The text with the included files in place of the include lines. */
    const std::string &
    text() const
    {
      return contents;
    }

    /**
     * Parses the text into @p prm, whose declared parameters are
     * @p declared (listed before parsing). A misspelt parameter or
     * subsection is named with its file and line and the declared ones
     * nearest to it; any other error of deal.II gets the true file and
     * line in place of those of the text.
     */
    void
    parse_into(ParameterHandler &prm, const ParameterNames &declared) const;

    /** Where line @p n (1-based) of the text came from: "line L of 'F'". */
    std::string
    where(const unsigned int n) const;

    /**
     * The parameter path that line @p n of the text names: "A/B/Name" for
     * a "set Name" line in subsections A, B; "A/B" for a "subsection B"
     * line in A (then @p subsection is set). Empty for other lines.
     */
    std::string
    path_at(const unsigned int n, bool &subsection) const;

    /** Replaces "Line <n> of file <<input>>" in a message of deal.II by
     * the true file and line, and "the parameter file <<input>>" by the
     * file's name. */
    std::string
    locate(const std::string &message) const;

  private:
    /** Appends @p file to the text, included @p depth deep, by the line
     * @p included_by names (empty for the file given). */
    void
    expand(const std::filesystem::path &file,
           const unsigned int           depth,
           const std::string           &included_by);

    std::string contents;
    /** The file and line of every line of the text. */
    std::vector<std::pair<std::string, unsigned int>> origin;
    /** The file given. */
    std::string top;
  };
} // namespace bsmpm

#endif
