#ifndef bsmpm_curve_contact_h
#define bsmpm_curve_contact_h

#include <deal.II/base/parameter_handler.h>

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/la_parallel_vector.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <bsmpm/boundary/boundary_curves.h>
#include <bsmpm/contact/rigid_body.h>
#include <bsmpm/contact/rigid_body_motion.h>
#include <bsmpm/geometry/background_grid.h>
#include <bsmpm/points/q1_cell_kernel.h>

#include <algorithm>
#include <map>
#include <ostream>
#include <string>
#include <vector>

namespace bsmpm
{
  using namespace dealii;

  /**
   * Contact of the body's B-spline boundary with rigid bodies
   * (doc/contact.md). Every free stretch of every boundary curve is a
   * candidate: where it touches a rigid body it takes the contact
   * condition, where it leaves it it is free again, with no input.
   *
   * The condition is imposed on the curve pieces in the cut cells (the
   * pieces of a curve in one cell that face one part of a rigid outline),
   * integrated with Gauss points on the spline of the step's start (the
   * curve that the points define), moved by the displacement increment: at
   * a Gauss point X, x = X + du(X), the gap g(x) to the rigid body (at the
   * load factor the increment ends at) and its normal n. Each piece has one
   * pressure for the mean gap g_m of its touching part, by default an
   * augmented Lagrangian p = max(0, lambda - eps g_m) with the multiplier
   * lambda updated after each converged Newton solve (Uzawa) until the
   * force on the rigid bodies stands ('Contact/Method'; lambda = 0: the
   * plain penalty). With friction the tangential traction is a return map
   * of Coulomb's law on the mean slip s of the increment relative to the
   * body, regularized by the penalty in both methods,
   *
   *   t_trial = t_previous - eps s,
   *   t_T     = t_trial                      if |t_trial| <= mu p (stick),
   *           = mu p sign(t_trial)           otherwise (slip).
   *
   * Which Gauss points touch is fixed within the Newton iterations and
   * updated between them, before the multipliers; the tangent is the
   * exact derivative, unsymmetric while anything slides. The penalty
   * eps = gamma max(E, kappa) / h is Nitsche's scale.
   *
   * The tangential traction of the last increment, the history of
   * friction, is kept at the curves' points and interpolated along the
   * segments.
   */
  class CurveContact
  {
  public:
    /** Declares "Contact" and the "Rigid body N" subsections. */
    static void
    declare_parameters(ParameterHandler &prm);

    void
    parse_parameters(ParameterHandler &prm);

    /** Whether the scene has rigid bodies. */
    bool
    enabled() const
    {
      return !bodies.empty();
    }

    /** Whether the load factor moves a rigid body (RigidBody::
     * moves_with_load()). */
    bool
    moves_bodies_with_load() const
    {
      return std::any_of(bodies.begin(), bodies.end(), [](const auto &body) {
        return body.moves_with_load();
      });
    }

    const std::vector<RigidBody> &
    rigid_bodies() const
    {
      return bodies;
    }

    /** Where the bodies are in the present increment, and the unknowns of
     * the force-controlled ones with the bordered terms of the last
     * add_newton_terms(). */
    RigidBodyMotion &
    motion()
    {
      return body_motion;
    }

    /** The bodies' outlines where the last finish_increment() left them
     * (closed polylines), for output. */
    std::vector<std::vector<Point<2>>>
    outlines() const;

    /**
     * Starts a load increment from load factor @p from to @p to: collects
     * the Gauss points of the curves' free pieces in locally owned cells
     * that can reach a rigid body in it. @p stiffness: the elastic scale
     * max(E, kappa) of the penalty.
     */
    void
    begin_increment(const BoundaryCurves &curves,
                    const BackgroundGrid &grid,
                    const double          stiffness,
                    const double          from,
                    const double          to);

    /**
     * Adds the contact forces on the body at the increment @p increment
     * (ghosted; @p prescribed as for the points) to @p force and their
     * derivative (with a minus: a stiffness) to @p tangent, and, for bodies
     * under a force, the bordered terms and the bodies' residual to
     * motion(). Returns
     * whether the tangent stays symmetric (no Gauss point slides), over
     * all processes.
     */
    bool
    add_newton_terms(
      const BackgroundGrid                             &grid,
      const Q1CellKernel                               &kernel,
      const LinearAlgebra::distributed::Vector<double> &increment,
      const LinearAlgebra::distributed::Vector<double> *prescribed,
      const AffineConstraints<double>                  &constraints,
      TrilinosWrappers::SparseMatrix                   &tangent,
      TrilinosWrappers::MPI::Vector                    &force);

