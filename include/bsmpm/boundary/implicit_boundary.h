#ifndef bsmpm_implicit_boundary_h
#define bsmpm_implicit_boundary_h

#include <deal.II/base/parameter_handler.h>

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/la_parallel_vector.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/lac/vector.h>

#include <bsmpm/boundary/boundary_curves.h>
#include <bsmpm/boundary/support_method.h>
#include <bsmpm/boundary/support_stress.h>
#include <bsmpm/geometry/background_grid.h>
#include <bsmpm/points/q1_cell_kernel.h>
#include <bsmpm/verification/exact_solution.h>

#include <array>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace bsmpm
{
  using namespace dealii;

  /**
   * Supports on the B-spline boundary by the implicit boundary method (IBM,
   * paper Sec. 3.5). Near a supported curve the displacement is
   *
   *   u = P(D(phi)) w + u^a,   w = M d,
   *
   * with phi the signed distance to the curve (positive inside the body) and
   * D the D-function of eq. 20, rising from 0 on the curve to 1 at the inner
   * edge of a band of width delta:
   * - fixed (and prescribed displacement): P = D I;
   * - roller (and, consistent formulation only, a prescribed normal
   *   displacement): P = I + (D - 1) n n^T, so only the normal component is
   *   held
   *   (method-notes Sec. 5: the boundary-frame form, exact on inclined
   *   boundaries). The paper's form with the rotation J_T of eq. 26 is
   *   available as "Formulation = D-scaled with J_T".
   *
   * The material points integrate the regular stiffness (D = 1 there); the
   * band adds k2 + k2^T + k3 of eqs. 21-28, integrated per curve piece with
   * Gauss points along the piece times Gauss points across the band
   * (paper Fig. 3b). Over the band, int D'^2 = 4 / (3 delta): k3 acts as a
   * penalty of order E / delta.
   *
   * A prescribed displacement enters through nodal values d^a, the global
   * least-squares fit of u^a along the boundary (eq. 36), and the force
   * f^d = int Bbar^T C B d^a (eq. 33).
   *
   * A SupportMethod, registered as "implicit boundary".
   */
  class ImplicitBoundary : public SupportMethod
  {
  public:
    /** A quadrature point of the band, kept for output and for the
     * tangent of nonlinear materials (ConstitutiveUpdate::SupportBandPoint). */
    using BandPoint = SupportMethod::BandPoint;

    ImplicitBoundary();

    static void
    declare_parameters(ParameterHandler &prm);
    void
    parse_parameters(ParameterHandler &prm) override;

    /** The D-function of eq. 20 and its derivative. */
    static double
    d_function(const double phi, const double delta);
    static double
    d_function_derivative(const double phi, const double delta);

    /** Band width delta on @p grid. */
    double
    band_width(const BackgroundGrid &grid) const
    {
      return relative_band_width * grid.min_cell_size();
    }

    /**
     * Adds the band terms of all IBM supports on locally owned cells to
     * @p matrix, and to @p rhs the band's share of the internal force of the
     * previous steps and of the force of a prescribed displacement: through
     * @p prescribed (d^a with ghosts, frame and paper formulations) or, in
     * the consistent formulation, from the prescribed values themselves
     * changed over @p increment (the context's exact solution for
     * "displacement exact"). With @p only, the supports of that curve alone
     * (SupportReaction). With a B-bar kernel, @p moments (by
     * active_cell_index) give each cell's centroid for the B-bar stress of
     * the band's cross terms.
     *
     * In finite strain, the consistent formulation adds nothing here
     * (but records the band points and the step's prescribed data): its
     * band terms depend on the stress of the step's deformation and join
     * the Newton system per iteration (add_finite_strain_terms()).
     */
    void
    assemble(const Context                                    &context,
             const LoadIncrement                              &increment,
             const LinearAlgebra::distributed::Vector<double> *prescribed,
             const std::vector<CellMoments>                   *moments,
             const AffineConstraints<double>                  &constraints,
             TrilinosWrappers::SparseMatrix                   &matrix,
             TrilinosWrappers::MPI::Vector                    &rhs,
             const BoundaryCurve *only = nullptr) override;

    /**
     * Finite strain, consistent formulation (doc/finite-strain.md,
     * "Supports in finite strain"): the band's share of the internal force
     * at the step's increment @p increment (with ghost values), for DoF i
     *
     *   f_i = sum_band w [P(f) : Delta_i + (A(f) : E) : (G_i + Delta_i)],
     *
     * f = 1 + grad w the grid's relative deformation gradient, E =
     * Delta(d) - Delta_g the band's mismatch of u = w - (1 - D) P (w(x_b) -
     * g), G_i the gradient of shape function i and Delta_i its band
     * correction, P the first Piola stress of @p stress with the curve's
     * state at the band point and A = dP/df: the band's stress P(f + E)
     * linearised about f. Added to @p internal_force, its derivative to
     * @p tangent unless nullptr, through @p constraints. With the linear
     * P = sigma_n + C eps these are the terms of assemble(). The prescribed
     * data are those of the last assemble(). With @p only, that curve's
     * supports
     * alone. Nothing for the frame and paper formulations.
     */
    void
    add_finite_strain_terms(
      const Context                                    &context,
      const LinearAlgebra::distributed::Vector<double> &increment,
      const SupportStress                              &stress,
      const AffineConstraints<double>                  &constraints,
      TrilinosWrappers::SparseMatrix                   *tangent,
      TrilinosWrappers::MPI::Vector                    &internal_force,
      const BoundaryCurve *only = nullptr) const override;

    /** Whether any IBM support prescribes a displacement (both
     * components: a normal displacement is imposed by the consistent
     * formulation only, which needs no fit). */
    static bool
    prescribes_displacement(const BoundaryCurves &curves);

    /**
     * Whether prescribed displacements go through nodal values d^a fitted
     * by least squares (fit_prescribed_displacement(), the paper's eq. 36:
     * the D-scaled formulations). The consistent formulation imposes
     * the prescribed value g on the boundary itself, u = w + (1 - D)(g -
     * w(x_b)), and needs no fit.
     */
    bool
    fits_prescribed_displacement(const BoundaryCurves &curves) const override
    {
      return formulation != Formulation::consistent &&
             prescribes_displacement(curves);
    }

    /**
     * The least-squares nodal values d^a of eq. 36 for the prescribed
     * displacement's change u^a over @p increment, over the pieces of IBM
     * displacement
     * supports; zero at DoFs whose support does not meet them. @p mass is a
     * matrix with the system's sparsity pattern, used as work space.
     * Returns the root mean square of M d^a - u^a along those pieces.
     */
    double
    fit_prescribed_displacement(
      const Context                              &context,
      const LoadIncrement                        &increment,
      TrilinosWrappers::SparseMatrix             &mass,
      LinearAlgebra::distributed::Vector<double> &prescribed) const override;

    /** The band changes the displacement of the points in it. */
    bool
    displaces_points() const override
    {
      return true;
    }

    /**
     * The displacement increment of a point at @p x (before it moves) whose
     * grid increment is @p w, if @p x lies in the band of an IBM support:
     * w - (1 - D) P w(x_b) (consistent formulation, with @p field the grid
     * increment anywhere in the point's cell and x_b the nearest boundary
     * point) or P(D) w; else w. Returns D (1 outside every band).
     */
    double
    support_displacement(
      const BoundaryCurves                                &curves,
      const BackgroundGrid                                &grid,
      const Point<2>                                      &x,
      const std::function<Tensor<1, 2>(const Point<2> &)> &field,
      Tensor<1, 2>                                        &w) const override;

    const std::vector<BandPoint> &
    band_points() const override
    {
      return points;
    }

  private:
    /**
     * What the band's terms need at a Gauss point c of a piece: the inward
     * normal n, the tangent t = n turned anticlockwise, n n^T, the grid
     * field on the boundary (the value of each shape function at c and its
     * derivative along t), and for a support that imposes a prescribed
     * displacement its increment g at c and dg/dt (zero otherwise). A
     * normal displacement is g = g_n n with n the normal at c: the
     * roller's terms treat n as constant across the band and along the
     * piece.
     */
    struct BoundaryFrame
    {
      Tensor<1, 2>                                          normal;
      Tensor<1, 2>                                          tangent;
      Tensor<2, 2>                                          nn;
      std::array<Tensor<1, 2>, Q1CellKernel::dofs_per_cell> trace;
      std::array<Tensor<1, 2>, Q1CellKernel::dofs_per_cell> trace_dt;
      Tensor<1, 2>                                          g;
      Tensor<1, 2>                                          dg_dt;

      /**
       * The band's correction Delta_i to the gradient of shape function
       * @p i at a band point where the D-function is @p D and its
       * derivative @p dD: the gradient of -(1 - D) P N_i(c) that u = w -
       * (1 - D) P (w(c) - g) adds, its normal part dD N_i(c) (x) n for a
       * fixed or prescribed support, and for a @p roller also the
       * tangential part of the normal component (assemble() says why a
       * full support keeps none). assemble() takes its symmetric part,
       * add_finite_strain_terms() the whole gradient.
       */
      Tensor<2, 2>
      band_correction(const unsigned int i,
                      const double       D,
                      const double       dD,
                      const bool         roller) const;

      /** The same correction Delta_g of the prescribed increment g, which
       * enters like a prescribed strain. */
      Tensor<2, 2>
      prescribed_band_correction(const double D,
                                 const double dD,
                                 const bool   roller) const;
    };

    /**
     * A point of the band across Gauss point c of a piece, at distance
     * phi = delta x_r inwards (x_r, w_r the r-th point and weight of the
     * rule across the band on [0, 1]): its place x = c + phi n, its
     * coordinates in the piece's cell, its weight ds delta w_r and the
     * D-function and its derivative there.
     */
    struct BandSample
    {
      Point<2> position;
      Point<2> cell_coordinates;
      double   weight;
      double   D;
      double   dD;
    };

    /** The BandSample of point @p r of @p across at Gauss point @p q of
     * @p values' piece, whose inward normal is @p normal, in a band of
     * width @p delta on @p grid. */
    BandSample
    band_sample(const CurvePieceValues &values,
                const unsigned int      q,
                const Tensor<1, 2>     &normal,
                const Quadrature<1>    &across,
                const unsigned int      r,
                const double            delta,
                const BackgroundGrid   &grid) const;

    /** What the small-strain terms at one band point are made of. */
    struct BandPointTerms
    {
      /** The frame of the Gauss point the band point lies across from. */
      const BoundaryFrame &frame;
      BandSample           sample;
      /** Whether the support holds the normal component only. */
      bool roller;
      /** Whether the support imposes its prescribed displacement itself
       * (nearest-point correction). */
      bool imposes;
      /** The strain of the fitted prescribed values d^a (D-scaled forms;
       * zero without). */
      Voigt strain_a;
      /** The boundary's stress of the previous steps at the Gauss point. */
      Voigt sigma_previous;
      /** The centroid of the cell's material with a B-bar kernel. */
      std::optional<Point<2>> bbar_point;
    };

    /**
     * The terms of the nearest-point correction at a band point (small
     * strain): (B + Delta)^T C (B + Delta) - B^T C B into @p cell_matrix,
     * and into @p cell_rhs the band's share of the internal force of the
     * stress of the previous steps and of the fitted strain, and for a
     * support that imposes a displacement the force of the prescribed
     * increment's band strain Delta_g.
     */
    void
    add_nearest_point_terms(const Context        &context,
                            const BandPointTerms &point,
                            FullMatrix<double>   &cell_matrix,
                            Vector<double>       &cell_rhs) const;

    /**
     * The terms of the D-scaled formulations at a band point: u = P(D) w,
     * the paper's k2 + k2^T + k3 (eqs. 24, 25) into @p cell_matrix and
     * the band part of f^d (eq. 33) and of the internal force of the
     * stress of the previous steps into @p cell_rhs.
     */
    void
    add_d_scaled_terms(const Context        &context,
                       const BandPointTerms &point,
                       FullMatrix<double>   &cell_matrix,
                       Vector<double>       &cell_rhs) const;

    /** Refuses what a formulation does not implement for the supports of
     * @p curves: a normal displacement (frame and paper), finite strain
     * (frame and paper). Collective: every process holds every curve. */
    void
    check_formulation(const BoundaryCurves &curves,
                      const bool            finite_strain) const;

    /** The BoundaryFrame of Gauss point @p q of the piece of @p values'
     * last reinit(); @p imposed: the condition whose prescribed
     * displacement's change over @p increment the support imposes, or
     * nullptr. */
    static void
    boundary_frame(const CurvePieceValues &values,
                   const unsigned int      q,
                   const Q1CellKernel     &kernel,
                   const CurveCondition   *imposed,
                   const LoadIncrement    &increment,
                   const ExactSolution    *exact,
                   BoundaryFrame          &frame);

    /** The change of u^a of @p condition at @p x over @p increment
     * (CurveCondition::displacement_increment()): of the displacement, or
     * for a normal displacement of u_n n with n = @p outward_normal (the
     * curve's outward normal, at x or at the boundary point the caller
     * holds it constant from). */
    static Tensor<1, 2>
    prescribed_increment(const CurveCondition &condition,
                         const ExactSolution  *exact,
                         const Point<2>       &x,
                         const Tensor<1, 2>   &outward_normal,
                         const LoadIncrement  &increment);

    double       relative_band_width = 1e-2;
    unsigned int points_along        = 2;
    unsigned int points_across       = 3;
    /** How the band modifies the displacement (see "Formulation"). */
    enum class Formulation
    {
      consistent,
      frame,
      paper
    };
    Formulation formulation = Formulation::consistent;

    std::vector<BandPoint> points;
    /** The load increment and exact solution of the last assemble(), for
     * support_displacement(). */
    LoadIncrement        last_increment;
    const ExactSolution *last_exact = nullptr;
  };
} // namespace bsmpm

#endif
