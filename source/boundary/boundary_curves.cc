#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <bsmpm/base/parameter_tools.h>
#include <bsmpm/boundary/boundary_curves.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

namespace bsmpm
{
  namespace
  {
    std::string
    curve_section(const unsigned int c)
    {
      return "Curve " + std::to_string(c + 1);
    }

    /** "x, y; x, y; ..." as points. */
    std::vector<Point<2>>
    parse_coordinates(const std::string &text, const std::string &where)
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
              ParameterTools::require_finite(p[0] + p[1], where);
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

    /** Points of a CSV file: one "x, y" (or "x y") per line; '#' starts a
     * comment; the first line may be a header. */
    std::vector<Point<2>>
    read_points_file(const std::string &file, const std::string &where)
    {
      std::ifstream in(file);
      AssertThrow(in,
                  ExcMessage(where + ": cannot read the points file '" + file +
                             "'."));
      // An ifstream opens a directory and reads nothing from it.
      AssertThrow(std::filesystem::is_regular_file(file),
                  ExcMessage(where + ": the points file '" + file +
                             "' is not a regular file (a directory?)."));
      std::vector<Point<2>> points;
      std::string           line;
      for (unsigned int number = 1; std::getline(in, line); ++number)
        {
          line = Utilities::trim(line.substr(0, line.find('#')));
          if (line.empty())
            continue;
          std::replace(line.begin(), line.end(), ',', ' ');
          std::istringstream fields(line);
          double             x, y;
          std::string        rest;
          const bool         ok =
            static_cast<bool>(fields >> x >> y) && !(fields >> rest);
          if (!ok && number == 1 && std::isalpha(line[0]))
            continue; // a header
          AssertThrow(ok && std::isfinite(x) && std::isfinite(y),
                      ExcMessage(where + ": line " + std::to_string(number) +
                                 " of '" + file + "' is not a point 'x, y': '" +
                                 line + "'."));
          points.emplace_back(x, y);
        }
      return points;
    }
    /** A parser of @p n_components expressions of x, y (separated by ';'),
     * evaluated once so that syntax errors show here; @p message starts the
     * error message. */
    std::shared_ptr<FunctionParser<2>>
    parse_function(const std::string &expressions,
                   const unsigned int n_components,
                   const std::string &message)
    {
      auto        function = std::make_shared<FunctionParser<2>>(n_components);
      std::string problem;
      try
        {
          function->initialize("x,y", expressions, {{"pi", numbers::PI}});
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
        try
          {
            condition.pressure = Utilities::string_to_double(arguments);
          }
        catch (...)
          {
            AssertThrow(false,
                        ExcMessage(where +
                                   ": 'pressure' needs a number, got '" +
                                   arguments + "'."));
          }
        ParameterTools::require_finite(condition.pressure, where);
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
                           "' needs two expressions of x and y separated by "
                           "';', got '" +
                           arguments + "'");
      }
    else if (kind == "normal" &&
             arguments.substr(0, arguments.find(' ')) == "displacement")
      {
        // "normal displacement exact" or "normal displacement <un>".
        condition.kind = Kind::normal_displacement;
        const std::string value =
          Utilities::trim(arguments.substr(std::string("displacement").size()));
        AssertThrow(!value.empty(),
                    ExcMessage(where +
                               ": 'normal displacement' needs a value (an "
                               "expression of x and y, the displacement along "
                               "the outward normal) or 'exact'."));
        if (value != "exact")
          condition.function =
            parse_function(value,
                           1,
                           where +
                             ": 'normal displacement' needs one expression "
                             "of x and y, got '" +
                             value + "'");
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



  Voigt
  BoundaryCurve::stress_at(const unsigned int segment, const double u) const
  {
    const auto         range = spline->segment_parameters(segment);
    const unsigned int k1    = (segment + 1) % positions.size();
    const double       f     = (u - range[0]) / (range[1] - range[0]);
    return (1 - f) * stresses[segment] + f * stresses[k1];
  }



  std::vector<double>
  BoundaryCurve::state_at(const unsigned int segment, const double u) const
  {
    using Property           = MaterialPoints::Property;
    const auto         range = spline->segment_parameters(segment);
    const unsigned int k1    = (segment + 1) % positions.size();
    const double       f     = (u - range[0]) / (range[1] - range[0]);
    const auto        &a     = states[segment];
    const auto        &b     = states[k1];
    const auto         at    = [&](const unsigned int k) {
      return (1 - f) * a[k] + f * b[k];
    };
    std::vector<double> props(Property::n_properties_inelastic, 0.);
    props[Property::volume] = 1.;
    for (unsigned int k = 0; k < 4; ++k)
      props[Property::elastic_strain + k] = at(k);
    props[Property::plastic_strain] = at(4);
    props[Property::det_F]          = at(5);
    props[Property::weight]         = 1.;
    return props;
  }



  const CurveCondition *
  BoundaryCurve::condition_of_segment(const unsigned int k) const
  {
    const CurveCondition *found = nullptr;
    for (const auto &c : conditions)
      if (c.covers(k, n_segments()))
        found = &c;
    return (found && found->kind != CurveCondition::Kind::free) ? found :
                                                                  nullptr;
  }



  const CurveCondition *
  BoundaryCurve::rigid_support(const unsigned int k) const
  {
    const unsigned int n    = n_segments();
    const unsigned int none = numbers::invalid_unsigned_int;
    // The ends of an open chain meet other curves, whose points there move
    // with the body: they must stay together.
    if (n == 0 || !spline || (!closed && (k == 0 || k == n)))
      return nullptr;
    const auto previous = [&](const unsigned int j) {
      return j == none ? none : j > 0 ? j - 1 : closed ? n - 1 : none;
    };
    const auto next = [&](const unsigned int j) {
      return j == none ? none : j + 1 < n ? j + 1 : closed ? 0 : none;
    };
    const auto condition = [&](const unsigned int j) -> const CurveCondition * {
      return j == none ? nullptr : condition_of_segment(j);
    };
    // The segments on either side of point k (none beyond the ends of an
    // open chain).
    const unsigned int    before = k > 0 ? k - 1 : closed ? n - 1 : none;
    const unsigned int    after  = k < n ? k : none;
    const CurveCondition *own    = nullptr;
    for (const unsigned int j : {before, after})
      if (const CurveCondition *c = condition(j);
          c != nullptr && c->kind == CurveCondition::Kind::normal_displacement)
        own = c;
    if (own == nullptr)
      return nullptr;
    for (const unsigned int j : {before, after})
      if (const CurveCondition *c = condition(j);
          c != nullptr && c != own && c->is_support())
        return nullptr;
    // The run of the condition's segments through the point: a rigid body
    // if one of its ends meets a segment that is no support.
    unsigned int first = condition(after) == own ? after : before;
    unsigned int last  = first;
    for (unsigned int s = 0; s < n && condition(previous(first)) == own; ++s)
      first = previous(first);
    for (unsigned int s = 0; s < n && condition(next(last)) == own; ++s)
      last = next(last);
    const auto meets_no_support = [&](const unsigned int j) {
      const CurveCondition *c = condition(j);
      return j != none && (c == nullptr || !c->is_support());
    };
    if (!meets_no_support(previous(first)) && !meets_no_support(next(last)))
      return nullptr;
    return own;
  }



  void
  BoundaryCurves::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Boundary curves");
    for (unsigned int c = 0; c < max_curves; ++c)
      {
        prm.enter_subsection(curve_section(c));
        prm.declare_entry(
          "Points",
          "none",
          Patterns::Selection("none|region edge|coordinates|file|"
                              "material points"),
          "Where the boundary points of this curve come from: none (no "
          "curve); region edge (zero-volume tracking points along an edge "
          "of the body region); coordinates or file (tracking points at "
          "given positions); material points (the outer layer of material "
          "points along an edge of the body region). The body must lie to "
          "the left of the chain's direction.");
        prm.declare_entry("Edge",
                          "boundary",
                          Patterns::Anything(),
                          "region edge, material points: the part of the "
                          "body region's boundary: bottom, right, top, left "
                          "(rectangle, rotated rectangle, rectangle minus "
                          "disc, in the rectangle's own frame); hole "
                          "(rectangle minus disc); inner arc, outer arc, "
                          "start edge, end edge (annulus sector); boundary "
                          "(any shape: its parts above, but a hole inside "
                          "the rectangle, as one closed chain).");
        prm.declare_entry("Number of points",
                          "5",
                          Patterns::Integer(2, max_points_per_edge),
                          "region edge: points per edge, ends included.");
        prm.declare_entry("Coordinates",
                          "",
                          Patterns::Anything(),
                          "coordinates: 'x0, y0; x1, y1; ...'.");
        prm.declare_entry("File",
                          "",
                          Patterns::Anything(),
                          "file: CSV file with one 'x, y' per line.");
        prm.declare_entry("Closed",
                          "false",
                          Patterns::Bool(),
                          "coordinates, file: whether the last point joins "
                          "the first.");
        prm.declare_entry("Corners",
                          "",
                          Patterns::List(Patterns::Integer(0)),
                          "Indices of points where the curve keeps a sharp "
                          "corner (besides those detected).");
        prm.declare_entry("Dirichlet method",
                          "implicit boundary",
                          Patterns::Selection("implicit boundary|nitsche"),
                          "How the supports of this curve (fixed, roller, "
                          "displacement, normal displacement) are imposed: by "
                          "the implicit boundary method (paper Sec. 3.5; its "
                          "band in 'Implicit boundary') or by Nitsche's "
                          "method (its penalty in 'Nitsche'). Both reproduce "
                          "a linear field that meets the support; Nitsche's "
                          "has no band and a condition number that no band "
                          "width raises, the implicit boundary method is the "
                          "paper's (doc/implicit-boundary.md).");
        prm.declare_entry("Halve point volumes",
                          "false",
                          Patterns::Bool(),
                          "material points: halve the volume of the curve's "
                          "points, so that the outer layer of points stands "
                          "for the body up to the curve (a corner point on "
                          "two such curves keeps a quarter).");
        prm.declare_entry("Trim material points",
                          "false",
                          Patterns::Bool(),
                          "Remove the material points that start on the "
                          "outer side of this curve.");
        for (const std::string name :
             {"Condition", "Condition 2", "Condition 3", "Condition 4"})
          prm.declare_entry(name,
                            name == "Condition" ? "free" : "",
                            Patterns::Anything(),
                            "'[i-j:] kind [arguments]': free; pressure <p>; "
                            "traction <tx>; <ty> (expressions of x, y); "
                            "exact traction; fixed; roller; displacement "
                            "exact; displacement <ux>; <uy>; normal "
                            "displacement exact; normal displacement <un>. "
                            "i-j restricts it to the segments between points "
                            "i and j of the chain, its points numbered from 0 "
                            "along the chain's direction (segment k joins "
                            "points k and k+1); without it the condition "
                            "covers the whole chain. On an open chain of N "
                            "points 0 <= i < j <= N-1. On a closed chain of N "
                            "points i and j lie in 0 .. N-1 (j may also be N, "
                            "point 0 after a full turn: '0-N' is the whole "
                            "loop) and i != j; a range with i > j wraps round: "
                            "it runs from point i forward past the last point "
                            "N-1 and point 0 to point j, i.e. segments i .. "
                            "N-1 (segment N-1 joins point N-1 to point 0) and "
                            "0 .. j-1. Later conditions override earlier "
                            "ones.");
        prm.leave_subsection();
      }
    BoundaryPointSpacing::declare_parameters(prm);
    CurveTouchCheck::declare_parameters(prm);
    prm.leave_subsection();
  }



