#ifndef bsmpm_exception_message_h
#define bsmpm_exception_message_h

#include <deal.II/base/exceptions.h>

#include <string>

namespace bsmpm
{
  using namespace dealii;

  /** The message of a deal.II exception without its source location and
   * without the indentation deal.II puts in front of each line: what a
   * user of bsmpm is told. */
  std::string
  message_of(const ExceptionBase &e);
} // namespace bsmpm

#endif
