#ifndef bsmpm_curve_contact_h
#define bsmpm_curve_contact_h

#include <deal.II/base/parameter_handler.h>

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/la_parallel_vector.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <bsmpm/boundary/boundary_curves.h>
#include <bsmpm/contact/contact_augmentation.h>
#include <bsmpm/contact/contact_history.h>
#include <bsmpm/contact/contact_nodes.h>
#include <bsmpm/contact/contact_pieces.h>
#include <bsmpm/contact/contact_results.h>
#include <bsmpm/contact/contact_tangent_check.h>
#include <bsmpm/contact/contact_terms.h>
#include <bsmpm/contact/nodal_contact_terms.h>
#include <bsmpm/contact/pressure_balance.h>
#include <bsmpm/contact/rigid_body.h>
#include <bsmpm/contact/rigid_body_motion.h>
#include <bsmpm/contact/rigid_body_placement.h>
#include <bsmpm/geometry/background_grid.h>
#include <bsmpm/points/q1_cell_kernel.h>

#include <algorithm>
#include <array>
#include <map>
#include <ostream>
#include <string>
#include <vector>

namespace bsmpm
{
  using namespace dealii;

  /**
   * Contact of the body's B-spline boundary with rigid bodies
   * (doc/contact.md): the order of contact in a load increment. Every free
   * stretch of every boundary curve is a candidate: where it touches a
   * rigid body it takes the contact condition, where it leaves it it is
   * free again, with no input.
   *
   * The condition is imposed on the curve pieces in the cut cells,
   * integrated with Gauss points on the spline of the step's start (the
   * curve that the points define), moved by the displacement increment: at
   * a Gauss point X, x = X + du(X), the gap g(x) to the rigid body (at the
   * load factor the increment ends at) and its normal n. A load increment
   * goes
   *
   * - begin_increment(): the candidate pieces (contact_pieces.h: one
   *   pressure per cell, or pressures at the grid lines), their friction
   *   history (ContactHistory), the augmented Lagrangian's multipliers
   *   (ContactAugmentation), a force-controlled body brought to touch;
   * - add_newton_terms() in every Newton iteration: the force and tangent
   *   of each piece (ContactTerms, with the contact law ContactLaw: normal
   *   penalty or augmented Lagrangian, Coulomb's return map) into the
   *   system, optionally checked by central differences
   *   (ContactTangentCheck);
   * - after_convergence(): the touching parts (fixed within the
   *   iterations, updated between them), then the multipliers' updates;
   * - finish_increment(): the forces on the bodies (ContactResults) and the
   *   history for the next increment.
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

    /** With the mortar pressures: the cells (of all processes)
     * whose DoFs the contact's stiffness couples with those of the 3 x 3
     * cells round them (ContactPattern); otherwise nullptr (the cell
     * pattern holds the contact's terms). */
    const std::vector<std::array<unsigned int, 2>> *
    coupled_cells() const
    {
      return pressure_at_nodes ? &contact_nodes.cells() : nullptr;
    }

    /** Where the bodies are in the present increment, and the unknowns of
     * the force-controlled ones with the bordered terms of the last
     * add_newton_terms(). */
    RigidBodyMotion &
    motion()
    {
      return body_motion;
    }

    /** Refuses rigid bodies that start inside the body (its material
     * @p points and @p curves) or inside each other, and those whose
     * prescribed motion up to load factor @p last_load_factor drives them
     * along a fixed face of @p grid into the material it holds, before
     * the first step (RigidBodyPlacement). Collective. */
    void
    check_initial_places(const BoundaryCurves &curves,
                         const MaterialPoints &points,
                         const BackgroundGrid &grid,
                         const double          last_load_factor) const;

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
     * motion(). Returns whether the tangent stays symmetric (no Gauss
     * point slides, and none with friction where the outline turns), over
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
     * the augmented Lagrangian the multipliers (ContactAugmentation, at
     * most 'Contact/Maximum augmentations' times). Returns whether the
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
     * The residual, as a fraction of the Newton tolerance's scale, to
     * which the solves before an update of the augmented Lagrangian's
     * multipliers need converge (0 without multipliers): a tenth of the
     * Augmentation tolerance. The update moves the increment by much more
     * than that residual's error, and the last solve, whose multipliers
     * stand, converges to the Newton tolerance.
     */
    double
    tolerance_between_updates() const
    {
      return augmented ? 0.1 * augmentation.force_tolerance() : 0.;
    }

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

