#ifndef bsmpm_parameter_sweep_h
#define bsmpm_parameter_sweep_h

#include <deal.II/base/parameter_handler.h>

#include <string>
#include <vector>

namespace bsmpm
{
  using namespace dealii;

  /**
   * The runs of bsmpm --sweep "Section/Name=v1,v2,...": one run of the
   * scene per value, in one process (a study need not start MPI and load
   * the library once per value), run k writing into
   * <Output/Directory>/sweep-<k>, and <Output/Directory>/sweep.json listing
   * the values with their directories for the scripts that read them.
   *
   * The driver sets each run's parameters with set_run() and runs the scene;
   * this class knows nothing of the scene.
   */
  class ParameterSweep
  {
  public:
    /**
     * Reads @p sweep, the argument of --sweep, for the parameters @p prm
     * read from the file and --set. Every value is set once in @p prm, so
     * that a bad one fails before the first run. Throws unless @p sweep has
     * the form, names a declared parameter, and has a value.
     */
    ParameterSweep(const std::string &sweep, ParameterHandler &prm);

    /**
     * The values of @p list: separated by ';' if it holds one (values that
     * are lists themselves, "1, 2; 3, 4"), by ',' otherwise; each trimmed,
     * empty ones dropped.
     */
    static std::vector<std::string>
    split_values(const std::string &list);

    /** The parameter swept, "Section/Name". */
    const std::string &
    parameter() const
    {
      return path;
    }

    /** The values, in the order of the runs. */
    const std::vector<std::string> &
    values() const
    {
      return list;
    }

    /** The output directory of run @p k: <Output/Directory>/sweep-<k>. */
    std::string
    directory(const unsigned int k) const;

    /** Sets in @p prm the value of run @p k and its output directory;
     * returns the assignment "Section/Name=value". */
    std::string
    set_run(const unsigned int k, ParameterHandler &prm) const;

    /** The text of sweep.json: the parameter, and for every run its value,
     * directory and summary file. */
    std::string
    record() const;

    /** Writes record() into <Output/Directory>/sweep.json (through a
     * temporary file, so that a reader never finds half of it). */
    void
    write_record() const;

  private:
    std::string              path;
    std::vector<std::string> list;
    /** Output/Directory of the parameters: the runs' directories are in
     * it. */
    std::string base;
  };
} // namespace bsmpm

#endif
