#include <bsmpm/assembly/constitutive_update.h>
#include <bsmpm/assembly/point_moments.h>

#include <algorithm>
#include <cmath>
#include <memory>

// ConstitutiveUpdate, part 1: its parameters, and the assembly of the
// points' share of the Newton system cell by cell. The class spans five
// files by concern (the ASPECT way): this one; the kinematics of a cell's
// points (constitutive_update_kinematics.cc); the system of one cell
// (constitutive_update_cell_system.cc); the cells that stay elastic
// (constitutive_update_elastic_cells.cc); the state stored at the end of a
// step (constitutive_update_commit.cc).

namespace bsmpm
{
  void
  ConstitutiveUpdate::declare_parameters(ParameterHandler &prm)
  {
    // The material's own entries are LinearElasticMaterial's and the
    // constitutive model's: these two choose how the points integrate it.
    prm.enter_subsection("Material");
    prm.declare_entry(
      "Volumetric strain",
      "B-bar",
      Patterns::Selection("B-bar|standard"),
      "B-bar (the default) replaces the volumetric strain of every point by "
      "its mean over the cell's material, so that neither isochoric plastic "
      "flow nor a nearly incompressible elastic material (Poisson's ratio "
      "near 0.5) locks the bilinear grid; standard keeps the points' own, as "
      "the paper does, and locks there: choose it only to reproduce the "
      "paper's kernel. Linear elasticity (small strain): the in-plane split, "
      "mean of eps_xx + eps_yy at the centroid of the cell's moments (fitted "
      "ones in cut cells), stress C eps + (lambda + mu)(theta_mean - "
      "theta)(1, 1, 0), also in the Nitsche and implicit-boundary terms "
      "(doc/b-bar.md); not with rigid bodies, where a mean per cell makes the "
      "contact pressures alternate from one grid line to the next (a nearly "
      "incompressible elastic body in contact locks). Nonlinear models: the "
      "3D split (zz included). Finite strain: F-bar for nonlinear models, "
      "none for linear elasticity.");
    prm.declare_entry(
      "Kinematics",
      "small strain",
      Patterns::Selection("small strain|finite strain"),
      "small strain (the default): the paper's formulation (strain increments "
      "added, stress of the small-strain model). finite strain: updated "
      "Lagrangian, a deformation gradient per point, logarithmic (Hencky) "
      "elastic strain with the exponential map, Kirchhoff stress, point "
      "volumes det(F) V0, a pressure that follows the boundary within the "
      "load step (doc/finite-strain.md); choose it where rotations or strains "
      "are no longer small. Finite strain always uses Newton iterations, also "
      "for linear elasticity, and needs plane strain. Without boundary "
      "curves, a free closed curve round the body region is added (Curve 1), "
      "so that the cut-cell quadrature integrates the cells the moving points "
      "fill unevenly.");
    prm.leave_subsection();
  }



  std::unique_ptr<ConstitutiveUpdate>
  ConstitutiveUpdate::create(ParameterHandler            &prm,
                             const ConstitutiveModel     &model,
                             const LinearElasticMaterial &material,
                             const bool                   newton,
                             const bool                   contact,
                             const bool                   nonlinear_bodies)
  {
    prm.enter_subsection("Material");
    const bool b_bar         = prm.get("Volumetric strain") == "B-bar";
    const bool finite_strain = prm.get("Kinematics") == "finite strain";
    prm.leave_subsection();
    AssertThrow(!finite_strain || material.model() ==
                                    LinearElasticMaterial::Model::plane_strain,
                ExcMessage("Material/Kinematics = finite strain needs "
                           "'Model = plane strain': in plane stress the "
                           "thickness stretch would be a further unknown."));
    // The volumetric mean per cell where a model flows isochorically, and
    // for linear elasticity in small strain as in the linear path, except
    // with contact (doc/b-bar.md, "Limitations").
    const bool nonlinear = !model.is_linear() || nonlinear_bodies;
    const bool mean_volumetric_strain =
      b_bar && (nonlinear || (!finite_strain && !contact));
    if (!model.is_linear() || finite_strain || newton)
      return std::make_unique<ConstitutiveUpdate>(model,
                                                  mean_volumetric_strain,
                                                  finite_strain ?
                                                    Kinematics::finite_strain :
                                                    Kinematics::small_strain);
    return nullptr;
  }



