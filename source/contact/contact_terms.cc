#include <bsmpm/contact/contact_terms.h>

#include <cmath>
#include <tuple>
#include <utility>

namespace bsmpm
{
  void
  ContactTerms::reinit(const ContactLaw::Method method,
                       const double             penalty,
                       const double             tilt_penalty,
                       const double             touching_tolerance)
  {
    this->method       = method;
    eps                = penalty;
    this->tilt_penalty = tilt_penalty;
    tolerance          = touching_tolerance;
  }



  ContactLaw
  ContactTerms::law(const RigidBody &body) const
  {
    return ContactLaw(
      method, eps, body.friction(), body.friction_coefficient(), tolerance);
  }



  ContactPieceState
  ContactTerms::evaluate(const ContactPiece              &piece,
                         const std::vector<RigidBody>    &bodies,
                         const RigidBodyMotion           &motion,
                         const BackgroundGrid            &grid,
                         const Q1CellKernel              &kernel,
                         const Q1CellKernel::LocalVector &d,
                         const Tensor<1, 2>              &body_shift) const
  {
    const RigidBody &body = bodies[piece.body];
    return piece.between_crossings ?
             evaluate_between_crossings(
               piece, body, motion, grid, kernel, d, body_shift) :
             evaluate_per_cell(
               piece, body, motion, grid, kernel, d, body_shift);
  }



  Tensor<1, 2>
  ContactTerms::shape_values(const BackgroundGrid              &grid,
                             const Q1CellKernel                &kernel,
                             const std::array<unsigned int, 2> &cell,
                             const Point<2>                    &x,
                             const Q1CellKernel::LocalVector   &d,
                             ShapeValues                       &N)
  {
    constexpr unsigned int n_grid = Q1CellKernel::dofs_per_cell;
    const Point<2>         st     = grid.local_coordinates(x, cell);
    Tensor<1, 2>           u;
    for (unsigned int i = 0; i < n_grid; ++i)
      {
        N[i] = kernel.shape_value(i, st);
        u += d[i] * N[i];
      }
    N[n_grid]     = Tensor<1, 2>({-1., 0.});
    N[n_grid + 1] = Tensor<1, 2>({0., -1.});
    return u;
  }



  std::pair<double, double>
  ContactTerms::mean_slip(const ContactPiece              &piece,
                          const std::vector<Tensor<1, 2>> &u,
                          const std::vector<SurfacePoint> &surface,
                          const Tensor<1, 2>              &rigid,
                          const double                     length)
  {
    double slip = 0, previous = 0;
    for (unsigned int q = 0; q < piece.positions.size(); ++q)
      if (piece.touching[q])
        {
          const Tensor<1, 2> &nq = surface[q].normal;
          const Tensor<1, 2>  tq({-nq[1], nq[0]});
          slip += piece.weights[q] * ((u[q] - rigid) * tq) / length;
          previous += piece.weights[q] * (piece.previous[q] * tq) / length;
        }
    return {slip, previous};
  }