    /**
     * After Newton iterations converged at @p increment: updates the
     * pieces' touching parts (update_touching_parts(), at most
     * max_touching_updates times per increment) and, once they stand, with
     * the augmented Lagrangian the multipliers (augment(), at most
     * 'Contact/Maximum augmentations' times). Returns whether the
     * iterations must go on from @p increment: a part or the multipliers
     * changed. Collective.
     */
    bool
    after_convergence(
      const BackgroundGrid                             &grid,
      const Q1CellKernel                               &kernel,
      const LinearAlgebra::distributed::Vector<double> &increment,
      const LinearAlgebra::distributed::Vector<double> *prescribed);

    /**
     * After Newton iterations converged at @p increment: marks the Gauss
     * points that touch their rigid body there as the pieces' touching
     * parts. Returns whether any changed (on any process): then the
     * iterations must go on with the new parts. Collective.
     */
    bool
    update_touching_parts(
      const BackgroundGrid                             &grid,
      const Q1CellKernel                               &kernel,
      const LinearAlgebra::distributed::Vector<double> &increment,
      const LinearAlgebra::distributed::Vector<double> *prescribed);

    /**
     * After the increment converged at @p increment: the force on each
     * rigid body and the length in contact, and the tangential tractions
     * at the curves' points for the next increment. Call before the
     * points move. Collective.
     */
    void
    finish_increment(
      const BoundaryCurves                             &curves,
      const BackgroundGrid                             &grid,
      const Q1CellKernel                               &kernel,
      const LinearAlgebra::distributed::Vector<double> &increment,
      const LinearAlgebra::distributed::Vector<double> *prescribed);

    /** Adds rigid_body_N_force_x/y (the force of the body on the rigid
     * body, N/m), _displacement_x/y, _contact_length, _sliding_length and
     * _penetration (the largest) of the last finish_increment(). */
    /** Carries the friction history (the tangential traction kept at the
     * curves' points) over to the chains that
     * BoundaryCurves::adapt_point_spacing() changed: a new point takes the
     * mean of its two origins'. */
    void
    follow_point_changes(
      const std::vector<BoundaryCurves::PointOrigins> &origins);

    void
    record(std::map<std::string, double> &quantities) const;

    /** What a load step leaves for the next: the friction history (and the
     * multipliers' start) at the curves' points and the bodies' places,
     * for checkpoints. */
    template <class Archive>
    void
    serialize(Archive &archive, const unsigned int)
    {
      archive &point_tractions &body_motion;
    }

    /** The Gauss points of the last finish_increment() on all processes
     * (collective; written by process 0 only): body, x, y (where they
     * touch), gap, p_N, t_T, ds, sliding, as CSV. */
    void
    write_tractions(std::ostream &out, const MPI_Comm communicator) const;

  private:
    /**
     * One Uzawa update of the augmented Lagrangian at the converged
     * @p increment: each piece's multiplier takes its pressure
     * max(0, lambda - eps g) there (zero where it does not touch), the
     * update of a touching piece filtered 1 2 1 with its touching
     * neighbours' along the curve (doc/contact.md). Returns whether the
     * force on some rigid body changed by more than 'Contact/Augmentation
     * tolerance' since the last call; if not, the multipliers are left as
     * they were. Collective.
     */
    bool
    augment(const BackgroundGrid                             &grid,
            const Q1CellKernel                               &kernel,
            const LinearAlgebra::distributed::Vector<double> &increment,
            const LinearAlgebra::distributed::Vector<double> *prescribed);

    /** With the augmented Lagrangian: each piece's multiplier at the start
     * of the increment, the pressure of the last increment (kept at the
     * curves' points) on its first guess of the touching part. */
    void
    initialize_multipliers();

    /** For body @p b with a force-controlled component that none of the
     * candidate Gauss points touch at the start of the iterations: moves
     * it along its force until it touches the nearest (a body that touches
     * nothing has no stiffness against its free motion), and notes it in
     * motion(). Throws if nothing within reach lies in that direction.
     * Collective. */
    void
    touch_if_free(const unsigned int b, const BackgroundGrid &grid);

    /** A piece of free curve in one locally owned cell that can touch a
     * rigid body in the increment, with its Gauss points at the
     * increment's start. */
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
      /** The part of the outline each Gauss point measures its gap to:
       * the nearest at the increment's start. */
      std::vector<unsigned int> features;
      /** Which Gauss points make up the part that touches: fixed within
       * Newton iterations, updated between them
       * (update_touching_parts()). */
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

    /** The pieces of the curves' free stretches from crossing to crossing
     * with the grid lines, for begin_increment(). */
    void
    collect_crossings(const BoundaryCurves &curves, const BackgroundGrid &grid);

