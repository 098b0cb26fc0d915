#include <bsmpm/contact/nodal_contact_terms.h>
#include <bsmpm/points/material_points.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

namespace bsmpm
{
  NodalContactTerms::State
  NodalContactTerms::evaluate(
    const ContactTerms                               &terms,
    const ContactNodes                               &nodes,
    const std::vector<RigidBody>                     &bodies,
    const RigidBodyMotion                            &motion,
    const BackgroundGrid                             &grid,
    const Q1CellKernel                               &kernel,
    const LinearAlgebra::distributed::Vector<double> &increment,
    const LinearAlgebra::distributed::Vector<double> *prescribed,
    const ContactPerturbation                        &perturbation)
  {
    constexpr unsigned int        n_grid  = Q1CellKernel::dofs_per_cell;
    const types::global_dof_index n_total = grid.dof_handler().n_dofs();
    const auto                   &points  = nodes.points();
    const auto                   &all     = nodes.nodes();
    State                         state;
    state.points.resize(points.size());

    // Per node and cell of this process: node, cell, G_a, the sums of the
    // previous traction and of the slip along t, the cell's DoFs and the
    // four vectors (c, d and the turning of t in the trial traction's two
    // parts) on its n_dofs DoFs.
    constexpr unsigned int width = 5 + n_grid + 4 * n_dofs;
    std::map<std::pair<unsigned int, unsigned int>, std::vector<double>>
                                         records;
    std::vector<types::global_dof_index> dof_indices(n_grid);
    for (unsigned int q = 0; q < points.size(); ++q)
      {
        const ContactNodes::GaussPoint &point = points[q];
        PointState                     &here  = state.points[q];
        Q1CellKernel::LocalVector       d =
          MaterialPoints::cell_increment(grid.locally_owned_cell(point.cell),
                                         increment,
                                         prescribed,
                                         dof_indices);
        Tensor<1, 2> shift;
        for (unsigned int i = 0; i < n_grid; ++i)
          {
            here.dofs[i] = dof_indices[i];
            if (dof_indices[i] == perturbation.dof)
              d[i] += perturbation.delta;
          }
        if (perturbation.dof >= n_total &&
            perturbation.dof != numbers::invalid_dof_index &&
            (perturbation.dof - n_total) / 2 == point.body)
          shift[(perturbation.dof - n_total) % 2] = perturbation.delta;
        // Moving the body by c moves a gap as moving the point by -c: the
        // body's translation enters as two more DoFs with the shapes -e_x,
        // -e_y.
        const Point<2> st = grid.local_coordinates(point.position, point.cell);
        Tensor<1, 2>   u;
        for (unsigned int i = 0; i < n_grid; ++i)
          {
            here.N[i] = kernel.shape_value(i, st);
            u += d[i] * here.N[i];
          }
        here.N[n_grid]           = Tensor<1, 2>({-1., 0.});
        here.N[n_grid + 1]       = Tensor<1, 2>({0., -1.});
        const Tensor<1, 2> place = motion.end(point.body) + shift;
        const Tensor<1, 2> rigid = place - motion.start(point.body);
        here.x                   = point.position + u;
        here.surface =
          bodies[point.body].to_feature(here.x, place, point.feature);
        const Tensor<1, 2> &n = here.surface.normal;
        const Tensor<1, 2>  t({-n[1], n[0]});
        // Where the outline turns, t turns with n (dt/dx = -n t^T / rho):
        // the trial traction (t_prev - eps (u - u_rigid)) . t feels it
        // through both of its parts.
        const double rho           = here.surface.turning_radius;
        const bool   turning       = std::isfinite(rho) && rho > 0;
        const double turn_previous = turning ? (point.previous * n) / rho : 0.;
        const double turn_slip     = turning ? ((u - rigid) * n) / rho : 0.;
        const double previous      = point.previous * t;
        const double slip          = (u - rigid) * t;
        const unsigned int cell =
          point.cell[1] * grid.n_cells(0) + point.cell[0];
        for (unsigned int v = 0; v < 4; ++v)
          {
            const unsigned int a = point.nodes[v];
            if (a == numbers::invalid_unsigned_int)
              continue;
            const double         w      = point.shape[v] * point.weight;
            std::vector<double> &record = records[{a, cell}];
            if (record.empty())
              {
                record.assign(width, 0.);
                record[0] = a;
                record[1] = cell;
                for (unsigned int i = 0; i < n_grid; ++i)
                  record[5 + i] = dof_indices[i];
              }
            record[2] += w * here.surface.gap;
            record[3] += w * previous;
            record[4] += w * slip;
            for (unsigned int i = 0; i < n_dofs; ++i)
              {
                const double nN = n * here.N[i], tN = t * here.N[i];
                double      *r = &record[5 + n_grid + 4 * i];
                r[0] += w * nN;
                r[1] += w * tN;
                r[2] += w * turn_previous * tN;
                r[3] += w * turn_slip * tN;
              }
          }
      }

    // Every process gets every node's records and sums them by node, then
    // by cell: the same sums on every process, whatever the partition.
    std::vector<double> local;
    local.reserve(records.size() * width);
    for (const auto &[key, record] : records)
      local.insert(local.end(), record.begin(), record.end());
    const std::vector<std::vector<double>> parts =
      Utilities::MPI::all_gather(grid.mpi_communicator(), local);
    std::vector<const double *> sorted;
    for (const auto &part : parts)
      for (unsigned int i = 0; i + width <= part.size(); i += width)
        sorted.push_back(&part[i]);
    std::sort(sorted.begin(),
              sorted.end(),
              [](const double *a, const double *b) {
                return std::make_pair(a[0], a[1]) < std::make_pair(b[0], b[1]);
              });
    state.nodes.resize(all.size());
    std::vector<std::map<types::global_dof_index, std::array<double, 4>>>
      vectors(all.size());
    for (const double *r : sorted)
      {
        const unsigned int a    = static_cast<unsigned int>(r[0]);
        NodeState         &node = state.nodes[a];
        node.gap += r[2];
        node.previous += r[3];
        node.slip += r[4];
        for (unsigned int i = 0; i < n_dofs; ++i)
          {
            const types::global_dof_index dof =
              i < n_grid ? static_cast<types::global_dof_index>(r[5 + i]) :
                           n_total + 2 * all[a].body + (i - n_grid);
            std::array<double, 4> &sum = vectors[a][dof];
            for (unsigned int k = 0; k < 4; ++k)
              sum[k] += r[5 + n_grid + 4 * i + k];
          }
      }

    // The law at every node, on its mean gap, previous traction and slip.
    for (unsigned int a = 0; a < all.size(); ++a)
      {
        NodeState &node = state.nodes[a];
        for (const auto &[dof, sum] : vectors[a])
          {
            node.dofs.push_back(dof);
            node.vectors.push_back(sum);
          }
        const double      W   = all[a].weight;
        const ContactLaw  law = terms.law(bodies[all[a].body]);
        ContactLaw::State history;
        history.multiplier          = all[a].multiplier;
        history.previous_tangential = node.previous / W;
        node.traction = law.evaluate(node.gap / W, node.slip / W, history);
        if (!node.traction.active)
          continue;
        state.symmetric = state.symmetric && node.traction.symmetric();
        if (law.has_friction())
          for (const auto &v : node.vectors)
            if (v[2] != 0 || v[3] != 0)
              state.symmetric = false;
      }

    // The continuous tractions at the points.
    for (unsigned int q = 0; q < points.size(); ++q)
      for (unsigned int v = 0; v < 4; ++v)
        {
          const unsigned int a = points[q].nodes[v];
          if (a == numbers::invalid_unsigned_int ||
              !state.nodes[a].traction.active)
            continue;
          const ContactLaw::Traction &traction = state.nodes[a].traction;
          PointState                 &here     = state.points[q];
          here.active                          = true;
          here.sliding = here.sliding || traction.sliding;
          here.pressure += points[q].shape[v] * traction.pressure;
          here.tangential += points[q].shape[v] * traction.tangential;
        }
    return state;
  }



