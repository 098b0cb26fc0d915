// Checks of the material and of the closed-form Q1 cell kernel:
// (i)   the Voigt stiffness of LinearElasticMaterial against the textbook
//       formulas for plane strain and plane stress, and that invalid E or nu
//       throw;
// (ii)  shape values and gradients of Q1CellKernel against FEValues of
//       FESystem(FE_Q(1), 2) with MappingCartesian on a non-square cell;
// (iii) stiffness, internal force and body force from the six volume moments
//       against the point-by-point sums computed with FEValues, and the strain
//       and displacement of random local displacements.
#ifndef bsmpm_tests_q1_cell_kernel_01_h
#define bsmpm_tests_q1_cell_kernel_01_h

#include <deal.II/base/quadrature.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_cartesian.h>

#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/tria.h>

#include <bsmpm/materials/material.h>
#include <bsmpm/points/q1_cell_kernel.h>

#include <algorithm>
#include <cstdint>
#include <vector>

// tests.h uses deallog unqualified: the using directive must come first.
using namespace dealii;

#include "../tests.h"

using namespace bsmpm;

namespace q1_cell_kernel_01
{
  namespace
  {
    const char *
    model_name(const LinearElasticMaterial::Model model)
    {
      return model == LinearElasticMaterial::Model::plane_strain ?
               "plane strain" :
               "plane stress";
    }



    // (i) Material matrix.
    void
    check_material()
    {
      deallog.push("material");
      const double E = 2.5e7, nu = 0.3;
      // Lame constants; plane stress replaces lambda by 2 lambda mu/(lambda+2
      // mu).
      const double lambda = E * nu / ((1 + nu) * (1 - 2 * nu));
      const double mu     = E / (2 * (1 + nu));

      for (const auto model : {LinearElasticMaterial::Model::plane_strain,
                               LinearElasticMaterial::Model::plane_stress})
        {
          const LinearElasticMaterial material(E, nu, model, 2000.);
          const bool                  strain =
            model == LinearElasticMaterial::Model::plane_strain;
          const double l =
            strain ? lambda : 2 * lambda * mu / (lambda + 2 * mu);

          // Textbook forms, written differently from the library's.
          Tensor<2, 3> expected;
          if (strain)
            {
              const double f = E / ((1 + nu) * (1 - 2 * nu));
              expected[0][0] = expected[1][1] = f * (1 - nu);
              expected[0][1] = expected[1][0] = f * nu;
              expected[2][2]                  = f * (1 - 2 * nu) / 2;
            }
          else
            {
              const double f = E / (1 - nu * nu);
              expected[0][0] = expected[1][1] = f;
              expected[0][1] = expected[1][0] = f * nu;
              expected[2][2]                  = f * (1 - nu) / 2;
            }
          Tensor<2, 3> from_lame;
          from_lame[0][0] = from_lame[1][1] = l + 2 * mu;
          from_lame[0][1] = from_lame[1][0] = l;
          from_lame[2][2]                   = mu;

          const Tensor<2, 3> &C = material.stiffness();
          deallog << model_name(model) << ": C / E =";
          for (unsigned int i = 0; i < 3; ++i)
            for (unsigned int j = 0; j < 3; ++j)
              deallog << ' ' << filter_roundoff(C[i][j] / E);
          deallog << std::endl;
          deallog << model_name(model) << ": equals the textbook matrix: "
                  << yes_no((C - expected).norm() < 1e-14 * E) << std::endl;
          deallog << model_name(model)
                  << ": equals (lambda + 2 mu, lambda, mu): "
                  << yes_no((C - from_lame).norm() < 1e-14 * E) << std::endl;
          deallog << model_name(model) << ": constrained modulus / E = "
                  << material.constrained_modulus() / E
                  << ", shear modulus / E = " << material.shear_modulus() / E
                  << ", kolosov constant = " << material.kolosov_constant()
                  << std::endl;
          deallog
            << model_name(model)
            << ": sigma = C eps for uniaxial stress gives eps_yy/eps_xx = " <<
            [&]() {
              // Uniaxial stress in x: eps = C^-1 (1, 0, 0).
              const Tensor<1, 3> eps = invert(C) * Tensor<1, 3>({1., 0., 0.});
              return eps[1] / eps[0];
            }()
            << " (-nu in plane stress, -nu/(1-nu) in plane strain)"
            << std::endl;
        }

      // Invalid input.
      const std::vector<std::pair<double, double>> invalid = {
        {0., 0.3},
        {-1e6, 0.3},
        {std::nan(""), 0.3},
        {1e6, 0.5},
        {1e6, -1.},
        {1e6, 0.7},
        {1e6, std::nan("")}};
      // NaN is printed as text: numdiff would not compare it as equal.
      const auto text = [](const double x) {
        return std::isnan(x) ? std::string("not-a-number") : std::to_string(x);
      };
      for (const auto &E_nu : invalid)
        {
          const double E_bad = E_nu.first, nu_bad = E_nu.second;
          bool         thrown = false;
          try
            {
              const LinearElasticMaterial material(
                E_bad, nu_bad, LinearElasticMaterial::Model::plane_strain);
              (void)material;
            }
          catch (const ExceptionBase &)
            {
              thrown = true;
            }
          deallog << "E = " << text(E_bad) << ", nu = " << text(nu_bad) << ": "
                  << (thrown ? "thrown" : "NOT thrown") << std::endl;
        }
      {
        bool thrown = false;
        try
          {
            const LinearElasticMaterial material(
              1e6, 0.2, LinearElasticMaterial::Model::plane_stress, -1.);
            (void)material;
          }
        catch (const ExceptionBase &)
          {
            thrown = true;
          }
        deallog << "negative density: " << (thrown ? "thrown" : "NOT thrown")
                << std::endl;
      }
      // The same check through the parameter file.
      {
        ParameterHandler prm;
        LinearElasticMaterial::declare_parameters(prm);
        prm.parse_input_from_string("subsection Material\n"
                                    "  set Poisson's ratio = 0.5\n"
                                    "end\n");
        LinearElasticMaterial material;
        bool                  thrown = false;
        try
          {
            material.parse_parameters(prm);
          }
        catch (const ExceptionBase &)
          {
            thrown = true;
          }
        deallog << "parse_parameters with nu = 0.5: "
                << (thrown ? "thrown" : "NOT thrown") << std::endl;
      }
      deallog.pop();
    }



