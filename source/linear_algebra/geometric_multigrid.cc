#include <deal.II/base/index_set.h>

#include <deal.II/lac/precondition.h>
#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/trilinos_precondition.h>

#include <bsmpm/linear_algebra/geometric_multigrid.h>
#include <bsmpm/linear_algebra/vertex_patch_smoother.h>

#include <Amesos.h>
#include <Amesos_BaseSolver.h>
#include <EpetraExt_MatrixMatrix.h>
#include <Epetra_CrsMatrix.h>
#include <Epetra_LinearProblem.h>
#include <Epetra_Map.h>
#include <Epetra_RowMatrixTransposer.h>
#include <Epetra_Vector.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <vector>


namespace bsmpm
{
  bool
  couples_off_diagonal(const Epetra_CrsMatrix &matrix, const int row)
  {
    int     n;
    double *values;
    int    *columns;
    matrix.ExtractMyRowView(row, n, values, columns);
    const int diagonal = matrix.LCID(matrix.GRID(row));
    for (int k = 0; k < n; ++k)
      if (columns[k] != diagonal && values[k] != 0.)
        return true;
    return false;
  }



  namespace
  {
    using VectorType = TrilinosWrappers::MPI::Vector;

    /** Corners and cell counts of a grid of equal cells. */
    struct FinestGrid
    {
      Point<2>                    lower, upper;
      std::array<unsigned int, 2> cells;
    };

    /** The grid of @p dof_handler: equal coarse cells refined globally.
     * Its corners and the coarse cell size come from the coarse cells,
     * which every process holds. */
    FinestGrid
    finest_grid(const DoFHandler<2> &dof_handler)
    {
      const auto &tria = dof_handler.get_triangulation();
      AssertThrow(dof_handler.get_fe().n_components() == 2 &&
                    dof_handler.get_fe().n_dofs_per_cell() == 8,
                  ExcMessage("Geometric multigrid: needs Q1 elements with "
                             "two components."));
      FinestGrid grid;
      grid.lower = tria.begin(0)->vertex(0);
      grid.upper = grid.lower;
      for (const auto &cell : tria.cell_iterators_on_level(0))
        for (const unsigned int v : cell->vertex_indices())
          for (unsigned int d = 0; d < 2; ++d)
            {
              grid.lower[d] = std::min(grid.lower[d], cell->vertex(v)[d]);
              grid.upper[d] = std::max(grid.upper[d], cell->vertex(v)[d]);
            }
      const unsigned int refinements = tria.n_global_levels() - 1;
      const Tensor<1, 2> coarse_size =
        tria.begin(0)->vertex(3) - tria.begin(0)->vertex(0);
      for (unsigned int d = 0; d < 2; ++d)
        grid.cells[d] = static_cast<unsigned int>(std::round(
                          (grid.upper[d] - grid.lower[d]) / coarse_size[d]))
                        << refinements;
      AssertThrow(tria.n_global_active_cells() ==
                    static_cast<types::global_cell_index>(grid.cells[0]) *
                      grid.cells[1],
                  ExcMessage("Geometric multigrid: the grid is not a uniform "
                             "rectangle of equal cells."));
      return grid;
    }

    /** Whether a level of @p cells is coarsened once more. */
    bool
    coarsens(const std::array<unsigned int, 2> &cells,
             const unsigned int                 coarse_size)
    {
      return cells[0] % 2 == 0 && cells[1] % 2 == 0 &&
             types::global_dof_index(2) * (cells[0] + 1) * (cells[1] + 1) >
               coarse_size;
    }

    /** A level's matrix as the Chebyshev smoother and the eigenvalue
     * estimate see it: a product with an Epetra matrix. The smoother
     * subscribes to this object, which the hierarchy owns, not to the
     * caller's matrix. */
    struct LevelOperator : public Subscriptor
    {
      const Epetra_CrsMatrix *matrix = nullptr;

