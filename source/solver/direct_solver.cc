#include <deal.II/base/mpi.h>

#include <bsmpm/solver/direct_solver.h>

#include <Amesos.h>
#include <Amesos_BaseSolver.h>
#include <Epetra_Import.h>
#include <Epetra_Map.h>
#include <Epetra_MpiComm.h>
#include <Epetra_Vector.h>
#include <dmumps_c.h>

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



    /** What MUMPS' INFOG(1) < 0 means for the caller (MUMPS users' guide,
     * "Error diagnostics"); -1 where more workspace may help. */
    int
    mumps_error_class(const int infog1)
    {
      switch (infog1)
        {
          case -8:
          case -9:
          case -11:
          case -14:
          case -15:
          case -17:
          case -20:
            return -1; // the workspace was too small
          case -5:
          case -7:
          case -13:
          case -19:
            return static_cast<int>(DirectSolver::Status::out_of_memory);
          case -6:
          case -10:
            return static_cast<int>(DirectSolver::Status::singular);
          default:
            return static_cast<int>(DirectSolver::Status::other);
        }
    }
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

    ~HostMumps()
    {
      if (initialised)
        {
          mumps.job = -2;
          dmumps_c(&mumps);
        }
    }

    /** Analysis and factorisation of @p matrix. */
    Status
    factorize(const Epetra_CrsMatrix &matrix)
    {
      // Collective: every process returns alike.
      if (dealii::Utilities::MPI::min(gather(matrix, true) ? 1 : 0,
                                      communicator) == 0)
        return Status::other;
      int status = 0;
      if (on_host)
        {
          mumps.comm_fortran = MPI_Comm_c2f(MPI_COMM_SELF);
          mumps.par          = 1;
          mumps.sym          = symmetric ? 2 : 0;
          mumps.job          = -1;
          dmumps_c(&mumps);
          initialised = mumps.infog[0] >= 0;
          if (!initialised)
            status = static_cast<int>(Status::other);
          else
            {
              // Those Amesos_Mumps::SetICNTLandCNTL() sets for one process:
              // silent, automatic permutation, ordering and scaling, no
              // iterative refinement, the matrix centralised on the host.
              // Pairs of ICNTL(k) and its value.
              static constexpr int controls[][2] = {{1, -1},
                                                    {2, -1},
                                                    {3, -1},
                                                    {4, -1},
                                                    {5, 0},
                                                    {6, 7},
                                                    {7, 7},
                                                    {8, 7},
                                                    {9, 1},
                                                    {10, 0},
                                                    {11, 0},
                                                    {12, 0},
                                                    {13, 0},
                                                    {15, 0},
                                                    {16, 0},
                                                    {18, 0}};
              for (const auto &control : controls)
                mumps.icntl[control[0] - 1] = control[1];
              // L D L^T with pivoting does not stop at a zero pivot as the
              // LU does (INFOG(1) = -10): it reports the null pivots it
              // met (ICNTL(24) = 1, INFOG(28)), which numeric_factorization()
              // calls singular.
              if (symmetric)
                mumps.icntl[24 - 1] = 1;
              mumps.n   = matrix.NumGlobalRows();
              mumps.nnz = values.size();
              mumps.nz  = values.size();
              mumps.irn = rows.data();
              mumps.jcn = columns.data();
              mumps.a   = values.data();
              mumps.job = 1;
              dmumps_c(&mumps);
              if (mumps.infog[0] < 0)
                {
                  // More workspace is no remedy in the analysis.
                  const int error = mumps_error_class(mumps.infog[0]);
                  status = error >= 0 ? error : static_cast<int>(Status::other);
                }
              if (status == 0)
                status = numeric_factorization();
            }
        }
      return static_cast<Status>(broadcast_from_host(communicator, status));
    }

    /** The factorisation of @p matrix, of the structure factorize() saw,
     * with its analysis. */
    Status
    refactorize(const Epetra_CrsMatrix &matrix)
    {
      const bool same = gather(matrix, false);
      int        status =
        dealii::Utilities::MPI::min(same ? 1 : 0, communicator) == 1 ?
                 (on_host ? numeric_factorization() : 0) :
                 static_cast<int>(Status::other);
      return static_cast<Status>(broadcast_from_host(communicator, status));
    }

    bool
    solve(Epetra_MultiVector &x, const Epetra_MultiVector &b)
    {
      if (!import)
        {
          // One process: MUMPS overwrites the right-hand side with the
          // solution.
          x          = b;
          mumps.rhs  = x[0];
          mumps.nrhs = 1;
          mumps.lrhs = x.MyLength();
          mumps.job  = 3;
          dmumps_c(&mumps);
          return mumps.infog[0] >= 0;
        }
      Epetra_Vector gathered(*all_rows);
      gathered.Import(b, *import, Insert);
      int error = 0;
      if (on_host && gathered.MyLength() > 0)
        {
          mumps.rhs  = gathered.Values();
          mumps.nrhs = 1;
          mumps.lrhs = gathered.MyLength();
          mumps.job  = 3;
          dmumps_c(&mumps);
          error = mumps.infog[0] < 0 ? 1 : 0;
        }
      error = broadcast_from_host(communicator, error);
      if (error == 0)
        x.Export(gathered, *import, Insert);
      return error == 0;
    }

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

    /** MUMPS' factorisation (JOB = 2) of the values, with more workspace
     * where the pivoting needs it; a Status on the host. */
    int
    numeric_factorization()
    {
      mumps.a = values.data();
      for (const int workspace : {20, 100, 400, 1600})
        {
          mumps.icntl[14 - 1] = workspace;
          mumps.job           = 2;
          dmumps_c(&mumps);
          if (mumps.infog[0] >= 0)
            return static_cast<int>(mumps.infog[28 - 1] > 0 ? Status::singular :
                                                              Status::success);
          const int error = mumps_error_class(mumps.infog[0]);
          if (error >= 0)
            return error;
        }
      return static_cast<int>(Status::out_of_memory);
    }

    const MPI_Comm communicator;
    const bool     on_host;
    const bool     symmetric;
    /** On several processes: every row on process 0, and the import
     * there. */
    std::unique_ptr<Epetra_Map>    all_rows;
    std::unique_ptr<Epetra_Import> import;
    /** The matrix gathered on process 0 (no rows elsewhere). */
    std::unique_ptr<Epetra_CrsMatrix> all;
    DMUMPS_STRUC_C                    mumps{};
    bool                              initialised = false;
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
    if (name == "MUMPS")
      {
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
    if (mumps)
      return mumps->solve(x.trilinos_vector(), b.trilinos_vector());
    problem.SetLHS(&x.trilinos_vector());
    problem.SetRHS(const_cast<Epetra_MultiVector *>(&b.trilinos_vector()));
    Silence quiet(std::cerr);
    return solver->Solve() == 0;
  }
} // namespace bsmpm
