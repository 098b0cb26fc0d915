// Assembly of the stiffness matrix and internal force over the same grid with
// the same number of points per cell, two ways:
//
// MP:       bsmpm's material-point assembly as Scene::assemble_system() does
//           it: MaterialPoints::compute_cell_moments(), then per cell
//           Q1CellKernel::add_stiffness() and add_internal_force(), and
//           CellScatter::add() (the entries' positions in Epetra's arrays
//           found once; AffineConstraints::distribute_local_to_global() for
//           cells with constrained DoFs) into a
//           TrilinosWrappers::SparseMatrix and MPI::Vector, then compress().
// FEValues: deal.II's FEValues with QGauss(n) (n x n points per cell) and a
//           hand-written kernel K += B^T C B JxW, f += B^T sigma JxW per
//           quadrature point from fe_values.shape_grad(), with the stresses
//           of the quadrature points read from an array (as a quadrature
//           point history would hold them), into the same kind of matrix.
//
// "local" times the cell matrices and vectors alone (for MP including
// compute_cell_moments(), which reads every point once); "total" adds
// distribute_local_to_global() and compress(). Every figure is the best of
// the repetitions (wall time); the ratio MP/FEValues is printed for both.
// Pieces (moments alone, the 8x8 kernel alone, distribute alone) are printed
// to show where the time goes, with alternatives for comparison: moments
// summed in local variables; the global part without constraints, through
// deal.II's own SparseMatrix, and as a scatter through pointers into
// Epetra's value arrays found once (the sparsity never changes).
//
// Usage: assembly_benchmark [cells per direction] [points per direction]
//                           [repetitions] [all|mp|fe] [B-bar|standard]
// The last chooses the kernel's volumetric strain (default B-bar, as
// bsmpm's linear path; doc/b-bar.md); the FEValues kernel is always the
// standard one.
// Without arguments it runs 128x128 cells with 8x8 points per cell and
// 64x64 cells with 16x16 points per cell (both 1,048,576 points), and a
// 16x16 grid with 8x8 and 16x16 points per cell. A small case with one
// repetition and one of mp|fe suits callgrind, e.g.
//   valgrind --tool=callgrind --toggle-collect='*assemble_mp_total*'
//            ./assembly_benchmark 16 8 1 mp

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/timer.h>

#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/fe_values.h>

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/sparsity_pattern.h>
#include <deal.II/lac/sparsity_tools.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/lac/vector.h>

#include <bsmpm/assembly/cell_scatter.h>
#include <bsmpm/geometry/background_grid.h>
#include <bsmpm/geometry/body_region.h>
#include <bsmpm/materials/material.h>
#include <bsmpm/points/material_point_layout.h>
#include <bsmpm/points/material_points.h>
#include <bsmpm/points/q1_cell_kernel.h>

#include <algorithm>
#include <functional>
#include <iomanip>
#include <iostream>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#if defined(__GNUC__)
#  define BENCHMARK_NOINLINE __attribute__((noinline))
#else
#  define BENCHMARK_NOINLINE
#endif

using namespace dealii;
using namespace bsmpm;

namespace
{
  // Keeps the compiler from discarding local matrices that are never used.
  volatile double sink = 0;

  class AssemblyBenchmark
  {
  public:
    AssemblyBenchmark(const unsigned int n_cells,
                      const unsigned int n_points,
                      const bool         b_bar);

    void
    run(const unsigned int repetitions, const std::string &mode);

    // The timed pieces (noinline, so that callgrind can collect them alone).
    BENCHMARK_NOINLINE void
    mp_moments();
    BENCHMARK_NOINLINE void
    mp_kernel_local();
    BENCHMARK_NOINLINE void
    assemble_mp_local();
    BENCHMARK_NOINLINE void
    assemble_mp_total();
    BENCHMARK_NOINLINE void
    assemble_fe_local();
    BENCHMARK_NOINLINE void
    assemble_fe_total();
    BENCHMARK_NOINLINE void
    distribute_only();
    BENCHMARK_NOINLINE void
    direct_add_only();
    BENCHMARK_NOINLINE void
    distribute_via_dealii_matrix();
    BENCHMARK_NOINLINE void
    scatter_cached();
    BENCHMARK_NOINLINE void
    moments_in_registers();

