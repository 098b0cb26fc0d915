// The cantilever of scene 2 (prm/cantilever.prm, issue 12) solved by
// body-fitted finite elements in finite strain: the reference that the
// finite-strain MPM is compared with.
//
// The beam [0, 10] x [0, 2] m (bsmpm's scene puts it at (0.25, 0.5); only
// displacements matter), plane strain, E = 1e6 Pa, nu = 0.25. Left edge
// x = 0 on rollers (u_x = 0), u_y = 0 at mid-height (the vertex (0, 1), or
// with --support-half-length L every node of the left edge with
// |y - 1| <= L). Pressure p on the top edge y = 2 that follows the deformed
// boundary: p per current length, normal to the current top, raised
// linearly to its final value in STEPS load steps.
//
// The point support does not converge under refinement: it carries the
// whole load F (15 kN/m at p = 1500), and the rollers make x = 0 a mirror
// plane, so near it the field is Kelvin's for a force 2F, singular like
// (3 - 4 nu) F / (4 pi mu (1 - nu)) ln(1/r): the beam sinks by that times
// ln 2 = 0.0055 m more at every halving of h (measured in small strain,
// 40 x 8 to 640 x 128 cells: 0.0055159 m each time, the formula's figure).
// --support-half-length 0.0625 fixes the 0.125 m of the left edge that
// bsmpm's scene fixes (the B-spline segment between points 7 and 8), which
// converges; it is exact for cells_y >= 32 (nodes at y = 1 +- 0.0625).
//
// Total Lagrangian, Hencky hyperelasticity: Kirchhoff stress
// tau = K ln(J) I + 2 mu dev(ln V), ln V = 1/2 ln(F F^T), F_zz = 1, first
// Piola stress P = tau F^-T with its exact tangent dP/dF; FE_Q(2)^2, 3 x 3
// Gauss points, UMFPACK, Newton to |R| <= 1e-10 |R_0| in every load step
// (R_0: the residual at the start of the step, or the round-off floor of R
// where that lies higher, see solve()). The follower load is linear in u
// (see assemble()), so its matrix is exact and Newton quadratic.
//
// --small-strain: linear elasticity (the tangent at F = I) and the pressure
// on the undeformed top, one solve. The paper's reference (1280 x 256 Q1
// elements, small strain, p = 1500) is 2.8220 m.
//
// --check: the tangent dP/dF against central differences of P, frame
// indifference and the small-strain limit of P, the Newton matrix (follower
// load included) against central differences of the residual on a small
// mesh, and Newton's iteration count on 20 x 4 cells; exit code 1 if any
// check fails (ctest benchmarks/fem_cantilever_check).
//
// Usage:
//   fem_cantilever [--small-strain] [--verbose] [--support-half-length L]
//                  PRESSURE STEPS MAX_REFINEMENT
//   fem_cantilever --check
// solves on 40 2^r x 8 2^r cells for r = 0 .. MAX_REFINEMENT and writes one
// CSV row per mesh:
//   kinematics,load,steps,cells_x,cells_y,n_dofs,tip_deflection,
//   newton_iterations_total,time_s
// tip_deflection is -u_y at the vertex (10, 1); time_s is wall seconds for
// mesh, setup and all load steps. On stderr: per mesh the largest final
// |R|/|R_0| of a step, the most Newton iterations in a step and the
// smallest det F; --verbose adds Newton's residuals.

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/tensor.h>
#include <deal.II/base/timer.h>

#include <deal.II/dofs/dof_handler.h>
#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_q1.h>

#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/tria.h>

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/sparse_direct.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/vector.h>

#include <array>
#include <cmath>
#include <cstdlib>
#include <iomanip>
#include <iostream>
#include <limits>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

using namespace dealii;

namespace
{
  const double       beam_length = 10;
  const double       beam_height = 2;
  const Tensor<2, 2> identity    = unit_symmetric_tensor<2>();

  /** Eigenvalues (descending) and eigenvectors of a symmetric positive
   * definite 2 x 2 tensor. */
  struct Spectrum
  {
    std::array<double, 2>       values;
    std::array<Tensor<1, 2>, 2> vectors;
  };