  void
  NodalContactTerms::node_terms(const NodeState    &node,
                                const double        weight,
                                Vector<double>     &force,
                                FullMatrix<double> &stiffness)
  {
    const unsigned int m = node.dofs.size();
    force.reinit(m);
    stiffness.reinit(m, m);
    const ContactLaw::Traction &T = node.traction;
    if (!T.active)
      return;
    // The force p_a c_a + tau_a d_a and minus its derivative:
    // dp_a = dp/dg dG_a / W_a with dG_a = c_a, and
    // dtau_a = (dtau/dt_prev (-e_prev) + dtau/ds (d_a - e_slip)
    //           + dtau/dp dp/dg c_a) / W_a,
    // e_prev and e_slip the turning of t in the previous traction and the
    // slip (zero on straight edges).
    const double        alpha = -T.d_pressure_d_gap / weight;
    std::vector<double> v(m);
    for (unsigned int j = 0; j < m; ++j)
      {
        const auto &e = node.vectors[j];
        v[j]          = (T.d_tangential_d_previous * e[2] -
                T.d_tangential_d_slip * (e[1] - e[3]) -
                T.d_tangential_d_pressure * T.d_pressure_d_gap * e[0]) /
               weight;
      }
    for (unsigned int i = 0; i < m; ++i)
      {
        const double c = node.vectors[i][0], d = node.vectors[i][1];
        force[i] = T.pressure * c + T.tangential * d;
        for (unsigned int j = 0; j < m; ++j)
          stiffness(i, j) = alpha * c * node.vectors[j][0] + d * v[j];
      }
  }



