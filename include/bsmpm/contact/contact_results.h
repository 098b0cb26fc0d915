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
   * largest penetration (summary.json), and per touching piece its place,
   * gap and tractions (contact-NNNN.csv).
   */
  class ContactResults
  {
  public:
    /** No results yet (zeros) for @p n_bodies bodies. */
    void
    reinit(const unsigned int n_bodies);

    /** The results of @p pieces in the state @p states (one per piece) on
     * all processes. Collective. */
    void
    collect(const std::vector<ContactPiece>      &pieces,
            const std::vector<ContactPieceState> &states,
            const MPI_Comm                        communicator);

    /** Adds rigid_body_N_force_x/y (the force of the body on the rigid
     * body, N/m), _displacement_x/y (where @p motion has it),
     * _contact_length, _sliding_length and _penetration (the largest). */
    void
    record(const std::vector<RigidBody>  &bodies,
           const RigidBodyMotion         &motion,
           std::map<std::string, double> &quantities) const;

    /** The touching pieces on all processes (collective; written by
     * process 0 only): body, x, y (where they touch), gap, p_N, t_T, ds,
     * sliding, as CSV. */
    void
    write_tractions(std::ostream &out, const MPI_Comm communicator) const;

  private:
    struct Resultant
    {
      Tensor<1, 2> force;
      double       contact_length = 0;
      double       sliding_length = 0;
      double       penetration    = 0;
    };
    std::vector<Resultant> resultants;
    /** The pieces' figures on this process: body, x, y, gap, p_N, t_T,
     * length, sliding. */
    std::vector<double> piece_rows;
  };
} // namespace bsmpm

#endif
