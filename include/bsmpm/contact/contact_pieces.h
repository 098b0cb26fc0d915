#ifndef bsmpm_contact_pieces_h
#define bsmpm_contact_pieces_h

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <bsmpm/boundary/boundary_curves.h>
#include <bsmpm/contact/rigid_body.h>
#include <bsmpm/contact/rigid_body_motion.h>
#include <bsmpm/geometry/background_grid.h>

#include <array>
#include <vector>

namespace bsmpm
{
  using namespace dealii;

  class ContactHistory;

  /**
   * A piece of free curve in one locally owned cell that can touch a rigid
   * body in the increment, with its Gauss points at the increment's start
   * (doc/contact.md, "Formulation"): what the contact terms integrate
   * over. Its touching part and its multipliers change between Newton
   * solves (CurveContact::update_touching_parts(), ContactAugmentation).
   */
  struct ContactPiece
  {
    static ContactPiece
    make(const unsigned int                 body,
         const unsigned int                 curve,
         const std::array<unsigned int, 2> &cell,
         const unsigned int                 feature,
         const double                       u_begin,
         const double                       u_end)
    {
      ContactPiece piece;
      piece.body    = body;
      piece.curve   = curve;
      piece.cell    = cell;
      piece.feature = feature;
      piece.u_begin = u_begin;
      piece.u_end   = u_end;
      return piece;
    }

    unsigned int                body  = 0;
    unsigned int                curve = 0;
    std::array<unsigned int, 2> cell  = {{0, 0}};
    /** The part of the rigid outline it faces (SurfacePoint::feature). */
    unsigned int          feature = 0;
    double                u_begin = 0;
    double                u_end   = 0;
    std::vector<Point<2>> positions;
    std::vector<double>   weights; ///< ds
    /** The body's outward normal of the curve there. */
    std::vector<Tensor<1, 2>> curve_normals;
    /** The part of the outline each Gauss point measures its gap to:
     * the nearest at the increment's start. */
    std::vector<unsigned int> features;
    /** Which Gauss points make up the part that touches: fixed within
     * Newton iterations, updated between them
     * (CurveContact::update_touching_parts()). */
    std::vector<bool> touching;
    /** The traction of the last increment, interpolated from the
     * curve's points. */
    std::vector<Tensor<1, 2>> previous;
    double                    length = 0;
    /** The augmented Lagrangian's multiplier of the piece:
     * p = max(0, lambda - eps g). */
    double multiplier_pressure = 0;
    /** 'Contact/Pressure = at grid lines': the piece runs from one
     * crossing of the curve with a grid line (or end of a free stretch)
     * to the next, the gap is taken at the two crossings and linear
     * between them (in the curve's parameter; phi: the weight of the
     * second crossing at each Gauss point), and the pressure
     * max(0, lambda - eps g) at each Gauss point of that gap. u_begin
     * and u_end are the crossings' parameters (u_end > 1 where a closed
     * curve's piece runs past its start). */
    bool                        between_crossings = false;
    std::array<Point<2>, 2>     ends;
    std::array<unsigned int, 2> end_features = {{0, 0}};
    /** The crossings' parameters, which the pieces on either side of
     * one share (the multipliers' keys). */
    std::array<double, 2>       end_keys        = {{0, 0}};
    std::array<double, 2>       end_multipliers = {{0, 0}};
    std::array<Tensor<1, 2>, 2> end_previous;
    std::vector<double>         phi;
  };



  /**
   * 'Contact/Pressure = per cell': the pieces of the curves' free
   * stretches in the locally owned cells that can reach a rigid body in
   * the increment (within two cells of it where the increment ends, or of
   * its path), one per cell, curve and part of the outline they face, each
   * with @p n_gauss_points Gauss points per spline piece, its friction
   * history from @p history and its first guess of the touching part
   * (where the body, moved to the increment's end, overlaps the curve that
   * has not moved yet).
   *
   * This is the contact's loop over the curves' pieces in the cells, by
   * CurvePieceValues as the loads' and the supports'.
   */
  std::vector<ContactPiece>
  collect_pieces_per_cell(const BoundaryCurves         &curves,
                          const BackgroundGrid         &grid,
                          const std::vector<RigidBody> &bodies,
                          const RigidBodyMotion        &motion,
                          const ContactHistory         &history,
                          const unsigned int            n_gauss_points);

  /**
   * 'Contact/Pressure = at grid lines': the pieces of the curves' free
   * stretches from one crossing with a grid line (or end of the stretch)
   * to the next, in locally owned cells, one per body that they can reach
   * in the increment (doc/contact.md, "Pressures at the grid lines").
   */
  std::vector<ContactPiece>
  collect_pieces_between_crossings(const BoundaryCurves         &curves,
                                   const BackgroundGrid         &grid,
                                   const std::vector<RigidBody> &bodies,
                                   const RigidBodyMotion        &motion,
                                   const ContactHistory         &history,
                                   const unsigned int n_gauss_points);
} // namespace bsmpm

#endif
