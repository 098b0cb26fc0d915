#ifndef bsmpm_contact_history_h
#define bsmpm_contact_history_h

#include <deal.II/base/mpi.h>
#include <deal.II/base/tensor.h>

#include <bsmpm/boundary/boundary_curves.h>
#include <bsmpm/contact/contact_pieces.h>
#include <bsmpm/contact/contact_terms.h>

#include <vector>

namespace bsmpm
{
  using namespace dealii;

  /**
   * What contact carries from one load increment to the next: the
   * traction on the rigid body at each of the curves' points (zero where
   * no contact), the history of friction (t_prev of ContactLaw) and the
   * augmented Lagrangian's start. It is kept at the curves' points, which
   * every process holds alike and which follow the points added and
   * removed, and interpolated along the segments.
   */
  class ContactHistory
  {
  public:
    /** Makes room for every curve's points; a curve whose points changed
     * in number starts without history. */
    void
    reinit(const BoundaryCurves &curves);

    /** The traction at parameter @p u of spline segment @p segment of
     * curve @p c (@p curve), linear between the segment's points. */
    Tensor<1, 2>
    at(const unsigned int   c,
       const BoundaryCurve &curve,
       const unsigned int   segment,
       const double         u) const;

    /**
     * Keeps the tractions of the converged increment: of each active
     * piece (@p states, one per piece of @p pieces) at the curve points
     * whose knots lie in it (u_begin <= u_k < u_end, and u = 1 in the
     * last), so that each point has one piece and one process; between
     * crossings, interpolated between the crossings' tractions.
     * Collective.
     */
    void
    store(const BoundaryCurves                 &curves,
          const std::vector<ContactPiece>      &pieces,
          const std::vector<ContactPieceState> &states,
          const MPI_Comm                        communicator);

    /** The traction at one of the curves' points. */
    struct PointTraction
    {
      unsigned int curve = 0;
      unsigned int index = 0;
      Tensor<1, 2> traction;
    };

    /** Keeps the tractions of the converged increment at the points of
     * @p tractions (this process's; a point given by two processes takes
     * the sum), zero elsewhere. Collective. */
    void
    store(const BoundaryCurves             &curves,
          const std::vector<PointTraction> &tractions,
          const MPI_Comm                    communicator);

    /** Carries the history over to the chains that
     * BoundaryCurves::adapt_point_spacing() changed: a new point takes the
     * mean of its two origins'. */
    void
    follow_point_changes(
      const std::vector<BoundaryCurves::PointOrigins> &origins);

    /** For checkpoints. */
    template <class Archive>
    void
    serialize(Archive &archive, const unsigned int)
    {
      archive &point_tractions;
    }

  private:
    /** Per curve and point: the traction on the body after the last
     * increment. */
    std::vector<std::vector<Tensor<1, 2>>> point_tractions;
  };
} // namespace bsmpm

#endif
