#ifndef bsmpm_contact_augmentation_h
#define bsmpm_contact_augmentation_h

#include <deal.II/base/mpi.h>
#include <deal.II/base/tensor.h>

#include <bsmpm/contact/contact_nodes.h>
#include <bsmpm/contact/contact_pieces.h>
#include <bsmpm/contact/contact_terms.h>
#include <bsmpm/contact/nodal_contact_terms.h>
#include <bsmpm/contact/rigid_body.h>
#include <bsmpm/contact/rigid_body_motion.h>

#include <vector>

namespace bsmpm
{
  using namespace dealii;

  /**
   * The augmented Lagrangian's updates of the pieces' multipliers within a
   * load increment (doc/contact.md, "The augmented Lagrangian"): their
   * start from the pressure of the last increment, Uzawa's update after a
   * converged Newton solve (filtered 1 2 1 along the curve with one
   * pressure per cell, a lumped projection at the crossings with pressures
   * at the grid lines), and when to stop: the force on every rigid body
   * (for a body under a force, its motion) no longer changes by more than
   * 'Contact/Augmentation tolerance'.
   */
  class ContactAugmentation
  {
  public:
    /** 'Contact/Augmentation tolerance', 'Contact/Maximum augmentations',
     * and whether the pieces run between crossings ('Contact/Pressure'). */
    void
    initialize(const double       tolerance,
               const unsigned int max_augmentations,
               const bool         at_crossings);

    /** Starts a load increment: no update yet, no force measured. */
    void
    begin_increment(const unsigned int n_bodies, const double penalty);

    /** Each piece's multiplier at the start of the increment: the
     * pressure of the last increment (its traction kept at the curves'
     * points, ContactHistory) on its first guess of the touching part. */
    void
    initialize_multipliers(std::vector<ContactPiece>    &pieces,
                           const std::vector<RigidBody> &bodies,
                           const RigidBodyMotion        &motion) const;

    /**
     * One Uzawa update of the multipliers of @p pieces at a converged
     * increment (@p states: what contact does there, one per piece).
     * Returns whether the force on some rigid body changed by more than
     * the tolerance since the last call and the maximum of updates is not
     * reached: then the multipliers took the update (counted) and the
     * Newton iterations must go on; if not, they are left as they were.
     * Collective.
     */
    bool
    augment(std::vector<ContactPiece>            &pieces,
            const std::vector<ContactPieceState> &states,
            const std::vector<RigidBody>         &bodies,
            const RigidBodyMotion                &motion,
            const MPI_Comm                        communicator);

    /**
     * augment() for mortar pressures: each node's multiplier becomes its
     * pressure in @p state (Uzawa's update lambda_a <- max(0, lambda_a -
     * eps G_a / W_a) on the node's weighted gap; one pressure per crossing
     * has no alternating mode to filter). Returns whether the force on
     * some rigid body changed by more than the tolerance. Collective.
     */
    bool
    augment_nodes(ContactNodes                   &nodes,
                  const NodalContactTerms::State &state,
                  const std::vector<RigidBody>   &bodies,
                  const RigidBodyMotion          &motion,
                  const MPI_Comm                  communicator);

    /** Whether the present increment's updates stopped at 'Contact/Maximum
     * augmentations' with the force still changing by more than ten times
     * the tolerance (the pressures not converged), and by how much. */
    bool
    stopped_unconverged() const
    {
      return unconverged_change > 0;
    }

    /** 'Contact/Augmentation tolerance'. */
    double
    force_tolerance() const
    {
      return tolerance;
    }

    double
    last_force_change() const
    {
      return unconverged_change;
    }

    /** The updates of the present increment. */
    unsigned int
    n_augmentations() const
    {
      return augmentations;
    }

  private:
    /** The raw updates of the pieces of all processes (per piece of
     * this process at @p offset on), filtered 1 2 1 along the curve with
     * one pressure per cell. Collective. */
    std::vector<double>
    piece_updates(const std::vector<ContactPiece>      &pieces,
                  const std::vector<ContactPieceState> &states,
                  const MPI_Comm                        communicator,
                  unsigned int                         &offset) const;

    /** Whether a force change @p change asks for one more update: above
     * the tolerance and below the maximum of updates (at the maximum it
     * is kept as unconverged_change if above ten times the tolerance). */
    bool
    needs_update(const double change);

    /** The largest relative change of a body's contact force @p forces
     * (2 per body, this process's part) or, under a force, of its motion
     * in the increment, since the last call, which it keeps. Collective. */
    double
    force_change(std::vector<double>           forces,
                 const std::vector<RigidBody> &bodies,
                 const RigidBodyMotion        &motion,
                 const MPI_Comm                communicator);

    /** Between crossings: each crossing's multiplier becomes the
     * pressure's lumped projection there, over the pieces on either side
     * (which may be on two processes). Collective. */
    void
    project_at_crossings(std::vector<ContactPiece>            &pieces,
                         const std::vector<ContactPieceState> &states,
                         const MPI_Comm communicator) const;

    double       tolerance         = 1e-4;
    unsigned int max_augmentations = 30;
    bool         at_crossings      = false;
    /** The penalty eps of the present increment. */
    double penalty = 0;
    /** In the present increment. */
    unsigned int augmentations = 0;
    /** The force change when the updates stopped at the maximum (zero if
     * they converged). */
    double unconverged_change = 0;
    /** The forces the last augment() measured, and where it found each
     * body (for those with a force-controlled component). */
    std::vector<Tensor<1, 2>> last_forces;
    std::vector<Tensor<1, 2>> last_places;
  };
} // namespace bsmpm

#endif
