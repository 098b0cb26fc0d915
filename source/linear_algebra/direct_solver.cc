#include <deal.II/base/mpi.h>

#include <bsmpm/linear_algebra/direct_solver.h>
#include <bsmpm/linear_algebra/mumps_factorization.h>
#include <bsmpm/linear_algebra/subdomain_mumps.h>

#include <Amesos.h>
#include <Amesos_BaseSolver.h>
#include <Epetra_Import.h>
#include <Epetra_Map.h>
#include <Epetra_MpiComm.h>
#include <Epetra_Vector.h>

#include <algorithm>
#include <chrono>
#include <iostream>
#include <sstream>
#include <thread>
#include <vector>

namespace bsmpm
{
  namespace
  {
    /** Keeps what is written to @p stream while it lives off the terminal. */
    class Silence
    {
    public:
      explicit Silence(std::ostream &stream)
        : stream(stream)
        , saved(stream.rdbuf(held.rdbuf()))
      {}

      ~Silence()
      {
        stream.rdbuf(saved);
      }

    private:
      std::ostringstream held;
      std::ostream      &stream;
      std::streambuf    *saved;
    };



    /** @p value of process 0 on every process (MPI_Bcast), the others
     * waiting asleep, testing every 0.2 ms, instead of in Open MPI's busy
     * polling: they wait for the whole factorisation on process 0, and on
     * a machine without a core to spare a polling process takes half of
     * process 0's. */
    int
    broadcast_from_host(const MPI_Comm communicator, int value)
    {
      MPI_Request request;
      int error = MPI_Ibcast(&value, 1, MPI_INT, 0, communicator, &request);
      AssertThrowMPI(error);
      int done = 0;
      while (true)
        {
          error = MPI_Test(&request, &done, MPI_STATUS_IGNORE);
          AssertThrowMPI(error);
          if (done)
            return value;
          std::this_thread::sleep_for(std::chrono::microseconds(200));
        }
    }



#ifdef DEBUG
    /** Whether the rows on this process of @p matrix, which has every row
     * there, are symmetric to round-off: |a_ij - a_ji| <= 1e-10 of the
     * larger diagonal of i and j (an entry without its mirror counts as
     * zero there). The L D L^T of MUMPS reads the lower triangle only, so
     * an assembly that is not symmetric would be solved wrongly, not
     * refused: checked in Debug builds, which run the tests. */
    bool
    symmetric_to_round_off(const Epetra_CrsMatrix &matrix)
    {
      const int n = matrix.NumMyRows();
      // Each row's entries by global column, sorted.
      std::vector<std::vector<std::pair<int, double>>> by_row(n);
      std::vector<double>                              diagonal(n, 0.);
      for (int row = 0; row < n; ++row)
        {
          int     count   = 0;
          double *values  = nullptr;
          int    *indices = nullptr;
          matrix.ExtractMyRowView(row, count, values, indices);
          for (int k = 0; k < count; ++k)
            {
              const int column = matrix.GCID(indices[k]);
              by_row[row].emplace_back(column, values[k]);
              if (column == matrix.GRID(row))
                diagonal[row] = std::abs(values[k]);
            }
          std::sort(by_row[row].begin(), by_row[row].end());
        }
      const auto entry = [&](const int row, const int column) {
        const auto &r = by_row[matrix.LRID(row)];
        const auto  it =
          std::lower_bound(r.begin(), r.end(), std::make_pair(column, -1e300));
        return it != r.end() && it->first == column ? it->second : 0.;
      };
      for (int row = 0; row < n; ++row)
        {
          const int i = matrix.GRID(row);
          for (const auto &[j, a_ij] : by_row[row])
            if (j > i &&
                std::abs(a_ij - entry(j, i)) >
                  1e-10 * std::max(diagonal[row], diagonal[matrix.LRID(j)]))
              return false;
        }
      return true;
    }
#endif
  } // namespace



  /**
   * MUMPS on process 0 alone, through its C interface on MPI_COMM_SELF. A
   * matrix of several processes is gathered there first (an Epetra_Import
   * onto a map that puts every row on process 0) and the right-hand side
   * likewise, the solution scattered back; on one process the matrix is
   * read as it is. A symmetric matrix is factorised as L D L^T (MUMPS'
   * SYM = 2, symmetric indefinite: the plastic and contact tangents need
   * not be definite) from its lower triangle, with half the entries and
   * about half the work of an LU (doc/benchmarks.md). Every call is
   * collective; the other processes only send and receive.
   */
  class DirectSolver::HostMumps
  {
  public:
    HostMumps(const Epetra_CrsMatrix &matrix, const bool symmetric)
      : communicator(dynamic_cast<const Epetra_MpiComm &>(matrix.Comm()).Comm())
      , on_host(dealii::Utilities::MPI::this_mpi_process(communicator) == 0)
      , symmetric(symmetric)
    {
      if (matrix.Comm().NumProc() > 1)
        {
          all_rows =
            std::make_unique<Epetra_Map>(matrix.RowMap().NumGlobalElements(),
                                         on_host ?
                                           matrix.RowMap().NumGlobalElements() :
                                           0,
                                         matrix.RowMap().IndexBase(),
                                         matrix.Comm());
          import = std::make_unique<Epetra_Import>(*all_rows, matrix.RowMap());
        }
      else
        // solve() hands MUMPS the vector's local entries as its global
        // rows.
        Assert(matrix.RowMap().LinearMap() &&
                 matrix.RowMap().MinMyGID() == matrix.RowMap().IndexBase(),
               dealii::ExcInternalError());
    }

