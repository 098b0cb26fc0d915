#include <bsmpm/contact/contact_tangent_check.h>

#include <algorithm>
#include <array>
#include <cmath>

namespace bsmpm
{
  std::optional<double>
  ContactTangentCheck::relative_error(const ContactTerms              &terms,
                                      const ContactPiece              &piece,
                                      const std::vector<RigidBody>    &bodies,
                                      const RigidBodyMotion           &motion,
                                      const BackgroundGrid            &grid,
                                      const Q1CellKernel              &kernel,
                                      const ContactPieceState         &state,
                                      const Q1CellKernel::LocalVector &d)
  {
    constexpr unsigned int n = Q1CellKernel::dofs_per_cell;
    // Central differences of the force on the cell's DoFs and the body's
    // translation by each of them, against minus the stiffness. Their
    // truncation error grows where a rough surface's smoothed law bends
    // (over tractions of 10 p: sharply where p is small); at 1e-7 of a cell
    // it stays below 1e-6 there (1e-6 of a cell: 1.5e-5), and the
    // round-off below 1e-9 elsewhere.
    const double step = 1e-7 * grid.min_cell_size();
    // A piece that touches by less than the differences move it has the
    // kink where it opens between them: no derivative to compare. (p / eps
    // is the distance to the kink: -g for the penalty, lambda / eps - g for
    // the augmented Lagrangian.)
    if (state.pressure / terms.penalty() < 10 * step)
      return std::nullopt;
    double largest = 0, difference = 0;
    for (unsigned int j = 0; j < n + 2; ++j)
      {
        std::array<ContactPieceState, 2> sides;
        for (unsigned int side = 0; side < 2; ++side)
          {
            const double              sign = side == 0 ? 1. : -1.;
            Q1CellKernel::LocalVector dj   = d;
            Tensor<1, 2>              shift;
            if (j < n)
              dj[j] += sign * step;
            else
              shift[j - n] = sign * step;
            sides[side] =
              terms.evaluate(piece, bodies, motion, grid, kernel, dj, shift);
          }
        // A Gauss point that starts or stops touching or sliding between
        // the two sides puts a kink of the law between them.
        for (const ContactPieceState &side : sides)
          if (side.active != state.active ||
              side.contact_length != state.contact_length ||
              side.sliding_length != state.sliding_length)
            return std::nullopt;
        const auto force = [&](const unsigned int side, const unsigned int i) {
          return sides[side].active ? sides[side].force[i] : 0.;
        };
        for (unsigned int i = 0; i < n + 2; ++i)
          {
            const double fi = force(0, i) - force(1, i);
            largest = std::max(largest, std::abs(state.stiffness(i, j)));
            difference =
              std::max(difference,
                       std::abs(state.stiffness(i, j) + fi / (2 * step)));
          }
      }
    return largest > 0 ? difference / largest : 0.;
  }



  void
  ContactTangentCheck::add(const std::optional<double> &error,
                           const bool                   sliding)
  {
    if (!error)
      return;
    largest_error = std::max(largest_error, *error);
    ++n_compared;
    if (sliding)
      ++n_sliding;
  }



  void
  ContactTangentCheck::gather(const MPI_Comm communicator)
  {
    largest_error  = Utilities::MPI::max(largest_error, communicator);
    total_compared = Utilities::MPI::sum(double(n_compared), communicator);
    total_sliding  = Utilities::MPI::sum(double(n_sliding), communicator);
  }



  void
  ContactTangentCheck::record(std::map<std::string, double> &quantities) const
  {
    quantities["contact_tangent_error"]          = largest_error;
    quantities["contact_tangent_checks"]         = total_compared;
    quantities["contact_tangent_checks_sliding"] = total_sliding;
  }
} // namespace bsmpm
