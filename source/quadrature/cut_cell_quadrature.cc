#include <deal.II/base/mpi.h>

#include <deal.II/lac/la_parallel_vector.h>

#include <bsmpm/quadrature/cut_cell_quadrature.h>
#include <bsmpm/quadrature/moment_fitting.h>

namespace bsmpm
{
  void
  CutCellQuadrature::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Cut cells");
    prm.declare_entry(
      "Quadrature",
      "moment fitting",
      Patterns::Selection("moment fitting|plain"),
      "How cells cut by the boundary are integrated. moment fitting (the "
      "default): where the boundary curves enclose the body, the stiffness "
      "takes the exact moments of the cell's part inside the body and the "
      "points' stresses are integrated with weights fitted to them, so a "
      "constant stress is exact whatever the points' layout "
      "(doc/cut-cells.md); plain: the points' physical volumes, as in the "
      "paper. Choose plain only to reproduce the paper's figures.");
    prm.leave_subsection();
  }



  void
  CutCellQuadrature::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Cut cells");
    use_moment_fitting = prm.get("Quadrature") == "moment fitting";
    prm.leave_subsection();
  }



  void
  CutCellQuadrature::initialize(const BoundaryCurves &curves)
  {
    why_off.clear();
    if (!use_moment_fitting)
      why_off = "plain quadrature selected";
    else
      curves.encloses_body(why_off);
    is_active = why_off.empty();
  }



  void
  CutCellQuadrature::update_geometry(const BoundaryCurves &curves,
                                     const BackgroundGrid &grid)
  {
    if (!is_active)
      return;
    CutCellGeometry::Boundary boundary;
    for (const auto &curve : curves.get_curves())
      {
        boundary.curves.push_back(curve.spline.get());
        boundary.pieces.push_back(&curve.pieces);
      }
    cut_geometry.reinit(boundary,
                        UniformGrid{grid.lower_left(),
                                    grid.cell_size(),
                                    {{grid.n_cells(0), grid.n_cells(1)}}});
  }



  namespace
  {
    /** The points of @p cell keep their volume as their weight (if the
     * points store weights). */
    void
    keep_volumes_as_weights(MaterialPoints                            &points,
                            const DoFHandler<2>::active_cell_iterator &cell)
    {
      using Property = MaterialPoints::Property;
      if (points.n_properties() == Property::n_properties_inelastic)
        for (auto &particle : points.particle_handler().particles_in_cell(
               typename Triangulation<2>::active_cell_iterator(cell)))
          particle.get_properties()[Property::weight] =
            particle.get_properties()[Property::volume];
    }
  } // namespace



  void
  CutCellQuadrature::correct_cell_moments(MaterialPoints           &points,
                                          const BackgroundGrid     &grid,
                                          std::vector<CellMoments> &moments)
  {
    counts.clear();
    if (!is_active)
      return;
    FitCounts                                 n;
    std::vector<DoFHandler<2>::cell_iterator> without_points;
    for (const auto &cell : grid.dof_handler().active_cell_iterators())
      if (cell->is_locally_owned() &&
          !fit_cell(points, grid, cell, moments[cell->active_cell_index()], n))
        without_points.push_back(cell);

    const MPI_Comm     comm = grid.mpi_communicator();
    const unsigned int n_without_all =
      Utilities::MPI::sum(static_cast<unsigned int>(without_points.size()),
                          comm);
    if (n_without_all > 0)
      fill_cells_without_points(points, grid, without_points, moments);

    counts["cut_cells"]            = Utilities::MPI::sum(n.n_cut, comm);
    counts["body_area"]            = cut_geometry.area();
    counts["cut_cells_fit6"]       = Utilities::MPI::sum(n.n_fitted[6], comm);
    counts["cut_cells_fit3"]       = Utilities::MPI::sum(n.n_fitted[3], comm);
    counts["cut_cells_fit1"]       = Utilities::MPI::sum(n.n_fitted[1], comm);
    counts["body_cells_no_points"] = n_without_all;
    counts["outside_body_cells"]   = Utilities::MPI::sum(n.n_outside, comm);
    counts["full_cells_fitted"]    = Utilities::MPI::sum(n.n_full_fit, comm);
  }



  bool
  CutCellQuadrature::fit_cell(MaterialPoints                            &points,
                              const BackgroundGrid                      &grid,
                              const DoFHandler<2>::active_cell_iterator &cell,
                              CellMoments                               &m,
                              FitCounts &n) const
  {
    using Property         = MaterialPoints::Property;
    const double cell_area = grid.cell_size()[0] * grid.cell_size()[1];
    auto        &particles = points.particle_handler();
    const auto   ij        = grid.cell_index(cell);
    const auto   fill      = cut_geometry.fill(ij);
    if (fill == CutCellGeometry::Fill::empty)
      {
        // Points the curves leave outside the body (by round-off, or
        // pushed across a support): they keep their plain quadrature.
        n.n_outside += (m.v > 0);
        keep_volumes_as_weights(points, cell);
        return true;
      }
    const bool full = fill == CutCellGeometry::Fill::full;
    n.n_cut += !full;

    // The exact volume moments of K ∩ Ω.
    const auto           &mu = cut_geometry.moments(ij);
    std::array<double, 6> target;
    for (unsigned int k = 0; k < 6; ++k)
      target[k] = mu[k] * cell_area;

    // A full cell whose points have the cell's area and centroid
    // integrates a linear stress field's force exactly already (the
    // points of a regular layout that have not moved).
    const double tolerance  = 1e-12 * cell_area;
    const bool   consistent = full && m.v > 0 &&
                            std::abs(m.v - target[0]) <= tolerance &&
                            std::abs(m.vs - target[1]) <= tolerance &&
                            std::abs(m.vt - target[2]) <= tolerance;
    const CellMoments plain = m;
    m                       = CellMoments();
    m.v                     = target[0];
    m.vs                    = target[1];
    m.vt                    = target[2];
    m.vss                   = target[3];
    m.vst                   = target[4];
    m.vtt                   = target[5];
    if (consistent)
      {
        m.stress   = plain.stress;
        m.stress_s = plain.stress_s;
        m.stress_t = plain.stress_t;
        keep_volumes_as_weights(points, cell);
        return true;
      }
    n.n_full_fit += full;

    std::vector<Point<2>> st;
    std::vector<double>   volume;
    std::vector<Voigt>    stress;
    for (const auto &particle : particles.particles_in_cell(
           typename Triangulation<2>::active_cell_iterator(cell)))
      {
        const auto props = particle.get_properties();
        if (props[Property::volume] == 0.)
          continue;
        st.push_back(particle.get_reference_location());
        volume.push_back(props[Property::volume]);
        stress.push_back(Voigt({props[Property::stress],
                                props[Property::stress + 1],
                                props[Property::stress + 2]}));
      }
    if (st.empty())
      return false;

    // Cut cells: all six moments where the points can carry them; full
    // cells: the area and centroid, which a linear stress field's force
    // needs.
    const auto fit = MomentFitting::fit(st, volume, target, full ? 3 : 6);
    if (!full)
      ++n.n_fitted[fit.n_moments];
    if (points.n_properties() == Property::n_properties_inelastic)
      {
        unsigned int p = 0;
        for (auto &particle : particles.particles_in_cell(
               typename Triangulation<2>::active_cell_iterator(cell)))
          {
            auto props = particle.get_properties();
            props[Property::weight] =
              props[Property::volume] == 0. ? 0. : fit.weights[p++];
          }
      }
    double sum_w = 0, sum_ws = 0, sum_wt = 0;
    for (unsigned int p = 0; p < st.size(); ++p)
      {
        const double w = fit.weights[p];
        m.stress += w * stress[p];
        m.stress_s += w * st[p][0] * stress[p];
        m.stress_t += w * st[p][1] * stress[p];
        sum_w += w;
        sum_ws += w * st[p][0];
        sum_wt += w * st[p][1];
      }
    // Complete the first moments the weights could not match with the
    // mean stress: exact for a constant stress (zero after a 3- or
    // 6-moment fit).
    if (sum_w > 0)
      {
        const Voigt mean = m.stress / sum_w;
        m.stress += (target[0] - sum_w) * mean;
        m.stress_s += (target[1] - sum_ws) * mean;
        m.stress_t += (target[2] - sum_wt) * mean;
      }
    return true;
  }



  void
  CutCellQuadrature::fill_cells_without_points(
    const MaterialPoints                            &points,
    const BackgroundGrid                            &grid,
    const std::vector<DoFHandler<2>::cell_iterator> &cells,
    std::vector<CellMoments>                        &moments) const
  {
    using Property        = MaterialPoints::Property;
    const auto &particles = points.particle_handler();
    // Per vertex DoF pair (component 0, 1): (w sigma_xx, w sigma_yy) in
    // one vector, (w sigma_xy, w) in the other.
    LinearAlgebra::distributed::Vector<double> normal_part(
      grid.locally_owned_dofs(),
      grid.locally_relevant_dofs(),
      grid.mpi_communicator());
    LinearAlgebra::distributed::Vector<double> shear_part(normal_part);
    const auto                                &fe = grid.fe();
    std::vector<types::global_dof_index> dof_indices(fe.n_dofs_per_cell());
    for (const auto &cell : grid.dof_handler().active_cell_iterators())
      {
        if (!cell->is_locally_owned())
          continue;
        cell->get_dof_indices(dof_indices);
        for (const auto &particle : particles.particles_in_cell(
               typename Triangulation<2>::active_cell_iterator(cell)))
          {
            const auto   props = particle.get_properties();
            const double V     = props[Property::volume];
            if (V == 0.)
              continue;
            const auto N = Q1CellKernel::vertex_shape_values(
              particle.get_reference_location());
            for (unsigned int i = 0; i < dof_indices.size(); ++i)
              {
                const unsigned int v =
                  fe.system_to_component_index(i).second; // vertex of the DoF
                const unsigned int c  = fe.system_to_component_index(i).first;
                const double       wN = V * N[v];
                normal_part(dof_indices[i]) += wN * props[Property::stress + c];
                shear_part(dof_indices[i]) +=
                  (c == 0) ? wN * props[Property::stress + 2] : wN;
              }
          }
      }
    normal_part.compress(VectorOperation::add);
    shear_part.compress(VectorOperation::add);
    normal_part.update_ghost_values();
    shear_part.update_ghost_values();

    for (const auto &cell : cells)
      {
        cell->get_dof_indices(dof_indices);
        // The DoFs of each vertex, by component.
        std::array<std::array<types::global_dof_index, 2>, 4> vertex_dofs;
        for (unsigned int i = 0; i < dof_indices.size(); ++i)
          vertex_dofs[fe.system_to_component_index(i).second]
                     [fe.system_to_component_index(i).first] = dof_indices[i];
        CellMoments &m = moments[cell->active_cell_index()];
        const auto   N =
          Q1CellKernel::vertex_shape_values(Point<2>(m.vs / m.v, m.vt / m.v));
        // sigma at the centroid of K ∩ Ω from the vertices that carry
        // stress, their shape values renormalised.
        Voigt  sigma;
        double used = 0;
        for (unsigned int v = 0; v < 4; ++v)
          {
            const double mass = shear_part(vertex_dofs[v][1]);
            if (!(mass > 0))
              continue;
            const Voigt nodal({normal_part(vertex_dofs[v][0]) / mass,
                               normal_part(vertex_dofs[v][1]) / mass,
                               shear_part(vertex_dofs[v][0]) / mass});
            sigma += N[v] * nodal;
            used += N[v];
          }
        if (used > 0)
          sigma /= used;
        m.stress   = m.v * sigma;
        m.stress_s = m.vs * sigma;
        m.stress_t = m.vt * sigma;
      }
  }



  std::vector<double>
  CutCellQuadrature::fill_fractions(
    const BackgroundGrid           &grid,
    const std::vector<CellMoments> &moments) const
  {
    std::vector<double> fraction(grid.triangulation().n_active_cells(), 0.);
    const double        area = grid.cell_size()[0] * grid.cell_size()[1];
    for (const auto &cell : grid.triangulation().active_cell_iterators())
      if (cell->is_locally_owned())
        {
          const unsigned int c = cell->active_cell_index();
          fraction[c]          = active() ?
                                   geometry().fraction(grid.cell_index(cell->center())) :
                                   (moments.empty() ? 0. : moments[c].v / area);
        }
    return fraction;
  }
} // namespace bsmpm