    /** Analysis and factorisation of @p matrix. */
    Status
    factorize(const Epetra_CrsMatrix &matrix)
    {
      // Collective: every process returns alike.
      if (dealii::Utilities::MPI::min(gather(matrix, true) ? 1 : 0,
                                      communicator) == 0)
        return Status::other;
      Status status = Status::success;
      if (on_host)
        {
          mumps  = std::make_unique<MumpsFactorization>(symmetric);
          status = mumps->analyse(matrix.NumGlobalRows(), rows, columns);
          if (status == Status::success)
            status = mumps->factorize(values);
        }
      return static_cast<Status>(
        broadcast_from_host(communicator, static_cast<int>(status)));
    }

    /** The factorisation of @p matrix, of the structure factorize() saw,
     * with its analysis. */
    Status
    refactorize(const Epetra_CrsMatrix &matrix)
    {
      const bool same = gather(matrix, false);
      Status     status =
        dealii::Utilities::MPI::min(same ? 1 : 0, communicator) == 1 ?
              (on_host ? mumps->factorize(values) : Status::success) :
              Status::other;
      return static_cast<Status>(
        broadcast_from_host(communicator, static_cast<int>(status)));
    }

    bool
    solve(Epetra_MultiVector &x, const Epetra_MultiVector &b)
    {
      if (!import)
        {
          // One process: MUMPS overwrites the right-hand side with the
          // solution.
          x = b;
          return mumps->solve(x[0]);
        }
      Epetra_Vector gathered(*all_rows);
      gathered.Import(b, *import, Insert);
      int error = 0;
      if (on_host && gathered.MyLength() > 0)
        error = mumps->solve(gathered.Values()) ? 0 : 1;
      error = broadcast_from_host(communicator, error);
      if (error == 0)
        x.Export(gathered, *import, Insert);
      return error == 0;
    }

#ifdef DEBUG
    /** The symmetry check of a factorisation (in gather()) on @p matrix
     * gathered on process 0, for a matrix that the subdomains factorise:
     * each of them reads one triangle of its part only. */
    void
    check_symmetric(const Epetra_CrsMatrix &matrix)
    {
      gather(matrix, true);
    }
#endif

  private:
    /** The triplets (1-based) of @p matrix on process 0, of its lower
     * triangle if symmetric; with @p structure the rows and columns are
     * taken anew, else only the values, of the structure of the last call
     * with @p structure (a gathered matrix keeps its entries in place: a
     * refactorisation of 29 k unknowns spent a third of its time building
     * it anew), and false if @p matrix has an entry outside that
     * structure. */
    bool
    gather(const Epetra_CrsMatrix &matrix, const bool structure)
    {
      const Epetra_CrsMatrix *host = &matrix;
      if (import)
        {
          if (structure || !all)
            {
              all = std::make_unique<Epetra_CrsMatrix>(Copy, *all_rows, 0);
              if (all->Import(matrix, *import, Insert) != 0 ||
                  all->FillComplete() != 0)
                {
                  all.reset();
                  return false;
                }
            }
          else
            {
              // The same structure: its entries summed from zero take the
              // values bit for bit; an entry outside it is an error of Add.
              all->PutScalar(0.);
              if (all->Import(matrix, *import, Add) != 0)
                return false;
            }
          host = all.get();
        }
      if (structure)
        {
          Assert(!symmetric || symmetric_to_round_off(*host),
                 dealii::ExcMessage(
                   "The direct solver was told the matrix is symmetric, "
                   "and it is not: MUMPS' L D L^T would solve another "
                   "system."));
          rows.clear();
          columns.clear();
          kept.clear();
          const int base = host->RowMap().IndexBase();
          for (int row = 0; row < host->NumMyRows(); ++row)
            {
              int  n       = 0;
              int *indices = nullptr;
              host->Graph().ExtractMyRowView(row, n, indices);
              for (int k = 0; k < n; ++k)
                {
                  // MUMPS counts from 1.
                  const int i = host->GRID(row) - base + 1;
                  const int j = host->GCID(indices[k]) - base + 1;
                  kept.push_back(!symmetric || j <= i);
                  if (kept.back())
                    {
                      rows.push_back(i);
                      columns.push_back(j);
                    }
                }
            }
        }
      values.clear();
      std::size_t entry = 0;
      for (int row = 0; row < host->NumMyRows(); ++row)
        {
          int     n       = 0;
          double *entries = nullptr;
          host->ExtractMyRowView(row, n, entries);
          if (entry + n > kept.size())
            return false;
          for (int k = 0; k < n; ++k)
            if (kept[entry++])
              values.push_back(entries[k]);
        }
      return entry == kept.size() && values.size() == rows.size();
    }