  private:
    void
    zero_system();

    const bool         b_bar;
    const unsigned int n_cells, n_points;

    ParameterHandler                prm;
    LinearElasticMaterial           material;
    BackgroundGrid                  grid;
    BodyRegion                      region;
    MaterialPointLayout             layout;
    std::unique_ptr<MaterialPoints> points;
    std::unique_ptr<Q1CellKernel>   kernel;
    std::vector<CellMoments>        moments;

    AffineConstraints<double>      constraints;
    TrilinosWrappers::SparseMatrix matrix;
    TrilinosWrappers::MPI::Vector  rhs;

    // Serial deal.II matrix with the same couplings, for comparison.
    SparsityPattern        serial_sparsity;
    SparseMatrix<double>   serial_matrix;
    dealii::Vector<double> serial_rhs;

    // For every cell, where its 64 matrix entries live in Epetra's storage.
    std::vector<double *> cached_entries;
    /** The cached scatter of SystemAssembly (CellScatter). */
    CellScatter scatter;

    QGauss<2>                    quadrature;
    std::unique_ptr<FEValues<2>> fe_values;
    // Stresses of the Gauss points, cell by cell.
    std::vector<Voigt>                                    gauss_stress;
    std::array<unsigned int, Q1CellKernel::dofs_per_cell> component;
  };



  AssemblyBenchmark::AssemblyBenchmark(const unsigned int n_cells,
                                       const unsigned int n_points,
                                       const bool         b_bar)
    : b_bar(b_bar)
    , n_cells(n_cells)
    , n_points(n_points)
    , grid(MPI_COMM_WORLD)
    , quadrature(n_points)
  {
    LinearElasticMaterial::declare_parameters(prm);
    BackgroundGrid::declare_parameters(prm);
    BodyRegion::declare_parameters(prm);
    MaterialPointLayout::declare_parameters(prm);
    const std::string n = std::to_string(n_cells);
    prm.parse_input_from_string("subsection Material\n"
                                "  set Young's modulus = 1e6\n"
                                "  set Poisson's ratio = 0.25\n"
                                "  set Model = plane strain\n"
                                "end\n"
                                "subsection Background grid\n"
                                "  set Lower left corner = 0, 0\n"
                                "  set Upper right corner = 2, 2\n"
                                "  set Cells per direction = " +
                                n + ", " + n +
                                "\n"
                                "  subsection Face conditions\n"
                                "    set Bottom = fixed\n"
                                "    set Left = roller\n"
                                "  end\n"
                                "end\n"
                                "subsection Body region\n"
                                "  set Shape = rectangle\n"
                                "  set Lower left corner = 0, 0\n"
                                "  set Upper right corner = 2, 2\n"
                                "end\n"
                                "subsection Material points\n"
                                "  set Layout = per cell\n"
                                "  set Points per cell = " +
                                std::to_string(n_points) +
                                "\n"
                                "end\n");
    material.parse_parameters(prm);
    grid.parse_parameters(prm);
    region.parse_parameters(prm);
    layout.parse_parameters(prm);
    grid.create();

    points = std::make_unique<MaterialPoints>(grid);
    points->generate(layout, region);
    // Non-zero stresses, so that the internal force is not trivially zero.
    for (auto &particle : points->particle_handler())
      {
        auto props                                  = particle.get_properties();
        props[MaterialPoints::Property::stress]     = -1e3;
        props[MaterialPoints::Property::stress + 1] = -3e3;
        props[MaterialPoints::Property::stress + 2] = 5e2;
      }
    kernel = std::make_unique<Q1CellKernel>(grid.fe(),
                                            grid.cell_size(),
                                            material.stiffness(),
                                            b_bar);

    // As Scene::setup_system() and make_constraints().
    constraints.reinit(grid.locally_relevant_dofs());
    grid.make_face_constraints(constraints);
    constraints.close();
    DynamicSparsityPattern dsp(grid.locally_relevant_dofs());
    DoFTools::make_sparsity_pattern(grid.dof_handler(), dsp);
    SparsityTools::distribute_sparsity_pattern(dsp,
                                               grid.locally_owned_dofs(),
                                               grid.mpi_communicator(),
                                               grid.locally_relevant_dofs());
    matrix.reinit(grid.locally_owned_dofs(),
                  grid.locally_owned_dofs(),
                  dsp,
                  grid.mpi_communicator());
    rhs.reinit(grid.locally_owned_dofs(), grid.mpi_communicator());
    serial_sparsity.copy_from(dsp);
    serial_matrix.reinit(serial_sparsity);
    serial_rhs.reinit(grid.dof_handler().n_dofs());

    fe_values =
      std::make_unique<FEValues<2>>(grid.mapping(),
                                    grid.fe(),
                                    quadrature,
                                    update_gradients | update_JxW_values);
    gauss_stress.assign(grid.triangulation().n_active_cells() *
                          quadrature.size(),
                        Voigt({-1e3, -3e3, 5e2}));
    for (unsigned int i = 0; i < Q1CellKernel::dofs_per_cell; ++i)
      component[i] = grid.fe().system_to_component_index(i).first;
  }