    // FEValues of the vector Q1 element at given local coordinates of a cell.
    struct Reference
    {
      Reference(const Point<2> &origin, const Tensor<1, 2> &h)
        : fe(FE_Q<2>(1), 2)
        , dof_handler(tria)
      {
        GridGenerator::hyper_rectangle(tria, origin, origin + h);
        dof_handler.distribute_dofs(fe);
      }

      std::unique_ptr<FEValues<2>>
      values_at(const std::vector<Point<2>> &st) const
      {
        const Quadrature<2> quadrature(st, std::vector<double>(st.size(), 1.));
        auto                fe_values =
          std::make_unique<FEValues<2>>(mapping,
                                        fe,
                                        quadrature,
                                        update_values | update_gradients |
                                          update_quadrature_points);
        fe_values->reinit(dof_handler.begin_active());
        return fe_values;
      }

      Triangulation<2>    tria;
      FESystem<2>         fe;
      MappingCartesian<2> mapping;
      DoFHandler<2>       dof_handler;
    };

    // Column i of B from FEValues: (du/dx, dv/dy, du/dy + dv/dx).
    Voigt
    strain_column(const FEValues<2> &fe_values,
                  const unsigned int i,
                  const unsigned int q)
    {
      const Tensor<1, 2> gu = fe_values.shape_grad_component(i, q, 0);
      const Tensor<1, 2> gv = fe_values.shape_grad_component(i, q, 1);
      return Voigt({gu[0], gv[1], gu[1] + gv[0]});
    }