      types::global_dof_index
      m() const
      {
        return matrix->NumGlobalRows64();
      }
      types::global_dof_index
      n() const
      {
        return matrix->NumGlobalCols64();
      }
      void
      vmult(VectorType &dst, const VectorType &src) const
      {
        const int error =
          matrix->Multiply(false, src.trilinos_vector(), dst.trilinos_vector());
        AssertThrow(error == 0, ExcTrilinosError(error));
      }
    };

    /** Jacobi: multiplication by the inverse diagonal. (deal.II's
     * DiagonalMatrix would make the Chebyshev smoother compile a serial
     * set-up path that Trilinos vectors do not have.) */
    struct InverseDiagonal : public Subscriptor
    {
      VectorType values;

      void
      vmult(VectorType &dst, const VectorType &src) const
      {
        dst = src;
        dst.scale(values);
      }
    };

    /** The Chebyshev smoother's preconditioner on a level: the inverse
     * diagonal, or the patches where a level has them. */
    struct LevelPreconditioner : public Subscriptor
    {
      InverseDiagonal                      jacobi;
      std::unique_ptr<VertexPatchSmoother> patches;

      void
      vmult(VectorType &dst, const VectorType &src) const
      {
        if (patches)
          patches->vmult(dst, src);
        else
          jacobi.vmult(dst, src);
      }
    };

    using Smoother =
      PreconditionChebyshev<LevelOperator, VectorType, LevelPreconditioner>;

    /** Which locally owned rows of @p matrix have no nonzero off the
     * diagonal (in the order of the row map, the ascending order of the
     * locally owned indices). */
    std::vector<bool>
    decoupled_rows(const Epetra_CrsMatrix &matrix)
    {
      std::vector<bool> decoupled(matrix.NumMyRows());
      for (int row = 0; row < matrix.NumMyRows(); ++row)
        decoupled[row] = !couples_off_diagonal(matrix, row);
      return decoupled;
    }

    void
    check(const int error)
    {
      AssertThrow(error == 0, ExcTrilinosError(error));
    }
  } // namespace



  struct GeometricMultigrid::Implementation
  {
    struct Level
    {
      /** Cells per direction. */
      unsigned int nx = 0, ny = 0;
      /** Locally owned unknowns, and as an Epetra map. */
      IndexSet                    owned;
      std::unique_ptr<Epetra_Map> map;
      /** For each locally owned unknown (in ascending order): its vertex
       * (i, j) on this level and its component. */
      std::vector<std::array<unsigned int, 3>> place;
      /** Coarse levels: P^T A P of the finer level. */
      std::unique_ptr<Epetra_CrsMatrix> matrix;
      LevelOperator                     op;
      /** From the next coarser level to this one (all but the coarsest),
       * and its transpose, the restriction, held by its transposer.
       * EpetraExt's product with a transposed factor crashed in Trilinos
       * 13.2 (FusedExport) when P has empty rows, hence the explicit R. */
      std::unique_ptr<Epetra_CrsMatrix>           prolongation;
      std::unique_ptr<Epetra_RowMatrixTransposer> transposer;
      Epetra_CrsMatrix                           *restriction = nullptr;
      Smoother                                    smoother;
      mutable VectorType rhs, solution, residual, correction;
    };

    MPI_Comm                            communicator;
    AdditionalData                      data;
    std::vector<std::unique_ptr<Level>> levels;

    /** The coarsest operator with a unit diagonal on unknowns without any
     * coupling (their rows and columns of P^T A P are empty), and its
     * factorisation, or its AMG when it is large. */
    std::unique_ptr<Epetra_CrsMatrix> coarsest;
    /** The coarsest operator with its diagonal raised by 1e-10 of itself,
     * where it is singular (setup_smoothers_and_coarse_solver()). */
    std::unique_ptr<Epetra_CrsMatrix>                  regularised;
    mutable Epetra_LinearProblem                       coarse_problem;
    std::unique_ptr<Amesos_BaseSolver>                 coarse_direct;
    std::unique_ptr<TrilinosWrappers::PreconditionAMG> coarse_amg;

