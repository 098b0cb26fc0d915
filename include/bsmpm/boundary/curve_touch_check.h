#ifndef bsmpm_curve_touch_check_h
#define bsmpm_curve_touch_check_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>

#include <string>
#include <vector>

namespace bsmpm
{
  using namespace dealii;

  struct BoundaryCurve;

  /**
   * Whether a boundary curve touches itself or another curve of the body:
   * two of their parts that are not neighbours along the boundary cross or
   * come closer than a fraction of the cell size h (issue 25, item 3). The
   * method has no contact of the body with itself, so a run that gets there
   * stops with the place (doc/contact.md).
   *
   * Each spline segment is taken as two chords (its ends and the middle of
   * its parameter range). Two chords are neighbours, and never touch, when
   * the boundary between them is shorter than three times the touching
   * distance: along the chain, or, for chords of two curves, through a
   * point where the two curves meet (an end of each at the same place).
   */
  class CurveTouchCheck
  {
  public:
    /** Declares the subsection "Self contact" of the current section. */
    static void
    declare_parameters(ParameterHandler &prm);

    /** Reads the subsection "Self contact" of the current section. */
    void
    parse_parameters(ParameterHandler &prm);

    /** Where two parts of @p curves touch, as a message naming the curves,
     * their segments (by point indices) and the place; empty if nowhere.
     * @p h is the cell size. */
    std::string
    find_touch(const std::vector<BoundaryCurve> &curves, const double h) const;

  private:
    bool   check    = true;
    double distance = 0.01;
  };
} // namespace bsmpm

#endif
