#ifndef bsmpm_parameter_names_h
#define bsmpm_parameter_names_h

#include <deal.II/base/parameter_handler.h>

#include <string>
#include <vector>

namespace bsmpm
{
  using namespace dealii;

  /**
   * The paths "Section/Subsection/Name" of every parameter declared in a
   * ParameterHandler, and the declared ones nearest to a misspelt path.
   *
   * deal.II's own message for an undeclared name only repeats it. A user
   * who typed "Material/Young's modulos" wants to read "Did you mean
   * "Material/Young's modulus"?", in the parameter file and on the command
   * line alike.
   */
  class ParameterNames
  {
  public:
    /** Lists the parameters declared in @p prm (from its own listing,
     * ParameterHandler::print_parameters()). */
    explicit ParameterNames(const ParameterHandler &prm);

    /** Every declared parameter, as "Section/Subsection/Name". */
    const std::vector<std::string> &
    parameters() const
    {
      return paths;
    }

    /** Every declared subsection, as "Section/Subsection": the prefixes of
     * the parameters' paths, sorted, each once. */
    std::vector<std::string>
    subsections() const;

    /** Throws, with @p what in front, the text "there is no parameter" and
     * the closest declared names, unless @p path is a declared parameter. */
    void
    check_declared(const std::string &path, const std::string &what) const;

    /**
     * " Did you mean "A", "B"?" with those of @p candidates closest to
     * @p path: at most three, and only those within an edit distance of a
     * third of the length of @p path (at least 2); empty if there is none.
     */
    static std::string
    suggestion(const std::string              &path,
               const std::vector<std::string> &candidates);

    /** The number of insertions, deletions and substitutions that turn
     * @p a into @p b, ignoring case (Levenshtein distance). */
    static unsigned int
    edit_distance(const std::string &a, const std::string &b);

  private:
    std::vector<std::string> paths;
  };
} // namespace bsmpm

#endif