    /** P_l from the decoupled rows of level l's operator. */
    void
    build_prolongation(const unsigned int l);

    /** Level l + 1's operator P_l^T A_l P_l. */
    void
    galerkin_product(const unsigned int l);

    /** The smoother of every level but the coarsest, and the coarsest
     * level's solver. */
    void
    setup_smoothers_and_coarse_solver();

    /** Level l's preconditioner of the Chebyshev smoother: Jacobi, or the
     * vertex (cell, large) patches. */
    std::shared_ptr<LevelPreconditioner>
    make_level_preconditioner(const unsigned int l) const;

    /** An estimate of the largest eigenvalue of level l's operator
     * preconditioned by @p preconditioner. */
    double
    largest_eigenvalue(const unsigned int         l,
                       const LevelPreconditioner &preconditioner) const;

    /** Level l's Chebyshev smoother. */
    void
    setup_smoother(const unsigned int l);

    /** coarsest: the coarsest operator with a unit diagonal where it has
     * empty rows. */
    void
    make_coarsest_invertible();

    /** The coarsest level's solver: KLU (regularised where singular) or
     * AMG. */
    void
    setup_coarse_solver();

    void
    cycle(const unsigned int l, VectorType &x, const VectorType &b) const;
  };



  GeometricMultigrid::GeometricMultigrid() = default;

  GeometricMultigrid::~GeometricMultigrid() = default;



  void
  GeometricMultigrid::initialize(const TrilinosWrappers::SparseMatrix &matrix,
                                 const DoFHandler<2>  &dof_handler,
                                 const AdditionalData &additional_data)
  {
    impl               = std::make_unique<Implementation>();
    impl->data         = additional_data;
    impl->communicator = dof_handler.get_communicator();
    auto &levels       = impl->levels;

    const FinestGrid grid  = finest_grid(dof_handler);
    const Point<2>  &lower = grid.lower, &upper = grid.upper;
    auto             fine = std::make_unique<Implementation::Level>();
    fine->nx              = grid.cells[0];
    fine->ny              = grid.cells[1];
    const double h[2]     = {(upper[0] - lower[0]) / fine->nx,
                             (upper[1] - lower[1]) / fine->ny};

    // Where each locally owned DoF sits: a process owns only DoFs of its
    // own cells.
    fine->owned = dof_handler.locally_owned_dofs();
    fine->place.resize(fine->owned.n_elements());
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        for (const unsigned int v : cell->vertex_indices())
          {
            const unsigned int i = static_cast<unsigned int>(
              std::round((cell->vertex(v)[0] - lower[0]) / h[0]));
            const unsigned int j = static_cast<unsigned int>(
              std::round((cell->vertex(v)[1] - lower[1]) / h[1]));
            for (unsigned int c = 0; c < 2; ++c)
              {
                const types::global_dof_index dof =
                  cell->vertex_dof_index(v, c);
                if (fine->owned.is_element(dof))
                  fine->place[fine->owned.index_within_set(dof)] = {{i, j, c}};
              }
          }
    levels.push_back(std::move(fine));

    // Coarser levels while both counts of cells are even and the level is
    // large enough to be worth it. A coarse vertex belongs to the owner of
    // the finer vertex at the same place.
    while (true)
      {
        const auto &f = *levels.back();
        if (!coarsens({{f.nx, f.ny}}, impl->data.coarse_size))
          break;
        auto c = std::make_unique<Implementation::Level>();
        c->nx  = f.nx / 2;
        c->ny  = f.ny / 2;
        std::vector<types::global_dof_index> indices;
        for (const auto &p : f.place)
          if (p[0] % 2 == 0 && p[1] % 2 == 0)
            indices.push_back(
              2 * (types::global_dof_index(p[0] / 2) +
                   types::global_dof_index(c->nx + 1) * (p[1] / 2)) +
              p[2]);
        std::sort(indices.begin(), indices.end());
        c->owned.set_size(types::global_dof_index(2) * (c->nx + 1) *
                          (c->ny + 1));
        c->owned.add_indices(indices.begin(), indices.end());
        c->owned.compress();
        c->place.reserve(indices.size());
        for (const auto index : indices)
          c->place.push_back(
            {{static_cast<unsigned int>((index / 2) % (c->nx + 1)),
              static_cast<unsigned int>((index / 2) / (c->nx + 1)),
              static_cast<unsigned int>(index % 2)}});
        levels.push_back(std::move(c));
      }

    for (auto &level : levels)
      {
        level->map = std::make_unique<Epetra_Map>(
          level->owned.make_trilinos_map(impl->communicator, false));
        level->residual.reinit(level->owned, impl->communicator);
        level->correction.reinit(level->owned, impl->communicator);
        level->rhs.reinit(level->owned, impl->communicator);
        level->solution.reinit(level->owned, impl->communicator);
      }

    // The prolongations depend on the decoupled rows of each level's
    // operator, so they are built level by level with the operators.
    levels[0]->op.matrix = &matrix.trilinos_matrix();
    for (unsigned int l = 0; l + 1 < levels.size(); ++l)
      {
        impl->build_prolongation(l);
        impl->galerkin_product(l);
      }
    impl->setup_smoothers_and_coarse_solver();
  }