  ContactPieceState
  ContactTerms::evaluate_per_cell(const ContactPiece              &piece,
                                  const RigidBody                 &body,
                                  const RigidBodyMotion           &motion,
                                  const BackgroundGrid            &grid,
                                  const Q1CellKernel              &kernel,
                                  const Q1CellKernel::LocalVector &d,
                                  const Tensor<1, 2> &body_shift) const
  {
    // The cell's DoFs and, as two more, the body's translation at the
    // increment's end (shape_values()): the extended force and stiffness
    // give the bordered terms of a force-controlled body (RigidBodyMotion)
    // with no other formula than the grid's.
    constexpr unsigned int n   = n_dofs;
    const unsigned int     n_q = piece.positions.size();
    const ContactLaw       law = this->law(body);
    // Where the Gauss points are after the increment, and their gaps to
    // the part of the outline each faces.
    std::vector<ShapeValues>   N(n_q);
    std::vector<Tensor<1, 2>>  u(n_q);
    ContactPieceState          state;
    std::vector<SurfacePoint> &surface = state.surface;
    surface.resize(n_q);
    double length = 0;
    for (unsigned int q = 0; q < n_q; ++q)
      {
        u[q] =
          shape_values(grid, kernel, piece.cell, piece.positions[q], d, N[q]);
        surface[q] = body.to_feature(piece.positions[q] + u[q],
                                     motion.end(piece.body) + body_shift,
                                     piece.features[q]);
        if (!piece.touching[q])
          continue;
        state.gap += piece.weights[q] * surface[q].gap;
        length += piece.weights[q];
        state.normal += piece.weights[q] * surface[q].normal;
        state.midpoint += piece.weights[q] * (piece.positions[q] + u[q]);
      }
    state.force.reinit(n);
    state.stiffness.reinit(n, n);
    if (length == 0)
      return state;
    state.gap /= length;

    const Tensor<1, 2> rigid =
      motion.end(piece.body) + body_shift - motion.start(piece.body);
    ContactLaw::State history;
    history.multiplier = piece.multiplier_pressure;
    double slip        = 0;
    if (law.has_friction())
      std::tie(slip, history.previous_tangential) =
        mean_slip(piece, u, surface, rigid, length);
    const ContactLaw::Traction traction =
      law.evaluate(state.gap, slip, history);
    if (!traction.active)
      return state;
    state.active = true;
    state.normal /= state.normal.norm();
    state.midpoint /= length;
    state.contact_length = length;
    const double L       = length;

    // The potential eps L g^2 / 2 of the mean gap g over the part of the
    // piece that touches: one pressure p = -eps g for the part. One
    // pressure per cell does not over-constrain the bilinear displacement,
    // as one per Gauss point did (its pressure alternated between zero and
    // twice Hertz's); which Gauss points touch is fixed within the Newton
    // iterations (CurveContact::update_touching_parts()), so that the
    // force stays a smooth function of the increment.
    // G_i = -d(L g)/du_i = int n . N_i.
    state.pressure = traction.pressure;
    Vector<double> G(n), T(n);
    for (unsigned int q = 0; q < n_q; ++q)
      {
        if (!piece.touching[q])
          continue;
        const Tensor<1, 2> &nq = surface[q].normal;
        const Tensor<1, 2>  tq({-nq[1], nq[0]});
        for (unsigned int i = 0; i < n; ++i)
          {
            G[i] += piece.weights[q] * (nq * N[q][i]);
            T[i] += piece.weights[q] * (tq * N[q][i]);
          }
        state.add_force(piece.positions[q] + u[q],
                        piece.weights[q] * state.pressure * nq);
        // p dn/dx with dn/dx = (I - n n) / rho where the surface turns.
        const double rho = surface[q].turning_radius;
        if (std::isfinite(rho) && rho > 0)
          for (unsigned int i = 0; i < n; ++i)
            for (unsigned int j = 0; j < n; ++j)
              state.stiffness(i, j) -=
                piece.weights[q] * state.pressure / rho *
                (N[q][i] * N[q][j] - (nq * N[q][i]) * (nq * N[q][j]));
      }
    for (unsigned int i = 0; i < n; ++i)
      {
        state.force[i] = state.pressure * G[i];
        for (unsigned int j = 0; j < n; ++j)
          state.stiffness(i, j) += -traction.d_pressure_d_gap / L * G[i] * G[j];
      }
    add_tilt_terms(piece, N, u, surface, state);
    if (!law.has_friction())
      return state;

    // The tangential traction t_T T_i: T_i = -d(L s)/du_i, and while
    // sliding t_T follows p.
    state.sliding        = traction.sliding;
    state.symmetric      = traction.symmetric();
    state.tangential     = traction.tangential;
    state.sliding_length = state.sliding ? length : 0.;
    // dt_T = dt_T/dp dp + dt_T/ds ds (Coulomb: one of the two is zero).
    for (unsigned int i = 0; i < n; ++i)
      {
        state.force[i] += state.tangential * T[i];
        for (unsigned int j = 0; j < n; ++j)
          state.stiffness(i, j) -= (traction.d_tangential_d_gap() * G[j] +
                                    traction.d_tangential_d_slip * T[j]) /
                                   L * T[i];
      }
    // Where the outline turns, t_q turns with n_q (dn/dx = t t^T / rho,
    // dt/dx = -n t^T / rho): T_i and, while sticking, the trial traction
    // (the mean of (t_previous - eps (u - u_rigid)) . t) feel it, the
    // latter as the trial traction of the normal components.
    for (unsigned int q = 0; q < n_q; ++q)
      {
        const double rho = surface[q].turning_radius;
        if (!piece.touching[q] || !std::isfinite(rho) || !(rho > 0))
          continue;
        const Tensor<1, 2> &nq = surface[q].normal;
        const Tensor<1, 2>  tq({-nq[1], nq[0]});
        const double        w = piece.weights[q] / rho;
        const double        trial_turning =
          law.trial_traction(piece.previous[q] * nq, (u[q] - rigid) * nq);
        const double c  = traction.d_tangential_d_previous * trial_turning / L;
        state.symmetric = false;
        for (unsigned int i = 0; i < n; ++i)
          for (unsigned int j = 0; j < n; ++j)
            state.stiffness(i, j) +=
              w * (c * T[i] + state.tangential * (nq * N[q][i])) *
              (tq * N[q][j]);
      }
    for (unsigned int q = 0; q < n_q; ++q)
      if (piece.touching[q])
        {
          const Tensor<1, 2> &nq = surface[q].normal;
          state.add_force(piece.positions[q] + u[q],
                          piece.weights[q] * state.tangential *
                            Tensor<1, 2>({-nq[1], nq[0]}));
        }
    return state;
  }



