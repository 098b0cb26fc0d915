#ifndef bsmpm_verification_h
#define bsmpm_verification_h

#include <deal.II/base/parameter_handler.h>

#include <map>
#include <ostream>
#include <string>
#include <vector>

namespace bsmpm
{
  using namespace dealii;

  /**
   * Bounds that a scene promises to meet, such as "R_sigma_yy <= 1e-14":
   * checked against the errors and quantities at the end of a run, so that a
   * scene file doubles as a regression test of its accuracy claims.
   */
  class Verification
  {
  public:
    static void
    declare_parameters(ParameterHandler &prm);
    void
    parse_parameters(ParameterHandler &prm);

    bool
    empty() const
    {
      return bounds.empty();
    }

    /**
     * Prints one line per bound to @p out and returns the failed ones (empty
     * if all hold). A bound on a name that the run did not produce fails.
     */
    std::vector<std::string>
    check(const std::map<std::string, double> &values, std::ostream &out) const;

  private:
    struct Bound
    {
      std::string name;
      bool        upper; // "<=" (true) or ">=" (false)
      double      value;
    };
    std::vector<Bound> bounds;
  };
} // namespace bsmpm

#endif