  void
  GeometricMultigrid::Implementation::build_prolongation(const unsigned int l)
  {
    Level                  &f         = *levels[l];
    const Level            &c         = *levels[l + 1];
    const std::vector<bool> decoupled = decoupled_rows(*f.op.matrix);

    // Bilinear interpolation: an even fine index sits on a coarse vertex,
    // an odd one halfway between two. Zero rows for unknowns without
    // coupling.
    f.prolongation = std::make_unique<Epetra_CrsMatrix>(Copy, *f.map, 4, true);
    std::vector<TrilinosWrappers::types::int_type> columns;
    std::vector<double>                            weights;
    for (int n = 0; n < f.map->NumMyElements(); ++n)
      if (!decoupled[n])
        {
          const auto &p = f.place[n];
          columns.clear();
          weights.clear();
          const unsigned int nx = p[0] % 2 == 0 ? 1 : 2;
          const unsigned int ny = p[1] % 2 == 0 ? 1 : 2;
          for (unsigned int b = 0; b < ny; ++b)
            for (unsigned int a = 0; a < nx; ++a)
              {
                const unsigned int i = p[0] / 2 + a, j = p[1] / 2 + b;
                columns.push_back(
                  2 * (TrilinosWrappers::types::int_type(i) +
                       TrilinosWrappers::types::int_type(c.nx + 1) * j) +
                  p[2]);
                weights.push_back((nx == 1 ? 1. : 0.5) * (ny == 1 ? 1. : 0.5));
              }
          TrilinosWrappers::types::int_type row = f.map->GID(n);
          check(f.prolongation->InsertGlobalValues(
            row, columns.size(), weights.data(), columns.data()));
        }
    check(f.prolongation->FillComplete(*c.map, *f.map));
    f.transposer =
      std::make_unique<Epetra_RowMatrixTransposer>(f.prolongation.get());
    check(f.transposer->CreateTranspose(true, f.restriction, c.map.get()));
  }



  void
  GeometricMultigrid::Implementation::galerkin_product(const unsigned int l)
  {
    Level           &f = *levels[l];
    Level           &c = *levels[l + 1];
    Epetra_CrsMatrix product(Copy, *f.map, 0);
    check(EpetraExt::MatrixMatrix::Multiply(
      *f.op.matrix, false, *f.prolongation, false, product));
    c.matrix = std::make_unique<Epetra_CrsMatrix>(Copy, *c.map, 0);
    check(EpetraExt::MatrixMatrix::Multiply(
      *f.restriction, false, product, false, *c.matrix));
    c.op.matrix = c.matrix.get();
  }



