#include <bsmpm/contact/rigid_body_motion.h>

#include <cmath>
#include <sstream>

namespace bsmpm
{
  void
  RigidBodyMotion::initialize(const std::vector<RigidBody> &bodies)
  {
    unknowns.clear();
    index.assign(bodies.size(), {{-1, -1}});
    sections.clear();
    frictional.clear();
    for (const RigidBody &body : bodies)
      {
        sections.push_back(body.section());
        frictional.push_back(body.friction() ==
                             RigidBody::Friction::frictional);
      }
    for (unsigned int b = 0; b < bodies.size(); ++b)
      for (unsigned int d = 0; d < 2; ++d)
        if (bodies[b].force_controlled(d))
          {
            index[b][d] = unknowns.size();
            unknowns.push_back(Unknown{b, d});
          }
    start_place.assign(bodies.size(), Tensor<1, 2>());
    for (unsigned int b = 0; b < bodies.size(); ++b)
      start_place[b] = bodies[b].displacement(0.);
    end_place = start_place;
    solved_start.assign(bodies.size(), Tensor<1, 2>());
    solved_end  = solved_start;
    last_motion = solved_start;
    approaches  = solved_start;
    last_delta  = 0;
  }



  void
  RigidBodyMotion::begin_increment(const std::vector<RigidBody> &bodies,
                                   const double                  from,
                                   const double                  to)
  {
    delta = to - from;
    approaches.assign(bodies.size(), Tensor<1, 2>());
    for (unsigned int b = 0; b < bodies.size(); ++b)
      {
        // The prediction: the last increment's motion per unit load. A
        // body under a force that grows steadily moves on as it did.
        solved_end[b] = solved_start[b];
        if (last_delta > 0)
          solved_end[b] += delta / last_delta * last_motion[b];
        start_place[b] = bodies[b].displacement(from) + solved_start[b];
        end_place[b]   = bodies[b].displacement(to) + solved_end[b];
      }
  }



  Vector<double>
  RigidBodyMotion::values() const
  {
    Vector<double> c(unknowns.size());
    for (unsigned int k = 0; k < unknowns.size(); ++k)
      c[k] = solved_end[unknowns[k].body][unknowns[k].component];
    return c;
  }



  Vector<double>
  RigidBodyMotion::start_values() const
  {
    Vector<double> c(unknowns.size());
    for (unsigned int k = 0; k < unknowns.size(); ++k)
      c[k] = solved_start[unknowns[k].body][unknowns[k].component];
    return c;
  }



  void
  RigidBodyMotion::set_values(const Vector<double> &c)
  {
    for (unsigned int k = 0; k < unknowns.size(); ++k)
      {
        const auto [b, d] = unknowns[k];
        end_place[b][d] += c[k] - solved_end[b][d];
        solved_end[b][d] = c[k];
      }
  }



  void
  RigidBodyMotion::add(const double factor, const Vector<double> &dc)
  {
    for (unsigned int k = 0; k < unknowns.size(); ++k)
      {
        const auto [b, d] = unknowns[k];
        solved_end[b][d] += factor * dc[k];
        end_place[b][d] += factor * dc[k];
      }
  }



  void
  RigidBodyMotion::approach(const unsigned int b, const Tensor<1, 2> &shift)
  {
    solved_end[b] += shift;
    end_place[b] += shift;
    approaches[b] += shift;
  }



  void
  RigidBodyMotion::reset_bordered_terms(const IndexSet &locally_owned,
                                        const MPI_Comm  mpi_communicator,
                                        const double    stiffness_scale)
  {
    communicator         = mpi_communicator;
    scale                = stiffness_scale;
    const unsigned int m = unknowns.size();
    columns.resize(m);
    rows.resize(m);
    for (unsigned int k = 0; k < m; ++k)
      {
        columns[k].reinit(locally_owned, communicator);
        rows[k].reinit(locally_owned, communicator);
      }
    h_block.reinit(m, m);
    force_on_body.reinit(m);
    residual.reinit(m);
  }