  bool
  NodalContactTerms::point_terms(const ContactNodes::GaussPoint &point,
                                 const PointState               &state,
                                 FullMatrix<double>             &stiffness)
  {
    // The turning of n and t in c_a and d_a (dn/dx = t t^T / rho, dt/dx =
    // -n t^T / rho): -p(x) (t . N_i)(t . N_j) / rho and tau(x) (n . N_i)
    // (t . N_j) / rho per unit length.
    const double rho = state.surface.turning_radius;
    if (!state.active || !std::isfinite(rho) || !(rho > 0))
      return false;
    const Tensor<1, 2> &n = state.surface.normal;
    const Tensor<1, 2>  t({-n[1], n[0]});
    const double        w = point.weight / rho;
    stiffness.reinit(n_dofs, n_dofs);
    for (unsigned int i = 0; i < n_dofs; ++i)
      for (unsigned int j = 0; j < n_dofs; ++j)
        stiffness(i, j) = w *
                          (-state.pressure * (t * state.N[i]) +
                           state.tangential * (n * state.N[i])) *
                          (t * state.N[j]);
    return true;
  }



  void
  NodalContactTerms::add_newton_terms(
    const State                     &state,
    const ContactNodes              &nodes,
    const BackgroundGrid            &grid,
    const AffineConstraints<double> &constraints,
    RigidBodyMotion                 &motion,
    TrilinosWrappers::SparseMatrix  &tangent,
    TrilinosWrappers::MPI::Vector   &force)
  {
    constexpr unsigned int        n_grid   = Q1CellKernel::dofs_per_cell;
    const types::global_dof_index n_total  = grid.dof_handler().n_dofs();
    const IndexSet               &owned    = grid.locally_owned_dofs();
    const bool                    bordered = motion.has_unknowns();
    const bool                    first =
      Utilities::MPI::this_mpi_process(grid.mpi_communicator()) == 0;
    // A body's translation DoF: its unknown, or -1 where prescribed.
    const auto unknown = [&](const types::global_dof_index dof) {
      return motion.unknown_of((dof - n_total) / 2, (dof - n_total) % 2);
    };

    // The nodes: every process adds the rows of the grid DoFs it owns (and
    // the bordered row entries of the columns it owns; process 0 those of
    // the bodies alone), so that a row is summed in the order of the
    // nodes whatever the partition.
    Vector<double>                       node_force;
    FullMatrix<double>                   node_stiffness;
    std::vector<unsigned int>            rows, columns, body;
    std::vector<types::global_dof_index> row_dofs, column_dofs;
    for (unsigned int a = 0; a < state.nodes.size(); ++a)
      {
        const NodeState &node = state.nodes[a];
        if (!node.traction.active)
          continue;
        node_terms(node, nodes.nodes()[a].weight, node_force, node_stiffness);
        rows.clear();
        columns.clear();
        body.clear();
        row_dofs.clear();
        column_dofs.clear();
        for (unsigned int i = 0; i < node.dofs.size(); ++i)
          if (node.dofs[i] >= n_total)
            body.push_back(i);
          else
            {
              columns.push_back(i);
              column_dofs.push_back(node.dofs[i]);
              if (owned.is_element(node.dofs[i]))
                {
                  rows.push_back(i);
                  row_dofs.push_back(node.dofs[i]);
                }
            }
        FullMatrix<double> block(rows.size(), columns.size());
        Vector<double>     row_force(rows.size());
        for (unsigned int r = 0; r < rows.size(); ++r)
          {
            row_force[r] = node_force[rows[r]];
            for (unsigned int c = 0; c < columns.size(); ++c)
              block(r, c) = node_stiffness(rows[r], columns[c]);
          }
        constraints.distribute_local_to_global(block,
                                               row_dofs,
                                               column_dofs,
                                               tangent);
        constraints.distribute_local_to_global(row_force, row_dofs, force);
        if (!bordered)
          continue;
        // A force-controlled component k of the body's translation: the
        // column -d(grid force)/dc_k, the row -d(force on the body)_k/du,
        // the block and the force on the body.
        for (const unsigned int j : body)
          {
            const int k = unknown(node.dofs[j]);
            if (k < 0)
              continue;
            Vector<double> column(rows.size()), row(rows.size());
            for (unsigned int r = 0; r < rows.size(); ++r)
              {
                column[r] = node_stiffness(rows[r], j);
                row[r]    = node_stiffness(j, rows[r]);
              }
            constraints.distribute_local_to_global(column,
                                                   row_dofs,
                                                   motion.column(k));
            constraints.distribute_local_to_global(row,
                                                   row_dofs,
                                                   motion.row(k));
            if (!first)
              continue;
            motion.contact_force()[k] += node_force[j];
            for (const unsigned int l : body)
              if (unknown(node.dofs[l]) >= 0)
                motion.block()(k, unknown(node.dofs[l])) +=
                  node_stiffness(j, l);
          }
      }

    // The points' turning terms, by the process that owns their cell.
    FullMatrix<double>                   stiffness(n_dofs, n_dofs);
    FullMatrix<double>                   cell_stiffness(n_grid, n_grid);
    Vector<double>                       column(n_grid), row(n_grid);
    std::vector<types::global_dof_index> dof_indices(n_grid);
    const auto                          &points = nodes.points();
    for (unsigned int q = 0; q < points.size(); ++q)
      {
        const PointState &here = state.points[q];
        if (!point_terms(points[q], here, stiffness))
          continue;
        for (unsigned int i = 0; i < n_grid; ++i)
          {
            dof_indices[i] = here.dofs[i];
            for (unsigned int j = 0; j < n_grid; ++j)
              cell_stiffness(i, j) = stiffness(i, j);
          }
        constraints.distribute_local_to_global(cell_stiffness,
                                               dof_indices,
                                               tangent);
        if (!bordered)
          continue;
        for (unsigned int d = 0; d < 2; ++d)
          {
            const int k = motion.unknown_of(points[q].body, d);
            if (k < 0)
              continue;
            for (unsigned int i = 0; i < n_grid; ++i)
              {
                column[i] = stiffness(i, n_grid + d);
                row[i]    = stiffness(n_grid + d, i);
              }
            constraints.distribute_local_to_global(column,
                                                   dof_indices,
                                                   motion.column(k));
            constraints.distribute_local_to_global(row,
                                                   dof_indices,
                                                   motion.row(k));
            for (unsigned int e = 0; e < 2; ++e)
              {
                const int l = motion.unknown_of(points[q].body, e);
                if (l >= 0)
                  motion.block()(k, l) += stiffness(n_grid + d, n_grid + e);
              }
          }
      }
  }