  void
  BoundaryCurves::parse_parameters(ParameterHandler &prm)
  {
    curves.clear();
    sources.clear();
    prm.enter_subsection("Boundary curves");
    point_spacing.parse_parameters(prm);
    touch_check.parse_parameters(prm);
    for (unsigned int c = 0; c < max_curves; ++c)
      {
        prm.enter_subsection(curve_section(c));
        const std::string where = "Boundary curves/" + curve_section(c);
        Source            source;
        source.kind = prm.get("Points");
        if (source.kind != "none")
          {
            BoundaryCurve curve;
            curve.name   = curve_section(c);
            curve.closed = prm.get_bool("Closed");
            for (const auto i : ParameterTools::get_unsigned(prm, "Corners"))
              curve.corners.push_back(i);
            curve.trims_material_points = prm.get_bool("Trim material points");
            curve.halve_point_volumes   = prm.get_bool("Halve point volumes");
            curve.dirichlet_method =
              prm.get("Dirichlet method") == "nitsche" ?
                BoundaryCurve::DirichletMethod::nitsche :
                BoundaryCurve::DirichletMethod::implicit_boundary;
            for (const std::string name :
                 {"Condition", "Condition 2", "Condition 3", "Condition 4"})
              if (!Utilities::trim(prm.get(name)).empty())
                curve.conditions.push_back(
                  CurveCondition::parse(prm.get(name), where + "/" + name));

            source.edge     = Utilities::trim(prm.get("Edge"));
            source.n_points = prm.get_integer("Number of points");
            if (source.kind == "coordinates")
              source.positions = parse_coordinates(prm.get("Coordinates"),
                                                   where + "/Coordinates");
            else if (source.kind == "file")
              source.positions = read_points_file(prm.get("File"), where);
            curves.push_back(std::move(curve));
            sources.push_back(source);
          }
        prm.leave_subsection();
      }
    prm.leave_subsection();

    // Conditions taken from the exact solution need one. (Checked here, on
    // every process: where they are used, in a loop over one process'
    // cells, an error would leave the others waiting.)
    prm.enter_subsection("Exact solution");
    const bool has_exact_solution = prm.get("Name") != "none";
    prm.leave_subsection();
    for (const auto &curve : curves)
      for (const auto &condition : curve.conditions)
        AssertThrow(
          has_exact_solution ||
            (condition.kind != CurveCondition::Kind::exact_traction &&
             (!condition.prescribes_displacement() || condition.function)),
          ExcMessage(condition.where + ": '" + condition.kind_name() +
                     (condition.prescribes_displacement() ? " exact" : "") +
                     "' needs an exact solution in the 'Exact "
                     "solution' section (its Name is none)."));
  }