  /** The spectrum of b = F F^T in closed form. The smaller eigenvalue is
   * det(b) / lambda_1 with det(b) = J^2 given: m - r would lose digits by
   * cancellation when b is far from isotropic. At b = c I the angle is
   * atan2(0, 0) = 0, any basis being one of eigenvectors. */
  Spectrum
  spectrum(const Tensor<2, 2> &b, const double det_b)
  {
    const double mean      = (b[0][0] + b[1][1]) / 2;
    const double half_diff = (b[0][0] - b[1][1]) / 2;
    const double radius    = std::hypot(half_diff, b[0][1]);
    const double angle     = std::atan2(b[0][1], half_diff) / 2;
    Spectrum     s;
    s.values[0]  = mean + radius;
    s.values[1]  = det_b / s.values[0];
    s.vectors[0] = Tensor<1, 2>({std::cos(angle), std::sin(angle)});
    s.vectors[1] = Tensor<1, 2>({-std::sin(angle), std::cos(angle)});
    return s;
  }

  /** (ln x - ln y) / (x - y), continuous at x = y where it is 1 / y: the
   * weight of the off-diagonal eigen-projections in the derivative of the
   * tensor logarithm. log1p keeps the digits for x close to y. */
  double
  log_divided_difference(const double x, const double y)
  {
    const double t = (x - y) / y;
    return (std::abs(t) < 1e-8 ? 1 - t / 2 : std::log1p(t) / t) / y;
  }

  /** Hencky hyperelasticity in plane strain (F_zz = 1, so ln V_zz = 0 and
   * only the in-plane block of tau enters P). */
  class Hencky
  {
  public:
    Hencky(const double youngs_modulus, const double poissons_ratio)
      : bulk_modulus(youngs_modulus / (3 * (1 - 2 * poissons_ratio)))
      , shear_modulus(youngs_modulus / (2 * (1 + poissons_ratio)))
    {}

    /** First Piola stress P = tau F^-T. */
    Tensor<2, 2>
    first_piola(const Tensor<2, 2> &F) const
    {
      return State(*this, F).P;
    }

    /** dP/dF as A[i][J][k][L] = dP_iJ / dF_kL, by the chain rule through
     * b = F F^T and the derivative of ln b from its spectrum:
     *   d ln b = sum_ab theta_ab (n_a . db n_b) n_a (x) n_b,
     *   theta_aa = 1 / lambda_a,
     *   theta_ab = (ln lambda_a - ln lambda_b) / (lambda_a - lambda_b),
     * and d(F^-T) = -F^-T dF^T F^-T. */
    Tensor<4, 2>
    tangent(const Tensor<2, 2> &F) const
    {
      const State  s(*this, F);
      const double lambda_lame = bulk_modulus - 2 * shear_modulus / 3;

      double theta[2][2];
      for (unsigned int a = 0; a < 2; ++a)
        for (unsigned int b = 0; b < 2; ++b)
          theta[a][b] =
            log_divided_difference(s.spectrum.values[a], s.spectrum.values[b]);

      Tensor<4, 2> A;
      for (unsigned int k = 0; k < 2; ++k)
        for (unsigned int l = 0; l < 2; ++l)
          {
            Tensor<2, 2> dF;
            dF[k][l]                  = 1;
            const double       d_ln_J = s.F_inv_T[k][l];
            const Tensor<2, 2> db     = dF * transpose(F) + F * transpose(dF);
            Tensor<2, 2>       d_ln_V;
            for (unsigned int a = 0; a < 2; ++a)
              for (unsigned int b = 0; b < 2; ++b)
                d_ln_V +=
                  (theta[a][b] / 2 *
                   (s.spectrum.vectors[a] * db * s.spectrum.vectors[b])) *
                  outer_product(s.spectrum.vectors[a], s.spectrum.vectors[b]);
            const Tensor<2, 2> d_tau =
              lambda_lame * d_ln_J * identity + 2 * shear_modulus * d_ln_V;
            const Tensor<2, 2> dP =
              d_tau * s.F_inv_T - s.tau * s.F_inv_T * transpose(dF) * s.F_inv_T;
            for (unsigned int i = 0; i < 2; ++i)
              for (unsigned int j = 0; j < 2; ++j)
                A[i][j][k][l] = dP[i][j];
          }
      return A;
    }

    const double bulk_modulus;
    const double shear_modulus;

