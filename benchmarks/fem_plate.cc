// The plate with a hole of scene 4a solved by body-fitted finite elements:
// what a user would pick instead of the unfitted MPM, for the comparison of
// run time at equal error (doc/benchmarks.md). Same region (the hole, the
// two symmetry axes and the 11-point B-spline of bsmpm's scene), same
// material, same Kirsch traction on the spline, rollers on the axes, the
// same relative L2 displacement error.
//
// The region is star-shaped about the centre of the hole, so the chart
// (theta, s) -> (r_i + s (R(theta) - r_i)) (cos theta, sin theta), with
// R(theta) where the ray at theta meets the spline, maps the unit rectangle
// onto it exactly; as a ChartManifold it gives curved cells for Q2.
//
// Usage: fem_plate DEGREE MAX_REFINEMENTS  -> one CSV row per refinement:
// degree,refinements,n_dofs,L2_u,time (wall seconds: mesh, assembly, solve)

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/timer.h>

#include <deal.II/dofs/dof_handler.h>
#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_q.h>

#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/manifold.h>
#include <deal.II/grid/tria.h>

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/sparse_direct.h>
#include <deal.II/lac/sparse_matrix.h>

#include <deal.II/numerics/vector_tools.h>

#include <bsmpm/geometry/b_spline_curve.h>
#include <bsmpm/materials/material.h>
#include <bsmpm/verification/exact_solution.h>

#include <cmath>
#include <iostream>

using namespace dealii;

namespace
{
  const double hole_radius = 0.5;

  /** (theta, s) <-> the plate between the hole and the spline. */
  class PlateChart : public ChartManifold<2, 2, 2>
  {
  public:
    explicit PlateChart(const bsmpm::BSplineCurve &spline)
      : spline(spline)
    {}

    std::unique_ptr<Manifold<2, 2>>
    clone() const override
    {
      return std::make_unique<PlateChart>(spline);
    }

    Point<2>
    pull_back(const Point<2> &x) const override
    {
      const double theta = std::atan2(x[1], x[0]);
      return Point<2>(theta,
                      (x.norm() - hole_radius) /
                        (outer_radius(theta) - hole_radius));
    }

    Point<2>
    push_forward(const Point<2> &chart) const override
    {
      const double r =
        hole_radius + chart[1] * (outer_radius(chart[0]) - hole_radius);
      return Point<2>(r * std::cos(chart[0]), r * std::sin(chart[0]));
    }

  private:
    /** Distance to the spline along the ray at angle theta (bisection on
     * the spline's parameter: its angle grows along it). */
    double
    outer_radius(const double theta) const
    {
      double lo = 0, hi = 1;
      for (unsigned int k = 0; k < 60; ++k)
        {
          const double   mid                         = (lo + hi) / 2;
          const Point<2> c                           = spline.value(mid);
          (std::atan2(c[1], c[0]) < theta ? lo : hi) = mid;
        }
      return spline.value((lo + hi) / 2).norm();
    }

    const bsmpm::BSplineCurve &spline;
  };
} // namespace



