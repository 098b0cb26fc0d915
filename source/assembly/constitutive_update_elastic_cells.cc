#include <bsmpm/assembly/constitutive_update.h>
#include <bsmpm/assembly/point_moments.h>

#include <cmath>
#include <limits>

// ConstitutiveUpdate, part 4: the cells whose points stay elastic, whose
// Newton systems of a load increment come from moments computed once
// (ElasticCell; doc/newton.md, "Cells that stay elastic").

namespace bsmpm
{
  ConstitutiveUpdate::ElasticCell
  ConstitutiveUpdate::elastic_cell(
    const std::vector<PointView> &cell_points) const
  {
    ElasticCell       cell;
    ConstitutiveState state;
    double            reach = std::numeric_limits<double>::infinity();
    double            s_min = 1, s_max = 0, t_min = 1, t_max = 0;
    for (const auto &point : cell_points)
      {
        const auto &props = point.props;
        cell.volume.add(point.st, props[Property::volume]);
        const double w = integration_weight(props);
        if (w == 0.)
          continue;
        // The shortcut's sums take the first body's elastic tangent.
        if (body_models.size() > 1 && props[Property::body] != 0.)
          return ElasticCell();
        state.elastic_strain[0][0]      = props[Property::elastic_strain];
        state.elastic_strain[1][1]      = props[Property::elastic_strain + 1];
        state.elastic_strain[2][2]      = props[Property::elastic_strain + 2];
        state.elastic_strain[0][1]      = props[Property::elastic_strain + 3];
        state.equivalent_plastic_strain = props[Property::plastic_strain];
        reach              = std::min(reach, model.elastic_reach(state));
        const Point<2> &st = point.st;
        s_min              = std::min(s_min, st[0]);
        s_max              = std::max(s_max, st[0]);
        t_min              = std::min(t_min, st[1]);
        t_max              = std::max(t_max, st[1]);
        const std::array<double, 6> m = PointMoments::weighted(w, st);
        for (unsigned int q = 0; q < 6; ++q)
          cell.M[q] += m[q];
        const double e[4] = {props[Property::elastic_strain],
                             props[Property::elastic_strain + 1],
                             props[Property::elastic_strain + 2],
                             2 * props[Property::elastic_strain + 3]};
        for (unsigned int a = 0; a < 3; ++a)
          for (unsigned int r = 0; r < 4; ++r)
            cell.strain_moments[a][r] += m[a] * e[r];
      }
    // No point with weight: the cell is left to the point-by-point path.
    if (s_min > s_max)
      return ElasticCell();
    cell.reach        = reach;
    cell.centre       = Point<2>((s_min + s_max) / 2, (t_min + t_max) / 2);
    cell.half_width_s = (s_max - s_min) / 2;
    cell.half_width_t = (t_max - t_min) / 2;
    return cell;
  }



  bool
  ConstitutiveUpdate::elastic_cell_system(
    const Q1CellKernel              &kernel,
    const ElasticCell               &cell,
    const Q1CellKernel::LocalVector &d,
    FullMatrix<double>              &K,
    Vector<double>                  &f,
    const CellMoments               *exact_moments) const
  {
    if (!(cell.reach > 0) || point_kinematics != Kinematics::small_strain)
      return false;
    const CellStrain strain =
      cell_strain(kernel, cell.volume, d, exact_moments);
    // The norm of a strain tensor from its (xx, yy, zz, engineering xy).
    const auto norm = [](const Tensor<1, 4> &e) {
      return std::sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2] +
                       e[3] * e[3] / 2);
    };
    // The largest |de| over the box of the points' coordinates.
    const auto  &E = strain.increment;
    const double largest =
      norm(E[0] + cell.centre[0] * E[1] + cell.centre[1] * E[2]) +
      cell.half_width_s * norm(E[1]) + cell.half_width_t * norm(E[2]);
    if (!(largest < cell.reach))
      return false;
    // S_a = D_e (sum_p w m_a e_n,p + sum_b M_ab E_b); H_ab = M_ab D_e.
    double S[3][4];
    for (unsigned int a = 0; a < 3; ++a)
      {
        Tensor<1, 4> e;
        for (unsigned int r = 0; r < 4; ++r)
          e[r] = cell.strain_moments[a][r];
        for (unsigned int b = 0; b < 3; ++b)
          e += cell.M[PointMoments::index[a][b]] * E[b];
        const Tensor<1, 4> sigma = elastic_voigt * e;
        for (unsigned int r = 0; r < 4; ++r)
          S[a][r] = sigma[r];
      }
    static constexpr double no_plastic_moments[6][16] = {};
    system_from_moments(strain, no_plastic_moments, false, cell.M, S, K, f);
    return true;
  }



  void
  ConstitutiveUpdate::prepare_elastic_cells(const MaterialPoints &points,
                                            const BackgroundGrid &grid,
                                            ElasticCells         &cells) const
  {
    cells.clear();
    if (point_kinematics != Kinematics::small_strain)
      return;
    cells.resize(grid.triangulation().n_active_cells());
    const auto            &particles = points.particle_handler();
    std::vector<PointView> views;
    for (const auto &cell : grid.dof_handler().active_cell_iterators())
      if (cell->is_locally_owned() && particles.n_particles_in_cell(cell) > 0)
        {
          gather_points(particles.particles_in_cell(cell),
                        particles.n_particles_in_cell(cell),
                        views);
          cells[cell->active_cell_index()] = elastic_cell(views);
        }
  }
} // namespace bsmpm