  private:
    /** What P and its tangent share. */
    struct State
    {
      State(const Hencky &material, const Tensor<2, 2> &F)
      {
        const double J = determinant(F);
        if (!(J > 0))
          throw std::runtime_error("det F <= 0 at a quadrature point");
        spectrum = ::spectrum(F * transpose(F), J * J);
        Tensor<2, 2> ln_V;
        for (unsigned int a = 0; a < 2; ++a)
          ln_V += std::log(spectrum.values[a]) / 2 *
                  outer_product(spectrum.vectors[a], spectrum.vectors[a]);
        // dev in 3D with ln V_zz = 0: tr(ln V) = ln J, so the in-plane
        // block is K ln J I + 2 mu (ln V - ln J / 3 I).
        const double ln_J = std::log(J);
        tau = (material.bulk_modulus - 2 * material.shear_modulus / 3) * ln_J *
                identity +
              2 * material.shear_modulus * ln_V;
        F_inv_T = transpose(invert(F));
        P       = tau * F_inv_T;
      }

      Spectrum     spectrum;
      Tensor<2, 2> tau;
      Tensor<2, 2> F_inv_T;
      Tensor<2, 2> P;
    };
  };



  enum class Kinematics
  {
    small_strain,
    finite_strain
  };

  /** The beam on cells_x x cells_y Q2 cells with its supports. */
  class Cantilever
  {
  public:
    Cantilever(const Hencky      &material,
               const unsigned int cells_x,
               const unsigned int cells_y,
               const double       support_half_length)
      : material(material)
      , fe(FE_Q<2>(2), 2)
      , dofs(tria)
      , quadrature(3)
      , face_quadrature(3)
    {
      // Even cells_y: (0, 1) and (10, 1) are vertices. Colorized boundary
      // ids: 0 left, 1 right, 2 bottom, 3 top.
      if (cells_y % 2 != 0)
        throw std::invalid_argument("cells_y must be even");
      GridGenerator::subdivided_hyper_rectangle(tria,
                                                {cells_x, cells_y},
                                                Point<2>(0, 0),
                                                Point<2>(beam_length,
                                                         beam_height),
                                                true);
      dofs.distribute_dofs(fe);

      // Supports and the probe by the dofs' support points (nodes of the
      // straight-sided Q2 cells).
      std::vector<Point<2>> nodes(dofs.n_dofs());
      DoFTools::map_dofs_to_support_points(MappingQ1<2>(), dofs, nodes);
      const IndexSet x_dofs =
        DoFTools::extract_dofs(dofs,
                               ComponentMask(std::vector<bool>{true, false}));
      const double tol          = 1e-9;
      tip_dof                   = numbers::invalid_dof_index;
      unsigned int n_y_supports = 0;
      for (types::global_dof_index i = 0; i < dofs.n_dofs(); ++i)
        {
          const Point<2> &X = nodes[i];
          if (x_dofs.is_element(i))
            {
              if (std::abs(X[0]) < tol)
                constraints.add_line(i);
            }
          else
            {
              if (std::abs(X[0]) < tol &&
                  std::abs(X[1] - beam_height / 2) <= support_half_length + tol)
                {
                  constraints.add_line(i);
                  ++n_y_supports;
                }
              if (X.distance(Point<2>(beam_length, beam_height / 2)) < tol)
                tip_dof = i;
            }
        }
      constraints.close();
      if (n_y_supports == 0 || tip_dof == numbers::invalid_dof_index)
        throw std::logic_error("support or probe node not found");

      DynamicSparsityPattern dsp(dofs.n_dofs());
      DoFTools::make_sparsity_pattern(dofs, dsp, constraints, false);
      sparsity.copy_from(dsp);
    }

    types::global_dof_index
    n_dofs() const
    {
      return dofs.n_dofs();
    }

