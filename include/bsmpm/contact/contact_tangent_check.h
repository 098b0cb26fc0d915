#ifndef bsmpm_contact_tangent_check_h
#define bsmpm_contact_tangent_check_h

#include <deal.II/base/mpi.h>

#include <bsmpm/contact/contact_pieces.h>
#include <bsmpm/contact/contact_terms.h>

#include <map>
#include <optional>
#include <string>
#include <vector>

namespace bsmpm
{
  using namespace dealii;

  /**
   * The self-check of the contact's tangent ('Contact/Check tangent'):
   * the stiffness of a piece (ContactTerms::evaluate(), with the body's
   * bordered terms) against central differences of its force by each of
   * the cell's DoFs and the body's translation. A sign or factor error in
   * any term of the tangent shows as a difference of order one
   * (tests/contact/check_tangent.py runs it on the regimes of the law).
   */
  class ContactTangentCheck
  {
  public:
    /** The largest difference of the stiffness of @p state (the piece's
     * at the nodal increment @p d) from central differences of its
     * forces, relative to the stiffness's largest entry. None where the
     * differences cross a kink of the contact law, which has no derivative
     * to compare: where the piece touches by less than they move it, or
     * where a Gauss point starts or stops touching or sliding between them
     * (at the edge of a stick zone). */
    static std::optional<double>
    relative_error(const ContactTerms              &terms,
                   const ContactPiece              &piece,
                   const std::vector<RigidBody>    &bodies,
                   const RigidBodyMotion           &motion,
                   const BackgroundGrid            &grid,
                   const Q1CellKernel              &kernel,
                   const ContactPieceState         &state,
                   const Q1CellKernel::LocalVector &d);

    /** Keeps @p error (of relative_error(), for a piece that slides or
     * not): the largest of the run, and how many pieces were compared. */
    void
    add(const std::optional<double> &error, const bool sliding);

    /** Gathers the figures of all processes. Collective. */
    void
    gather(const MPI_Comm communicator);

    /** contact_tangent_error (the largest relative difference),
     * contact_tangent_checks and contact_tangent_checks_sliding of the run
     * up to the last gather(). */
    void
    record(std::map<std::string, double> &quantities) const;

  private:
    /** On this process, of all checks of the run; after gather(), the
     * largest of all processes. */
    double largest_error = 0;
    /** On this process. */
    unsigned int n_compared = 0;
    unsigned int n_sliding  = 0;
    /** Of all processes, at the last gather(). */
    double total_compared = 0;
    double total_sliding  = 0;
  };
} // namespace bsmpm

#endif