  void
  BoundaryCurves::enclose_body_region(ParameterHandler &prm,
                                      const BodyRegion &region,
                                      const double      cell_size)
  {
    // Points that move across cells leave full cells with uneven point
    // sets and partly filled cells at the surface: integrated by the points
    // alone, the stress of a column compressed by 38 % did not converge
    // under refinement (L2_u 8.3e-2, 7.5e-2, 8.0e-2 for h = 0.5 .. 0.125).
    // A closed curve round the body lets the cut-cell quadrature integrate
    // those cells consistently (1.2e-3, 2.3e-4, 9.1e-5; doc/finite-strain.md).
    prm.enter_subsection("Boundary curves");
    for (unsigned int c = 1; c <= max_curves; ++c)
      {
        prm.enter_subsection("Curve " + std::to_string(c));
        const bool used = prm.get("Points") != "none";
        prm.leave_subsection();
        if (used)
          {
            prm.leave_subsection();
            return;
          }
      }
    // Tracking points about a cell apart on the longest side.
    double longest = 0;
    for (const auto &name : region.boundary_part_names())
      {
        const auto points = region.boundary_points(name, 129).points;
        double     length = 0;
        for (unsigned int i = 1; i < points.size(); ++i)
          length += points[i].distance(points[i - 1]);
        longest = std::max(longest, length);
      }
    const unsigned int n =
      std::max<unsigned int>(2, std::ceil(longest / cell_size - 1e-9) + 1);
    prm.enter_subsection("Curve 1");
    prm.set("Points", "region edge");
    prm.set("Edge", "boundary");
    prm.set("Number of points", std::to_string(n));
    prm.leave_subsection();
    prm.leave_subsection();
  }



