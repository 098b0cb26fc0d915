#include <deal.II/base/exceptions.h>

#include <bsmpm/linear_algebra/mumps_factorization.h>

#include <mpi.h>

namespace bsmpm
{
  namespace
  {
    /** What MUMPS' INFOG(1) < 0 means for the caller (MUMPS users' guide,
     * "Error diagnostics"); `other` with @p workspace set where more
     * workspace may help. */
    DirectSolver::Status
    mumps_error(const int infog1, bool &workspace)
    {
      workspace = false;
      switch (infog1)
        {
          case -8:
          case -9:
          case -11:
          case -14:
          case -15:
          case -17:
          case -20:
            workspace = true;
            return DirectSolver::Status::other;
          case -5:
          case -7:
          case -13:
          case -19:
            return DirectSolver::Status::out_of_memory;
          case -6:
          case -10:
            return DirectSolver::Status::singular;
          default:
            return DirectSolver::Status::other;
        }
    }
  } // namespace



  MumpsFactorization::MumpsFactorization(const bool symmetric)
    : symmetric(symmetric)
  {
    mumps.comm_fortran = MPI_Comm_c2f(MPI_COMM_SELF);
    mumps.par          = 1;
    mumps.sym          = symmetric ? 2 : 0;
    mumps.job          = -1;
    dmumps_c(&mumps);
    initialised = mumps.infog[0] >= 0;
  }



  MumpsFactorization::~MumpsFactorization()
  {
    if (initialised)
      {
        mumps.job = -2;
        dmumps_c(&mumps);
      }
  }



  DirectSolver::Status
  MumpsFactorization::analyse(const int               n,
                              const std::vector<int> &rows_,
                              const std::vector<int> &columns_,
                              const int               schur_size)
  {
    if (!initialised)
      return DirectSolver::Status::other;
    rows    = rows_;
    columns = columns_;
    // Silent; automatic ordering; no iterative refinement (the caller
    // refines with the distributed matrix); the matrix centralised. The
    // maximum transversal and the scaling (ICNTL(6), (8)) where MUMPS can
    // have them: not with a Schur complement. Pairs of ICNTL(k) and its
    // value.
    const int permute       = schur_size > 0 ? 0 : 7;
    const int controls[][2] = {{1, -1},
                               {2, -1},
                               {3, -1},
                               {4, -1},
                               {5, 0},
                               {6, permute},
                               {7, 7},
                               {8, permute},
                               {9, 1},
                               {10, 0},
                               {11, 0},
                               {12, 0},
                               {13, 0},
                               {15, 0},
                               {16, 0},
                               {18, 0},
                               {19, schur_size > 0 ? 1 : 0}};
    for (const auto &control : controls)
      mumps.icntl[control[0] - 1] = control[1];
    // L D L^T with pivoting does not stop at a zero pivot as the LU does
    // (INFOG(1) = -10): it reports the null pivots it met (ICNTL(24) = 1,
    // INFOG(28)), which factorize() calls singular.
    if (symmetric)
      mumps.icntl[24 - 1] = 1;
    schur_variables.resize(schur_size);
    for (int k = 0; k < schur_size; ++k)
      schur_variables[k] = n - schur_size + k + 1;
    schur.assign(static_cast<std::size_t>(schur_size) * schur_size, 0.);
    mumps.size_schur    = schur_size;
    mumps.listvar_schur = schur_size > 0 ? schur_variables.data() : nullptr;
    mumps.schur         = schur_size > 0 ? schur.data() : nullptr;
    mumps.schur_lld     = schur_size;
    mumps.n             = n;
    mumps.nnz           = rows.size();
    mumps.nz            = rows.size();
    mumps.irn           = rows.data();
    mumps.jcn           = columns.data();
    mumps.job           = 1;
    dmumps_c(&mumps);
    analysed = mumps.infog[0] >= 0;
    if (analysed)
      return DirectSolver::Status::success;
    // More workspace is no remedy in the analysis.
    bool workspace = false;
    return mumps_error(mumps.infog[0], workspace);
  }



  DirectSolver::Status
  MumpsFactorization::factorize(std::vector<double> &values)
  {
    if (!analysed || values.size() != rows.size())
      return DirectSolver::Status::other;
    mumps.a = values.data();
    for (const int workspace : {20, 100, 400, 1600})
      {
        mumps.icntl[14 - 1] = workspace;
        mumps.job           = 2;
        dmumps_c(&mumps);
        if (mumps.infog[0] >= 0)
          return mumps.infog[28 - 1] > 0 ? DirectSolver::Status::singular :
                                           DirectSolver::Status::success;
        bool                       more_workspace = false;
        const DirectSolver::Status error =
          mumps_error(mumps.infog[0], more_workspace);
        if (!more_workspace)
          return error;
      }
    return DirectSolver::Status::out_of_memory;
  }



  bool
  MumpsFactorization::run_solve(double   *rhs,
                                double   *reduced,
                                const int schur_phase)
  {
    mumps.rhs           = rhs;
    mumps.nrhs          = 1;
    mumps.lrhs          = mumps.n;
    mumps.redrhs        = reduced;
    mumps.lredrhs       = mumps.size_schur;
    mumps.icntl[26 - 1] = schur_phase;
    mumps.job           = 3;
    dmumps_c(&mumps);
    mumps.icntl[26 - 1] = 0;
    return mumps.infog[0] >= 0;
  }



  bool
  MumpsFactorization::solve(double *rhs)
  {
    Assert(mumps.size_schur == 0, dealii::ExcInternalError());
    return run_solve(rhs, nullptr, 0);
  }



  bool
  MumpsFactorization::reduce(double *rhs, double *reduced)
  {
    Assert(mumps.size_schur > 0, dealii::ExcInternalError());
    return run_solve(rhs, reduced, 1);
  }



  bool
  MumpsFactorization::expand(double *rhs, double *reduced)
  {
    Assert(mumps.size_schur > 0, dealii::ExcInternalError());
    return run_solve(rhs, reduced, 2);
  }
} // namespace bsmpm
