#ifndef bsmpm_subdomain_mumps_h
#define bsmpm_subdomain_mumps_h

#include <bsmpm/linear_algebra/direct_solver.h>
#include <bsmpm/linear_algebra/mumps_factorization.h>

#include <Epetra_CrsMatrix.h>
#include <Epetra_MultiVector.h>
#include <mpi.h>

#include <map>
#include <memory>
#include <vector>

namespace bsmpm
{
  /**
   * A direct solve of a matrix of several processes in which each process
   * factorises its own unknowns, at the same time as the others, and only
   * the unknowns on the seams between processes are solved together: a
   * substructuring (Schur complement) solve.
   *
   * The seam: an unknown of process p is an *interface* unknown if its row
   * has an entry in a column of a process q > p, or a row of a process
   * q > p has an entry in its column. Every other unknown of p is
   * *interior*, and then no entry couples it to another process' interior
   * (an entry between interiors of p < q would make one of the two an
   * interface unknown). So the matrix is, with the interiors I_p first,
   *
   *   [A_11        A_1G]
   *   [     A_22   A_2G]
   *   [A_G1  A_G2  A_GG],
   *
   * and with S_p = A_GG^(p) - A_Gp A_pp^-1 A_pG (A_GG^(p) the interface
   * rows that p owns), S = sum_p S_p is the Schur complement of the
   * interface: S x_G = b_G - sum_p A_Gp A_pp^-1 b_p, then
   * x_p = A_pp^-1 (b_p - A_pG x_G) on every process at once.
   *
   * Each process factorises [A_pp A_pG; A_Gp A_GG^(p)] with MUMPS on
   * MPI_COMM_SELF, the interface unknowns it touches kept as MUMPS' Schur
   * complement (which hands back S_p dense and does the two half solves);
   * the rows A_Gp that other processes own are sent to p. Process 0 adds
   * the S_p in the order of the processes and factorises S (dense, by
   * MUMPS again). Every step is deterministic: one run gives the bits of
   * the next, which a distributed MUMPS does not (direct_solver.h).
   *
   * At the 29 k unknowns of the plastic footing on two processes the
   * interface has a few hundred unknowns (doc/benchmarks.md); an interface
   * of more than `max_interface_size` unknowns is refused (status
   * `other`), for the caller to gather the matrix on one process instead.
   */
  class SubdomainMumps
  {
  public:
    /** The interface a dense S may have: 5000^2 doubles are 200 MB. */
    static constexpr int max_interface_size = 5000;

    SubdomainMumps(const Epetra_CrsMatrix &matrix, const bool symmetric);

    /** Finds the interface, analyses and factorises; collective. */
    DirectSolver::Status
    factorize(const Epetra_CrsMatrix &matrix);

    /** The factorisation of @p matrix, of the structure factorize() saw,
     * with its analyses. */
    DirectSolver::Status
    refactorize(const Epetra_CrsMatrix &matrix);

    /** x = A^-1 b; collective. */
    bool
    solve(Epetra_MultiVector &x, const Epetra_MultiVector &b);

  private:
    /** The matrix's structure as factorize() finds it (defined in the
     * source). */
    struct Structure;

    /** factorize(), steps 1 and 2: the interface rows and the interface
     * numbers (n_interface); collective. */
    void
    find_interface(Structure &structure);

    /** factorize(), step 3: the local entries as pairs of codes, those sent
     * to and received from other processes, the interior (n_interior);
     * collective. */
    void
    collect_entries(Structure &structure);

    /** factorize(), steps 4 and 5: the local unknowns (local_index,
     * touched) and the local matrix's triplets. */
    void
    number_local_unknowns(const Structure &structure);

    /** The place among the local unknowns of an entry's @p code (an
     * interior index, or -1 - an interface number). */
    int
    local_of(const int code) const;

    /** factorize(), step 6: the analyses of the local matrix and of S;
     * collective. */
    DirectSolver::Status
    analyse();

    /** The values of @p matrix for the local factorisation (own entries
     * and those other processes send), in the order of the triplets. */
    bool
    collect_values(const Epetra_CrsMatrix &matrix);

    /** S_p (or the local entries where p has no interior) summed into S
     * on process 0 and factorised there; a Status everywhere. */
    DirectSolver::Status
    factorize_interface(DirectSolver::Status local_status);

    const MPI_Comm     communicator;
    const unsigned int this_process;
    const bool         symmetric;

    /** Per row of this process: its place in the local unknowns, the
     * interior ones first (n_interior of them), then the interface
     * unknowns that this process' factorisation holds (`touched`: those of
     * its own rows and those its entries couple to, in their global
     * interface numbering, which counts the interface unknowns in the
     * order of the processes and their rows). */
    std::vector<int> local_index;
    int              n_interior = 0;
    std::vector<int> touched;
    int              n_interface = 0;

    /** Where each entry of this process' rows goes (in the order of the
     * rows and their entries): its position among the local values, or -1
     * (sent, or the upper triangle of a symmetric matrix). */
    std::vector<int> value_position;
    /** Per process: the entries (flat positions as above) sent there, and
     * the local value positions of the entries received from there. */
    std::map<unsigned int, std::vector<int>> sent_entries;
    std::map<unsigned int, std::vector<int>> received_positions;
    std::vector<double>                      flat_values, values;
    /** The local matrix's triplets (from 1, local unknowns). */
    std::vector<int> triplet_rows, triplet_columns;

    std::unique_ptr<MumpsFactorization> local;

    /** On process 0: every process' touched interface numbers, the sum S
     * (dense, by rows) and its factorisation. */
    std::vector<std::vector<int>>       touched_by_process;
    std::vector<double>                 interface_entries;
    std::unique_ptr<MumpsFactorization> interface;

    /** The local right-hand side and solution (interior, then touched
     * interface), and the reduced right-hand side. */
    std::vector<double> local_rhs, reduced;
  };
} // namespace bsmpm

#endif