  void
  AssemblyBenchmark::zero_system()
  {
    matrix = 0;
    rhs    = 0;
  }



  // The moments alone: one pass over the points.
  void
  AssemblyBenchmark::mp_moments()
  {
    points->compute_cell_moments(moments);
  }



  // The 8x8 kernel alone, from moments computed before.
  void
  AssemblyBenchmark::mp_kernel_local()
  {
    FullMatrix<double> cell_matrix(8, 8);
    Vector<double>     cell_rhs(8);
    double             check = 0;
    for (const auto &cell : grid.dof_handler().active_cell_iterators())
      {
        if (!cell->is_locally_owned())
          continue;
        const CellMoments &m = moments[cell->active_cell_index()];
        if (m.v == 0.)
          continue;
        cell_matrix = 0;
        cell_rhs    = 0;
        kernel->add_stiffness(m, cell_matrix);
        kernel->add_internal_force(m, cell_rhs);
        check += cell_matrix(3, 5) + cell_rhs(2);
      }
    sink = sink + check;
  }



  void
  AssemblyBenchmark::assemble_mp_local()
  {
    mp_moments();
    mp_kernel_local();
  }



  // As Scene::assemble_system(), without the body force.
  void
  AssemblyBenchmark::assemble_mp_total()
  {
    if (!scatter.serves(matrix))
      scatter.reinit(matrix, grid.triangulation().n_active_cells());
    points->compute_cell_moments(moments);
    FullMatrix<double>                   cell_matrix(8, 8);
    Vector<double>                       cell_rhs(8), internal(8);
    std::vector<types::global_dof_index> dof_indices(8);
    for (const auto &cell : grid.dof_handler().active_cell_iterators())
      {
        if (!cell->is_locally_owned())
          continue;
        const CellMoments &m = moments[cell->active_cell_index()];
        if (m.v == 0.)
          continue;
        cell_matrix = 0;
        cell_rhs    = 0;
        internal    = 0;
        kernel->add_stiffness(m, cell_matrix);
        kernel->add_internal_force(m, internal);
        cell_rhs -= internal;
        cell->get_dof_indices(dof_indices);
        scatter.add(cell->active_cell_index(),
                    cell_matrix,
                    cell_rhs,
                    dof_indices,
                    constraints,
                    matrix,
                    rhs);
      }
    matrix.compress(VectorOperation::add);
    rhs.compress(VectorOperation::add);
  }