  void
  BoundaryCurves::complete_region_boundary(const BodyRegion     &region,
                                           const BackgroundGrid &grid)
  {
    std::set<std::string> used;
    for (const auto &source : sources)
      {
        if (source.kind != "region edge")
          return;
        used.insert(source.edge);
      }
    if (used.empty() || used.count("boundary") > 0)
      return;
    const auto names = region.boundary_part_names();
    for (const auto &name : names)
      if (used.count(name) == 0 &&
          std::count(names.begin(), names.end(), name) > 1)
        return; // a part the region cannot name on its own

    for (const auto &name : names)
      if (used.count(name) == 0)
        {
          // Tracking points about one cell apart, so that the curve follows
          // the body as it deforms.
          const auto fine   = region.boundary_points(name, 129).points;
          double     length = 0;
          for (unsigned int i = 1; i < fine.size(); ++i)
            length += fine[i].distance(fine[i - 1]);
          Source source;
          source.kind     = "region edge";
          source.edge     = name;
          source.n_points = std::max<unsigned int>(
            2, std::ceil(length / grid.min_cell_size() - 1e-9) + 1);
          BoundaryCurve curve;
          curve.name = "free " + name + " (completes the boundary)";
          curve.conditions.push_back(CurveCondition());
          curves.push_back(std::move(curve));
          sources.push_back(source);
          used.insert(name);
        }
  }