    /** What contact does on a piece for a displacement increment. */
    struct PieceState
    {
      bool active  = false;
      bool sliding = false;
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
      /** On the cell's DoFs and, as two more, the body's translation
       * (x, y) at the increment's end: the force and minus its
       * derivative. */
      Vector<double>     force;
      FullMatrix<double> stiffness;
      /** Between crossings: at each crossing, the integral of the
       * pressure times the crossing's weight phi along the piece, that of
       * phi, and the traction there (their lumped projection). */
      std::array<double, 2>       end_pressures = {{0, 0}};
      std::array<double, 2>       end_weights   = {{0, 0}};
      std::array<Tensor<1, 2>, 2> end_tractions;
    };

    /** What contact does on @p piece at the nodal increment @p d of its
     * cell, with the body moved by @p body_shift from where motion() has
     * it (for the differences of tangent_error()). */
    PieceState
    evaluate(const ContactPiece              &piece,
             const BackgroundGrid            &grid,
             const Q1CellKernel              &kernel,
             const Q1CellKernel::LocalVector &d,
             const Tensor<1, 2> &body_shift = Tensor<1, 2>()) const;

    /** evaluate() for a piece between crossings. */
    PieceState
    evaluate_between_crossings(const ContactPiece              &piece,
                               const BackgroundGrid            &grid,
                               const Q1CellKernel              &kernel,
                               const Q1CellKernel::LocalVector &d,
                               const Tensor<1, 2> &body_shift) const;

    /** Adds to @p state the force and stiffness of the penalty on the
     * tilt of the gap along the piece's touching part (Contact/Tilt
     * penalty), @p N the shape values of the Gauss points on the cell's
     * DoFs and the body's translation. */
    template <typename ShapeValues>
    void
    add_tilt_terms(const ContactPiece              &piece,
                   const ShapeValues               &N,
                   const std::vector<SurfacePoint> &surface,
                   PieceState                      &state) const;

    /** The largest difference of the stiffness of @p state (the piece's
     * at @p increment) from central differences of its forces, relative
     * to the stiffness's largest entry ('Contact/Check tangent'). */
    double
    tangent_error(
      const ContactPiece                               &piece,
      const BackgroundGrid                             &grid,
      const Q1CellKernel                               &kernel,
      const PieceState                                 &state,
      const LinearAlgebra::distributed::Vector<double> &increment,
      const LinearAlgebra::distributed::Vector<double> *prescribed) const;

    /** As above, at the nodal increment of the piece's cell (its DoFs
     * into @p dof_indices). */
    PieceState
    evaluate(const ContactPiece                               &piece,
             const BackgroundGrid                             &grid,
             const Q1CellKernel                               &kernel,
             const LinearAlgebra::distributed::Vector<double> &increment,
             const LinearAlgebra::distributed::Vector<double> *prescribed,
             std::vector<types::global_dof_index> &dof_indices) const;

    std::vector<RigidBody> bodies;
    RigidBodyMotion        body_motion;
    double                 gamma = 10;
    /** 'Contact/Pressure': one pressure per crossing of a curve with a
     * grid line (true) or per piece of curve in a cell. */
    bool pressure_at_crossings = true;
    /** The tilt's penalty as a factor of the mean gap's. */
    double gamma_tilt    = 0;
    double tilt_penalty  = 0;
    bool   check_tangent = false;
    /** On this process, of all checks of the run (check_tangent). */
    double       largest_tangent_error = 0;
    unsigned int n_gauss_points        = 4;
    /** 'Contact/Method': the augmented Lagrangian (true) or the plain
     * penalty. */
    bool         augmented              = true;
    double       augmentation_tolerance = 1e-4;
    unsigned int max_augmentations      = 30;
    /** Updates of the touching parts that one increment may ask for; then
     * the last parts stand. */
    static constexpr unsigned int max_touching_updates = 8;
    /** In the present increment. */
    unsigned int touching_updates = 0;
    unsigned int augmentations    = 0;
    /** The largest relative change of a body's contact force (or, under
     * a force, of its motion in the increment) in the last augment(), and
     * the forces it measured. */
    double                    force_change = 0;
    std::vector<Tensor<1, 2>> last_forces;
    /** Where the last augment() found each body (for those with a
     * force-controlled component). */
    std::vector<Tensor<1, 2>> last_places;

    double                    penalty = 0;
    double                    from = 0, to = 0;
    std::vector<ContactPiece> pieces;
    /** Per curve and point: the traction on the body after the last
     * increment (zero where no contact). */
    std::vector<std::vector<Tensor<1, 2>>> point_tractions;

    /** Of the last finish_increment(), per body. */
    struct Resultant
    {
      Tensor<1, 2> force;
      double       contact_length = 0;
      double       sliding_length = 0;
      double       penetration    = 0;
    };
    std::vector<Resultant> resultants;
    /** The pieces' figures of the last finish_increment() on this
     * process: body, x, y, gap, p_N, t_T, length, sliding. */
    std::vector<double> last_tractions;
  };
} // namespace bsmpm

#endif