    /** The residual R(u) = f_int(u) - f_ext(u) and, if jacobian is given,
     * dR/du; constrained rows are zero in R (unit diagonal in the matrix).
     *
     * Follower pressure: along the top, traversed right to left (body on
     * the left) with the reference tangent t0 = dX/dS = (-1, 0), the
     * current tangent is dx/dS = t0 + grad u t0, and p n da = p R dx/dS dS
     * with R (a, b) = (b, -a) (rotation by -90 degrees), so
     *   f_ext,a = -p int N_a R (t0 + grad u t0) dS,
     * linear in u: its derivative -p int N_a R (grad N_b t0) dS is exact.
     * In small strain the load is -p int N_a R t0 dS and P = C : grad u. */
    void
    assemble(const Vector<double> &u,
             const double          pressure,
             const Kinematics      kinematics,
             Vector<double>       &residual,
             SparseMatrix<double> *jacobian) const
    {
      FEValues<2>                          fe_values(fe,
                            quadrature,
                            update_gradients | update_JxW_values);
      FEFaceValues<2>                      face_values(fe,
                                  face_quadrature,
                                  update_values | update_gradients |
                                    update_JxW_values);
      const FEValuesExtractors::Vector     displacement(0);
      const unsigned int                   n = fe.n_dofs_per_cell();
      FullMatrix<double>                   cell_matrix(n, n);
      Vector<double>                       cell_residual(n);
      std::vector<types::global_dof_index> dof_indices(n);
      std::vector<Tensor<2, 2>>            grad_u(quadrature.size());
      std::vector<Tensor<2, 2>>            face_grad_u(face_quadrature.size());
      std::vector<unsigned int>            component(n);
      for (unsigned int i = 0; i < n; ++i)
        component[i] = fe.system_to_component_index(i).first;
      const Tensor<4, 2> linear_tangent = material.tangent(identity);
      const Tensor<1, 2> t0({-1, 0});

      residual = 0;
      if (jacobian)
        *jacobian = 0;
      for (const auto &cell : dofs.active_cell_iterators())
        {
          fe_values.reinit(cell);
          fe_values[displacement].get_function_gradients(u, grad_u);
          cell_matrix   = 0;
          cell_residual = 0;
          for (unsigned int q = 0; q < quadrature.size(); ++q)
            {
              Tensor<2, 2> P;
              Tensor<4, 2> A;
              if (kinematics == Kinematics::finite_strain)
                {
                  const Tensor<2, 2> F = identity + grad_u[q];
                  P                    = material.first_piola(F);
                  if (jacobian)
                    A = material.tangent(F);
                }
              else
                {
                  P = double_contract<2, 0, 3, 1>(linear_tangent, grad_u[q]);
                  A = linear_tangent;
                }
              const double JxW = fe_values.JxW(q);
              // Each shape function has one nonzero component c: its
              // gradient is e_c (x) g, so P : grad N = P[c] . g.
              for (unsigned int i = 0; i < n; ++i)
                {
                  const Tensor<1, 2> &g_i = fe_values.shape_grad(i, q);
                  cell_residual[i] += P[component[i]] * g_i * JxW;
                  if (jacobian)
                    for (unsigned int j = 0; j < n; ++j)
                      {
                        const Tensor<1, 2> &g_j = fe_values.shape_grad(j, q);
                        double              a   = 0;
                        for (unsigned int J = 0; J < 2; ++J)
                          for (unsigned int L = 0; L < 2; ++L)
                            a += g_i[J] * A[component[i]][J][component[j]][L] *
                                 g_j[L];
                        cell_matrix(i, j) += a * JxW;
                      }
                }
            }

          for (const auto f : cell->face_indices())
            if (cell->at_boundary(f) && cell->face(f)->boundary_id() == 3)
              {
                face_values.reinit(cell, f);
                face_values[displacement].get_function_gradients(u,
                                                                 face_grad_u);
                for (unsigned int q = 0; q < face_quadrature.size(); ++q)
                  {
                    const Tensor<1, 2> tangent =
                      kinematics == Kinematics::finite_strain ?
                        t0 + face_grad_u[q] * t0 :
                        t0;
                    const Tensor<1, 2> normal({tangent[1], -tangent[0]});
                    const double       JxW = face_values.JxW(q);
                    for (unsigned int i = 0; i < n; ++i)
                      {
                        const double N_i = face_values.shape_value(i, q);
                        // R = f_int - f_ext = f_int + p int N R dx/dS.
                        cell_residual[i] +=
                          pressure * N_i * normal[component[i]] * JxW;
                        if (jacobian && kinematics == Kinematics::finite_strain)
                          for (unsigned int j = 0; j < n; ++j)
                            {
                              // grad N_j t0 = (g_j . t0) e_c, and
                              // R e_0 = (0, -1), R e_1 = (1, 0).
                              const double s =
                                face_values.shape_grad(j, q) * t0;
                              const double R_e =
                                component[j] == 0 ?
                                  (component[i] == 0 ? 0. : -1.) :
                                  (component[i] == 0 ? 1. : 0.);
                              cell_matrix(i, j) +=
                                pressure * N_i * s * R_e * JxW;
                            }
                      }
                  }
              }

          cell->get_dof_indices(dof_indices);
          if (jacobian)
            constraints.distribute_local_to_global(
              cell_matrix, cell_residual, dof_indices, *jacobian, residual);
          else
            constraints.distribute_local_to_global(cell_residual,
                                                   dof_indices,
                                                   residual);
        }
    }