  void
  BoundaryCurves::create_initial_curves(const BodyRegion     &region,
                                        const BackgroundGrid &grid)
  {
    // An edge the region's shape does not have is refused here, naming the
    // parameter, before any curve is built.
    for (unsigned int c = 0; c < curves.size(); ++c)
      if (sources[c].kind == "region edge" ||
          sources[c].kind == "material points")
        region.check_edge(sources[c].edge,
                          "Boundary curves/" + curves[c].name + "/Edge");
    complete_region_boundary(region, grid);
    for (unsigned int c = 0; c < curves.size(); ++c)
      {
        BoundaryCurve &curve  = curves[c];
        Source        &source = sources[c];
        if (source.kind == "region edge")
          {
            const auto edge =
              region.boundary_points(source.edge, source.n_points);
            source.positions = edge.points;
            curve.closed     = edge.closed;
            curve.corners.insert(curve.corners.end(),
                                 edge.corners.begin(),
                                 edge.corners.end());
          }
        if (source.kind != "material points")
          {
            curve.positions = source.positions;
            rebuild(curve);
            AssertThrow(!curve.closed || !curve.spline->is_self_intersecting(),
                        ExcMessage("Boundary curves/" + curve.name +
                                   ": the closed curve through the given "
                                   "points intersects itself."));
          }
      }

    // Curves that the input draws across each other, or closer than the
    // touching distance, are refused here, before the first step (a
    // touch that deformation makes is found after the step that makes it:
    // check_touching()).
    const std::string touch =
      touch_check.find_touch(curves, grid.min_cell_size());
    AssertThrow(touch.empty(), ExcMessage("In the input: " + touch));

    trimming_grid = &grid;
    trimming_state.assign(std::size_t(grid.n_cells(0)) * grid.n_cells(1), 0);
    const UniformGrid uniform{grid.lower_left(),
                              grid.cell_size(),
                              {{grid.n_cells(0), grid.n_cells(1)}}};
    for (const auto &curve : curves)
      if (curve.trims_material_points && curve.spline)
        for (const auto &piece :
             CurveCellIntersection::cut(*curve.spline, uniform))
          trimming_state[piece.cell[1] * grid.n_cells(0) + piece.cell[0]] = 3;
  }



  bool
  BoundaryCurves::trims(const Point<2> &p) const
  {
    if (trimming_grid == nullptr || !trimming_grid->contains(p))
      return outside_trimming_curve(p);
    const auto     ij = trimming_grid->cell_index(p);
    unsigned char &state =
      trimming_state[ij[1] * trimming_grid->n_cells(0) + ij[0]];
    if (state == 3)
      return outside_trimming_curve(p);
    if (state == 0)
      {
        const Point<2> center =
          trimming_grid->cell_origin(ij) + 0.5 * trimming_grid->cell_size();
        state = outside_trimming_curve(center) ? 2 : 1;
      }
    return state == 2;
  }



  bool
  BoundaryCurves::outside_trimming_curve(const Point<2> &p) const
  {
    for (const auto &curve : curves)
      if (curve.trims_material_points && curve.spline)
        {
          const auto closest = curve.spline->closest_point(p);
          if ((p - closest.point) * curve.spline->outward_normal(closest.u) > 0)
            return true;
        }
    return false;
  }



  std::vector<types::particle_index>
  BoundaryCurves::create_points(MaterialPoints   &points,
                                const BodyRegion &region)
  {
    // A point may belong to two curves (a corner of the outer layer): it is
    // tracked once.
    std::vector<types::particle_index>              tracked;
    std::map<types::particle_index, unsigned int>   slot_of;
    std::vector<std::vector<types::particle_index>> ids(curves.size());
    for (unsigned int c = 0; c < curves.size(); ++c)
      {
        BoundaryCurve &curve  = curves[c];
        Source        &source = sources[c];
        if (source.kind == "material points")
          {
            const auto edge = region.boundary_points(source.edge, 2);
            ids[c]          = points.outer_layer(edge.points, edge.closed);
            curve.closed    = edge.closed;
          }
        else
          ids[c] = points.add_tracking_points(curve.positions);

        curve.tracked_slots.clear();
        for (const auto id : ids[c])
          {
            const auto [it, inserted] = slot_of.emplace(id, tracked.size());
            if (inserted)
              tracked.push_back(id);
            curve.tracked_slots.push_back(it->second);
          }
      }
    // The outer layer stands for the body up to its boundary: its points
    // keep half their volume on a side, a quarter at a corner (paper
    // Sec. 4.1.2).
    for (unsigned int c = 0; c < curves.size(); ++c)
      if (curves[c].halve_point_volumes)
        points.scale_volumes(ids[c], 0.5);
    return tracked;
  }



