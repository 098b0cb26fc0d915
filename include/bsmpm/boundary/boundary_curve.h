#ifndef bsmpm_boundary_curve_h
#define bsmpm_boundary_curve_h

#include <bsmpm/boundary/curve_condition.h>
#include <bsmpm/geometry/b_spline_curve.h>
#include <bsmpm/geometry/curve_cell_intersection.h>
#include <bsmpm/points/material_points.h>

#include <memory>
#include <string>
#include <vector>

namespace bsmpm
{
  using namespace dealii;

  /**
   * One boundary curve: an ordered chain of boundary points (zero-volume
   * tracking points or material points) that moves with the body, the cubic
   * B-spline through their current positions, and its pieces per grid cell,
   * both rebuilt every load step.
   */
  struct BoundaryCurve
  {
    std::string name;
    /** The registered name of the SupportMethod that imposes the curve's
     * supports, its "Dirichlet method" ("implicit boundary", "nitsche"). */
    std::string                 dirichlet_method = "implicit boundary";
    bool                        closed           = false;
    std::vector<unsigned int>   corners;
    std::vector<CurveCondition> conditions;
    bool                        trims_material_points = false;
    /** Slots of the chain's points in MaterialPoints' tracked list. */
    std::vector<unsigned int> tracked_slots;
    std::vector<Point<2>>     positions;
    /** Positions of the points at the start of the run. */
    std::vector<Point<2>> initial_positions;
    /** Stresses of the points (Voigt), as of the last load step. */
    std::vector<Voigt> stresses;
    /** Their constitutive states (elastic strain, plastic strain, det F),
     * as of the last load step: the state of the boundary that finite
     * strain's support terms load further (state_at()). */
    std::vector<MaterialPoints::TrackedState> states;
    std::unique_ptr<BSplineCurve>             spline;
    std::vector<CurvePiece>                   pieces;

    unsigned int
    n_segments() const
    {
      return closed ? positions.size() : positions.size() - 1;
    }

    /**
     * The condition of the rigid body that point @p k belongs to, or
     * nullptr. A rigid body is pushed by a prescribed normal displacement
     * (a smooth footing): a run of segments with the same 'normal
     * displacement' condition of which at least one end meets a segment
     * that is no support (the footing's edge meets the free surface). Its
     * points move with the body, by the prescribed normal displacement, so
     * that the contact keeps its extent while the soil slides along it. An
     * end of the run that meets another support (the corner of a box held
     * on two sides) slides with the body as before.
     */
    const CurveCondition *
    rigid_support(const unsigned int k) const;

    /** The stress of the curve's points as of the last load step at
     * parameter @p u of segment @p segment, interpolated linearly between
     * the segment's two points: the boundary's stress, whose traction is the
     * reaction that supports carry from step to step. */
    Voigt
    stress_at(const unsigned int segment, const double u) const;

    /** The constitutive state of the curve at parameter @p u of segment
     * @p segment, interpolated linearly between the segment's two points,
     * as the properties of a material point (MaterialPoints::Property:
     * elastic strain, plastic strain and det F set, volume and weight 1,
     * the rest zero): what the supports' terms in finite strain load with
     * the step's deformation (ImplicitBoundary, NitscheBoundary). */
    std::vector<double>
    state_at(const unsigned int segment, const double u) const;

    /** The condition on segment @p k (the last one given that covers it),
     * or nullptr if the segment is free. */
    const CurveCondition *
    condition_of_segment(const unsigned int k) const;
  };
} // namespace bsmpm

#endif
