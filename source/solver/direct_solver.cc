#include <deal.II/base/mpi.h>

#include <bsmpm/solver/direct_solver.h>

#include <Amesos.h>
#include <Amesos_BaseSolver.h>
#include <Amesos_Mumps.h>
#include <Epetra_MpiComm.h>
#include <Teuchos_ParameterList.hpp>

#include <algorithm>
#include <iostream>
#include <sstream>

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
  } // namespace



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
        switch (status)
          {
            case -8:
            case -9:
            case -11:
            case -14:
            case -15:
            case -17:
            case -20:
              // Workspace too small: more.
              if (workspace < 1600)
                continue;
              return Status::out_of_memory;
            case -5:
            case -7:
            case -13:
            case -19:
              // An allocation failed.
              return Status::out_of_memory;
            case -6:
            case -10:
              return Status::singular;
            default:
              return Status::other;
          }
      }
    return Status::out_of_memory;
  }



  DirectSolver::Status
  DirectSolver::refactorize(const Epetra_CrsMatrix &matrix)
  {
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
    problem.SetLHS(&x.trilinos_vector());
    problem.SetRHS(const_cast<Epetra_MultiVector *>(&b.trilinos_vector()));
    Silence quiet(std::cerr);
    return solver->Solve() == 0;
  }
} // namespace bsmpm
