#ifndef bsmpm_contact_results_h
#define bsmpm_contact_results_h

#include <deal.II/base/mpi.h>
#include <deal.II/base/tensor.h>

#include <bsmpm/contact/contact_pieces.h>
#include <bsmpm/contact/contact_terms.h>
#include <bsmpm/contact/rigid_body.h>
#include <bsmpm/contact/rigid_body_motion.h>

#include <map>
#include <ostream>
#include <string>
#include <vector>

namespace bsmpm
{
  using namespace dealii;

  /**
   * What contact did in the last converged increment, for output: per
   * rigid body the force on it, the lengths in contact and sliding and the
   * largest penetration (summary.json), and per touching piece (or
   * crossing, or Gauss point) its place, the rigid outline's normal
   * there, gap and tractions (contact-NNNN.csv,
   * after every load step).
   */
  class ContactResults
  {
  public:
    /** A place where a curve touches a body: a piece (one pressure per
     * cell), a crossing of the curve with a grid line (pressures at the
     * grid lines: x its place, the traction and gap projected on its hat
     * function, length W_k) or a Gauss point (mortar pressures). */
    struct Touch
    {
      unsigned int body  = 0;
      unsigned int curve = 0;
      Point<2>     x;
      /** The rigid surface's outward normal there. */
      Tensor<1, 2> normal;
      double       gap        = 0;
      double       pressure   = 0;
      double       tangential = 0;
      /** The length it stands for, and of it the length that touches
       * and that slides. */
      double length         = 0;
      double contact_length = 0;
      double sliding_length = 0;
      bool   sliding        = false;
      /** The traction's integral: the force on the curve. */
      Tensor<1, 2> resultant;
      /** Its moment about the origin (the traction's, integrated along
       * the curve). */
      double moment = 0;
    };

    /** No results yet (zeros) for @p n_bodies bodies. */
    void
    reinit(const unsigned int n_bodies);

    /** The results of @p pieces in the state @p states (one per piece) on
     * all processes. Collective. */
    void
    collect(const std::vector<ContactPiece>      &pieces,
            const std::vector<ContactPieceState> &states,
            const MPI_Comm                        communicator);

    /** The results of @p touches (this process's) with the largest
     * penetration @p penetration per body (of this process) on all
     * processes. Collective. */
    void
    collect(const std::vector<Touch>  &touches,
            const std::vector<double> &penetration,
            const MPI_Comm             communicator);

    /** Adds rigid_body_N_force_x/y (the force of the body on the rigid
     * body, N/m), _moment (that force's moment about the centroid of the
     * rigid outline where @p motion has it, N m/m, counter-clockwise
     * positive), _displacement_x/y, _contact_length, _sliding_length and
     * _penetration (the largest). */
    void
    record(const std::vector<RigidBody>  &bodies,
           const RigidBodyMotion         &motion,
           std::map<std::string, double> &quantities) const;

    /** The touches on all processes (collective; written by process 0
     * only), as CSV: body and curve (numbered from 1, the curves as in the
     * ParaView series curves), x, y, the rigid outline's outward normal n
     * there, the gap, the pressure p_N and tangential traction t_T (on the
     * body, along n and t = (-n_y, n_x)), the length the row stands for
     * and whether and how much of it slides (Touch). The force on the
     * rigid body is minus the sum of (p_N n + t_T t) length over its
     * rows. */
    void
    write_tractions(std::ostream &out, const MPI_Comm communicator) const;

  private:
    /** One touch per piece that touches (one pressure per cell). */
    static std::vector<Touch>
    touches_of_pieces(const std::vector<ContactPiece>      &pieces,
                      const std::vector<ContactPieceState> &states);

    /** Pressures at the grid lines: one touch per crossing that carries a
     * traction, on process 0 (none elsewhere), its traction the lumped
     * projection of the pieces' on either side, its length W_k = int
     * phi_k ds. Collective. */
    static std::vector<Touch>
    touches_at_crossings(const std::vector<ContactPiece>      &pieces,
                         const std::vector<ContactPieceState> &states,
                         const MPI_Comm                        communicator);

    struct Resultant
    {
      Tensor<1, 2> force;
      /** The force's moment about the origin. */
      double moment         = 0;
      double contact_length = 0;
      double sliding_length = 0;
      double penetration    = 0;
    };
    std::vector<Resultant> resultants;
    /** The pieces' figures on this process: body, curve, x, y, n_x, n_y,
     * gap, p_N, t_T, length, sliding. */
    std::vector<double>           piece_rows;
    static constexpr unsigned int row_size = 12;
  };
} // namespace bsmpm

#endif