    // (ii) Shape values and gradients.
    void
    check_shape_functions()
    {
      deallog.push("shape");
      Random                      random(20240601);
      const Point<2>              origin(1.3, -0.4);
      const Tensor<1, 2>          h({0.7, 0.3});
      Reference                   reference(origin, h);
      const LinearElasticMaterial material(
        1e6, 0.25, LinearElasticMaterial::Model::plane_strain);
      const Q1CellKernel kernel(reference.fe, h, material.stiffness());

      std::vector<Point<2>> st(40);
      for (auto &p : st)
        p = Point<2>(random(), random());
      // The vertices and edge midpoints as well.
      for (const double s : {0., 0.5, 1.})
        for (const double t : {0., 0.5, 1.})
          st.emplace_back(s, t);
      const auto fe_values = reference.values_at(st);

      // The quadrature points are where the kernel's local coordinates say.
      double position_error = 0;
      for (unsigned int q = 0; q < st.size(); ++q)
        position_error =
          std::max(position_error,
                   (fe_values->quadrature_point(q) -
                    (origin + Tensor<1, 2>({st[q][0] * h[0], st[q][1] * h[1]})))
                     .norm());
      deallog << "points map to x0 + (s hx, t hy): "
              << yes_no(position_error < 1e-15) << std::endl;

      // Gradients scale like 1/h: compare relative to 1/min(h).
      const double grad_scale  = 1. / std::min(h[0], h[1]);
      double       value_error = 0, grad_error = 0, column_error = 0;
      double       vertex_error = 0;
      for (unsigned int q = 0; q < st.size(); ++q)
        {
          const auto N = Q1CellKernel::vertex_shape_values(st[q]);
          for (unsigned int i = 0; i < Q1CellKernel::dofs_per_cell; ++i)
            {
              const Tensor<1, 2> value    = kernel.shape_value(i, st[q]);
              const Tensor<2, 2> gradient = kernel.shape_gradient(i, st[q]);
              for (unsigned int c = 0; c < 2; ++c)
                {
                  value_error =
                    std::max(value_error,
                             std::abs(
                               value[c] -
                               fe_values->shape_value_component(i, q, c)));
                  grad_error =
                    std::max(grad_error,
                             (gradient[c] -
                              fe_values->shape_grad_component(i, q, c))
                                 .norm() /
                               grad_scale);
                }
              column_error = std::max(column_error,
                                      (kernel.strain_column(i, st[q]) -
                                       strain_column(*fe_values, i, q))
                                          .norm() /
                                        grad_scale);
              vertex_error = std::max(vertex_error,
                                      std::abs(N[kernel.vertex(i)] -
                                               fe_values->shape_value_component(
                                                 i, q, kernel.component(i))));
            }
        }
      deallog << st.size()
              << " points, hx = 0.7, hy = 0.3: max error of shape_value below "
                 "1e-14: "
              << yes_no(value_error < 1e-14) << std::endl;
      deallog << "max error of shape_gradient below 1e-14 (relative to 1/h): "
              << yes_no(grad_error < 1e-14) << std::endl;
      deallog << "max error of strain_column below 1e-14 (relative to 1/h): "
              << yes_no(column_error < 1e-14) << std::endl;
      deallog << "vertex()/component() match the element's numbering: "
              << yes_no(vertex_error < 1e-14) << std::endl;
      deallog.pop();
    }



    // Maximum of |a_ij| over a matrix.
    double
    max_abs(const FullMatrix<double> &A)
    {
      double m = 0;
      for (unsigned int i = 0; i < A.m(); ++i)
        for (unsigned int j = 0; j < A.n(); ++j)
          m = std::max(m, std::abs(A(i, j)));
      return m;
    }

    double
    max_abs(const Vector<double> &v)
    {
      return v.linfty_norm();
    }