  void
  BoundaryCurves::read_initial_positions(const MaterialPoints &points)
  {
    std::vector<Point<2>> positions;
    std::vector<Voigt>    stresses;
    points.tracked_states(positions, stresses);
    for (auto &curve : curves)
      {
        curve.initial_positions.clear();
        for (const unsigned int slot : curve.tracked_slots)
          curve.initial_positions.push_back(positions[slot]);
      }
  }



  void
  BoundaryCurves::update(const MaterialPoints &points,
                         const BackgroundGrid &grid)
  {
    std::vector<Point<2>>                     positions;
    std::vector<Voigt>                        stresses;
    std::vector<MaterialPoints::TrackedState> states;
    points.tracked_states(positions, stresses, &states);
    const UniformGrid uniform{grid.lower_left(),
                              grid.cell_size(),
                              {{grid.n_cells(0), grid.n_cells(1)}}};
    for (auto &curve : curves)
      {
        curve.positions.clear();
        curve.stresses.clear();
        curve.states.clear();
        for (const unsigned int slot : curve.tracked_slots)
          {
            curve.positions.push_back(positions[slot]);
            curve.stresses.push_back(stresses[slot]);
            curve.states.push_back(states[slot]);
          }
        rebuild(curve);
        try
          {
            curve.pieces = CurveCellIntersection::cut(*curve.spline, uniform);
          }
        catch (const ExceptionBase &e)
          {
            std::ostringstream message;
            e.print_info(message);
            AssertThrow(false,
                        ExcMessage("Boundary curves/" + curve.name + ": " +
                                   Utilities::trim(message.str())));
          }
      }
  }



  std::vector<std::pair<bool, Tensor<1, 2>>>
  BoundaryCurves::rigid_support_increments(const unsigned int   n_slots,
                                           const ExactSolution *exact,
                                           const double         factor) const
  {
    std::vector<std::pair<bool, Tensor<1, 2>>> increments(n_slots,
                                                          {false,
                                                           Tensor<1, 2>()});
    for (const auto &curve : curves)
      for (unsigned int k = 0; k < curve.tracked_slots.size(); ++k)
        if (const CurveCondition *condition = curve.rigid_support(k);
            condition != nullptr && curve.tracked_slots[k] < n_slots)
          {
            AssertThrow(condition->function || exact != nullptr,
                        ExcMessage("Boundary curves/" + curve.name + ": '" +
                                   condition->kind_name() +
                                   " exact' needs an exact solution."));
            const unsigned int n = curve.n_segments();
            const double u = k < n ? curve.spline->segment_parameters(k)[0] :
                                     curve.spline->segment_parameters(n - 1)[1];
            const Tensor<1, 2> normal = curve.spline->outward_normal(u);
            const Point<2>    &x      = curve.positions[k];
            const double       u_n    = condition->function ?
                                          condition->function->value(x, 0) :
                                          exact->displacement(x) * normal;
            increments[curve.tracked_slots[k]] = {true, factor * u_n * normal};
          }
    return increments;
  }



  void
  BoundaryCurves::rebuild(BoundaryCurve &curve) const
  {
    for (const auto &condition : curve.conditions)
      condition.check_range(curve.positions.size(), curve.closed, curve.name);
    for (const unsigned int corner : curve.corners)
      AssertThrow(
        corner < curve.positions.size(),
        ExcMessage("Boundary curves/" + curve.name + "/Corners: corner index " +
                   std::to_string(corner) + " lies beyond the chain of " +
                   std::to_string(curve.positions.size()) +
                   " points (numbered from 0 to " +
                   std::to_string(curve.positions.size() - 1) + ")."));
    try
      {
        curve.spline = std::make_unique<BSplineCurve>(curve.positions,
                                                      curve.closed,
                                                      curve.corners);
      }
    catch (const ExceptionBase &e)
      {
        std::ostringstream message;
        e.print_info(message);
        AssertThrow(false,
                    ExcMessage("Boundary curves/" + curve.name + ": " +
                               Utilities::trim(message.str())));
      }
  }



  bool
  BoundaryCurves::has_loads() const
  {
    for (const auto &curve : curves)
      for (const auto &condition : curve.conditions)
        if (condition.is_load())
          return true;
    return false;
  }



  bool
  BoundaryCurves::prescribe_displacement() const
  {
    for (const auto &curve : curves)
      for (const auto &condition : curve.conditions)
        if (condition.prescribes_displacement())
          return true;
    return false;
  }