  void
  AssemblyBenchmark::assemble_fe_local()
  {
    const Tensor<2, 3> &C   = material.stiffness();
    const unsigned int  n_q = quadrature.size();
    FullMatrix<double>  cell_matrix(8, 8);
    Vector<double>      cell_rhs(8);
    double              check = 0;
    for (const auto &cell : grid.dof_handler().active_cell_iterators())
      {
        if (!cell->is_locally_owned())
          continue;
        fe_values->reinit(cell);
        cell_matrix          = 0;
        cell_rhs             = 0;
        const Voigt *sigma_q = &gauss_stress[cell->active_cell_index() * n_q];
        for (unsigned int q = 0; q < n_q; ++q)
          {
            const double JxW = fe_values->JxW(q);
            // B (3 x 8), two non-zeros per column, and C B.
            double B[3][8], CB[3][8];
            for (unsigned int i = 0; i < 8; ++i)
              {
                const Tensor<1, 2> &g = fe_values->shape_grad(i, q);
                if (component[i] == 0)
                  {
                    B[0][i] = g[0];
                    B[1][i] = 0;
                    B[2][i] = g[1];
                  }
                else
                  {
                    B[0][i] = 0;
                    B[1][i] = g[1];
                    B[2][i] = g[0];
                  }
              }
            for (unsigned int r = 0; r < 3; ++r)
              for (unsigned int j = 0; j < 8; ++j)
                CB[r][j] = JxW * (C[r][0] * B[0][j] + C[r][1] * B[1][j] +
                                  C[r][2] * B[2][j]);
            for (unsigned int i = 0; i < 8; ++i)
              {
                for (unsigned int j = 0; j < 8; ++j)
                  cell_matrix(i, j) += B[0][i] * CB[0][j] + B[1][i] * CB[1][j] +
                                       B[2][i] * CB[2][j];
                cell_rhs(i) -=
                  JxW * (B[0][i] * sigma_q[q][0] + B[1][i] * sigma_q[q][1] +
                         B[2][i] * sigma_q[q][2]);
              }
          }
        check += cell_matrix(3, 5) + cell_rhs(2);
      }
    sink = sink + check;
  }



  void
  AssemblyBenchmark::assemble_fe_total()
  {
    const Tensor<2, 3>                  &C   = material.stiffness();
    const unsigned int                   n_q = quadrature.size();
    FullMatrix<double>                   cell_matrix(8, 8);
    Vector<double>                       cell_rhs(8);
    std::vector<types::global_dof_index> dof_indices(8);
    for (const auto &cell : grid.dof_handler().active_cell_iterators())
      {
        if (!cell->is_locally_owned())
          continue;
        fe_values->reinit(cell);
        cell_matrix          = 0;
        cell_rhs             = 0;
        const Voigt *sigma_q = &gauss_stress[cell->active_cell_index() * n_q];
        for (unsigned int q = 0; q < n_q; ++q)
          {
            const double JxW = fe_values->JxW(q);
            double       B[3][8], CB[3][8];
            for (unsigned int i = 0; i < 8; ++i)
              {
                const Tensor<1, 2> &g = fe_values->shape_grad(i, q);
                if (component[i] == 0)
                  {
                    B[0][i] = g[0];
                    B[1][i] = 0;
                    B[2][i] = g[1];
                  }
                else
                  {
                    B[0][i] = 0;
                    B[1][i] = g[1];
                    B[2][i] = g[0];
                  }
              }
            for (unsigned int r = 0; r < 3; ++r)
              for (unsigned int j = 0; j < 8; ++j)
                CB[r][j] = JxW * (C[r][0] * B[0][j] + C[r][1] * B[1][j] +
                                  C[r][2] * B[2][j]);
            for (unsigned int i = 0; i < 8; ++i)
              {
                for (unsigned int j = 0; j < 8; ++j)
                  cell_matrix(i, j) += B[0][i] * CB[0][j] + B[1][i] * CB[1][j] +
                                       B[2][i] * CB[2][j];
                cell_rhs(i) -=
                  JxW * (B[0][i] * sigma_q[q][0] + B[1][i] * sigma_q[q][1] +
                         B[2][i] * sigma_q[q][2]);
              }
          }
        cell->get_dof_indices(dof_indices);
        constraints.distribute_local_to_global(
          cell_matrix, cell_rhs, dof_indices, matrix, rhs);
      }
    matrix.compress(VectorOperation::add);
    rhs.compress(VectorOperation::add);
  }



