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



    std::vector<Point<2>>
    parse_points(const std::string &text, const std::string &where)
    {
      std::vector<Point<2>> points;
      for (const auto &pair : Utilities::split_string_list(text, ';'))
        {
          if (pair.empty())
            continue;
          const auto xy = Utilities::split_string_list(pair, ',');
          AssertThrow(xy.size() == 2,
                      ExcMessage(where + ": '" + pair +
                                 "' is not a point 'x, y'."));
          try
            {
              const Point<2> p(Utilities::string_to_double(xy[0]),
                               Utilities::string_to_double(xy[1]));
              require_finite(p[0] + p[1], where);
              points.push_back(p);
            }
          catch (const ExceptionBase &)
            {
              AssertThrow(false,
                          ExcMessage(where + ": '" + pair +
                                     "' is not a point 'x, y'."));
            }
        }
      return points;
    }



    void
    require_finite(const double value, const std::string &what)
    {
      AssertThrow(std::isfinite(value),
                  ExcMessage(what + ": the value is not a finite number."));
    }
  } // namespace ParameterTools
} // namespace bsmpm