  bool
  ConstitutiveUpdate::uses_b_bar(ParameterHandler &prm)
  {
    prm.enter_subsection("Material");
    const bool b_bar = prm.get("Volumetric strain") == "B-bar";
    prm.leave_subsection();
    return b_bar;
  }



  ConstitutiveUpdate::ConstitutiveUpdate(const ConstitutiveModel &model,
                                         const bool               b_bar,
                                         const Kinematics         kinematics)
    : model(model)
    , body_models{&model}
    , body_voigt{voigt_tangent(model.elastic_tangent())}
    , symmetric_tangents(model.symmetric_tangent())
    , b_bar(b_bar)
    , elastic_voigt(voigt_tangent(model.elastic_tangent()))
    , point_kinematics(kinematics)
  {}



  void
  ConstitutiveUpdate::set_further_bodies(
    const std::vector<const ConstitutiveModel *> &models)
  {
    body_models.resize(1);
    body_voigt.resize(1);
    symmetric_tangents = model.symmetric_tangent();
    for (const ConstitutiveModel *m : models)
      {
        body_models.push_back(m);
        body_voigt.push_back(voigt_tangent(m->elastic_tangent()));
        symmetric_tangents = symmetric_tangents && m->symmetric_tangent();
      }
  }



  double
  ConstitutiveUpdate::integration_weight(
    const ArrayView<const double> &props) const
  {
    return props[Property::volume] == 0. ? 0. :
           quadrature_weights            ? props[Property::weight] :
                                           props[Property::volume];
  }



  Tensor<2, 4>
  ConstitutiveUpdate::voigt_tangent(const SymmetricTensor<4, 3> &tangent)
  {
    // sigma_ij = T_ijkl eps_kl; the engineering shear gamma = 2 eps_xy
    // takes both T_ij01 and T_ij10 = T_ij01. deal.II stores T as the 6x6
    // table of the pairs (00, 11, 22, 01, 02, 12), whose first four are
    // (xx, yy, zz, xy): read it directly (the chained [i][j][k][l] looks
    // every entry up by its indices).
    Tensor<2, 4> D;
    for (unsigned int r = 0; r < 4; ++r)
      for (unsigned int c = 0; c < 4; ++c)
        D[r][c] = tangent.access_raw_entry(6 * r + c);
    return D;
  }



  void
  ConstitutiveUpdate::gather_points(
    const Particles::ParticleHandler<2>::particle_iterator_range &range,
    const unsigned int                                            n_points,
    std::vector<PointView>                                       &views)
  {
    // Written by index into a vector sized once (push_back checked the
    // capacity of every point).
    views.resize(n_points);
    auto view = views.begin();
    for (const auto &particle : range)
      {
        view->st    = particle.get_reference_location();
        view->props = particle.get_properties();
        ++view;
      }
  }