    /** The smallest det F over the quadrature points: how close the
     * mesh comes to inverting (near the point support). */
    double
    min_det_F(const Vector<double> &u) const
    {
      FEValues<2>               fe_values(fe, quadrature, update_gradients);
      std::vector<Tensor<2, 2>> grad_u(quadrature.size());
      double                    min_J = std::numeric_limits<double>::max();
      for (const auto &cell : dofs.active_cell_iterators())
        {
          fe_values.reinit(cell);
          fe_values[FEValuesExtractors::Vector(0)].get_function_gradients(
            u, grad_u);
          for (const auto &G : grad_u)
            min_J = std::min(min_J, determinant(identity + G));
        }
      return min_J;
    }

    const Hencky             &material;
    Triangulation<2>          tria;
    const FESystem<2>         fe;
    DoFHandler<2>             dofs;
    const QGauss<2>           quadrature;
    const QGauss<1>           face_quadrature;
    AffineConstraints<double> constraints;
    SparsityPattern           sparsity;
    types::global_dof_index   tip_dof;
  };



  struct Solution
  {
    Vector<double>           u;
    unsigned int             newton_iterations   = 0;
    unsigned int             max_step_iterations = 0;
    double                   worst_residual      = 0; // max |R| / |R_0|
    std::vector<std::string> log; // one line per Newton iteration
  };

  /** Small strain: one solve. Finite strain: Newton in every load step,
   * from the previous step's solution extrapolated linearly (equal load
   * increments), until |R| <= tolerance |R_0|, R_0 the residual at the
   * previous step's solution under the new load (independent of the
   * predictor).
   *
   * An update that inverts a cell (det F <= 0) is halved, up to 20 times;
   * one that only raises |R| is taken whole: the first update of a step
   * rotates the beam along tangents, which stretches it, and |R| grows
   * 15-fold (40 x 8 cells, 300 Pa steps, no predictor), yet the next ones
   * converge quadratically (5 iterations); a line search on |R| took 15.
   *
   * Round-off: a direct solve leaves |R| ~ eps |K| |u|, which grows like
   * h^-1.5 against |R_0| (|u| ~ h^-1/2 |u|_L2, |R_0| ~ p h^1/2). At
   * 320 x 64 cells it is 2e-10 |R_0| (measured: repeated Newton steps of
   * the linear problem stagnate at 1.7-2.1e-10), above the tolerance. So a
   * step also ends when an update changed u by less than 1e-13 |u| (the
   * residual it answered was noise: measured 1e-16 there, while the last
   * quadratic update is ~1e-9) and |R| <= 1e-8 |R_0|; worst_residual
   * records what was reached. */
  Solution
  solve(const Cantilever  &problem,
        const Kinematics   kinematics,
        const double       pressure,
        const unsigned int steps,
        const bool         verbose   = false,
        const double       tolerance = 1e-10)
  {
    Solution             result;
    const unsigned int   n = problem.n_dofs();
    SparseMatrix<double> jacobian(problem.sparsity);
    Vector<double>       residual(n), delta(n), trial(n), previous(n);
    result.u.reinit(n);

    const auto log = [&](const std::string &line) {
      result.log.push_back(line);
      if (verbose)
        std::cerr << line << std::endl;
    };
    const auto newton_update = [&]() {
      SparseDirectUMFPACK direct;
      direct.initialize(jacobian);
      direct.vmult(delta, residual);
      delta *= -1;
      problem.constraints.distribute(delta);
      ++result.newton_iterations;
    };

    if (kinematics == Kinematics::small_strain)
      {
        problem.assemble(result.u, pressure, kinematics, residual, &jacobian);
        const double r0 = residual.l2_norm();
        newton_update();
        result.u = delta;
        problem.assemble(result.u, pressure, kinematics, residual, nullptr);
        result.worst_residual      = residual.l2_norm() / r0;
        result.max_step_iterations = 1;
        return result;
      }

    for (unsigned int step = 1; step <= steps; ++step)
      {
        const double load = pressure * step / steps;
        problem.assemble(result.u, load, kinematics, residual, nullptr);
        const double r0 = residual.l2_norm();

        if (step > 1)
          {
            trial = result.u;
            trial.sadd(2, -1, previous);
            previous = result.u;
            try
              {
                problem.assemble(trial, load, kinematics, residual, nullptr);
                result.u = trial;
              }
            catch (const std::runtime_error &)
              {
                // The extrapolation inverts a cell: start from u_n.
              }
          }
        else
          previous = result.u;

        problem.assemble(result.u, load, kinematics, residual, &jacobian);
        double r = residual.l2_norm();
        {
          std::ostringstream line;
          line << "step " << step
               << " predictor |R|/|R_0| = " << std::scientific
               << std::setprecision(3) << r / r0;
          log(line.str());
        }
        for (unsigned int it = 1; r > tolerance * r0; ++it)
          {
            if (it > 30)
              throw std::runtime_error("Newton: no convergence in 30 "
                                       "iterations in load step " +
                                       std::to_string(step));
            newton_update();
            double alpha = 1;
            for (unsigned int halvings = 0;; ++halvings)
              {
                trial = result.u;
                trial.add(alpha, delta);
                try
                  {
                    problem.assemble(
                      trial, load, kinematics, residual, &jacobian);
                    break;
                  }
                catch (const std::runtime_error &)
                  {
                    if (halvings == 20)
                      throw;
                  }
                alpha /= 2;
              }
            result.u            = trial;
            r                   = residual.l2_norm();
            const double change = alpha * delta.l2_norm() / result.u.l2_norm();
            std::ostringstream line;
            line << "step " << step << " iteration " << it
                 << " |R|/|R_0| = " << std::scientific << std::setprecision(3)
                 << r / r0 << " |du|/|u| = " << change
                 << (alpha < 1 ? " (damped)" : "");
            log(line.str());
            result.max_step_iterations =
              std::max(result.max_step_iterations, it);
            if (change < 1e-13 && r <= 1e-8 * r0)
              {
                log("  round-off floor reached");
                break;
              }
          }
        result.worst_residual = std::max(result.worst_residual, r / r0);
      }
    return result;
  }