    /**
     * What to add to the message of a load increment that failed however
     * far it was cut, where friction can be the cause: a frictional rigid
     * body whose force-controlled components the pressures where it
     * touches cannot hold (pressures_can_balance()), or, if @p body_load is
     * given (the loads on the body, which nothing but contact supports),
     * loads that the pressures of the rigid bodies touching it cannot
     * balance while one of them is frictional. Empty where friction cannot
     * be the cause (smooth or rough surfaces, bodies under prescribed
     * motion on a supported body, forces along the contact's normals).
     * Collective.
     */
    std::string
    friction_hint(const BackgroundGrid &grid,
                  const Tensor<1, 2>   *body_load) const;

    /** Carries the friction history (the tangential traction kept at the
     * curves' points) over to the chains that
     * BoundaryCurves::adapt_point_spacing() changed: a new point takes the
     * mean of its two origins'. */
    void
    follow_point_changes(
      const std::vector<BoundaryCurves::PointOrigins> &origins);

    /** Adds rigid_body_N_force_x/y (the force of the body on the rigid
     * body, N/m), _displacement_x/y, _contact_length, _sliding_length and
     * _penetration (the largest) of the last finish_increment(), the
     * multipliers' updates of the last increment (contact_augmentations)
     * and what motion() records. */
    void
    record(std::map<std::string, double> &quantities) const;

    /** What a load step leaves for the next: the friction history (and the
     * multipliers' start) at the curves' points and the bodies' places,
     * for checkpoints. */
    template <class Archive>
    void
    serialize(Archive &archive, const unsigned int version)
    {
      history.serialize(archive, version);
      archive &body_motion;
    }

    /** The touches of the last finish_increment() on all
     * processes as CSV (collective; written by process 0 only):
     * ContactResults::write_tractions(). */
    void
    write_tractions(std::ostream &out, const MPI_Comm communicator) const;

  private:
    /** For body @p b with a force-controlled component that none of the
     * candidate Gauss points touch at the start of the iterations: moves
     * it along its force until it touches the nearest (a body that touches
     * nothing has no stiffness against its free motion), and notes it in
     * motion(). Throws if nothing within reach lies in that direction.
     * Collective. */
    void
    touch_if_free(const unsigned int b, const BackgroundGrid &grid);

    /** What contact does on every piece at @p increment (ghosted;
     * @p prescribed as for the points). */
    /** With the mortar pressures: the tractions at the curves'
     * points and the touching places for the results, from @p state. */
    void
    finish_nodal_increment(const BoundaryCurves           &curves,
                           const BackgroundGrid           &grid,
                           const NodalContactTerms::State &state);

    /** With the mortar pressures: what contact does at its nodes at
     * @p increment (ghosted; @p prescribed as for the points).
     * Collective. */
    NodalContactTerms::State
    evaluate_nodes(
      const BackgroundGrid                             &grid,
      const Q1CellKernel                               &kernel,
      const LinearAlgebra::distributed::Vector<double> &increment,
      const LinearAlgebra::distributed::Vector<double> *prescribed) const;

    std::vector<ContactPieceState>
    evaluate_all(
      const BackgroundGrid                             &grid,
      const Q1CellKernel                               &kernel,
      const LinearAlgebra::distributed::Vector<double> &increment,
      const LinearAlgebra::distributed::Vector<double> *prescribed) const;

    std::vector<RigidBody> bodies;
    RigidBodyMotion        body_motion;
    double                 gamma = 10;
    /** 'Contact/Pressure': one pressure per crossing of a curve with a
     * grid line (true) or per piece of curve in a cell. */
    bool pressure_at_crossings = true;
    /** 'Contact/Pressure = mortar': one pressure per crossing of a curve
     * with a grid line, for the weighted gap round it (ContactNodes,
     * NodalContactTerms). */
    bool pressure_at_nodes = false;
    /** The tilt's penalty as a factor of the mean gap's. */
    double       gamma_tilt     = 0;
    bool         check_tangent  = false;
    unsigned int n_gauss_points = 4;
    /** 'Contact/Method': the augmented Lagrangian (true) or the plain
     * penalty. */
    bool augmented = true;
    /** Updates of the touching parts that one increment may ask for; then
     * the last parts stand. */
    static constexpr unsigned int max_touching_updates = 8;
    /** In the present increment. */
    unsigned int touching_updates = 0;
    double       from = 0, to = 0;

    /** The candidate pieces of the present increment. */
    std::vector<ContactPiece> pieces;
    /** With the mortar pressures: the nodes of the pieces. */
    ContactNodes contact_nodes;
    /** The contact law and the force and tangent on a piece, with the
     * penalty of the present increment. */
    ContactTerms        terms;
    ContactAugmentation augmentation;
    /** 'Contact/Check tangent'. */
    ContactTangentCheck tangent_check;
    /** The tractions at the curves' points after the last increment. */
    ContactHistory history;
    /** Of the last finish_increment(). */
    ContactResults results;
  };
} // namespace bsmpm

#endif