  ConstitutiveUpdate::AssemblyCount
  ConstitutiveUpdate::assemble(
    const MaterialPoints                             &points,
    const BackgroundGrid                             &grid,
    const Q1CellKernel                               &kernel,
    const LinearAlgebra::distributed::Vector<double> &increment,
    const LinearAlgebra::distributed::Vector<double> *prescribed,
    const AffineConstraints<double>                  &constraints,
    TrilinosWrappers::SparseMatrix                   &tangent,
    TrilinosWrappers::MPI::Vector                    &internal_force,
    CellScatter                                      &scatter,
    const SupportBands                               *bands,
    const ElasticCells                               *elastic_cells) const
  {
    constexpr unsigned int               n = Q1CellKernel::dofs_per_cell;
    const auto                          &particles = points.particle_handler();
    FullMatrix<double>                   cell_matrix(n, n);
    Vector<double>                       cell_vector(n);
    std::vector<types::global_dof_index> dof_indices(n);
    Q1CellKernel::LocalVector            d;
    std::vector<PointView>               views;
    std::vector<double>                  borrowed;
    AssemblyCount                        count;
    // A cell whose force is not finite (an inverted point) is counted and
    // left out: the caller then knows the increment is inadmissible, and
    // the system holds no NaN.
    const auto add_cell = [&](const unsigned int cell_index) {
      for (const double v : cell_vector)
        if (!std::isfinite(v))
          {
            ++count.inverted_cells;
            return;
          }
      scatter.add(cell_index,
                  cell_matrix,
                  cell_vector,
                  dof_indices,
                  constraints,
                  tangent,
                  internal_force);
    };

    for (const auto &cell : grid.dof_handler().active_cell_iterators())
      {
        if (!cell->is_locally_owned())
          continue;
        const unsigned int index = cell->active_cell_index();
        // A cell that stays elastic needs none of its points (outside a
        // support's band, whose virtual points take the points' mean
        // state).
        if (elastic_cells != nullptr && !elastic_cells->empty() &&
            (*elastic_cells)[index].reach > 0 &&
            (bands == nullptr || (*bands)[index].empty()))
          {
            d = MaterialPoints::cell_increment(cell,
                                               increment,
                                               prescribed,
                                               dof_indices);
            if (elastic_cell_system(kernel,
                                    (*elastic_cells)[index],
                                    d,
                                    cell_matrix,
                                    cell_vector,
                                    exact_moments ? &(*exact_moments)[index] :
                                                    nullptr))
              {
                add_cell(index);
                continue;
              }
          }
        // The points once (MaterialPoints::holds_material() would walk
        // them again).
        views.clear();
        if (particles.n_particles_in_cell(cell) > 0)
          gather_points(particles.particles_in_cell(cell),
                        particles.n_particles_in_cell(cell),
                        views);
        if (std::none_of(views.begin(), views.end(), [](const auto &point) {
              return point.props[Property::volume] > 0;
            }))
          {
            // A cell of the body without points (a sliver the boundary has
            // just entered, the part of the top row above the points): the
            // four points of PointMoments::exact_four_point_rule() with the
            // state of the neighbourhood. Their tangent holds every deformation
            // mode of the cell (as the exact moments of the linear path do),
            // and a homogeneous state stays exact (SystemAssembly leaves such
            // cells to us).
            const CellMoments *m =
              completes_moments() ?
                &(*exact_moments)[cell->active_cell_index()] :
                nullptr;
            if (m == nullptr || !(m->v > 0))
              continue;
            borrowed = points.neighbourhood_mean_properties(cell);
            if (borrowed.empty())
              continue;
            borrowed[Property::weight] = m->v / 4;
            const ArrayView<const double> state(borrowed.data(),
                                                borrowed.size());
            views.clear();
            for (const Point<2> &st : PointMoments::exact_four_point_rule(*m))
              views.push_back({st, state});
            d = MaterialPoints::cell_increment(cell,
                                               increment,
                                               prescribed,
                                               dof_indices);
            cell_system(kernel, views, d, cell_matrix, cell_vector);
            add_cell(cell->active_cell_index());
            continue;
          }
        d = MaterialPoints::cell_increment(cell,
                                           increment,
                                           prescribed,
                                           dof_indices);
        const auto *band =
          bands != nullptr && !(*bands)[cell->active_cell_index()].empty() ?
            &(*bands)[cell->active_cell_index()] :
            nullptr;
        count.yielded +=
          cell_system(kernel,
                      views,
                      d,
                      cell_matrix,
                      cell_vector,
                      exact_moments ?
                        &(*exact_moments)[cell->active_cell_index()] :
                        nullptr,
                      band);
        add_cell(cell->active_cell_index());
      }
    return count;
  }
} // namespace bsmpm
