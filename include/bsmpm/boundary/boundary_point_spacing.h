#ifndef bsmpm_boundary_point_spacing_h
#define bsmpm_boundary_point_spacing_h

#include <deal.II/base/parameter_handler.h>

#include <vector>

namespace bsmpm
{
  using namespace dealii;

  struct BoundaryCurve;

  /**
   * Where the tracking points of a boundary curve are too far apart or too
   * close together after the body moved them, and what to do about it
   * (issue 25, item 3; doc/contact.md).
   *
   * A segment is split by a new point at the middle of its parameter range
   * on the current spline when it is longer than `Insert above` times the
   * cell size h and has stretched to more than 1.5 times its length at the
   * start (the distance of its points' initial positions): the resolution
   * the scene started with is the user's choice, and only stretching past
   * it (and past the fraction of h) adds points. A point goes where one of
   * its segments has become shorter than `Remove below` times h and than
   * 1/1.5 of its starting length, so long as the segment that replaces its
   * two is not split again at once (shorter than `Insert above` times h).
   *
   * A point is never removed if it is an end of an open chain, point 0 of
   * a closed chain, a corner (marked), an end of a condition's range i-j,
   * or a place where the chain turns by more than 30 degrees (a corner the
   * spline detects, or soil wrapping round a footing's edge), nor next to
   * another point removed in the same pass; a closed chain keeps at least
   * four points.
   */
  class BoundaryPointSpacing
  {
  public:
    /** What to change on one curve: the points to remove and the segments
     * to split (indices of the chain before the change, increasing). */
    struct Plan
    {
      std::vector<unsigned int> removed_points;
      std::vector<unsigned int> split_segments;

      bool
      empty() const
      {
        return removed_points.empty() && split_segments.empty();
      }
    };

    /** Declares the subsection "Point spacing" of the current section. */
    static void
    declare_parameters(ParameterHandler &prm);

    /** Reads the subsection "Point spacing" of the current section. */
    void
    parse_parameters(ParameterHandler &prm);

    bool
    enabled() const
    {
      return adapt;
    }

    /** The changes to @p curve (its positions, initial positions, spline
     * through the positions, corners and conditions) for cell size @p h. */
    Plan
    plan(const BoundaryCurve &curve, const double h) const;

    /** A segment must have stretched by more than this (its length over
     * its starting length) before it is split. */
    static constexpr double stretch_before_split = 1.5;

  private:
    bool   adapt        = true;
    double insert_above = 0.5;
    double remove_below = 0.1;
  };
} // namespace bsmpm

#endif
