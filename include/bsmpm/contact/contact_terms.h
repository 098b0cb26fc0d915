#ifndef bsmpm_contact_terms_h
#define bsmpm_contact_terms_h

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include <bsmpm/contact/contact_law.h>
#include <bsmpm/contact/contact_pieces.h>
#include <bsmpm/contact/rigid_body.h>
#include <bsmpm/contact/rigid_body_motion.h>
#include <bsmpm/geometry/background_grid.h>
#include <bsmpm/points/q1_cell_kernel.h>

#include <array>
#include <utility>
#include <vector>

namespace bsmpm
{
  using namespace dealii;

  /** The moment about the origin of a force @p f at @p x in the plane
   * (its z component). */
  inline double
  moment_about_origin(const Tensor<1, 2> &x, const Tensor<1, 2> &f)
  {
    return x[0] * f[1] - x[1] * f[0];
  }

  /** What contact does on a piece for a displacement increment
   * (ContactTerms::evaluate()). */
  struct ContactPieceState
  {
    bool active  = false;
    bool sliding = false;
    /** Whether the stiffness is symmetric: not while a Gauss point slides,
     * nor with friction where the outline turns (the tangential traction
     * turns with the normal). */
    bool symmetric = true;
    /** Of the part that touches, the length that slides. */
    double sliding_length = 0;
    /** Minus the mean penetration where the piece touches. */
    double       gap            = 0;
    double       contact_length = 0; ///< of the part that touches
    double       pressure       = 0;
    double       tangential     = 0;
    Tensor<1, 2> normal; ///< mean normal of the rigid surface
    /** Every Gauss point's gap and normal, touching or not. */
    std::vector<SurfacePoint> surface;
    Point<2>                  midpoint;
    /** Force on the body (N) and the piece's share of the rigid body's
     * reaction is its opposite. */
    Tensor<1, 2> resultant;
    /** That force's moment about the origin, int x x t ds (x the Gauss
     * points' places after the increment, t the traction on the body). */
    double moment = 0;

    /** Adds the force @p f, acting at @p x, to the resultant and its
     * moment. */
    void
    add_force(const Point<2> &x, const Tensor<1, 2> &f)
    {
      resultant += f;
      moment += moment_about_origin(x, f);
    }
    /** On the cell's DoFs and, as two more, the body's translation
     * (x, y) at the increment's end: the force and minus its
     * derivative. */
    Vector<double>     force;
    FullMatrix<double> stiffness;
    /** Between crossings: at each crossing, the integral of the
     * crossing's weight phi along the piece, that of the gap times phi
     * where the piece presses (the augmented Lagrangian's update), and the
     * traction there (its lumped projection, the next increment's
     * history). */
    std::array<double, 2>       end_weights = {{0, 0}};
    std::array<double, 2>       end_gaps    = {{0, 0}};
    std::array<Tensor<1, 2>, 2> end_tractions;
    /** Between crossings, for the output per crossing (ContactResults):
     * where each crossing is after the increment, the outline's outward
     * normal there, the integral of phi times the gap over all Gauss
     * points (touching or not) and of phi where the piece slides. */
    std::array<Point<2>, 2>     end_places;
    std::array<Tensor<1, 2>, 2> end_normals;
    std::array<double, 2>       end_weighted_gaps = {{0, 0}};
    std::array<double, 2>       end_sliding       = {{0, 0}};
    /** The moment's share of each crossing: int phi x x t ds. */
    std::array<double, 2> end_moments = {{0, 0}};
  };



  /**
   * The contact's share of the Newton system on one piece (doc/contact.md,
   * "Formulation", "Pressures at the grid lines", "Rigid bodies under a
   * force"): where the piece's Gauss points are after the increment, their
   * gaps and slips, the contact law (ContactLaw) on them, and the force
   * and its exact derivative (a stiffness) on the cell's 8 DoFs and the
   * body's translation (two more DoFs, the bordered terms of a
   * force-controlled body).
   *
   * One pressure per cell: the law on the mean gap and slip of the
   * piece's touching part, G_i = int_A n . N_i ds, T_i = int_A t . N_i ds,
   * the tangent eps / L G G^T (sticking also eps / L T T^T, sliding
   * mu sign eps / L T G^T), plus the turning of n where the outline turns
   * and the tilt penalty. Between crossings: the law at each Gauss point
   * of the gap linear between the crossings.
   */
  class ContactTerms
  {
  public:
    /** The cell's DoFs and, as two more, the body's translation. */
    static constexpr unsigned int n_dofs = Q1CellKernel::dofs_per_cell + 2;