  // The global part alone: one fixed cell matrix distributed to every cell.
  void
  AssemblyBenchmark::distribute_only()
  {
    FullMatrix<double> cell_matrix(8, 8);
    Vector<double>     cell_rhs(8);
    kernel->add_stiffness(moments[0], cell_matrix);
    kernel->add_internal_force(moments[0], cell_rhs);
    std::vector<types::global_dof_index> dof_indices(8);
    for (const auto &cell : grid.dof_handler().active_cell_iterators())
      if (cell->is_locally_owned())
        {
          cell->get_dof_indices(dof_indices);
          constraints.distribute_local_to_global(
            cell_matrix, cell_rhs, dof_indices, matrix, rhs);
        }
    matrix.compress(VectorOperation::add);
    rhs.compress(VectorOperation::add);
  }



  // For comparison: the same without constraints, straight into the matrix
  // (what distribute_local_to_global() costs beyond the plain add).
  void
  AssemblyBenchmark::direct_add_only()
  {
    FullMatrix<double> cell_matrix(8, 8);
    Vector<double>     cell_rhs(8);
    kernel->add_stiffness(moments[0], cell_matrix);
    kernel->add_internal_force(moments[0], cell_rhs);
    std::vector<types::global_dof_index> dof_indices(8);
    for (const auto &cell : grid.dof_handler().active_cell_iterators())
      if (cell->is_locally_owned())
        {
          cell->get_dof_indices(dof_indices);
          matrix.add(dof_indices, cell_matrix, /*elide_zero_values=*/false);
          rhs.add(dof_indices, cell_rhs);
        }
    matrix.compress(VectorOperation::add);
    rhs.compress(VectorOperation::add);
  }



  // For comparison: distribute into deal.II's own SparseMatrix and Vector,
  // then copy them row by row into the Trilinos matrix and vector.
  void
  AssemblyBenchmark::distribute_via_dealii_matrix()
  {
    FullMatrix<double> cell_matrix(8, 8);
    Vector<double>     cell_rhs(8);
    kernel->add_stiffness(moments[0], cell_matrix);
    kernel->add_internal_force(moments[0], cell_rhs);
    serial_matrix = 0;
    serial_rhs    = 0;
    std::vector<types::global_dof_index> dof_indices(8);
    for (const auto &cell : grid.dof_handler().active_cell_iterators())
      if (cell->is_locally_owned())
        {
          cell->get_dof_indices(dof_indices);
          constraints.distribute_local_to_global(
            cell_matrix, cell_rhs, dof_indices, serial_matrix, serial_rhs);
        }
    std::vector<types::global_dof_index> columns;
    std::vector<double>                  values;
    for (types::global_dof_index row = 0; row < serial_matrix.m(); ++row)
      {
        columns.clear();
        values.clear();
        for (auto entry = serial_matrix.begin(row);
             entry != serial_matrix.end(row);
             ++entry)
          {
            columns.push_back(entry->column());
            values.push_back(entry->value());
          }
        matrix.add(row, columns.size(), columns.data(), values.data(), false);
        rhs(row) += serial_rhs(row);
      }
    matrix.compress(VectorOperation::add);
    rhs.compress(VectorOperation::add);
  }