  std::optional<double>
  NodalContactTerms::relative_error(
    const ContactTerms                               &terms,
    const ContactNodes                               &nodes,
    const std::vector<RigidBody>                     &bodies,
    const RigidBodyMotion                            &motion,
    const BackgroundGrid                             &grid,
    const Q1CellKernel                               &kernel,
    const LinearAlgebra::distributed::Vector<double> &increment,
    const LinearAlgebra::distributed::Vector<double> *prescribed,
    const State                                      &state)
  {
    const MPI_Comm communicator = grid.mpi_communicator();
    // The DoFs of the active nodes (the same list on every process).
    std::map<types::global_dof_index, unsigned int> index;
    for (const NodeState &node : state.nodes)
      if (node.traction.active)
        for (const auto dof : node.dofs)
          index.emplace(dof, 0);
    if (index.empty())
      return {};
    unsigned int m = 0;
    for (auto &[dof, i] : index)
      i = m++;
    // The nodes' force on those DoFs (the same on every process).
    const auto nodal_force = [&](const State &s) {
      std::vector<double> f(m, 0.);
      for (const NodeState &node : s.nodes)
        if (node.traction.active)
          for (unsigned int k = 0; k < node.dofs.size(); ++k)
            f[index[node.dofs[k]]] +=
              node.traction.pressure * node.vectors[k][0] +
              node.traction.tangential * node.vectors[k][1];
      return f;
    };
    // The stiffness: the nodes' (on every process alike) and the points'
    // turning terms (of this process's points, summed over processes).
    FullMatrix<double> K(m, m), point_part(m, m);
    Vector<double>     node_force;
    FullMatrix<double> node_stiffness;
    for (unsigned int a = 0; a < state.nodes.size(); ++a)
      {
        const NodeState &node = state.nodes[a];
        node_terms(node, nodes.nodes()[a].weight, node_force, node_stiffness);
        for (unsigned int i = 0; i < node.dofs.size(); ++i)
          for (unsigned int j = 0; j < node.dofs.size(); ++j)
            K(index[node.dofs[i]], index[node.dofs[j]]) += node_stiffness(i, j);
      }
    const types::global_dof_index n_total = grid.dof_handler().n_dofs();
    FullMatrix<double>            stiffness;
    for (unsigned int q = 0; q < nodes.points().size(); ++q)
      if (point_terms(nodes.points()[q], state.points[q], stiffness))
        {
          std::array<types::global_dof_index, n_dofs> dofs;
          for (unsigned int i = 0; i < n_dofs; ++i)
            dofs[i] = i < Q1CellKernel::dofs_per_cell ?
                        state.points[q].dofs[i] :
                        n_total + 2 * nodes.points()[q].body +
                          (i - Q1CellKernel::dofs_per_cell);
          for (unsigned int i = 0; i < n_dofs; ++i)
            for (unsigned int j = 0; j < n_dofs; ++j)
              {
                const auto row = index.find(dofs[i]), col = index.find(dofs[j]);
                if (row != index.end() && col != index.end())
                  point_part(row->second, col->second) += stiffness(i, j);
              }
        }
    std::vector<double> flat(&point_part(0, 0), &point_part(0, 0) + m * m);
    Utilities::MPI::sum(flat, communicator, flat);
    for (unsigned int i = 0; i < m; ++i)
      for (unsigned int j = 0; j < m; ++j)
        K(i, j) += flat[i * m + j];

    const double scale   = K.linfty_norm() > 0 ? K.linfty_norm() : 1.;
    double       largest = 0;
    bool         any     = false;
    const double delta   = 1e-7 * grid.min_cell_size();
    const auto   regime  = [](const State &s) {
      std::vector<int> r;
      for (const NodeState &node : s.nodes)
        r.push_back(node.traction.active + 2 * node.traction.sliding);
      return r;
    };
    const std::vector<int> here = regime(state);
    for (const auto &[dof, j] : index)
      {
        const State plus  = evaluate(terms,
                                    nodes,
                                    bodies,
                                    motion,
                                    grid,
                                    kernel,
                                    increment,
                                    prescribed,
                                    {dof, delta});
        const State minus = evaluate(terms,
                                     nodes,
                                     bodies,
                                     motion,
                                     grid,
                                     kernel,
                                     increment,
                                     prescribed,
                                     {dof, -delta});
        if (regime(plus) != here || regime(minus) != here)
          continue;
        const std::vector<double> fp = nodal_force(plus),
                                  fm = nodal_force(minus);
        for (unsigned int i = 0; i < m; ++i)
          largest =
            std::max(largest,
                     std::abs(-(fp[i] - fm[i]) / (2 * delta) - K(i, j)) /
                       scale);
        any = true;
      }
    if (!any)
      return {};
    return largest;
  }
} // namespace bsmpm