  void
  GeometricMultigrid::reinit(const TrilinosWrappers::SparseMatrix &matrix)
  {
    impl->levels[0]->op.matrix = &matrix.trilinos_matrix();
    for (unsigned int l = 0; l + 1 < impl->levels.size(); ++l)
      impl->galerkin_product(l);
    impl->setup_smoothers_and_coarse_solver();
  }



  void
  GeometricMultigrid::set_fine_matrix(
    const TrilinosWrappers::SparseMatrix &matrix)
  {
    impl->levels[0]->op.matrix = &matrix.trilinos_matrix();
  }



  void
  GeometricMultigrid::Implementation::setup_smoothers_and_coarse_solver()
  {
    for (unsigned int l = 0; l + 1 < levels.size(); ++l)
      setup_smoother(l);
    // The old coarse solver first: it refers to the old coarse operators.
    coarse_direct.reset();
    coarse_amg.reset();
    regularised.reset();
    make_coarsest_invertible();
    setup_coarse_solver();
  }



  std::shared_ptr<LevelPreconditioner>
  GeometricMultigrid::Implementation::make_level_preconditioner(
    const unsigned int l) const
  {
    const Level            &level = *levels[l];
    const Epetra_CrsMatrix &A     = *level.op.matrix;
    // Jacobi: the inverse diagonal, zero where the diagonal is (the
    // empty rows of a coarse operator, which the coarse correction
    // never touches: their restricted residual is zero).
    auto        preconditioner   = std::make_shared<LevelPreconditioner>();
    VectorType &inverse_diagonal = preconditioner->jacobi.values;
    inverse_diagonal.reinit(level.owned, communicator);
    Epetra_Vector &d = *inverse_diagonal.trilinos_vector()(0);
    check(A.ExtractDiagonalCopy(d));
    for (int k = 0; k < d.MyLength(); ++k)
      d[k] = d[k] != 0. ? 1. / d[k] : 0.;
    if (data.blocks != GeometricMultigrid::Blocks::point &&
        (data.patch_levels == 0 || l < data.patch_levels))
      {
        preconditioner->patches = std::make_unique<VertexPatchSmoother>();
        preconditioner->patches->initialize(
          A,
          *level.map,
          level.place,
          level.nx,
          level.ny,
          data.blocks == GeometricMultigrid::Blocks::vertex_patch ?
            VertexPatchSmoother::Patch::vertex :
            (data.blocks == GeometricMultigrid::Blocks::cell_patch ?
               VertexPatchSmoother::Patch::cell :
               VertexPatchSmoother::Patch::large));
      }
    return preconditioner;
  }



  double
  GeometricMultigrid::Implementation::largest_eigenvalue(
    const unsigned int         l,
    const LevelPreconditioner &preconditioner) const
  {
    const Level         &level = *levels[l];
    const Epetra_Vector &d = *preconditioner.jacobi.values.trilinos_vector()(0);
    // The largest eigenvalue of D^-1 A (or B A with the patches' B)
    // from the Lanczos process of a few CG steps, started from a
    // vector with high-frequency content that depends on the global
    // index only (the same at any number of processes on the coarse
    // levels).
    VectorType     start(level.owned, communicator), x(start);
    Epetra_Vector &s = *start.trilinos_vector()(0);
    for (int k = 0; k < s.MyLength(); ++k)
      s[k] = d[k] != 0. ? double(s.Map().GID(k) % 11) - 5. : 0.;
    double lambda_max = 1.;
    {
      IterationNumberControl control(12, 1e-14, false, false);
      SolverCG<VectorType>   cg(control);
      cg.connect_eigenvalues_slot(
        [&lambda_max](const std::vector<double> &eigenvalues) {
          if (!eigenvalues.empty())
            lambda_max = eigenvalues.back();
        });
      cg.solve(level.op, x, start, preconditioner);
    }
    return lambda_max;
  }