  ContactPieceState
  ContactTerms::evaluate_between_crossings(const ContactPiece    &piece,
                                           const RigidBody       &body,
                                           const RigidBodyMotion &motion,
                                           const BackgroundGrid  &grid,
                                           const Q1CellKernel    &kernel,
                                           const Q1CellKernel::LocalVector &d,
                                           const Tensor<1, 2> &body_shift) const
  {
    // The curve's displacement is taken at the two crossings and linear
    // between them, u = (1 - phi) u_0 + phi u_1 (on a straight curve the
    // bilinear field's own trace): a Gauss point X moves to X + u, its gap
    // g to the outline is measured there, and its pressure is
    // p = max(0, lambda - eps g), lambda interpolated as u from the
    // crossings' multipliers. The potential int (max(0, lambda - eps g)^2
    // - lambda^2) / (2 eps) ds then has the force int p n . N and the
    // tangent eps int (n . N)(n . N)^T ds (with N = (1 - phi) N(x_0) +
    // phi N(x_1)), plus the turning of n where the outline turns. The
    // gap has only the two crossings' freedom per piece, so a pressure
    // per Gauss point does not over-constrain it, and it is held at the
    // grid lines, where alternating up and down would hide from a mean
    // per cell. As in evaluate_per_cell(), the body's translation enters
    // as two more DoFs.
    constexpr unsigned int n     = n_dofs;
    const ContactLaw       law   = this->law(body);
    const Tensor<1, 2>     place = motion.end(piece.body) + body_shift;
    const Tensor<1, 2>     rigid = place - motion.start(piece.body);
    ContactPieceState      state;
    state.force.reinit(n);
    state.stiffness.reinit(n, n);
    std::array<ShapeValues, 2>  N_end;
    std::array<Tensor<1, 2>, 2> u_end;
    for (unsigned int e = 0; e < 2; ++e)
      {
        u_end[e] =
          shape_values(grid, kernel, piece.cell, piece.ends[e], d, N_end[e]);
        state.end_places[e] = piece.ends[e] + u_end[e];
        state.end_normals[e] =
          body.to_feature(state.end_places[e], place, piece.end_features[e])
            .normal;
      }
    ShapeValues    N;
    Vector<double> G(n), T(n);
    double         length = 0;
    for (unsigned int q = 0; q < piece.positions.size(); ++q)
      {
        const double w      = piece.weights[q];
        const double phi[2] = {1 - piece.phi[q], piece.phi[q]};
        for (unsigned int e = 0; e < 2; ++e)
          state.end_weights[e] += w * phi[e];
        for (unsigned int i = 0; i < n; ++i)
          N[i] = phi[0] * N_end[0][i] + phi[1] * N_end[1][i];
        const Tensor<1, 2> u = phi[0] * u_end[0] + phi[1] * u_end[1];
        const SurfacePoint surface =
          body.to_feature(piece.positions[q] + u, place, piece.features[q]);
        for (unsigned int e = 0; e < 2; ++e)
          state.end_weighted_gaps[e] += w * phi[e] * surface.gap;
        const Tensor<1, 2> &nq = surface.normal;
        const Tensor<1, 2>  tq({-nq[1], nq[0]});
        // Coulomb's return map at the Gauss point, on its slip relative
        // to the body and the traction of the last increment there.
        ContactLaw::State history;
        history.multiplier =
          phi[0] * piece.end_multipliers[0] + phi[1] * piece.end_multipliers[1];
        history.previous_tangential = piece.previous[q] * tq;
        const ContactLaw::Traction traction =
          law.evaluate(surface.gap, (u - rigid) * tq, history);
        if (!traction.active)
          continue;
        state.active   = true;
        const double p = traction.pressure;
        length += w;
        state.gap += w * surface.gap;
        state.pressure += w * p;
        state.normal += w * nq;
        state.midpoint += w * (piece.positions[q] + u);
        for (unsigned int i = 0; i < n; ++i)
          {
            G[i] = nq * N[i];
            T[i] = tq * N[i];
          }
        double t_T = 0;
        if (law.has_friction())
          {
            const bool sliding = traction.sliding;
            t_T                = traction.tangential;
            state.sliding      = state.sliding || sliding;
            state.symmetric    = state.symmetric && traction.symmetric();
            state.sliding_length += sliding ? w : 0.;
            for (unsigned int e = 0; e < 2; ++e)
              state.end_sliding[e] += sliding ? w * phi[e] : 0.;
            state.tangential += w * t_T;
            // dt_T = dt_T/dp dp + dt_T/ds ds (Coulomb: one of the two is
            // zero).
            for (unsigned int i = 0; i < n; ++i)
              for (unsigned int j = 0; j < n; ++j)
                state.stiffness(i, j) -= w *
                                         (traction.d_tangential_d_gap() * G[j] +
                                          traction.d_tangential_d_slip * T[j]) *
                                         T[i];
            // Where the outline turns, the tangent t turns with n:
            // dn/dx = t t^T / rho and dt/dx = -n t^T / rho, which the force
            // t_T t . N_i and, while sticking, the trial traction
            // (t_previous - eps (u - u_rigid)) . t feel.
            const double rho = surface.turning_radius;
            if (std::isfinite(rho) && rho > 0)
              {
                const double trial_turning =
                  traction.d_tangential_d_previous *
                  law.trial_traction(piece.previous[q] * nq, (u - rigid) * nq);
                state.symmetric = false;
                for (unsigned int i = 0; i < n; ++i)
                  for (unsigned int j = 0; j < n; ++j)
                    state.stiffness(i, j) +=
                      w / rho * (trial_turning * T[i] + t_T * G[i]) * T[j];
              }
          }
        for (unsigned int i = 0; i < n; ++i)
          {
            state.force[i] += w * (p * G[i] + t_T * T[i]);
            for (unsigned int j = 0; j < n; ++j)
              state.stiffness(i, j) +=
                w * -traction.d_pressure_d_gap * G[i] * G[j];
          }
        // p dn/dx with dn/dx = (I - n n) / rho where the outline turns.
        const double rho = surface.turning_radius;
        if (p > 0 && std::isfinite(rho) && rho > 0)
          for (unsigned int i = 0; i < n; ++i)
            for (unsigned int j = 0; j < n; ++j)
              state.stiffness(i, j) -=
                w * p / rho * (N[i] * N[j] - (nq * N[i]) * (nq * N[j]));
        const Tensor<1, 2> t = p * nq + t_T * tq;
        const Point<2>     x = piece.positions[q] + u;
        state.add_force(x, w * t);
        for (unsigned int e = 0; e < 2; ++e)
          {
            state.end_gaps[e] += w * phi[e] * surface.gap;
            state.end_tractions[e] += w * phi[e] * t;
            state.end_moments[e] += moment_about_origin(x, w * phi[e] * t);
          }
      }
    for (unsigned int e = 0; e < 2; ++e)
      if (state.end_weights[e] > 0)
        state.end_tractions[e] /= state.end_weights[e];
    if (!state.active)
      return state;
    state.contact_length = length;
    state.gap /= length;
    state.pressure /= length;
    state.tangential /= length;
    state.normal /= state.normal.norm();
    state.midpoint /= length;
    return state;
  }