  void
  BoundaryCurves::mark_support_cells(
    const BackgroundGrid                &grid,
    const BoundaryCurve::DirichletMethod method,
    const bool                           both_components_only,
    std::vector<bool>                   &cells) const
  {
    for (const auto &curve : curves)
      if (curve.dirichlet_method == method)
        for (const auto &piece : curve.pieces)
          {
            const CurveCondition *condition =
              curve.condition_of_segment(piece.segment);
            if (condition == nullptr || !condition->is_support() ||
                (both_components_only && !condition->holds_both_components()))
              continue;
            const auto cell = grid.locally_owned_cell(piece.cell);
            if (cell != grid.dof_handler().end())
              cells[cell->active_cell_index()] = true;
          }
  }



  bool
  BoundaryCurves::has_supports(
    const BoundaryCurve::DirichletMethod method) const
  {
    for (const auto &curve : curves)
      if (curve.dirichlet_method == method)
        for (const auto &condition : curve.conditions)
          if (condition.is_support())
            return true;
    return false;
  }



  bool
  BoundaryCurves::encloses_body(std::string &reason) const
  {
    reason.clear();
    if (curves.empty())
      reason = "no boundary curves";
    for (unsigned int c = 0; c < curves.size() && reason.empty(); ++c)
      if (sources[c].kind == "material points" &&
          !curves[c].halve_point_volumes)
        reason = curves[c].name +
                 " runs through material points whose volumes reach "
                 "beyond it ('Halve point volumes' makes it the boundary)";
    if (!reason.empty())
      return false;

    // Each open curve must end where another one starts.
    double scale = 0;
    for (const auto &curve : curves)
      for (const auto &p : curve.initial_positions)
        scale = std::max(scale, std::max(std::abs(p[0]), std::abs(p[1])));
    const double      tolerance = 1e-10 * std::max(scale, 1e-300);
    std::vector<bool> start_taken(curves.size(), false);
    for (unsigned int c = 0; c < curves.size(); ++c)
      {
        if (curves[c].closed)
          continue;
        const Point<2> end   = curves[c].initial_positions.back();
        bool           found = false;
        for (unsigned int d = 0; d < curves.size() && !found; ++d)
          if (!curves[d].closed && !start_taken[d] &&
              curves[d].initial_positions.front().distance(end) <= tolerance)
            {
              start_taken[d] = true;
              found          = true;
            }
        if (!found)
          {
            std::ostringstream where;
            where << curves[c].name << " ends at (" << end[0] << ", " << end[1]
                  << ") where no other curve starts";
            reason = where.str();
            return false;
          }
      }
    return true;
  }



  std::vector<std::pair<std::string, std::vector<Point<2>>>>
  BoundaryCurves::given_points() const
  {
    std::vector<std::pair<std::string, std::vector<Point<2>>>> result;
    for (unsigned int c = 0; c < curves.size(); ++c)
      if (sources[c].kind == "coordinates" || sources[c].kind == "file")
        result.emplace_back(curves[c].name, sources[c].positions);
    return result;
  }



  unsigned int
  BoundaryCurves::n_points() const
  {
    unsigned int n = 0;
    for (const auto &curve : curves)
      n += curve.positions.size();
    return n;
  }



