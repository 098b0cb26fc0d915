#include <deal.II/base/utilities.h>

#include <bsmpm/base/parameter_tools.h>
#include <bsmpm/boundary/boundary_curves.h>
#include <bsmpm/boundary/support_method.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

// BoundaryCurves, part 1: the parameters, and the curves rebuilt and cut by
// the grid at every step with what the other subsystems ask of them. The
// class spans three files by concern (the ASPECT way): this one; building
// the curves and their points before the first step
// (boundary_curves_setup.cc); the tracking points inserted and removed as
// the body stretches (boundary_curves_point_spacing.cc). The grammar of a
// condition is CurveCondition's (curve_condition.cc), one curve
// BoundaryCurve (boundary_curve.cc).

namespace bsmpm
{
  namespace
  {
    std::string
    curve_section(const unsigned int c)
    {
      return "Curve " + std::to_string(c + 1);
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
  } // namespace



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
                          Patterns::Selection(support_method_names()),
                          "How the supports of this curve (fixed, roller, "
                          "displacement, normal displacement) are imposed: by "
                          "the implicit boundary method (paper Sec. 3.5; its "
                          "band in 'Implicit boundary') or by Nitsche's "
                          "method (its penalty in 'Nitsche'). Both reproduce "
                          "a linear field that meets the support; Nitsche's "
                          "has no band and a condition number that no band "
                          "width raises, the implicit boundary method is the "
                          "paper's (doc/implicit-boundary.md).");
        prm.declare_entry(
          "Curve position",
          "region edge",
          Patterns::Selection(
            "region edge|through the points|through halved points"),
          "material points: where the curve runs. region edge (the "
          "default): along the body region's edge, through one tracking "
          "point beside each point of the outer layer (and the edge's "
          "corners); the points' volumes fill the body up to the curve, so "
          "cut cells are integrated exactly, whatever the number of points "
          "per cell. through the points: through the outer layer of points "
          "themselves (the paper's cantilever, Sec. 4.2); their volumes "
          "reach half a point spacing beyond the curve, so the curve is not "
          "the body's boundary, cells are integrated by their points alone, "
          "and fewer than about two points per cell in a direction may leave "
          "the system singular. through halved points: through the points, "
          "with their volumes halved (a quarter at a corner point of two "
          "such curves) so that they stand for the body up to the curve "
          "(the paper's patch test, Sec. 4.1.2).");
        prm.declare_entry("Halve point volumes",
                          "false",
                          Patterns::Bool(),
                          "material points: true is Curve position = "
                          "through halved points.");
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
                            "'[i-j:] kind [arguments]': free; pressure <p> "
                            "(a number or an expression of t); traction "
                            "<tx>; <ty> (expressions of x, y and t); exact "
                            "traction; fixed; roller; displacement exact; "
                            "displacement <ux>; <uy>; normal displacement "
                            "exact; normal displacement <un> (expressions of "
                            "x, y and t). Loads and displacements are scaled "
                            "by the load factor t, except those whose "
                            "expression uses t: it is the load or the "
                            "displacement at t itself (of one stage only, "
                            "doc/stages.md). "
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
            curve.dirichlet_method      = prm.get("Dirichlet method");
            for (const std::string name :
                 {"Condition", "Condition 2", "Condition 3", "Condition 4"})
              if (!Utilities::trim(prm.get(name)).empty())
                curve.conditions.push_back(
                  CurveCondition::parse(prm.get(name), where + "/" + name));

            source.edge                = Utilities::trim(prm.get("Edge"));
            source.n_points            = prm.get_integer("Number of points");
            const std::string position = prm.get("Curve position");
            source.outer_layer         = prm.get_bool("Halve point volumes") ||
                                     position == "through halved points" ?
                                           OuterLayer::through_halved_points :
                                         position == "through the points" ?
                                           OuterLayer::through_points :
                                           OuterLayer::region_edge;
            if (source.kind == "coordinates")
              source.positions =
                ParameterTools::parse_points(prm.get("Coordinates"),
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
                                           const LoadIncrement &increment) const
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
            std::string        unreported; // the supports' terms report it
            const double       u_n =
              condition->function ?
                      condition->normal_displacement_increment(x,
                                                         increment,
                                                         unreported) :
                      increment.share() * (exact->displacement(x) * normal);
            increments[curve.tracked_slots[k]] = {true, u_n * normal};
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
  BoundaryCurves::loads_proportional() const
  {
    for (const auto &curve : curves)
      for (const auto &condition : curve.conditions)
        if (condition.is_load() && condition.expression_of_t)
          return false;
    return true;
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
  BoundaryCurves::mark_support_cells(const BackgroundGrid &grid,
                                     const std::string    &method,
                                     const bool            both_components_only,
                                     std::vector<bool>    &cells) const
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
  BoundaryCurves::has_supports(const std::string &method) const
  {
    for (const auto &curve : curves)
      if (method.empty() || curve.dirichlet_method == method)
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
          sources[c].outer_layer == OuterLayer::through_points)
        reason = curves[c].name +
                 " runs through material points whose volumes reach "
                 "beyond it (Curve position = through the points)";
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



  void
  BoundaryCurves::check_touching(const double h) const
  {
    const std::string problem = touch_check.find_touch(curves, h);
    AssertThrow(problem.empty(), ExcMessage(problem));
  }
} // namespace bsmpm