int
main(int argc, char **argv)
{
  const unsigned int degree          = argc > 1 ? std::stoi(argv[1]) : 1;
  const unsigned int max_refinements = argc > 2 ? std::stoi(argv[2]) : 5;

  // The 11 points of bsmpm's scene, counter-clockwise about the body.
  const bsmpm::BSplineCurve          spline({Point<2>(1.50, 0.00),
                                             Point<2>(1.78, 0.21),
                                             Point<2>(2.00, 0.75),
                                             Point<2>(1.75, 1.30),
                                             Point<2>(1.50, 1.35),
                                             Point<2>(1.00, 1.15),
                                             Point<2>(0.73, 1.31),
                                             Point<2>(0.60, 1.80),
                                             Point<2>(0.35, 1.95),
                                             Point<2>(0.10, 1.75),
                                             Point<2>(0.00, 1.50)},
                                   false);
  const bsmpm::LinearElasticMaterial material(
    1e8, 0.2, bsmpm::LinearElasticMaterial::Model::plane_stress);
  const bsmpm::KirschPlate exact(material, Point<2>(), hole_radius, 1e7);
  const PlateChart         chart(spline);
  const double             mu = material.shear_modulus();
  const double lambda = material.stiffness()[0][1]; // plane stress lambda

  std::cout << "degree,refinements,n_dofs,L2_u,time" << std::endl;
  for (unsigned int refinements = 0; refinements <= max_refinements;
       ++refinements)
    {
      Timer timer;

      // Mesh: 8 x 4 coarse cells in the chart, pushed forward.
      Triangulation<2> tria;
      GridGenerator::subdivided_hyper_rectangle(tria,
                                                {8, 4},
                                                Point<2>(0, 0),
                                                Point<2>(numbers::PI / 2, 1));
      for (auto &v : tria.get_vertices())
        const_cast<Point<2> &>(v) = chart.push_forward(v);
      tria.set_all_manifold_ids(0);
      tria.set_manifold(0, chart);
      // Boundary ids: 0 y = 0 (roller u_y), 1 x = 0 (roller u_x), 2 hole,
      // 3 the spline (Kirsch traction).
      for (const auto &cell : tria.active_cell_iterators())
        for (const auto f : cell->face_indices())
          if (cell->at_boundary(f))
            {
              const Point<2> c = chart.pull_back(cell->face(f)->center());
              cell->face(f)->set_boundary_id(
                c[0] < 1e-6 ?
                  0 :
                  (c[0] > numbers::PI / 2 - 1e-6 ? 1 : (c[1] < 0.5 ? 2 : 3)));
            }
      tria.refine_global(refinements);

      const FESystem<2> fe(FE_Q<2>(degree), 2);
      const MappingQ<2> mapping(degree);
      DoFHandler<2>     dofs(tria);
      dofs.distribute_dofs(fe);

      AffineConstraints<double> constraints;
      VectorTools::interpolate_boundary_values(
        mapping,
        dofs,
        0,
        Functions::ZeroFunction<2>(2),
        constraints,
        ComponentMask(std::vector<bool>{false, true}));
      VectorTools::interpolate_boundary_values(
        mapping,
        dofs,
        1,
        Functions::ZeroFunction<2>(2),
        constraints,
        ComponentMask(std::vector<bool>{true, false}));
      constraints.close();

      DynamicSparsityPattern dsp(dofs.n_dofs());
      DoFTools::make_sparsity_pattern(dofs, dsp, constraints, false);
      SparsityPattern sparsity;
      sparsity.copy_from(dsp);
      SparseMatrix<double> matrix(sparsity);
      Vector<double>       rhs(dofs.n_dofs()), solution(dofs.n_dofs());

      const QGauss<2>                      quadrature(degree + 1);
      const QGauss<1>                      face_quadrature(degree + 1);
      FEValues<2>                          fe_values(mapping,
                            fe,
                            quadrature,
                            update_gradients | update_JxW_values);
      FEFaceValues<2>                      face_values(mapping,
                                  fe,
                                  face_quadrature,
                                  update_values | update_quadrature_points |
                                    update_normal_vectors | update_JxW_values);
      const unsigned int                   n = fe.n_dofs_per_cell();
      FullMatrix<double>                   cell_matrix(n, n);
      Vector<double>                       cell_rhs(n);
      std::vector<types::global_dof_index> dof_indices(n);
      const FEValuesExtractors::Vector     u(0);

      for (const auto &cell : dofs.active_cell_iterators())
        {
          fe_values.reinit(cell);
          cell_matrix = 0;
          cell_rhs    = 0;
          for (unsigned int q = 0; q < quadrature.size(); ++q)
            for (unsigned int i = 0; i < n; ++i)
              {
                const auto eps_i = fe_values[u].symmetric_gradient(i, q);
                for (unsigned int j = 0; j < n; ++j)
                  {
                    const auto eps_j = fe_values[u].symmetric_gradient(j, q);
                    cell_matrix(i, j) +=
                      (2 * mu * scalar_product(eps_i, eps_j) +
                       lambda * trace(eps_i) * trace(eps_j)) *
                      fe_values.JxW(q);
                  }
              }
          for (const auto f : cell->face_indices())
            if (cell->at_boundary(f) && cell->face(f)->boundary_id() == 3)
              {
                face_values.reinit(cell, f);
                for (unsigned int q = 0; q < face_quadrature.size(); ++q)
                  {
                    const Tensor<1, 2> t =
                      exact.traction(face_values.quadrature_point(q),
                                     face_values.normal_vector(q));
                    for (unsigned int i = 0; i < n; ++i)
                      cell_rhs[i] +=
                        face_values[u].value(i, q) * t * face_values.JxW(q);
                  }
              }
          cell->get_dof_indices(dof_indices);
          constraints.distribute_local_to_global(
            cell_matrix, cell_rhs, dof_indices, matrix, rhs);
        }

      SparseDirectUMFPACK direct;
      direct.solve(matrix, rhs);
      solution = rhs;
      constraints.distribute(solution);
      const double time = timer.wall_time();

      // Relative L2 error of the displacement over the body.
      const QGauss<2>           error_quadrature(degree + 3);
      FEValues<2>               error_values(mapping,
                               fe,
                               error_quadrature,
                               update_values | update_quadrature_points |
                                 update_JxW_values);
      std::vector<Tensor<1, 2>> uh(error_quadrature.size());
      double                    error2 = 0, norm2 = 0;
      for (const auto &cell : dofs.active_cell_iterators())
        {
          error_values.reinit(cell);
          error_values[u].get_function_values(solution, uh);
          for (unsigned int q = 0; q < error_quadrature.size(); ++q)
            {
              const Tensor<1, 2> ua =
                exact.displacement(error_values.quadrature_point(q));
              error2 += (uh[q] - ua).norm_square() * error_values.JxW(q);
              norm2 += ua.norm_square() * error_values.JxW(q);
            }
        }
      std::cout << degree << ',' << refinements << ',' << dofs.n_dofs() << ','
                << std::sqrt(error2 / norm2) << ',' << time << std::endl;
    }
}