  // For comparison: the global part as a plain scatter. The position of
  // every entry of every cell matrix in Epetra's value arrays is found once
  // (the sparsity pattern never changes); then each assembly only adds
  // through these pointers. No constraints: their rows and columns would
  // point to a dummy slot, and their diagonal be set once.
  void
  AssemblyBenchmark::scatter_cached()
  {
    const Epetra_CrsMatrix &A = matrix.trilinos_matrix();
    if (cached_entries.empty())
      {
        std::vector<types::global_dof_index> dof_indices(8);
        for (const auto &cell : grid.dof_handler().active_cell_iterators())
          if (cell->is_locally_owned())
            {
              cell->get_dof_indices(dof_indices);
              for (unsigned int i = 0; i < 8; ++i)
                {
                  int     n_entries;
                  double *values;
                  int    *columns;
                  A.ExtractMyRowView(A.LRID(int(dof_indices[i])),
                                     n_entries,
                                     values,
                                     columns);
                  for (unsigned int j = 0; j < 8; ++j)
                    {
                      const int column = A.LCID(int(dof_indices[j]));
                      const int k =
                        std::find(columns, columns + n_entries, column) -
                        columns;
                      AssertThrow(k < n_entries, ExcInternalError());
                      cached_entries.push_back(values + k);
                    }
                }
            }
      }
    FullMatrix<double> cell_matrix(8, 8);
    kernel->add_stiffness(moments[0], cell_matrix);
    const double     *k             = &cell_matrix(0, 0);
    double *const    *entry         = cached_entries.data();
    const std::size_t n_cells_owned = cached_entries.size() / 64;
    for (std::size_t c = 0; c < n_cells_owned; ++c, entry += 64)
      for (unsigned int ij = 0; ij < 64; ++ij)
        *entry[ij] += k[ij];
    matrix.compress(VectorOperation::add);
  }



  // For comparison: compute_cell_moments() with the sums of a cell kept in
  // local variables and stored once per cell.
  void
  AssemblyBenchmark::moments_in_registers()
  {
    using P = MaterialPoints::Property;
    moments.assign(grid.triangulation().n_active_cells(), CellMoments());
    const auto &particles = points->particle_handler();
    for (const auto &cell : grid.triangulation().active_cell_iterators())
      if (cell->is_locally_owned())
        {
          double v = 0, vs = 0, vt = 0, vss = 0, vtt = 0, vst = 0;
          double s0[3] = {0, 0, 0}, ss[3] = {0, 0, 0}, st[3] = {0, 0, 0};
          for (const auto &particle : particles.particles_in_cell(cell))
            {
              const auto     props  = particle.get_properties();
              const double   volume = props[P::volume];
              const Point<2> x      = particle.get_reference_location();
              const double   vs_ = volume * x[0], vt_ = volume * x[1];
              v += volume;
              vs += vs_;
              vt += vt_;
              vss += vs_ * x[0];
              vtt += vt_ * x[1];
              vst += vs_ * x[1];
              for (unsigned int r = 0; r < 3; ++r)
                {
                  const double sigma = props[P::stress + r];
                  s0[r] += volume * sigma;
                  ss[r] += vs_ * sigma;
                  st[r] += vt_ * sigma;
                }
            }
          CellMoments &m = moments[cell->active_cell_index()];
          m.v            = v;
          m.vs           = vs;
          m.vt           = vt;
          m.vss          = vss;
          m.vtt          = vtt;
          m.vst          = vst;
          for (unsigned int r = 0; r < 3; ++r)
            {
              m.stress[r]   = s0[r];
              m.stress_s[r] = ss[r];
              m.stress_t[r] = st[r];
            }
        }
  }



