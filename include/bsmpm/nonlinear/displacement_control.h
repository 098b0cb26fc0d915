#ifndef bsmpm_displacement_control_h
#define bsmpm_displacement_control_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <deal.II/lac/la_parallel_vector.h>
#include <deal.II/lac/trilinos_vector.h>

#include <bsmpm/geometry/background_grid.h>

#include <vector>

namespace bsmpm
{
  using namespace dealii;

  /**
   * Displacement control of the prescribed loads ("Loading/Control =
   * displacement"): the load factor lambda of the tractions and the body
   * force becomes an unknown of every load step, fixed by the condition that
   * one displacement component, c . u at the grid vertex nearest to
   * 'Control point' along 'Control direction', grows by 'Displacement
   * increment' per step. The load factor can then fall after a peak, or
   * stay at a plateau, where load control cannot pass the limit load.
   *
   * Per Newton iteration (Batoz and Dhatt 1979, "Incremental displacement
   * algorithms for nonlinear problems", IJNME 14, 1262-1267) with the
   * residual R = R_0(x) + d lambda F_ref (F_ref the loads of lambda = 1)
   * and the tangent K: K a = R, K b = F_ref, and the correction
   * dx = a + d(d lambda) b with d(d lambda) = (target - c.x - c.a) / (c.b),
   * so that after every correction c . x is the prescribed increment.
   * This class holds the parameters, the control DoFs and that formula;
   * IncrementSolver does the solves.
   */
  class DisplacementControl
  {
  public:
    static void
    declare_parameters(ParameterHandler &prm);
    void
    parse_parameters(ParameterHandler &prm);

    bool
    enabled() const
    {
      return active;
    }

    /** The prescribed growth of c . u per load step (m). */
    double
    displacement_increment() const
    {
      return step_increment;
    }

    /** Finds the DoFs of the grid vertex nearest to the control point.
     * Collective. */
    void
    locate(const BackgroundGrid &grid);

    /** c . x over all processes (x with the grid's locally owned DoFs). */
    double
    value(const LinearAlgebra::distributed::Vector<double> &x) const;
    double
    value(const TrilinosWrappers::MPI::Vector &x) const;

    /** The vertex that controls, for messages. */
    const Point<2> &
    vertex() const
    {
      return control_vertex;
    }

  private:
    bool         active = false;
    Point<2>     control_point;
    Tensor<1, 2> direction;
    double       step_increment = 0;

    Point<2> control_vertex;
    MPI_Comm communicator = MPI_COMM_WORLD;
    /** The locally owned DoFs of the control vertex, with their weights. */
    std::vector<types::global_dof_index> dofs;
    std::vector<double>                  weights;
  };
} // namespace bsmpm

#endif