    /** Shape values on the n_dofs DoFs of a piece: as Tensor<1, 2>. */
    using ShapeValues = std::array<Tensor<1, 2>, n_dofs>;

    /** For a load increment: the penalty eps (the law's), the tilt's
     * penalty (zero: none), and the gap up to which a place counts as
     * touching. */
    void
    reinit(const ContactLaw::Method method,
           const double             penalty,
           const double             tilt_penalty,
           const double             touching_tolerance);

    double
    penalty() const
    {
      return eps;
    }

    /** The gap up to which a place counts as touching. */
    double
    touching_tolerance() const
    {
      return tolerance;
    }

    /** The contact law on the surface of @p body. */
    ContactLaw
    law(const RigidBody &body) const;

    /** What contact does on @p piece at the nodal increment @p d of its
     * cell, with the body moved by @p body_shift from where @p motion
     * has it (for the central differences of ContactTangentCheck). */
    ContactPieceState
    evaluate(const ContactPiece              &piece,
             const std::vector<RigidBody>    &bodies,
             const RigidBodyMotion           &motion,
             const BackgroundGrid            &grid,
             const Q1CellKernel              &kernel,
             const Q1CellKernel::LocalVector &d,
             const Tensor<1, 2> &body_shift = Tensor<1, 2>()) const;

  private:
    /** The shape values at @p x in @p cell (into @p N) and the
     * displacement there at the nodal increment @p d: moving the body by
     * c moves a gap as moving the point by -c does, so the body's
     * translation enters as two more DoFs with the shapes -e_x, -e_y. */
    static Tensor<1, 2>
    shape_values(const BackgroundGrid              &grid,
                 const Q1CellKernel                &kernel,
                 const std::array<unsigned int, 2> &cell,
                 const Point<2>                    &x,
                 const Q1CellKernel::LocalVector   &d,
                 ShapeValues                       &N);

    /** One pressure per cell: the mean slip, relative to the body (which
     * moved by @p rigid in the increment), of the piece's touching part
     * (of length @p length) at the Gauss points' displacements @p u, and
     * the mean tangential traction of the last increment there: the
     * inputs of Coulomb's return map. */
    static std::pair<double, double>
    mean_slip(const ContactPiece              &piece,
              const std::vector<Tensor<1, 2>> &u,
              const std::vector<SurfacePoint> &surface,
              const Tensor<1, 2>              &rigid,
              const double                     length);

    /** evaluate() with one pressure for the mean gap of the piece's
     * touching part. */
    ContactPieceState
    evaluate_per_cell(const ContactPiece              &piece,
                      const RigidBody                 &body,
                      const RigidBodyMotion           &motion,
                      const BackgroundGrid            &grid,
                      const Q1CellKernel              &kernel,
                      const Q1CellKernel::LocalVector &d,
                      const Tensor<1, 2>              &body_shift) const;

    /** evaluate() for a piece between crossings. */
    ContactPieceState
    evaluate_between_crossings(const ContactPiece              &piece,
                               const RigidBody                 &body,
                               const RigidBodyMotion           &motion,
                               const BackgroundGrid            &grid,
                               const Q1CellKernel              &kernel,
                               const Q1CellKernel::LocalVector &d,
                               const Tensor<1, 2> &body_shift) const;

    /** Adds to @p state the force and stiffness of the penalty on the
     * tilt of the gap along the piece's touching part (Contact/Tilt
     * penalty), @p N the shape values of the Gauss points on the cell's
     * DoFs and the body's translation, @p u their displacements. */
    void
    add_tilt_terms(const ContactPiece              &piece,
                   const std::vector<ShapeValues>  &N,
                   const std::vector<Tensor<1, 2>> &u,
                   const std::vector<SurfacePoint> &surface,
                   ContactPieceState               &state) const;

    ContactLaw::Method method       = ContactLaw::Method::penalty;
    double             eps          = 0;
    double             tilt_penalty = 0;
    double             tolerance    = 0;
  };
} // namespace bsmpm

#endif