  void
  ContactTerms::add_tilt_terms(const ContactPiece              &piece,
                               const std::vector<ShapeValues>  &N,
                               const std::vector<Tensor<1, 2>> &u,
                               const std::vector<SurfacePoint> &surface,
                               ContactPieceState               &state) const
  {
    // The gap's tilt along the touching part: with xi the distance along
    // the part from its centre (arc length of the Gauss points at the
    // increment's start), m = int_A xi g ds and I = int_A xi^2 ds, the
    // potential eps_t m^2 / (2 I) holds the linear part m / I of the gap.
    // One pressure per cell leaves it free: the nodes of the cells under a
    // flat rigid base may move up and down in turn with every cell's mean
    // gap zero, and plastic soil does not resist that (doc/contact.md,
    // "The tilt of the gap"). dm/du_i = int xi n . N_i = H_i; force
    // -eps_t m / I H_i, stiffness eps_t / I (H H^T + m int xi (N_i . N_j -
    // (n . N_i) (n . N_j)) / rho) where the outline turns.
    if (tilt_penalty == 0)
      return;
    const unsigned int  n_q = piece.positions.size();
    std::vector<double> xi(n_q, 0.);
    double              s = 0, centre = 0, L = 0;
    // The Gauss points lie in order along the curve: xi counts the arc
    // length of those that do not touch too.
    for (unsigned int q = 0; q < n_q; ++q)
      {
        xi[q] = s + piece.weights[q] / 2;
        s += piece.weights[q];
        if (!piece.touching[q])
          continue;
        centre += piece.weights[q] * xi[q];
        L += piece.weights[q];
      }
    centre /= L;
    double m = 0, I = 0;
    for (unsigned int q = 0; q < n_q; ++q)
      if (piece.touching[q])
        {
          xi[q] -= centre;
          m += piece.weights[q] * xi[q] * surface[q].gap;
          I += piece.weights[q] * xi[q] * xi[q];
        }
    if (!(I > 0))
      return;
    const unsigned int n = state.force.size();
    Vector<double>     H(n);
    for (unsigned int q = 0; q < n_q; ++q)
      if (piece.touching[q])
        {
          const Tensor<1, 2> &nq = surface[q].normal;
          for (unsigned int i = 0; i < n; ++i)
            H[i] += piece.weights[q] * xi[q] * (nq * N[q][i]);
          // The traction -eps_t m / I xi n on the curve.
          state.add_force(piece.positions[q] + u[q],
                          piece.weights[q] * (-tilt_penalty * m / I * xi[q]) *
                            nq);
          const double rho = surface[q].turning_radius;
          if (std::isfinite(rho) && rho > 0)
            for (unsigned int i = 0; i < n; ++i)
              for (unsigned int j = 0; j < n; ++j)
                state.stiffness(i, j) +=
                  tilt_penalty * m / I * piece.weights[q] * xi[q] / rho *
                  (N[q][i] * N[q][j] - (nq * N[q][i]) * (nq * N[q][j]));
        }
    for (unsigned int i = 0; i < n; ++i)
      {
        state.force[i] -= tilt_penalty * m / I * H[i];
        for (unsigned int j = 0; j < n; ++j)
          state.stiffness(i, j) += tilt_penalty / I * H[i] * H[j];
      }
  }
} // namespace bsmpm