  void
  AssemblyBenchmark::run(const unsigned int repetitions,
                         const std::string &mode)
  {
    const auto n_mp = points->n_global_material_points();
    std::cout << "grid " << n_cells << "x" << n_cells << ", " << n_points << "x"
              << n_points << " points per cell = " << n_mp
              << " points; QGauss<2>(" << n_points
              << ") = " << quadrature.size() << " points per cell; "
              << grid.dof_handler().n_dofs() << " DoFs; best of " << repetitions
              << std::endl;

    // Both assemble nearly the same stiffness: B^T C B is quadratic in s and
    // t, which QGauss(n) integrates exactly and the midpoint points of the
    // per-cell layout with an error of order 1/(12 n^2) in the s^2, t^2
    // moments.
    points->compute_cell_moments(moments);
    double mp_norm = 0, fe_norm = 0, difference = 0;
    if (mode == "all")
      {
        zero_system();
        assemble_mp_total();
        TrilinosWrappers::SparseMatrix mp_matrix;
        mp_matrix.copy_from(matrix);
        mp_norm = mp_matrix.frobenius_norm();
        zero_system();
        assemble_fe_total();
        fe_norm = matrix.frobenius_norm();
        mp_matrix.add(-1., matrix);
        difference = mp_matrix.frobenius_norm();
        std::cout << "  check: |K_MP - K_FE| / |K_FE| = "
                  << difference / fe_norm
                  << " (|K_MP| / |K_FE| = " << mp_norm / fe_norm
                  << "; midpoint against Gauss rule)" << std::endl;

        // The Gauss rule is exact: K_FE equals the kernel with the exact
        // moments of a uniformly filled cell.
        TrilinosWrappers::SparseMatrix fe_matrix;
        fe_matrix.copy_from(matrix);
        zero_system();
        const double A = grid.cell_size()[0] * grid.cell_size()[1];
        CellMoments  exact;
        exact.v  = A;
        exact.vs = exact.vt = A / 2;
        exact.vss = exact.vtt = A / 3;
        exact.vst             = A / 4;
        FullMatrix<double> cell_matrix(8, 8);
        Vector<double>     cell_rhs(8);
        kernel->add_stiffness(exact, cell_matrix);
        std::vector<types::global_dof_index> dof_indices(8);
        for (const auto &cell : grid.dof_handler().active_cell_iterators())
          if (cell->is_locally_owned())
            {
              cell->get_dof_indices(dof_indices);
              constraints.distribute_local_to_global(
                cell_matrix, cell_rhs, dof_indices, matrix, rhs);
            }
        matrix.compress(VectorOperation::add);
        rhs.compress(VectorOperation::add);
        fe_matrix.add(-1., matrix);
        std::cout << "  check: |K_FE - K(exact moments)| / |K_FE| = "
                  << fe_matrix.frobenius_norm() / fe_norm << std::endl;
      }

    // Zeroing the matrix is not timed.
    const auto time_piece = [&](const std::function<void()> &f,
                                const bool                   zero) {
      double best = std::numeric_limits<double>::max();
      for (unsigned int r = 0; r < repetitions; ++r)
        {
          if (zero)
            zero_system();
          Timer timer;
          f();
          timer.stop();
          best = std::min(best, timer.wall_time());
        }
      return best;
    };

    double mp_local = 0, mp_total = 0, fe_local = 0, fe_total = 0;
    std::cout << std::fixed << std::setprecision(2);
    if (mode == "all" || mode == "mp")
      {
        const double moments_time = time_piece([&]() { mp_moments(); }, false);
        const double kernel_time =
          time_piece([&]() { mp_kernel_local(); }, false);
        mp_local = time_piece([&]() { assemble_mp_local(); }, false);
        mp_total = time_piece([&]() { assemble_mp_total(); }, true);
        std::cout << "  MP       local " << 1e3 * mp_local << " ms (moments "
                  << 1e3 * moments_time << " ms, 8x8 kernel "
                  << 1e3 * kernel_time << " ms), total " << 1e3 * mp_total
                  << " ms" << std::endl;
      }
    if (mode == "all" || mode == "fe")
      {
        fe_local = time_piece([&]() { assemble_fe_local(); }, false);
        fe_total = time_piece([&]() { assemble_fe_total(); }, true);
        std::cout << "  FEValues local " << 1e3 * fe_local << " ms, total "
                  << 1e3 * fe_total << " ms" << std::endl;
      }
    if (mode == "all")
      {
        const double distribute =
          time_piece([&]() { distribute_only(); }, true);
        const double direct = time_piece([&]() { direct_add_only(); }, true);
        const double via_dealii =
          time_piece([&]() { distribute_via_dealii_matrix(); }, true);
        scatter_cached(); // finds the positions once
        const double scatter = time_piece([&]() { scatter_cached(); }, true);
        std::vector<CellMoments> library_moments;
        points->compute_cell_moments(library_moments);
        const double registers =
          time_piece([&]() { moments_in_registers(); }, false);
        bool same = true;
        for (unsigned int c = 0; c < moments.size(); ++c)
          same = same && moments[c].v == library_moments[c].v &&
                 moments[c].vss == library_moments[c].vss &&
                 moments[c].stress_t == library_moments[c].stress_t;
        std::cout << "  moments with the sums of a cell in local variables "
                  << 1e3 * registers
                  << " ms (same moments: " << (same ? "yes" : "NO") << ")"
                  << std::endl;
        std::cout << "  global part alone (one fixed cell matrix and vector):"
                  << std::endl
                  << "    AffineConstraints::distribute_local_to_global into "
                     "Trilinos + compress "
                  << 1e3 * distribute << " ms" << std::endl
                  << "    plain Trilinos matrix.add/vector.add (no "
                     "constraints) + compress "
                  << 1e3 * direct << " ms" << std::endl
                  << "    distribute_local_to_global into deal.II "
                     "SparseMatrix, then rows into Trilinos + compress "
                  << 1e3 * via_dealii << " ms" << std::endl
                  << "    matrix only: scatter through cached pointers into "
                     "Epetra's values, no constraints, + compress "
                  << 1e3 * scatter << " ms" << std::endl;
        std::cout << std::setprecision(3) << "  ratio MP/FEValues: local "
                  << mp_local / fe_local << ", total " << mp_total / fe_total
                  << std::endl;
      }
    std::cout << std::defaultfloat << std::setprecision(6);
  }
} // namespace