    const MPI_Comm communicator;
    const bool     on_host;
    const bool     symmetric;
    /** On several processes: every row on process 0, and the import
     * there. */
    std::unique_ptr<Epetra_Map>    all_rows;
    std::unique_ptr<Epetra_Import> import;
    /** The matrix gathered on process 0 (no rows elsewhere). */
    std::unique_ptr<Epetra_CrsMatrix>   all;
    std::unique_ptr<MumpsFactorization> mumps;
    /** Whether each entry of the host's rows goes to MUMPS. */
    std::vector<bool>   kept;
    std::vector<int>    rows, columns;
    std::vector<double> values;
  };



  DirectSolver::DirectSolver() = default;

  DirectSolver::~DirectSolver() = default;



  DirectSolver::Status
  DirectSolver::factorize(const Epetra_CrsMatrix &matrix,
                          const std::string      &name,
                          const bool              symmetric)
  {
    solver.reset();
    mumps.reset();
    subdomains.reset();
    if (name == "MUMPS")
      {
        if (matrix.Comm().NumProc() > 1)
          {
            // Each process its own unknowns, the seams together; where
            // that fails (a seam too long for a dense Schur complement,
            // a process' interior singular on its own), the matrix
            // gathered on process 0.
#ifdef DEBUG
            if (symmetric)
              HostMumps(matrix, symmetric).check_symmetric(matrix);
#endif
            subdomains = std::make_unique<SubdomainMumps>(matrix, symmetric);
            const Status status = subdomains->factorize(matrix);
            if (status == Status::success)
              return status;
            subdomains.reset();
          }
        mumps = std::make_unique<HostMumps>(matrix, symmetric);
        return mumps->factorize(matrix);
      }
    Amesos factory;
    if (!factory.Query(name))
      return Status::unavailable;
    matrix_copy = std::make_unique<Epetra_CrsMatrix>(matrix);
    problem.SetOperator(matrix_copy.get());
    solver.reset(factory.Create(name, problem));
    if (!solver)
      return Status::unavailable;
    int error = 0;
    {
      Silence quiet(std::cerr);
      error = solver->SymbolicFactorization();
      if (error == 0)
        error = solver->NumericFactorization();
    }
    if (error == 0)
      return Status::success;
    return error == StructurallySingularMatrixError ||
               error == NumericallySingularMatrixError ?
             Status::singular :
             Status::other;
  }



  DirectSolver::Status
  DirectSolver::refactorize(const Epetra_CrsMatrix &matrix)
  {
    if (subdomains)
      return subdomains->refactorize(matrix);
    if (mumps)
      return mumps->refactorize(matrix);
    if (!solver || matrix.NumMyRows() != matrix_copy->NumMyRows())
      return Status::other;
    // The same structure: the values row by row.
    for (int row = 0; row < matrix.NumMyRows(); ++row)
      {
        int     n = 0, n_copy = 0;
        double *values = nullptr, *copy = nullptr;
        int    *columns = nullptr, *copy_columns = nullptr;
        matrix.ExtractMyRowView(row, n, values, columns);
        matrix_copy->ExtractMyRowView(row, n_copy, copy, copy_columns);
        if (n != n_copy)
          return Status::other;
        std::copy(values, values + n, copy);
      }
    Silence quiet(std::cerr);
    return solver->NumericFactorization() == 0 ? Status::success :
                                                 Status::other;
  }



  bool
  DirectSolver::solve(TrilinosWrappers::MPI::Vector       &x,
                      const TrilinosWrappers::MPI::Vector &b)
  {
    if (subdomains)
      return subdomains->solve(x.trilinos_vector(), b.trilinos_vector());
    if (mumps)
      return mumps->solve(x.trilinos_vector(), b.trilinos_vector());
    problem.SetLHS(&x.trilinos_vector());
    problem.SetRHS(const_cast<Epetra_MultiVector *>(&b.trilinos_vector()));
    Silence quiet(std::cerr);
    return solver->Solve() == 0;
  }
} // namespace bsmpm
