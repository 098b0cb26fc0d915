#ifndef bsmpm_parameter_listing_h
#define bsmpm_parameter_listing_h

#include <deal.II/base/parameter_handler.h>

#include <ostream>

namespace bsmpm
{
  using namespace dealii;

  /**
   * What `bsmpm --print-parameters` writes: every parameter as a valid
   * parameter file, each entry preceded by its documentation and by the
   * values it allows (the pattern: the choices of a selection, the range of
   * a number) as comments. deal.II's PRM style leaves the patterns out, so
   * this listing is made from the handler's JSON form, which has them.
   */
  namespace ParameterListing
  {
    void
    print(const ParameterHandler &prm, std::ostream &out);
  } // namespace ParameterListing
} // namespace bsmpm

#endif