  void
  RigidBodyMotion::finish_bordered_terms(const std::vector<RigidBody> &bodies,
                                         const double                  t)
  {
    const unsigned int m = unknowns.size();
    for (unsigned int k = 0; k < m; ++k)
      {
        columns[k].compress(VectorOperation::add);
        rows[k].compress(VectorOperation::add);
      }
    std::vector<double> sums(m * m + m);
    for (unsigned int k = 0; k < m; ++k)
      {
        for (unsigned int l = 0; l < m; ++l)
          sums[k * m + l] = h_block(k, l);
        sums[m * m + k] = force_on_body[k];
      }
    Utilities::MPI::sum(sums, communicator, sums);
    for (unsigned int k = 0; k < m; ++k)
      {
        for (unsigned int l = 0; l < m; ++l)
          h_block(k, l) = sums[k * m + l];
        force_on_body[k]  = sums[m * m + k];
        const auto [b, d] = unknowns[k];
        residual[k]       = bodies[b].applied_force(t)[d] + force_on_body[k];
      }
  }



  Vector<double>
  RigidBodyMotion::bordered_correction(
    const TrilinosWrappers::MPI::Vector              &X,
    const std::vector<TrilinosWrappers::MPI::Vector> &Y) const
  {
    const unsigned int m = unknowns.size();
    // The Schur complement S = H - G Y and its right-hand side r_c - G X:
    // the body's stiffness against its free motion with the grid's
    // response to it.
    FullMatrix<double> S(h_block);
    Vector<double>     rhs(residual);
    for (unsigned int k = 0; k < m; ++k)
      {
        rhs[k] -= rows[k] * X;
        for (unsigned int l = 0; l < m; ++l)
          S(k, l) -= rows[k] * Y[l];
      }
    // A free component that no contact resists has S_kk = 0 (nothing
    // touches the body, or only a smooth surface across that direction):
    // the body has no equilibrium under its force.
    for (unsigned int k = 0; k < m; ++k)
      {
        const auto [b, d] = unknowns[k];
        std::ostringstream message;
        // A frictional surface across the direction holds at most mu times
        // its pressure, nothing where the body only touches: then it
        // slides, and sliding has no stiffness.
        message << sections[b] << ": nothing resists its force-controlled "
                << (d == 0 ? "x" : "y")
                << " motion (its stiffness in that direction is " << S(k, k)
                << " N/m^2, that of one cell in contact " << scale
                << "): it touches no boundary curve (a force that pulls it "
                   "off), "
                << (frictional[b] ?
                      "only a frictional one across that direction that "
                      "the force makes slide (friction holds at most mu "
                      "times the pressure, nothing where the body only "
                      "touches)" :
                      "only a smooth one across that direction")
                << ", or material that yields freely under it (a force "
                   "beyond the limit load). Place it touching the body, "
                << (frictional[b] ? "make its surface rough, " :
                                    "make its surface rough or frictional, ")
                << "prescribe that component (Displacement), or, beyond a "
                   "limit load, ramp the force of a plastic material: the "
                   "run then ends at the limit load (doc/limit-loads.md).";
        AssertThrow(S(k, k) > 1e-10 * scale,
                    ExcUnresistedMotion(message.str()));
      }
    if (m == 2)
      {
        const double det = S(0, 0) * S(1, 1) - S(0, 1) * S(1, 0);
        AssertThrow(det > 1e-10 * S(0, 0) * S(1, 1),
                    ExcUnresistedMotion(
                      "The rigid bodies' two force-controlled "
                      "components are not both resisted by "
                      "contact: the stiffness against them is "
                      "singular (a body on a smooth surface "
                      "inclined to both)."));
      }
    FullMatrix<double> inverse(m, m);
    inverse.invert(S);
    Vector<double> dc(m);
    inverse.vmult(dc, rhs);
    return dc;
  }



  void
  RigidBodyMotion::accept()
  {
    for (unsigned int b = 0; b < solved_start.size(); ++b)
      {
        last_motion[b]  = solved_end[b] - solved_start[b] - approaches[b];
        solved_start[b] = solved_end[b];
        start_place[b]  = end_place[b];
      }
    last_delta = delta;
  }



  void
  RigidBodyMotion::record(const std::vector<RigidBody>  &bodies,
                          const double                   t,
                          std::map<std::string, double> &quantities) const
  {
    for (unsigned int b = 0; b < bodies.size(); ++b)
      if (bodies[b].has_free_motion())
        {
          const Tensor<1, 2> f = bodies[b].applied_force(t);
          quantities[bodies[b].name() + "_applied_force_x"] = f[0];
          quantities[bodies[b].name() + "_applied_force_y"] = f[1];
        }
  }
} // namespace bsmpm
