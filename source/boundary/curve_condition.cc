#include <deal.II/base/utilities.h>

#include <bsmpm/base/parameter_tools.h>
#include <bsmpm/boundary/curve_condition.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <sstream>

namespace bsmpm
{
  namespace
  {
    /** Whether @p expressions use the variable @p name (a name of its own,
     * not a part of another name nor a function such as tan). */
    bool
    uses_variable(const std::string &expressions, const char name)
    {
      const auto is_name_character = [](const char c) {
        return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
      };
      for (std::size_t i = 0; i < expressions.size(); ++i)
        {
          if (expressions[i] != name ||
              (i > 0 && is_name_character(expressions[i - 1])) ||
              (i + 1 < expressions.size() &&
               is_name_character(expressions[i + 1])))
            continue;
          const std::size_t next = expressions.find_first_not_of(' ', i + 1);
          if (next == std::string::npos || expressions[next] != '(')
            return true;
        }
      return false;
    }



    /** A parser of @p n_components expressions of x, y and t (separated by
     * ';'), evaluated once so that syntax errors show here; @p message
     * starts the error message. */
    std::shared_ptr<FunctionParser<2>>
    parse_function(const std::string &expressions,
                   const unsigned int n_components,
                   const std::string &message)
    {
      auto        function = std::make_shared<FunctionParser<2>>(n_components);
      std::string problem;
      try
        {
          function->initialize("x,y,t",
                               expressions,
                               {{"pi", numbers::PI}},
                               /*time_dependent=*/true);
          // The parser reports syntax errors only when it first evaluates,
          // which would be in a loop over one process' cells: evaluate once
          // here, on every process alike.
          for (unsigned int c = 0; c < n_components; ++c)
            function->value(Point<2>(), c);
        }
      catch (const ExceptionBase &e)
        {
          std::ostringstream text;
          e.print_info(text);
          problem = Utilities::trim(text.str());
        }
      catch (...)
        {
          problem = "not understood";
        }
      AssertThrow(problem.empty(), ExcMessage(message + " (" + problem + ")."));
      return function;
    }
  } // namespace