int
main(int argc, char *argv[])
{
  try
    {
      Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
      AssertThrow(Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD) == 1,
                  ExcMessage("The assembly benchmark runs on one process."));

      const unsigned int repetitions = argc > 3 ? std::stoi(argv[3]) : 5;
      const std::string  mode        = argc > 4 ? argv[4] : "all";
      const std::string  volumetric  = argc > 5 ? argv[5] : "B-bar";
      AssertThrow(volumetric == "B-bar" || volumetric == "standard",
                  ExcMessage("volumetric strain must be B-bar or standard"));
      AssertThrow(mode == "all" || mode == "mp" || mode == "fe",
                  ExcMessage("mode must be all, mp or fe"));

      std::vector<std::pair<unsigned int, unsigned int>> cases;
      if (argc > 2)
        cases.emplace_back(std::stoi(argv[1]), std::stoi(argv[2]));
      else if (argc > 1)
        cases.emplace_back(std::stoi(argv[1]), 8);
      else
        cases = {{128, 8}, {64, 16}, {16, 8}, {16, 16}};

      for (const auto &c : cases)
        {
          AssemblyBenchmark benchmark(c.first, c.second, volumetric == "B-bar");
          benchmark.run(repetitions, mode);
        }
    }
  catch (const std::exception &e)
    {
      std::cerr << "assembly_benchmark: " << e.what() << std::endl;
      return 1;
    }
  return 0;
}
