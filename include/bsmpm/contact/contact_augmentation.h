#ifndef bsmpm_contact_augmentation_h
#define bsmpm_contact_augmentation_h

#include <deal.II/base/mpi.h>
#include <deal.II/base/tensor.h>

#include <bsmpm/contact/contact_pieces.h>
#include <bsmpm/contact/contact_terms.h>
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
    begin_increment(const unsigned int n_bodies);

    /** Each piece's multiplier at the start of the increment: the
     * pressure of the last increment (its traction kept at the curves'
     * points, ContactHistory) on its first guess of the touching part. */
    void
    initialize_multipliers(std::vector<ContactPiece>    &pieces,
                           const std::vector<RigidBody> &bodies,
                           const RigidBodyMotion        &motion) const;

    /**
     * One Uzawa update of the multipliers of @p pieces at a converged
     * increment (@p states: what contact does there, one per piece; call
     * while may_augment()). Returns whether the force on some rigid body
     * changed by more than the tolerance since the last call: then the
     * multipliers took the update (counted) and the Newton iterations must
     * go on; if not, they are left as they were. Collective.
     */
    bool
    augment(std::vector<ContactPiece>            &pieces,
            const std::vector<ContactPieceState> &states,
            const std::vector<RigidBody>         &bodies,
            const RigidBodyMotion                &motion,
            const MPI_Comm                        communicator);

    /** Whether augment() may update once more in this increment. */
    bool
    may_augment() const
    {
      return augmentations < max_augmentations;
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

    /** The largest relative change of a body's contact force (or, under
     * a force, of its motion in the increment) since the last call, which
     * it keeps. Collective. */
    double
    force_change(const std::vector<ContactPiece>      &pieces,
                 const std::vector<ContactPieceState> &states,
                 const std::vector<RigidBody>         &bodies,
                 const RigidBodyMotion                &motion,
                 const MPI_Comm                        communicator);

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
    /** In the present increment. */
    unsigned int augmentations = 0;
    /** The forces the last augment() measured, and where it found each
     * body (for those with a force-controlled component). */
    std::vector<Tensor<1, 2>> last_forces;
    std::vector<Tensor<1, 2>> last_places;
  };
} // namespace bsmpm

#endif