  CurveCondition
  CurveCondition::parse(const std::string &input, const std::string &where)
  {
    CurveCondition condition;
    condition.where  = where;
    std::string text = Utilities::trim(input);

    const auto colon = text.find(':');
    if (colon != std::string::npos)
      {
        const std::string range = Utilities::trim(text.substr(0, colon));
        const auto        dash  = range.find('-');
        int               first = 0, last = 0;
        try
          {
            AssertThrow(dash != std::string::npos, ExcInternalError());
            first =
              Utilities::string_to_int(Utilities::trim(range.substr(0, dash)));
            last =
              Utilities::string_to_int(Utilities::trim(range.substr(dash + 1)));
          }
        catch (...)
          {
            AssertThrow(false,
                        ExcMessage(where + ": '" + range +
                                   "' is not a range of points 'i-j' (two "
                                   "point indices, counted from 0 along the "
                                   "chain, before the ':')."));
          }
        // A negative index would wrap to a huge one (and -1 to 'no range').
        AssertThrow(first >= 0 && last >= 0,
                    ExcMessage(where + ": '" + range +
                               "' is not a range of points 'i-j': point "
                               "indices count from 0 along the chain and "
                               "cannot be negative."));
        AssertThrow(first != last,
                    ExcMessage(where + ": the range '" + range +
                               "' starts and ends at point " +
                               std::to_string(first) +
                               ", so it covers no segment. A range 'i-j' "
                               "covers the segments between points i and "
                               "j != i; for the whole chain give no range."));
        condition.first_segment = first;
        condition.end_segment   = last;
        text                    = Utilities::trim(text.substr(colon + 1));
      }

    const auto        space = text.find(' ');
    const std::string kind  = text.substr(0, space);
    const std::string arguments =
      space == std::string::npos ? "" : Utilities::trim(text.substr(space + 1));

    if (kind == "free" && arguments.empty())
      condition.kind = Kind::free;
    else if (kind == "pressure")
      {
        condition.kind = Kind::pressure;
        AssertThrow(!arguments.empty() && !uses_variable(arguments, 'x') &&
                      !uses_variable(arguments, 'y'),
                    ExcMessage(where +
                               ": 'pressure' needs a number or an expression "
                               "of the load factor t (one pressure along its "
                               "stretch; 'traction' varies along it), got '" +
                               arguments + "'."));
        if (uses_variable(arguments, 't'))
          {
            condition.function        = parse_function(arguments,
                                                1,
                                                where +
                                                  ": 'pressure' needs a "
                                                         "number or an expression "
                                                         "of t, got '" +
                                                  arguments + "'");
            condition.expression_of_t = true;
          }
        else
          {
            try
              {
                condition.pressure = Utilities::string_to_double(arguments);
              }
            catch (...)
              {
                AssertThrow(false,
                            ExcMessage(where +
                                       ": 'pressure' needs a number or an "
                                       "expression of the load factor t, "
                                       "got '" +
                                       arguments + "'."));
              }
            ParameterTools::require_finite(condition.pressure, where);
          }
      }
    else if ((kind == "traction" || kind == "displacement") &&
             arguments != "exact")
      {
        condition.kind =
          kind == "traction" ? Kind::traction : Kind::displacement;
        condition.function =
          parse_function(arguments,
                         2,
                         where + ": '" + kind +
                           "' needs two expressions of x, y and t separated by "
                           "';', got '" +
                           arguments + "'");
        condition.expression_of_t = uses_variable(arguments, 't');
      }
    else if (kind == "normal" &&
             arguments.substr(0, arguments.find(' ')) == "displacement")
      {
        // "normal displacement exact" or "normal displacement <un>".
        condition.kind = Kind::normal_displacement;
        const std::string value =
          Utilities::trim(arguments.substr(std::string("displacement").size()));
        AssertThrow(
          !value.empty(),
          ExcMessage(where + ": 'normal displacement' needs a value (an "
                             "expression of x, y and t, the displacement along "
                             "the outward normal) or 'exact'."));
        if (value != "exact")
          condition.function =
            parse_function(value,
                           1,
                           where +
                             ": 'normal displacement' needs one expression "
                             "of x, y and t, got '" +
                             value + "'");
        condition.expression_of_t = uses_variable(value, 't');
      }
    else if (text == "exact traction")
      condition.kind = Kind::exact_traction;
    else if (text == "displacement exact")
      condition.kind = Kind::displacement;
    else if (text == "fixed")
      condition.kind = Kind::fixed;
    else if (text == "roller")
      condition.kind = Kind::roller;
    else
      AssertThrow(false,
                  ExcMessage(where + ": unknown condition '" + text +
                             "'. Known: free, pressure <p>, traction <tx>; "
                             "<ty>, exact traction, fixed, roller, "
                             "displacement exact, displacement <ux>; <uy>, "
                             "normal displacement exact, normal displacement "
                             "<un>."));
    return condition;
  }



  Tensor<1, 2>
  CurveCondition::load_traction(const Point<2>     &x,
                                const Tensor<1, 2> &normal,
                                const double        t,
                                std::string        &problem) const
  {
    Assert(kind == Kind::pressure || kind == Kind::traction,
           ExcInternalError());
    if (kind == Kind::pressure)
      return -pressure_at(t) * normal;
    return value_at(t, [&]() { return function_value(x, problem); });
  }



  double
  CurveCondition::pressure_at(const double t) const
  {
    return value_at(t, [&]() {
      return expression_of_t ? function->value(Point<2>(), 0) : pressure;
    });
  }



  Tensor<1, 2>
  CurveCondition::displacement_increment(const Point<2>      &x,
                                         const LoadIncrement &increment,
                                         std::string         &problem) const
  {
    return change_over(increment, [&]() { return function_value(x, problem); });
  }