  std::vector<BoundaryCurves::PointOrigins>
  BoundaryCurves::adapt_point_spacing(MaterialPoints       &points,
                                      const BackgroundGrid &grid)
  {
    std::vector<PointOrigins> origins(curves.size());
    n_inserted.resize(curves.size(), 0);
    n_removed.resize(curves.size(), 0);
    if (!point_spacing.enabled())
      return origins;
    const double       h       = grid.min_cell_size();
    const unsigned int invalid = numbers::invalid_unsigned_int;
    for (unsigned int c = 0; c < curves.size(); ++c)
      {
        // Points of the outer layer of material points carry volume:
        // they cannot be made or dropped here.
        if (sources[c].kind == "material points")
          continue;
        BoundaryCurve                   &curve = curves[c];
        const BoundaryPointSpacing::Plan plan  = point_spacing.plan(curve, h);
        if (plan.empty())
          continue;
        const unsigned int n = curve.positions.size();
        std::vector<bool>  removed(n, false), split(n, false);
        for (const unsigned int k : plan.removed_points)
          removed[k] = true;
        for (const unsigned int s : plan.split_segments)
          split[s] = true;

        // The new chain, its new points at the middle of their segments'
        // parameter ranges on the spline through the moved points.
        PointOrigins             &origin = origins[c];
        std::vector<unsigned int> new_index(n, invalid);
        std::vector<Point<2>>     new_positions;
        std::vector<unsigned int> neighbour_slots;
        for (unsigned int k = 0; k < n; ++k)
          {
            if (!removed[k])
              {
                new_index[k] = origin.size();
                origin.push_back({{k, k}});
              }
            if (split[k])
              {
                const unsigned int k1    = (k + 1) % n;
                const auto         range = curve.spline->segment_parameters(k);
                origin.push_back({{k, k1}});
                new_positions.push_back(
                  curve.spline->value((range[0] + range[1]) / 2));
                neighbour_slots.push_back(curve.tracked_slots[k]);
                neighbour_slots.push_back(curve.tracked_slots[k1]);
              }
          }

        // The state of a new point: the mean of its neighbours'; its total
        // displacement takes it from the mean of their starting places to
        // where it is.
        const auto neighbours = points.tracked_properties(neighbour_slots);
        std::vector<std::vector<double>> new_properties;
        std::vector<Point<2>>            new_initial_positions;
        for (unsigned int i = 0; i < new_positions.size(); ++i)
          {
            std::vector<double> props = neighbours[2 * i];
            for (unsigned int j = 0; j < props.size(); ++j)
              props[j] = (props[j] + neighbours[2 * i + 1][j]) / 2;
            using P = MaterialPoints::Property;
            const Point<2> X(props[P::initial_position],
                             props[P::initial_position + 1]);
            props[P::displacement]     = new_positions[i][0] - X[0];
            props[P::displacement + 1] = new_positions[i][1] - X[1];
            new_properties.push_back(props);
            new_initial_positions.push_back(X);
          }
        const std::vector<unsigned int> new_slots =
          points.add_tracked_points(new_positions, new_properties);
        std::vector<unsigned int> removed_slots;
        for (const unsigned int k : plan.removed_points)
          removed_slots.push_back(curve.tracked_slots[k]);
        points.remove_tracked_points(removed_slots);

        // The chain's own records, in the new order.
        std::vector<Point<2>>     positions, initial_positions;
        std::vector<Voigt>        stresses;
        std::vector<unsigned int> slots;
        unsigned int              next_new = 0;
        for (const auto &[a, b] : origin)
          if (a == b)
            {
              positions.push_back(curve.positions[a]);
              initial_positions.push_back(curve.initial_positions[a]);
              stresses.push_back(curve.stresses[a]);
              slots.push_back(curve.tracked_slots[a]);
            }
          else
            {
              positions.push_back(new_positions[next_new]);
              initial_positions.push_back(new_initial_positions[next_new]);
              stresses.push_back(0.5 * (curve.stresses[a] + curve.stresses[b]));
              slots.push_back(new_slots[next_new]);
              ++next_new;
            }
        // Corners and the ends of ranges are never removed: renumbered,
        // they bound the same stretch of material as before.
        const unsigned int n_new    = origin.size();
        const auto         renumber = [&](const unsigned int k) {
          AssertThrow(k == n || new_index[k % n] != invalid,
                      ExcInternalError());
          return k == n ? n_new : new_index[k];
        };
        for (auto &corner : curve.corners)
          corner = renumber(corner);
        for (auto &condition : curve.conditions)
          if (condition.has_range())
            {
              condition.first_segment = renumber(condition.first_segment);
              condition.end_segment   = renumber(condition.end_segment);
            }
        curve.positions         = std::move(positions);
        curve.initial_positions = std::move(initial_positions);
        curve.stresses          = std::move(stresses);
        curve.tracked_slots     = std::move(slots);
        n_inserted[c] += new_positions.size();
        n_removed[c] += removed_slots.size();
        any_points_changed = true;
      }
    return origins;
  }



  void
  BoundaryCurves::check_touching(const double h) const
  {
    const std::string problem = touch_check.find_touch(curves, h);
    AssertThrow(problem.empty(), ExcMessage(problem));
  }



  void
  BoundaryCurves::record_point_changes(
    std::map<std::string, double> &quantities)
  {
    if (!any_points_changed)
      return;
    for (unsigned int c = 0; c < curves.size(); ++c)
      {
        const std::string name                = "curve" + std::to_string(c + 1);
        quantities[name + "_points_inserted"] = n_inserted[c];
        quantities[name + "_points_removed"]  = n_removed[c];
        quantities[name + "_points"]          = curves[c].positions.size();
        n_inserted[c] = n_removed[c] = 0;
      }
  }
} // namespace bsmpm