    // (iii) Moment assembly against point-by-point sums.
    void
    check_moments(const LinearElasticMaterial::Model model,
                  const unsigned int                 n_points)
    {
      deallog.push(std::string(model_name(model)) + ", " +
                   std::to_string(n_points) + " points");
      Random                      random(20240601);
      const Point<2>              origin(-2.1, 0.6);
      const Tensor<1, 2>          h({0.7, 0.3});
      Reference                   reference(origin, h);
      const LinearElasticMaterial material(3e7, 0.2, model);
      const Tensor<2, 3>         &C = material.stiffness();
      const Q1CellKernel          kernel(reference.fe, h, C);
      constexpr unsigned int      n_dofs = Q1CellKernel::dofs_per_cell;

      std::vector<Point<2>> st(n_points);
      std::vector<double>   volume(n_points);
      std::vector<Voigt>    sigma(n_points);
      for (unsigned int q = 0; q < n_points; ++q)
        {
          st[q]     = Point<2>(random(), random());
          volume[q] = h[0] * h[1] / n_points * random(0.2, 1.8);
          sigma[q] =
            Voigt({random(-1e5, 1e5), random(-1e5, 1e5), random(-1e5, 1e5)});
        }
      const Tensor<1, 2> body_force({random(-2e4, 2e4), random(-2e4, 2e4)});
      const auto         fe_values = reference.values_at(st);

      // The point-by-point sums with FEValues.
      FullMatrix<double> K_ref(n_dofs, n_dofs);
      Vector<double>     f_int_ref(n_dofs), f_body_ref(n_dofs);
      for (unsigned int q = 0; q < n_points; ++q)
        for (unsigned int i = 0; i < n_dofs; ++i)
          {
            const Voigt Bi = strain_column(*fe_values, i, q);
            for (unsigned int j = 0; j < n_dofs; ++j)
              K_ref(i, j) +=
                Bi * (C * strain_column(*fe_values, j, q)) * volume[q];
            f_int_ref(i) += Bi * sigma[q] * volume[q];
            for (unsigned int c = 0; c < 2; ++c)
              f_body_ref(i) += fe_values->shape_value_component(i, q, c) *
                               body_force[c] * volume[q];
          }

      CellMoments moments;
      for (unsigned int q = 0; q < n_points; ++q)
        moments.add(st[q], volume[q], sigma[q]);

      FullMatrix<double> K(n_dofs, n_dofs);
      Vector<double>     f_int(n_dofs), f_body(n_dofs);
      kernel.add_stiffness(moments, K);
      kernel.add_internal_force(moments, f_int);
      kernel.add_body_force(moments, body_force, f_body);

      FullMatrix<double> difference(K);
      difference.add(-1., K_ref);
      deallog << "stiffness equals sum of B^T C B V to 1e-12 (relative): "
              << yes_no(max_abs(difference) < 1e-12 * max_abs(K_ref))
              << std::endl;
      FullMatrix<double> asymmetry(K);
      asymmetry.Tadd(-1., K);
      deallog << "stiffness symmetric to 1e-14: "
              << yes_no(max_abs(asymmetry) < 1e-14 * max_abs(K)) << std::endl;

      // Rigid motions: two translations and the rotation u = (-y, x).
      double rigid_residual = 0;
      for (unsigned int mode = 0; mode < 3; ++mode)
        {
          Vector<double> u(n_dofs), Ku(n_dofs);
          for (unsigned int i = 0; i < n_dofs; ++i)
            {
              const unsigned int v = kernel.vertex(i), c = kernel.component(i);
              const Point<2>     x(origin[0] + (v % 2) * h[0],
                               origin[1] + (v / 2) * h[1]);
              u(i) = mode < 2 ? double(c == mode) : (c == 0 ? -x[1] : x[0]);
            }
          K.vmult(Ku, u);
          rigid_residual =
            std::max(rigid_residual,
                     max_abs(Ku) / (max_abs(K) * u.linfty_norm()));
        }
      deallog << "rigid motions in the kernel of K (to 1e-14): "
              << yes_no(rigid_residual < 1e-14) << std::endl;

      // Adding to a non-zero matrix adds.
      FullMatrix<double> K2(K);
      kernel.add_stiffness(moments, K2);
      K2.add(-2., K);
      deallog << "add_stiffness adds: "
              << yes_no(max_abs(K2) < 1e-15 * max_abs(K)) << std::endl;

      Vector<double> df(f_int);
      df -= f_int_ref;
      deallog
        << "internal force equals sum of B^T sigma V to 1e-12 (relative): "
        << yes_no(max_abs(df) < 1e-12 * max_abs(f_int_ref)) << std::endl;
      df = f_body;
      df -= f_body_ref;
      deallog << "body force equals sum of N^T b V to 1e-12 (relative): "
              << yes_no(max_abs(df) < 1e-12 * max_abs(f_body_ref)) << std::endl;
      double total_body_force[2] = {0, 0};
      for (unsigned int i = 0; i < n_dofs; ++i)
        total_body_force[kernel.component(i)] += f_body(i);
      deallog << "body force sums to b * sum V: "
              << yes_no(
                   std::abs(total_body_force[0] - body_force[0] * moments.v) <
                     1e-12 * body_force.norm() * moments.v &&
                   std::abs(total_body_force[1] - body_force[1] * moments.v) <
                     1e-12 * body_force.norm() * moments.v)
              << std::endl;

      // Strain and displacement of random local displacements.
      Q1CellKernel::LocalVector d;
      for (auto &di : d)
        di = random(-1e-3, 1e-3);
      const auto e          = kernel.strain_coefficients(d);
      double     strain_err = 0, strain_scale = 0, disp_err = 0;
      for (unsigned int q = 0; q < n_points; ++q)
        {
          Voigt        eps_ref;
          Tensor<1, 2> u_ref;
          for (unsigned int i = 0; i < n_dofs; ++i)
            {
              eps_ref += d[i] * strain_column(*fe_values, i, q);
              for (unsigned int c = 0; c < 2; ++c)
                u_ref[c] += d[i] * fe_values->shape_value_component(i, q, c);
            }
          const Voigt eps = e[0] + st[q][0] * e[1] + st[q][1] * e[2];
          strain_err      = std::max(strain_err, (eps - eps_ref).norm());
          strain_scale    = std::max(strain_scale, eps_ref.norm());
          disp_err =
            std::max(disp_err, (kernel.displacement(d, st[q]) - u_ref).norm());
        }
      deallog << "strain_coefficients reproduce the FEValues strain to 1e-13 "
                 "(relative): "
              << yes_no(strain_err < 1e-13 * strain_scale) << std::endl;
      deallog << "displacement reproduces the FEValues values to 1e-16 "
                 "(absolute, |d| <= 1e-3): "
              << yes_no(disp_err < 1e-16) << std::endl;
      deallog.pop();
    }