  /** The checks of --check; returns the number of failures. */
  unsigned int
  run_checks(const Hencky &material)
  {
    unsigned int failures = 0;
    const auto   report =
      [&](const std::string &what, const double error, const double tolerance) {
        const bool ok = error <= tolerance;
        std::cout << (ok ? "ok     " : "FAILED ") << what << ": "
                  << std::scientific << std::setprecision(2) << error
                  << " (tolerance " << tolerance << ")" << std::endl;
        failures += ok ? 0 : 1;
      };

    // 1. dP/dF against central differences of P, max-norm relative to
    // max |A|, step 1e-6: truncation ~1e-12, round-off ~1e-10. F = I and a
    // stretch with eigenvalues 1e-9 apart test the limit of theta_ab.
    const auto rotation = [](const double angle) {
      return Tensor<2, 2>({{std::cos(angle), -std::sin(angle)},
                           {std::sin(angle), std::cos(angle)}});
    };
    const std::vector<std::pair<std::string, Tensor<2, 2>>> gradients = {
      {"F = I", identity},
      {"F = R(0.7) (1 + 1e-9 diag(1, -1))",
       rotation(0.7) * Tensor<2, 2>({{1 + 1e-9, 0}, {0, 1 - 1e-9}})},
      {"F = R(0.3) diag(1.4, 0.8)",
       rotation(0.3) * Tensor<2, 2>({{1.4, 0}, {0, 0.8}})},
      {"F = [[1.1, 0.4], [-0.2, 0.8]]",
       Tensor<2, 2>({{1.1, 0.4}, {-0.2, 0.8}})},
      {"F = [[0.6, 0.1], [0.05, 0.7]]",
       Tensor<2, 2>({{0.6, 0.1}, {0.05, 0.7}})},
      {"F = R(-1.2) [[2.5, 0.9], [0, 0.5]]",
       rotation(-1.2) * Tensor<2, 2>({{2.5, 0.9}, {0, 0.5}})}};
    for (const auto &[name, F] : gradients)
      {
        const Tensor<4, 2> A     = material.tangent(F);
        const double       h     = 1e-6;
        double             error = 0, scale = 0;
        for (unsigned int k = 0; k < 2; ++k)
          for (unsigned int l = 0; l < 2; ++l)
            {
              Tensor<2, 2> dF;
              dF[k][l] = h;
              const Tensor<2, 2> fd =
                (material.first_piola(F + dF) - material.first_piola(F - dF)) /
                (2 * h);
              for (unsigned int i = 0; i < 2; ++i)
                for (unsigned int j = 0; j < 2; ++j)
                  {
                    error = std::max(error, std::abs(A[i][j][k][l] - fd[i][j]));
                    scale = std::max(scale, std::abs(A[i][j][k][l]));
                  }
            }
        report("dP/dF vs central differences, " + name, error / scale, 1e-6);
      }

    // 2. Frame indifference: P(Q F) = Q P(F).
    {
      const Tensor<2, 2> F({{1.3, 0.2}, {-0.4, 0.9}});
      const Tensor<2, 2> Q = rotation(2.1);
      report(
        "P(Q F) = Q P(F)",
        (material.first_piola(Q * F) - Q * material.first_piola(F)).norm() /
          material.first_piola(F).norm(),
        1e-12);
    }

    // 3. Small strain: P(I + e H) = e C : H + O(e^2), C the plane-strain
    // Hooke tensor with lambda = K - 2 mu / 3.
    {
      const Tensor<2, 2> H({{0.3, -0.7}, {0.5, 0.2}});
      const double       e = 1e-6;
      const double       lambda =
        material.bulk_modulus - 2 * material.shear_modulus / 3;
      const Tensor<2, 2> sym_H = (H + transpose(H)) / 2;
      const Tensor<2, 2> hooke =
        e * (lambda * trace(H) * identity + 2 * material.shear_modulus * sym_H);
      report("P(I + e H) / (e C : H) - 1, e = 1e-6",
             (material.first_piola(identity + e * H) - hooke).norm() /
               hooke.norm(),
             1e-5);
    }

    // 4. The Newton matrix, follower load included, against central
    // differences of the residual on 4 x 2 cells at a random u with
    // |grad u| up to ~0.4, and p = 2e5 so that the load matrix weighs.
    {
      const Cantilever                       problem(material, 4, 2, 0);
      const unsigned int                     n = problem.n_dofs();
      std::mt19937                           random(12);
      std::uniform_real_distribution<double> uniform(-1, 1);
      Vector<double>                         u(n), direction(n);
      for (unsigned int i = 0; i < n; ++i)
        {
          u[i]         = 0.05 * uniform(random);
          direction[i] = uniform(random);
        }
      problem.constraints.set_zero(u);
      problem.constraints.set_zero(direction);

      SparseMatrix<double> jacobian(problem.sparsity);
      Vector<double>       residual(n), plus(n), minus(n), product(n);
      const double         pressure = 2e5;
      problem.assemble(
        u, pressure, Kinematics::finite_strain, residual, &jacobian);
      jacobian.vmult(product, direction);
      const double   h = 1e-6;
      Vector<double> trial(u);
      trial.add(h, direction);
      problem.assemble(
        trial, pressure, Kinematics::finite_strain, plus, nullptr);
      trial.add(-2 * h, direction);
      problem.assemble(
        trial, pressure, Kinematics::finite_strain, minus, nullptr);
      Vector<double> fd(plus);
      fd -= minus;
      fd /= 2 * h;
      Vector<double> difference(product);
      difference -= fd;
      report("Newton matrix . d vs central differences of R (4 x 2 cells)",
             difference.l2_norm() / product.l2_norm(),
             1e-6);

      // The follower load alone (the material part cancels in the
      // difference of two pressures): its share must be right too.
      Vector<double>       load_product(n), load_fd(n);
      SparseMatrix<double> unloaded(problem.sparsity);
      problem.assemble(u, 0, Kinematics::finite_strain, residual, &unloaded);
      unloaded.vmult(load_product, direction);
      load_product *= -1;
      load_product += product;
      problem.assemble(trial, 0, Kinematics::finite_strain, minus, nullptr);
      trial.add(2 * h, direction);
      problem.assemble(trial, 0, Kinematics::finite_strain, plus, nullptr);
      load_fd = fd;
      load_fd.add(-1 / (2 * h), plus);
      load_fd.add(1 / (2 * h), minus);
      difference = load_product;
      difference -= load_fd;
      report("load matrix . d vs central differences (4 x 2 cells)",
             difference.l2_norm() / load_product.l2_norm(),
             1e-6);
    }

    // 5. Newton on 20 x 4 cells, p = 1500 in 5 steps: with the exact
    // tangent every step converges quadratically, in at most 5 iterations
    // (see the output); without the load matrix or the geometric term
    // -tau F^-T dF^T F^-T of dP/dF it takes 10 or more on 40 x 8 cells.
    {
      const Cantilever problem(material, 20, 4, 0);
      const Solution   solution =
        solve(problem, Kinematics::finite_strain, 1500, 5);
      for (const auto &line : solution.log)
        std::cout << "       " << line << std::endl;
      report(
        "most Newton iterations in a step, 20 x 4 cells, p = 1500, 5 steps",
        solution.max_step_iterations,
        5);
    }
    return failures;
  }
} // namespace



