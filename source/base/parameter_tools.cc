#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <bsmpm/base/parameter_tools.h>

#include <cmath>

namespace bsmpm
{
  namespace ParameterTools
  {
    Patterns::List
    point_pattern()
    {
      return Patterns::List(Patterns::Double(), 2, 2, ",");
    }



    std::vector<double>
    get_doubles(const ParameterHandler &prm, const std::string &name)
    {
      std::vector<double> values;
      for (const auto &item : Utilities::split_string_list(prm.get(name), ','))
        {
          if (item.empty())
            continue;
          double value = 0;
          try
            {
              value = Utilities::string_to_double(item);
            }
          catch (...)
            {
              AssertThrow(false,
                          ExcMessage("Parameter '" + name + "': '" + item +
                                     "' is not a number."));
            }
          require_finite(value, "Parameter '" + name + "'");
          values.push_back(value);
        }
      return values;
    }



    Point<2>
    get_point(const ParameterHandler &prm, const std::string &name)
    {
      const auto values = get_doubles(prm, name);
      AssertThrow(values.size() == 2,
                  ExcMessage("Parameter '" + name +
                             "' must be a point 'x, y', got '" + prm.get(name) +
                             "'."));
      return Point<2>(values[0], values[1]);
    }



    std::vector<unsigned int>
    get_unsigned(const ParameterHandler &prm, const std::string &name)
    {
      std::vector<unsigned int> values;
      for (const double v : get_doubles(prm, name))
        {
          AssertThrow(v >= 0 && v == std::floor(v),
                      ExcMessage("Parameter '" + name +
                                 "' must list non-negative integers, got '" +
                                 prm.get(name) + "'."));
          values.push_back(static_cast<unsigned int>(v));
        }
      return values;
    }



    void
    throw_if_any(const std::string &message, const MPI_Comm communicator)
    {
      const unsigned int rank  = Utilities::MPI::this_mpi_process(communicator);
      const unsigned int first = Utilities::MPI::min(
        message.empty() ? numbers::invalid_unsigned_int : rank, communicator);
      if (first == numbers::invalid_unsigned_int)
        return;
      const std::string text =
        Utilities::MPI::broadcast(communicator, message, first);
      AssertThrow(false, ExcMessage(text));
    }



    void
    require_finite(const double value, const std::string &what)
    {
      AssertThrow(std::isfinite(value),
                  ExcMessage(what + ": the value is not a finite number."));
    }
  } // namespace ParameterTools
} // namespace bsmpm