  void
  GeometricMultigrid::Implementation::setup_smoother(const unsigned int l)
  {
    // Chebyshev smoothing with Jacobi or the vertex patches, scaled by the
    // largest eigenvalue of its preconditioned operator.
    Level       &level          = *levels[l];
    const auto   preconditioner = make_level_preconditioner(l);
    const double lambda_max     = largest_eigenvalue(l, *preconditioner);
    typename Smoother::AdditionalData smoother_data;
    smoother_data.degree          = data.smoother_degree;
    smoother_data.smoothing_range = data.smoothing_range;
    // Lanczos approaches the largest eigenvalue from below.
    smoother_data.max_eigenvalue      = 1.2 * lambda_max;
    smoother_data.eig_cg_n_iterations = 0;
    smoother_data.preconditioner      = preconditioner;
    level.smoother.initialize(level.op, smoother_data);
  }



  void
  GeometricMultigrid::Implementation::make_coarsest_invertible()
  {
    // The coarsest level: P^T A P has empty rows and columns for the coarse
    // unknowns that no coupled fine unknown interpolates from; a unit
    // diagonal there makes it invertible without changing the solution
    // elsewhere (their right-hand side is zero). The finest level, when it
    // is the only one, has its diagonal.
    const Level            &last = *levels.back();
    const Epetra_CrsMatrix &C    = *last.op.matrix;
    coarsest.reset();
    if (levels.size() > 1)
      {
        coarsest = std::make_unique<Epetra_CrsMatrix>(Copy,
                                                      *last.map,
                                                      C.MaxNumEntries() + 1);
        std::vector<TrilinosWrappers::types::int_type> columns;
        std::vector<double>                            values;
        for (int row = 0; row < C.NumMyRows(); ++row)
          {
            int     n;
            double *v;
            int    *local;
            C.ExtractMyRowView(row, n, v, local);
            const TrilinosWrappers::types::int_type global = C.GRID(row);
            columns.clear();
            values.clear();
            bool        empty    = true;
            std::size_t diagonal = n;
            for (int k = 0; k < n; ++k)
              {
                columns.push_back(C.GCID(local[k]));
                values.push_back(v[k]);
                empty = empty && v[k] == 0.;
                if (columns.back() == global)
                  diagonal = k;
              }
            if (empty && diagonal < columns.size())
              values[diagonal] = 1.;
            else if (empty)
              {
                columns.push_back(global);
                values.push_back(1.);
              }
            check(coarsest->InsertGlobalValues(
              global, columns.size(), values.data(), columns.data()));
          }
        check(coarsest->FillComplete(*last.map, *last.map));
      }
  }



