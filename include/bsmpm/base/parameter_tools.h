#ifndef bsmpm_parameter_tools_h
#define bsmpm_parameter_tools_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>

#include <string>
#include <vector>

namespace bsmpm
{
  using namespace dealii;

  /** Small helpers for reading lists and points out of a ParameterHandler
   * with error messages that name the parameter. */
  namespace ParameterTools
  {
    /** Pattern of a comma-separated pair of numbers "x, y". */
    Patterns::List
    point_pattern();

    /** Reads entry @p name of the current subsection as "x, y". */
    Point<2>
    get_point(const ParameterHandler &prm, const std::string &name);

    /** Reads entry @p name as a list of numbers (any length). */
    std::vector<double>
    get_doubles(const ParameterHandler &prm, const std::string &name);

    /** Reads entry @p name as a list of non-negative integers. */
    std::vector<unsigned int>
    get_unsigned(const ParameterHandler &prm, const std::string &name);

    /** Reads @p text as points "x0, y0; x1, y1; ..." (empty items
     * skipped); a malformed one is an input error naming @p where. */
    std::vector<Point<2>>
    parse_points(const std::string &text, const std::string &where);

    /** Throws an input error unless @p value is finite. */
    void
    require_finite(const double value, const std::string &what);

    /**
     * Collective: if any process passes a non-empty @p message, every
     * process throws the message of the first such process. Errors found
     * in a loop over a process' own cells must go through this, or the
     * other processes would wait for it in the next collective call.
     */
    void
    throw_if_any(const std::string &message, const MPI_Comm communicator);
  } // namespace ParameterTools
} // namespace bsmpm

#endif
