#include <deal.II/base/mpi.h>

#include <bsmpm/solver/direct_solver.h>

#include <Amesos.h>
#include <Amesos_BaseSolver.h>
#include <Amesos_Mumps.h>
#include <Epetra_Import.h>
#include <Epetra_Map.h>
#include <Epetra_MpiComm.h>
#include <Epetra_Vector.h>
#include <Teuchos_ParameterList.hpp>
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
   * The matrix of all processes gathered on process 0 (an Epetra_Import
   * onto a map that puts every row there), as triplets, factorised by
   * MUMPS on MPI_COMM_SELF with the controls Amesos_Mumps sets; the
   * right-hand side is gathered likewise and the solution scattered back.
   * Every call is collective; the other processes only send and receive.
   */
  class DirectSolver::GatheredMumps
  {
  public:
    explicit GatheredMumps(const Epetra_CrsMatrix &matrix)
      : communicator(dynamic_cast<const Epetra_MpiComm &>(matrix.Comm()).Comm())
      , on_host(dealii::Utilities::MPI::this_mpi_process(communicator) == 0)
      , all_rows(matrix.RowMap().NumGlobalElements(),
                 on_host ? matrix.RowMap().NumGlobalElements() : 0,
                 matrix.RowMap().IndexBase(),
                 matrix.Comm())
      , import(all_rows, matrix.RowMap())
    {}

    ~GatheredMumps()
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
          mumps.sym          = 0;
          mumps.job          = -1;
          dmumps_c(&mumps);
          initialised = mumps.infog[0] >= 0;
          if (!initialised)
            status = static_cast<int>(Status::other);
          else
            {
              // Those of Amesos_Mumps::SetICNTLandCNTL() for one process:
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
              mumps.n   = all_rows.NumGlobalElements();
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
      Epetra_Vector gathered(all_rows);
      gathered.Import(b, import, Insert);
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
        x.Export(gathered, import, Insert);
      return error == 0;
    }

  private:
    /** The local triplets (1-based) of @p matrix on process 0; with
     * @p structure the rows and columns are taken anew, else only the
     * values into the gathered matrix of the last call with @p structure
     * (its entries in place: a refactorisation of 29 k unknowns spent a
     * third of its time building the gathered matrix anew), and false if
     * @p matrix has an entry outside that structure. */
    bool
    gather(const Epetra_CrsMatrix &matrix, const bool structure)
    {
      if (structure || !all)
        {
          all = std::make_unique<Epetra_CrsMatrix>(Copy, all_rows, 0);
          if (all->Import(matrix, import, Insert) != 0 ||
              all->FillComplete() != 0)
            {
              all.reset();
              return false;
            }
          const int base = all_rows.IndexBase();
          rows.clear();
          columns.clear();
          for (int row = 0; row < all->NumMyRows(); ++row)
            {
              int  n       = 0;
              int *indices = nullptr;
              all->Graph().ExtractMyRowView(row, n, indices);
              for (int k = 0; k < n; ++k)
                {
                  // MUMPS counts from 1.
                  rows.push_back(all->GRID(row) - base + 1);
                  columns.push_back(all->GCID(indices[k]) - base + 1);
                }
            }
        }
      else
        {
          // The same structure: its entries summed from zero take the
          // values bit for bit; an entry outside it is an error of Add.
          all->PutScalar(0.);
          if (all->Import(matrix, import, Add) != 0)
            return false;
        }
      values.clear();
      for (int row = 0; row < all->NumMyRows(); ++row)
        {
          int     n       = 0;
          double *entries = nullptr;
          all->ExtractMyRowView(row, n, entries);
          values.insert(values.end(), entries, entries + n);
        }
      return values.size() == rows.size();
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
            return static_cast<int>(Status::success);
          const int error = mumps_error_class(mumps.infog[0]);
          if (error >= 0)
            return error;
        }
      return static_cast<int>(Status::out_of_memory);
    }

    const MPI_Comm      communicator;
    const bool          on_host;
    const Epetra_Map    all_rows;
    const Epetra_Import import;
    /** The matrix gathered on process 0 (no rows elsewhere). */
    std::unique_ptr<Epetra_CrsMatrix> all;
    DMUMPS_STRUC_C                    mumps{};
    bool                              initialised = false;
    std::vector<int>                  rows, columns;
    std::vector<double>               values;
  };



  DirectSolver::DirectSolver() = default;

  DirectSolver::~DirectSolver() = default;



  DirectSolver::Status
  DirectSolver::factorize(const Epetra_CrsMatrix &matrix,
                          const std::string      &name)
  {
    Amesos factory;
    if (!factory.Query(name))
      return Status::unavailable;
    solver.reset();
    gathered.reset();
    if (name == "Amesos_Mumps" && matrix.Comm().NumProc() > 1)
      {
        gathered = std::make_unique<GatheredMumps>(matrix);
        return gathered->factorize(matrix);
      }
    matrix_copy = std::make_unique<Epetra_CrsMatrix>(matrix);
    problem.SetOperator(matrix_copy.get());
    const bool mumps = name == "Amesos_Mumps";
    for (const int workspace : {20, 100, 400, 1600})
      {
        solver.reset(factory.Create(name, problem));
        if (!solver)
          return Status::unavailable;
        if (mumps && workspace != 20)
          {
            Teuchos::ParameterList parameters;
            parameters.sublist("mumps").set("ICNTL(14)", workspace);
            solver->SetParameters(parameters);
          }
        int error = 0;
        {
          Silence quiet(std::cerr);
          error = solver->SymbolicFactorization();
          if (error == 0)
            error = solver->NumericFactorization();
        }
        if (error == 0)
          return Status::success;
        if (!mumps)
          return error == StructurallySingularMatrixError ||
                     error == NumericallySingularMatrixError ?
                   Status::singular :
                   Status::other;
        // INFOG is defined on the host, process 0.
        auto *mumps_solver = dynamic_cast<Amesos_Mumps *>(solver.get());
        int   status = mumps_solver != nullptr && mumps_solver->GetINFOG() ?
                         mumps_solver->GetINFOG()[0] :
                         0;
        if (const auto *comm =
              dynamic_cast<const Epetra_MpiComm *>(&matrix.Comm()))
          status = dealii::Utilities::MPI::broadcast(comm->Comm(), status, 0);
        const int error_class = mumps_error_class(status);
        if (error_class >= 0)
          return static_cast<Status>(error_class);
        // Workspace too small: more.
        if (workspace == 1600)
          return Status::out_of_memory;
      }
    return Status::out_of_memory;
  }



  DirectSolver::Status
  DirectSolver::refactorize(const Epetra_CrsMatrix &matrix)
  {
    if (gathered)
      return gathered->refactorize(matrix);
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
    if (gathered)
      return gathered->solve(x.trilinos_vector(), b.trilinos_vector());
    problem.SetLHS(&x.trilinos_vector());
    problem.SetRHS(const_cast<Epetra_MultiVector *>(&b.trilinos_vector()));
    Silence quiet(std::cerr);
    return solver->Solve() == 0;
  }
} // namespace bsmpm