int
main(int argc, char **argv)
{
  const Hencky material(1e6, 0.25);
  try
    {
      Kinematics               kinematics          = Kinematics::finite_strain;
      bool                     verbose             = false;
      double                   support_half_length = 0;
      std::vector<std::string> positional;
      for (int a = 1; a < argc; ++a)
        {
          const std::string arg = argv[a];
          if (arg == "--check")
            {
              const unsigned int failures = run_checks(material);
              std::cout << (failures == 0 ?
                              "all checks passed" :
                              std::to_string(failures) + " check(s) failed")
                        << std::endl;
              return failures == 0 ? 0 : 1;
            }
          else if (arg == "--small-strain")
            kinematics = Kinematics::small_strain;
          else if (arg == "--verbose")
            verbose = true;
          else if (arg == "--support-half-length" && a + 1 < argc)
            support_half_length = std::stod(argv[++a]);
          else if (arg.size() > 1 && arg[0] == '-' && !std::isdigit(arg[1]))
            throw std::invalid_argument("unknown option " + arg);
          else
            positional.push_back(arg);
        }
      if (positional.size() != 3)
        throw std::invalid_argument(
          "usage: fem_cantilever [--small-strain] [--verbose] "
          "[--support-half-length L] PRESSURE STEPS MAX_REFINEMENT\n"
          "       fem_cantilever --check");
      const double       pressure       = std::stod(positional[0]);
      const unsigned int steps          = std::stoi(positional[1]);
      const unsigned int max_refinement = std::stoi(positional[2]);
      // Small strain is linear: one solve whatever STEPS says.
      const unsigned int n_steps =
        kinematics == Kinematics::small_strain ? 1 : steps;

      std::cout << "kinematics,load,steps,cells_x,cells_y,n_dofs,"
                   "tip_deflection,newton_iterations_total,time_s"
                << std::endl;
      for (unsigned int r = 0; r <= max_refinement; ++r)
        {
          Timer              timer;
          const unsigned int cells_x = 40 << r, cells_y = 8 << r;
          const Cantilever   problem(material,
                                   cells_x,
                                   cells_y,
                                   support_half_length);
          const Solution     solution =
            solve(problem, kinematics, pressure, n_steps, verbose);
          const double time = timer.wall_time();
          std::cout << std::setprecision(6)
                    << (kinematics == Kinematics::small_strain ? "small" :
                                                                 "finite")
                    << ',' << pressure << ',' << n_steps << ',' << cells_x
                    << ',' << cells_y << ',' << problem.n_dofs() << ','
                    << std::setprecision(12) << -solution.u[problem.tip_dof]
                    << ',' << solution.newton_iterations << ','
                    << std::setprecision(4) << time << std::endl;
          // What Newton reached, off the CSV.
          std::cerr << cells_x << 'x' << cells_y
                    << ": |R|/|R_0| <= " << std::scientific
                    << std::setprecision(2) << solution.worst_residual
                    << std::defaultfloat
                    << " at the end of every step, at most "
                    << solution.max_step_iterations
                    << " Newton iterations in a step, min det F = "
                    << problem.min_det_F(solution.u) << std::endl;
        }
    }
  catch (const std::exception &e)
    {
      std::cerr << "fem_cantilever: " << e.what() << std::endl;
      return 2;
    }
  return 0;
}