  void
  GeometricMultigrid::Implementation::setup_coarse_solver()
  {
    // KLU up to a size, else AMG with the two translations as its constant
    // modes.
    const Level            &last          = *levels.back();
    const Epetra_CrsMatrix &C             = *last.op.matrix;
    const Epetra_CrsMatrix &coarse_matrix = coarsest ? *coarsest : C;

    if (static_cast<types::global_dof_index>(coarse_matrix.NumGlobalRows64()) <=
        data.direct_size)
      {
        coarse_problem.SetOperator(
          const_cast<Epetra_CrsMatrix *>(&coarse_matrix));
        Amesos factory;
        coarse_direct.reset(factory.Create("Amesos_Klu", coarse_problem));
        AssertThrow(coarse_direct, ExcMessage("Amesos_Klu is missing."));
        check(coarse_direct->SymbolicFactorization());
        if (coarse_direct->NumericFactorization() != 0)
          {
            // P^T A P is singular where two coarse unknowns reach the
            // coupled fine unknowns only through the same ones with the
            // same weights: P has two equal columns. The thick cylinder of
            // issue 24 in its second step: the points moved 1e-5 across
            // y = 2, so the fine cell [0, h] x [2, 2 + h] gained material;
            // the roller on x = 0 holds the x unknowns of its left
            // vertices, and of the new ones only that at (h, 2 + h) is
            // left, halfway between the coarse vertices (0, 17) and
            // (1, 17), which reach no other coupled fine unknown. A is
            // positive definite on the coupled unknowns, so the null space
            // of P^T A P is that of P: the restricted residual P^T r has
            // no component in it, and the prolongation maps any component
            // there to zero. Raising the diagonal by 1e-10 of itself makes
            // the operator invertible and changes the correction elsewhere
            // by that fraction.
            regularised = std::make_unique<Epetra_CrsMatrix>(coarse_matrix);
            Epetra_Vector diagonal(*last.map);
            check(regularised->ExtractDiagonalCopy(diagonal));
            for (int k = 0; k < diagonal.MyLength(); ++k)
              diagonal[k] *= 1. + 1e-10;
            check(regularised->ReplaceDiagonalValues(diagonal));
            coarse_problem.SetOperator(regularised.get());
            coarse_direct.reset(factory.Create("Amesos_Klu", coarse_problem));
            check(coarse_direct->SymbolicFactorization());
            check(coarse_direct->NumericFactorization());
          }
      }
    else
      {
        TrilinosWrappers::PreconditionAMG::AdditionalData amg_data;
        amg_data.elliptic              = true;
        amg_data.higher_order_elements = false;
        amg_data.smoother_sweeps       = 2;
        amg_data.aggregation_threshold = 0.02;
        // The two translations: the unknowns of each component.
        amg_data.constant_modes.assign(2,
                                       std::vector<bool>(last.place.size(),
                                                         false));
        for (std::size_t k = 0; k < last.place.size(); ++k)
          amg_data.constant_modes[last.place[k][2]][k] = true;
        coarse_amg = std::make_unique<TrilinosWrappers::PreconditionAMG>();
        coarse_amg->initialize(coarse_matrix, amg_data);
      }
  }



  void
  GeometricMultigrid::Implementation::cycle(const unsigned int l,
                                            VectorType        &x,
                                            const VectorType  &b) const
  {
    if (l + 1 == levels.size())
      {
        if (coarse_direct)
          {
            coarse_problem.SetLHS(&x.trilinos_vector());
            coarse_problem.SetRHS(
              const_cast<Epetra_MultiVector *>(&b.trilinos_vector()));
            check(coarse_direct->Solve());
          }
        else
          coarse_amg->vmult(x, b);
        return;
      }
    const Level &level  = *levels[l];
    const Level &coarse = *levels[l + 1];
    level.smoother.vmult(x, b);
    level.op.vmult(level.residual, x);
    level.residual.sadd(-1., 1., b);
    check(level.restriction->Multiply(false,
                                      level.residual.trilinos_vector(),
                                      coarse.rhs.trilinos_vector()));
    cycle(l + 1, coarse.solution, coarse.rhs);
    check(level.prolongation->Multiply(false,
                                       coarse.solution.trilinos_vector(),
                                       level.correction.trilinos_vector()));
    x += level.correction;
    level.smoother.step(x, b);
  }



  void
  GeometricMultigrid::vmult(VectorType &dst, const VectorType &src) const
  {
    impl->cycle(0, dst, src);
  }



  unsigned int
  GeometricMultigrid::n_coarse_levels(const DoFHandler<2>  &dof_handler,
                                      const AdditionalData &data)
  {
    std::array<unsigned int, 2> cells = finest_grid(dof_handler).cells;
    unsigned int                n     = 0;
    for (; coarsens(cells, data.coarse_size); ++n)
      cells = {{cells[0] / 2, cells[1] / 2}};
    return n;
  }



  unsigned int
  GeometricMultigrid::n_levels() const
  {
    return impl ? impl->levels.size() : 0;
  }



  std::string
  GeometricMultigrid::level_sizes() const
  {
    std::string sizes;
    if (impl)
      for (const auto &level : impl->levels)
        sizes += (sizes.empty() ? "" : " ") +
                 std::to_string(2 * (level->nx + 1) * (level->ny + 1));
    return sizes;
  }
} // namespace bsmpm