    // The moments of a single point at a vertex reproduce B^T C B V there: a
    // check that does not rely on averaging over many points.
    void
    check_single_points()
    {
      deallog.push("single points");
      const Tensor<1, 2>          h({0.7, 0.3});
      Reference                   reference(Point<2>(), h);
      const LinearElasticMaterial material(
        1., 0.3, LinearElasticMaterial::Model::plane_stress);
      const Q1CellKernel          kernel(reference.fe, h, material.stiffness());
      const std::vector<Point<2>> corners   = {Point<2>(0, 0),
                                               Point<2>(1, 0),
                                               Point<2>(0, 1),
                                               Point<2>(1, 1)};
      const auto                  fe_values = reference.values_at(corners);
      bool                        all_equal = true;
      for (unsigned int q = 0; q < corners.size(); ++q)
        {
          CellMoments m;
          m.add(corners[q], 0.5, Voigt());
          FullMatrix<double> K(8, 8), K_ref(8, 8);
          kernel.add_stiffness(m, K);
          for (unsigned int i = 0; i < 8; ++i)
            for (unsigned int j = 0; j < 8; ++j)
              K_ref(i, j) =
                0.5 * strain_column(*fe_values, i, q) *
                (material.stiffness() * strain_column(*fe_values, j, q));
          K.add(-1., K_ref);
          all_equal = all_equal && max_abs(K) < 1e-13 * max_abs(K_ref);
        }
      deallog << "one point at each vertex: K equals B^T C B V: "
              << yes_no(all_equal) << std::endl;
      deallog.pop();
    }
  } // namespace



  void
  run()
  {
    check_material();
    check_shape_functions();
    check_moments(LinearElasticMaterial::Model::plane_strain, 64);
    check_moments(LinearElasticMaterial::Model::plane_stress, 7);
    check_moments(LinearElasticMaterial::Model::plane_strain, 1);
    check_single_points();
    deallog << "OK" << std::endl;
  }
} // namespace q1_cell_kernel_01

#endif