  double
  CurveCondition::normal_displacement_increment(const Point<2>      &x,
                                                const LoadIncrement &increment,
                                                std::string &problem) const
  {
    return change_over(increment,
                       [&]() { return scalar_function_value(x, problem); });
  }



  Tensor<1, 2>
  CurveCondition::function_value(const Point<2> &x, std::string &problem) const
  {
    const Tensor<1, 2> value({function->value(x, 0), function->value(x, 1)});
    if (problem.empty() &&
        !(std::isfinite(value[0]) && std::isfinite(value[1])))
      {
        std::ostringstream message;
        message << where << ": the " << kind_name() << " is (" << value[0]
                << ", " << value[1] << ") at (" << x[0] << ", " << x[1]
                << "), not a finite vector: check the expression.";
        problem = message.str();
      }
    return value;
  }



  double
  CurveCondition::scalar_function_value(const Point<2> &x,
                                        std::string    &problem) const
  {
    const double value = function->value(x, 0);
    if (problem.empty() && !std::isfinite(value))
      {
        std::ostringstream message;
        message << where << ": the " << kind_name() << " is " << value
                << " at (" << x[0] << ", " << x[1]
                << "), not a finite number: check the expression.";
        problem = message.str();
      }
    return value;
  }



  void
  CurveCondition::check_range(const unsigned int n_points,
                              const bool         closed,
                              const std::string &curve_name) const
  {
    // A chain of fewer than two points is refused when its spline is built.
    if (!has_range() || n_points < 2)
      return;
    const std::string n    = std::to_string(n_points);
    const std::string last = std::to_string(n_points - 1);
    const std::string range =
      std::to_string(first_segment) + "-" + std::to_string(end_segment);
    const std::string chain =
      curve_name + " is " + (closed ? "a closed" : "an open") + " chain of " +
      n + " points, numbered from 0 to " + last + " along its direction; ";
    const std::string forms =
      closed ? "a range 'i-j' covers the segments from point i forward to "
               "point j and needs i, j in 0 .. " +
                 last + " (j = " + n +
                 " is point 0 after a full turn) and i != j; with i > j "
                 "it wraps round past point " +
                 last + " and point 0." :
               "a range 'i-j' covers the segments between points i and j "
               "and needs 0 <= i < j <= " +
                 last + ".";
    AssertThrow(first_segment < n_points &&
                  end_segment <= (closed ? n_points : n_points - 1),
                ExcMessage(where + ": the range '" + range +
                           "' lies beyond the chain: " + chain + forms));
    AssertThrow(closed || first_segment < end_segment,
                ExcMessage(where + ": the range '" + range +
                           "' runs backwards: " + chain + forms +
                           " Only a closed chain's ranges wrap round (i > "
                           "j); for the segments between points " +
                           std::to_string(end_segment) + " and " +
                           std::to_string(first_segment) + " write '" +
                           std::to_string(end_segment) + "-" +
                           std::to_string(first_segment) + "'."));
  }



  bool
  CurveCondition::covers(const unsigned int k,
                         const unsigned int n_segments) const
  {
    const unsigned int end = std::min(end_segment, n_segments);
    if (first_segment <= end)
      return k >= first_segment && k < end;
    return k >= first_segment || k < end; // wraps round a closed chain
  }



  std::string
  CurveCondition::kind_name() const
  {
    switch (kind)
      {
        case Kind::free:
          return "free";
        case Kind::pressure:
          return "pressure";
        case Kind::traction:
          return "traction";
        case Kind::exact_traction:
          return "exact traction";
        case Kind::fixed:
          return "fixed";
        case Kind::roller:
          return "roller";
        case Kind::displacement:
          return "displacement";
        case Kind::normal_displacement:
          return "normal displacement";
      }
    return "";
  }
} // namespace bsmpm
