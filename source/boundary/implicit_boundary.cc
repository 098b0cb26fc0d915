#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>

#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/trilinos_solver.h>

#include <bsmpm/base/parameter_tools.h>
#include <bsmpm/boundary/curve_piece_values.h>
#include <bsmpm/boundary/implicit_boundary.h>

#include <cmath>
#include <limits>
#include <memory>
#include <string>

namespace bsmpm
{
  namespace
  {
    /** Voigt strain (engineering shear) of a displacement gradient. */
    Voigt
    voigt(const Tensor<2, 2> &gradient)
    {
      return Voigt(
        {gradient[0][0], gradient[1][1], gradient[0][1] + gradient[1][0]});
    }

    /** The registered name of the implicit boundary method. */
    constexpr char implicit_boundary_name[] = "implicit boundary";

    bool
    is_ibm_support(const BoundaryCurve &curve, const CurveCondition *condition)
    {
      return condition != nullptr && condition->is_support() &&
             curve.dirichlet_method == implicit_boundary_name;
    }

    /**
     * The present name of a value of "Implicit boundary/Formulation": the
     * values are named after what each form does; "consistent", "frame" and
     * "paper" are their names of before, which parameter files written then
     * still use.
     */
    std::string
    formulation_name(const std::string &value)
    {
      return value == "consistent" ? "nearest-point correction" :
             value == "frame"      ? "D-scaled" :
             value == "paper"      ? "D-scaled with J_T" :
                                     value;
    }


    /** The values of "Implicit boundary/Formulation", matched under their
     * names of before too, which are not listed as allowed values
     * (description() is the Selection's). */
    class ImplicitBoundaryFormulationPattern : public Patterns::Selection
    {
    public:
      ImplicitBoundaryFormulationPattern()
        : Patterns::Selection(
            "nearest-point correction|D-scaled|D-scaled with J_T")
      {}

      bool
      match(const std::string &value) const override
      {
        return Patterns::Selection::match(formulation_name(value));
      }

      std::unique_ptr<Patterns::PatternBase>
      clone() const override
      {
        return std::make_unique<ImplicitBoundaryFormulationPattern>();
      }
    };
  } // namespace



  BSMPM_REGISTER_SUPPORT_METHOD(ImplicitBoundary, "implicit boundary")



  ImplicitBoundary::ImplicitBoundary()
    : SupportMethod(implicit_boundary_name)
  {}



  void
  ImplicitBoundary::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Implicit boundary");
    prm.declare_entry(
      "Relative band width",
      "1e-2",
      Patterns::Double(0.),
      "Band width delta of the D-function over the cell size h. With the "
      "nearest-point correction (the default formulation) the band has no "
      "error of order delta, so a wide band costs no accuracy and keeps the "
      "system well conditioned (the condition number grows like 1 / delta, "
      "and a very thin band over-constrains cut cells along curved supports): "
      "keep the default. The D-scaled forms err by order delta and need about "
      "1e-6, as the paper recommends; the paper's scenes in prm/ set 1e-6 to "
      "compare with its figures (doc/implicit-boundary.md).");
    prm.declare_entry("Points along piece",
                      "2",
                      Patterns::Integer(1, 100),
                      "Gauss points along each curve piece for the band "
                      "integrals; the default is the paper's. Change it only "
                      "to study the band's quadrature.");
    prm.declare_entry("Points across band",
                      "3",
                      Patterns::Integer(1, 100),
                      "Gauss points across the band; the default is the "
                      "paper's. Change it only to study the band's "
                      "quadrature.");
    prm.declare_entry(
      "Formulation",
      "nearest-point correction",
      ImplicitBoundaryFormulationPattern(),
      "How the band turns the grid field w into the supported "
      "displacement u. nearest-point correction (the default): u = w - (1 "
      "- D) P (w(x_b) - g), with x_b the boundary point nearest to x, g "
      "the prescribed value and P the identity (fixed) or n n (roller); "
      "the band's own stiffness replaces the regular one there, so a "
      "linear field that meets the support is reproduced exactly whatever "
      "the band width, in small and finite strain. D-scaled: the paper's "
      "u = D w (fixed) or w - (1 - D)(w.n) n (roller), band terms k2 + "
      "k2^T + k3 added to the regular stiffness, errors of order delta. "
      "D-scaled with J_T: as D-scaled, but rollers by the paper's band "
      "strain with the rotation J_T (eqs. 22-26). Change it only to "
      "reproduce the paper's figures: the D-scaled forms are small-strain "
      "forms (refused with Material/Kinematics = finite strain) and "
      "cannot impose a normal displacement (doc/implicit-boundary.md).");
    prm.leave_subsection();
  }



  void
  ImplicitBoundary::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Implicit boundary");
    relative_band_width    = prm.get_double("Relative band width");
    points_along           = prm.get_integer("Points along piece");
    points_across          = prm.get_integer("Points across band");
    const std::string form = formulation_name(prm.get("Formulation"));
    formulation = form == "nearest-point correction" ? Formulation::consistent :
                  form == "D-scaled"                 ? Formulation::frame :
                                                       Formulation::paper;
    prm.leave_subsection();
    AssertThrow(relative_band_width > 0 && relative_band_width <= 1,
                ExcMessage("Implicit boundary: the relative band width must "
                           "lie in (0, 1], got " +
                           std::to_string(relative_band_width) + "."));
  }



  double
  ImplicitBoundary::d_function(const double phi, const double delta)
  {
    if (phi <= 0)
      return 0;
    if (phi >= delta)
      return 1;
    const double r = 1 - phi / delta;
    return 1 - r * r;
  }



  double
  ImplicitBoundary::d_function_derivative(const double phi, const double delta)
  {
    if (phi < 0 || phi > delta)
      return 0;
    return 2 * (1 - phi / delta) / delta;
  }



  void
  ImplicitBoundary::check_formulation(const BoundaryCurves &curves,
                                      const bool            finite_strain) const
  {
    // Every process holds every curve: the check is collective.
    if (formulation != Formulation::consistent)
      for (const auto &curve : curves.get_curves())
        if (imposes(curve))
          for (const auto &condition : curve.conditions)
            AssertThrow(
              condition.kind != CurveCondition::Kind::normal_displacement,
              ExcMessage(
                condition.where +
                ": 'normal displacement' is implemented for the "
                "nearest-point correction of the implicit boundary method "
                "only (the D-scaled forms impose a displacement through "
                "nodal values fitted to both of its components). Set "
                "'Implicit boundary/Formulation = nearest-point "
                "correction' or the curve's 'Dirichlet method = "
                "nitsche'."));
    // The frame and paper forms pair the band's field with the elastic
    // stiffness and the stress of the step's start: small-strain terms,
    // O(delta) errors even there, kept to reproduce the paper. In finite
    // strain only the consistent band takes the stress of the step's
    // deformation (add_finite_strain_terms()) and is exact, whatever the
    // band width; a second, less accurate finite-strain band would serve
    // nobody, so these forms are refused rather than run wrong.
    if (finite_strain && formulation != Formulation::consistent)
      AssertThrow(
        !used_by(curves),
        ExcMessage(
          "Implicit boundary/Formulation = " +
          std::string(formulation == Formulation::frame ? "D-scaled" :
                                                          "D-scaled with J_T") +
          " keeps the small-strain band terms (the elastic stiffness "
          "and the stress of the step's start) and is not right with "
          "'Material/Kinematics = finite strain'. Set 'Implicit "
          "boundary/Formulation = nearest-point correction' (the default, "
          "exact in finite strain) or the curves' 'Dirichlet method = "
          "nitsche'."));
  }



  void
  ImplicitBoundary::assemble(
    const Context                                    &context,
    const LoadIncrement                              &increment,
    const LinearAlgebra::distributed::Vector<double> *prescribed,
    const std::vector<CellMoments>                   *moments,
    const AffineConstraints<double>                  &constraints,
    TrilinosWrappers::SparseMatrix                   &matrix,
    TrilinosWrappers::MPI::Vector                    &rhs,
    const BoundaryCurve                              *only)
  {
    check_formulation(context.curves, context.finite_strain);
    // The three formulations share the pieces, the band's geometry at each
    // Gauss point and its band points, and differ only in the terms at a
    // band point (add_nearest_point_terms(), add_d_scaled_terms()).
    points.clear();
    last_increment = increment;
    last_exact     = context.exact_solution;
    std::string               problem;
    const Q1CellKernel       &kernel = context.kernel;
    const double              delta  = band_width(context.grid);
    const QGauss<1>           across(points_across);
    Q1CellKernel::LocalVector da;
    BoundaryFrame             frame;
    const QGauss<1>           along(points_along);

    // The band terms of one piece: for each Gauss point along it its
    // frame and the stress of the previous steps, for each band point
    // across the terms of the formulation.
    const auto piece_terms = [&](const CurvePieceValues &values,
                                 FullMatrix<double>     &cell_matrix,
                                 Vector<double>         &cell_rhs) {
      const LocallyOwnedCurvePiece &piece     = values.get_piece();
      const CurveCondition         *condition = piece.condition;
      if (prescribed)
        for (unsigned int i = 0; i < Q1CellKernel::dofs_per_cell; ++i)
          da[i] = (*prescribed)(values.dof_indices()[i]);
      // A roller and a prescribed normal displacement hold the normal
      // component only.
      const bool roller  = condition->holds_normal_component_only();
      const bool imposes = formulation == Formulation::consistent &&
                           condition->prescribes_displacement();
      const std::optional<Point<2>> centroid = bbar_point(moments, piece);
      for (unsigned int q = 0; q < values.n_quadrature_points(); ++q)
        {
          boundary_frame(values,
                         q,
                         kernel,
                         imposes ? condition : nullptr,
                         increment,
                         context.exact_solution,
                         frame);
          const Point<2> &c = values.position(q);
          if (imposes && problem.empty() &&
              !(std::isfinite(frame.g[0]) && std::isfinite(frame.g[1])))
            problem = condition->where +
                      ": the prescribed displacement is not finite at (" +
                      std::to_string(c[0]) + ", " + std::to_string(c[1]) +
                      "): check the expression.";
          // The boundary's stress from the previous steps: the band's
          // share of the internal force, int B2^T sigma, which carries
          // the support's reaction from step to step.
          BandPointTerms point{frame,
                               {},
                               roller,
                               imposes,
                               {},
                               piece.curve->stress_at(piece.segment,
                                                      values.parameter(q)),
                               centroid};
          for (unsigned int r = 0; r < across.size(); ++r)
            {
              point.sample = band_sample(
                values, q, frame.normal, across, r, delta, context.grid);
              points.push_back({point.sample.position,
                                point.sample.D,
                                point.sample.weight,
                                piece.owned_cell->active_cell_index(),
                                point.sample.cell_coordinates});
              // Finite strain: the consistent band's terms come per
              // Newton iteration (add_finite_strain_terms()).
              if (context.finite_strain &&
                  formulation == Formulation::consistent)
                continue;
              point.strain_a = Voigt();
              if (prescribed)
                for (unsigned int i = 0; i < Q1CellKernel::dofs_per_cell; ++i)
                  point.strain_a +=
                    da[i] *
                    kernel.strain_column(i, point.sample.cell_coordinates);
              if (formulation == Formulation::consistent)
                add_nearest_point_terms(context, point, cell_matrix, cell_rhs);
              else
                add_d_scaled_terms(context, point, cell_matrix, cell_rhs);
            }
        }
    };
    add_piece_terms(
      context, along, only, constraints, &matrix, rhs, piece_terms);
    ParameterTools::throw_if_any(problem, context.grid.mpi_communicator());
  }



  void
  ImplicitBoundary::add_nearest_point_terms(const Context        &context,
                                            const BandPointTerms &point,
                                            FullMatrix<double>   &cell_matrix,
                                            Vector<double> &cell_rhs) const
  {
    constexpr unsigned int n      = Q1CellKernel::dofs_per_cell;
    const BandSample      &sample = point.sample;
    const Point<2>        &st     = sample.cell_coordinates;
    const double           w      = sample.weight;
    const BoundaryFrame   &frame  = point.frame;
    const Q1CellKernel    &kernel = context.kernel;
    const Tensor<2, 3>    &C      = context.material.stiffness();
    std::array<Voigt, n>   B1, B2, CB1, CB2;
    // u = w - (1 - D) P w(c): its strain is B + Delta, with Delta the
    // band's correction to the regular strain B, which the material points
    // integrate. A fixed or prescribed support keeps the normal part of
    // Delta only: the tangential part, -(1 - D) dw(c)/dt (x) t, integrates
    // across the band to (delta / 3) dw/dt, whose sum along a side leaves
    // (delta / 3) w . sigma t at its ends: at a corner of two displacement
    // supports the tangents differ and a linear field is off by O(delta)
    // (doc/implicit-boundary.md, "The band at corners"). Without it,
    // int Delta^T sigma over the band is exactly the boundary flux
    // int w . sigma n, corners or not.
    for (unsigned int i = 0; i < n; ++i)
      {
        B1[i] = kernel.strain_column(i, st);
        B2[i] =
          voigt(frame.band_correction(i, sample.D, sample.dD, point.roller));
        // B-bar: the regular strain's stress takes the volumetric strain
        // at the centroid of the cell's material, as the points' stiffness
        // does.
        CB1[i] = kernel.stress_column(i, st, point.bbar_point.value_or(st));
        CB2[i] = C * B2[i];
      }
    // (B + Delta)^T C (B + Delta) - B^T C B, with B-bar
    // (Bbar + Delta)^T C (Bbar + Delta) - Bbar^T C Bbar:
    // Delta has no zz part, so Bbar^T C Delta is the
    // B-bar stress of B times Delta.
    for (unsigned int i = 0; i < n; ++i)
      for (unsigned int j = 0; j < n; ++j)
        cell_matrix(i, j) +=
          w * (CB1[i] * B2[j] + B2[i] * CB1[j] + B2[i] * CB2[j]);
    // Band part of f^d, int Delta^T C B d^a, and of the internal force.
    const Voigt sigma = point.sigma_previous + C * point.strain_a;
    for (unsigned int i = 0; i < n; ++i)
      cell_rhs[i] -= w * B2[i] * sigma;
    // u = w - (1 - D) P (w(c) - g), P g = g: the band strain of g,
    // Delta_g, enters the energy like a prescribed strain. It is the same
    // band strain as that of w (no tangential part for a full
    // displacement), so that w(c) = g(c) leaves no band strain at all.
    if (point.imposes)
      {
        const Voigt strain_g = voigt(
          frame.prescribed_band_correction(sample.D, sample.dD, point.roller));
        const Voigt sigma_g = C * strain_g;
        for (unsigned int i = 0; i < n; ++i)
          cell_rhs[i] += w * (CB1[i] * strain_g + B2[i] * sigma_g);
      }
  }



  void
  ImplicitBoundary::add_d_scaled_terms(const Context        &context,
                                       const BandPointTerms &point,
                                       FullMatrix<double>   &cell_matrix,
                                       Vector<double>       &cell_rhs) const
  {
    const Q1CellKernel    &kernel = context.kernel;
    const Tensor<2, 3>    &C      = context.material.stiffness();
    const BoundaryFrame   &frame  = point.frame;
    const BandSample      &sample = point.sample;
    const bool             roller = point.roller;
    constexpr unsigned int n      = Q1CellKernel::dofs_per_cell;
    const Point<2>        &st     = sample.cell_coordinates;
    const double           w = sample.weight, D = sample.D, dD = sample.dD;
    const Tensor<1, 2>    &normal = frame.normal;
    std::array<Voigt, n>   B1, B2, CB1, CB2;
    // u = P(D) w: grad u = P grad w + (dP/dphi) w (x) n.
    Tensor<2, 2> P, dP;
    if (roller)
      {
        P  = unit_symmetric_tensor<2>() + (D - 1) * frame.nn;
        dP = dD * frame.nn;
      }
    else
      {
        P  = D * unit_symmetric_tensor<2>();
        dP = dD * unit_symmetric_tensor<2>();
      }
    for (unsigned int i = 0; i < n; ++i)
      {
        const Tensor<1, 2> value = kernel.shape_value(i, st);
        B1[i]                    = voigt(P * kernel.shape_gradient(i, st));
        if (roller && formulation == Formulation::paper)
          // eqs. 23-26: (d D / d x, d D / d y) of the normal
          // component, which J_T extracts from w.
          B2[i] = dD * (normal * value) * Voigt({normal[0], 0., normal[1]});
        else
          B2[i] = voigt(outer_product(dP * value, normal));
        CB1[i] = C * B1[i];
        CB2[i] = C * B2[i];
      }
    // k2 + k2^T + k3 (eqs. 24, 25).
    for (unsigned int i = 0; i < n; ++i)
      for (unsigned int j = 0; j < n; ++j)
        cell_matrix(i, j) +=
          w * (B1[i] * CB2[j] + B2[i] * CB1[j] + B2[i] * CB2[j]);
    // Band part of f^d = int (B1 + B2)^T C B d^a (eq. 33), and of the
    // internal force.
    const Voigt sigma_a = C * point.strain_a;
    for (unsigned int i = 0; i < n; ++i)
      cell_rhs[i] -=
        w * ((B1[i] + B2[i]) * sigma_a + B2[i] * point.sigma_previous);
  }



  Tensor<2, 2>
  ImplicitBoundary::BoundaryFrame::band_correction(const unsigned int i,
                                                   const double       D,
                                                   const double       dD,
                                                   const bool roller) const
  {
    if (roller)
      return dD * (trace[i] * normal) * nn -
             (1 - D) * (trace_dt[i] * normal) * outer_product(normal, tangent);
    return dD * outer_product(trace[i], normal);
  }



  Tensor<2, 2>
  ImplicitBoundary::BoundaryFrame::prescribed_band_correction(
    const double D,
    const double dD,
    const bool   roller) const
  {
    if (roller)
      return dD * outer_product(g, normal) -
             (1 - D) * outer_product(dg_dt, tangent);
    return dD * outer_product(g, normal);
  }



  ImplicitBoundary::BandSample
  ImplicitBoundary::band_sample(const CurvePieceValues &values,
                                const unsigned int      q,
                                const Tensor<1, 2>     &normal,
                                const Quadrature<1>    &across,
                                const unsigned int      r,
                                const double            delta,
                                const BackgroundGrid   &grid) const
  {
    const double phi = delta * across.point(r)[0];
    BandSample   sample;
    sample.position = values.position(q) + phi * normal;
    sample.cell_coordinates =
      grid.local_coordinates(sample.position, values.get_piece().cell);
    sample.weight = values.JxW(q) * delta * across.weight(r);
    sample.D      = d_function(phi, delta);
    sample.dD     = d_function_derivative(phi, delta);
    return sample;
  }



  void
  ImplicitBoundary::add_finite_strain_terms(
    const Context                                    &context,
    const LinearAlgebra::distributed::Vector<double> &increment,
    const SupportStress                              &stress,
    const AffineConstraints<double>                  &constraints,
    TrilinosWrappers::SparseMatrix                   *tangent,
    TrilinosWrappers::MPI::Vector                    &internal_force,
    const BoundaryCurve                              *only) const
  {
    if (formulation != Formulation::consistent)
      return;
    const Q1CellKernel    &kernel = context.kernel;
    constexpr unsigned int n      = Q1CellKernel::dofs_per_cell;
    const double           delta  = band_width(context.grid);
    const QGauss<1>        across(points_across);

    Q1CellKernel::LocalVector d;
    // Per shape function: its gradient G, its band correction Delta, the
    // band's gradient G + Delta, and A : (G + Delta), A : G.
    std::array<Tensor<2, 2>, n> G, Delta, T, AT, AG;
    BoundaryFrame               frame;

    const QGauss<1> along(points_along);

    // The finite-strain band terms of one piece, at the increment d on
    // its cell.
    const auto piece_terms = [&](const CurvePieceValues &values,
                                 FullMatrix<double>     &cell_matrix,
                                 Vector<double>         &cell_force) {
      const LocallyOwnedCurvePiece &piece     = values.get_piece();
      const CurveCondition         *condition = piece.condition;
      for (unsigned int i = 0; i < n; ++i)
        d[i] = increment(values.dof_indices()[i]);
      const bool roller  = condition->holds_normal_component_only();
      const bool imposes = condition->prescribes_displacement();

      for (unsigned int q = 0; q < values.n_quadrature_points(); ++q)
        {
          // The geometry and prescribed data of assemble().
          boundary_frame(values,
                         q,
                         kernel,
                         imposes ? condition : nullptr,
                         last_increment,
                         last_exact,
                         frame);
          // The state of the boundary as of the step's start.
          const std::vector<double> props =
            piece.curve->state_at(piece.segment, values.parameter(q));
          const ArrayView<const double> state(props.data(), props.size());

          for (unsigned int r = 0; r < across.size(); ++r)
            {
              const BandSample sample = band_sample(
                values, q, frame.normal, across, r, delta, context.grid);
              const double w = sample.weight;
              // The band corrections of assemble() as full gradients
              // (its strains are their symmetric parts), and the
              // band's mismatch E = Delta(d) - Delta_g.
              Tensor<2, 2> f = unit_symmetric_tensor<2>(), E;
              for (unsigned int i = 0; i < n; ++i)
                {
                  G[i] = kernel.shape_gradient(i, sample.cell_coordinates);
                  Delta[i] =
                    frame.band_correction(i, sample.D, sample.dD, roller);
                  T[i] = G[i] + Delta[i];
                  f += d[i] * G[i];
                  E += d[i] * Delta[i];
                }
              if (imposes)
                E -=
                  frame.prescribed_band_correction(sample.D, sample.dD, roller);
              // P(f + E) linearised about the grid's f: E is the
              // constraint's, of order (w(x_b) - g) / delta, and would
              // invert the band long before Newton has met the support
              // (doc/finite-strain.md, "Supports in finite strain").
              Tensor<2, 2> P;
              Tensor<4, 2> A;
              // An inverted point is left out; @p stress reports it
              // to the solver, which rejects the increment.
              if (!stress(state, f, P, A))
                continue;
              const Tensor<2, 2> AE = contract(A, E);
              for (unsigned int i = 0; i < n; ++i)
                cell_force[i] +=
                  w * (scalar_product(P, Delta[i]) + scalar_product(AE, T[i]));
              if (tangent == nullptr)
                continue;
              // d(A : E)/d d_j = A : Delta_j + (dA/df : G_j) : E, the
              // latter D_E A(f) : G_j (second derivatives commute), by
              // central differences along E. That part is of the order
              // of E, the support's mismatch over the band width: where
              // the mismatch is a sizeable part of the cell (the first
              // iterations of a step that imposes a large displacement:
              // |E| delta / h about 1 at the start of a 30 %
              // compression in one step), it made the first correction
              // some 25 times too long (8 m for an imposed 0.27 m),
              // inverting points, and the step was cut three times.
              // So it joins the tangent only once the mismatch is below
              // 1e-2 h, where it keeps Newton quadratic
              // (doc/finite-strain.md, "Supports in finite strain").
              Tensor<4, 2> dA_E;
              const double size = E.norm();
              if (size > 0 && size * relative_band_width <= 1e-2)
                {
                  const double h = 1e-5 / size;
                  Tensor<2, 2> P_other;
                  Tensor<4, 2> A_plus, A_minus;
                  if (stress(state, f + h * E, P_other, A_plus) &&
                      stress(state, f - h * E, P_other, A_minus))
                    dA_E = (A_plus - A_minus) / (2 * h);
                }
              for (unsigned int j = 0; j < n; ++j)
                {
                  AT[j] = contract(A, Delta[j]) + contract(dA_E, G[j]);
                  AG[j] = contract(A, G[j]);
                }
              for (unsigned int i = 0; i < n; ++i)
                for (unsigned int j = 0; j < n; ++j)
                  cell_matrix(i, j) += w * (scalar_product(AG[j], Delta[i]) +
                                            scalar_product(AT[j], T[i]));
            }
        }
    };
    add_piece_terms(
      context, along, only, constraints, tangent, internal_force, piece_terms);
  }



  void
  ImplicitBoundary::boundary_frame(const CurvePieceValues &values,
                                   const unsigned int      q,
                                   const Q1CellKernel     &kernel,
                                   const CurveCondition   *imposed,
                                   const LoadIncrement    &increment,
                                   const ExactSolution    *exact,
                                   BoundaryFrame          &frame)
  {
    const double        u       = values.parameter(q);
    const Point<2>     &c       = values.position(q);
    const Tensor<1, 2> &outward = values.normal(q);
    frame.normal                = -outward; // inward
    frame.tangent        = Tensor<1, 2>({-frame.normal[1], frame.normal[0]});
    frame.nn             = outer_product(frame.normal, frame.normal);
    const Point<2> &st_c = values.local_coordinates(q);
    for (unsigned int i = 0; i < Q1CellKernel::dofs_per_cell; ++i)
      {
        frame.trace[i]    = kernel.shape_value(i, st_c);
        frame.trace_dt[i] = kernel.shape_gradient(i, st_c) * frame.tangent;
      }
    frame.g     = Tensor<1, 2>();
    frame.dg_dt = Tensor<1, 2>();
    if (imposed == nullptr)
      return;
    // dg/dt by central differences along the curve.
    const LocallyOwnedCurvePiece &piece  = values.get_piece();
    const BSplineCurve           &spline = *piece.curve->spline;
    const double                  tau    = 1e-6 * (piece.u_end - piece.u_begin);
    const Point<2> a = spline.value(u - tau), b = spline.value(u + tau);
    frame.g = prescribed_increment(*imposed, exact, c, outward, increment);
    frame.dg_dt =
      (prescribed_increment(*imposed, exact, b, outward, increment) -
       prescribed_increment(*imposed, exact, a, outward, increment)) /
      ((b - a) * frame.tangent);
  }



  bool
  ImplicitBoundary::prescribes_displacement(const BoundaryCurves &curves)
  {
    for (const auto &curve : curves.get_curves())
      if (curve.dirichlet_method == implicit_boundary_name)
        for (const auto &condition : curve.conditions)
          if (condition.kind == CurveCondition::Kind::displacement)
            return true;
    return false;
  }



  Tensor<1, 2>
  ImplicitBoundary::prescribed_increment(const CurveCondition &condition,
                                         const ExactSolution  *exact,
                                         const Point<2>       &x,
                                         const Tensor<1, 2>   &outward_normal,
                                         const LoadIncrement  &increment)
  {
    AssertThrow(condition.function || exact != nullptr,
                ExcMessage("Boundary curves: '" + condition.kind_name() +
                           " exact' needs an exact solution in the 'Exact "
                           "solution' section."));
    // Not finite values are reported by the callers, with the place.
    std::string unreported;
    if (condition.kind == CurveCondition::Kind::normal_displacement)
      return (condition.function ?
                condition.normal_displacement_increment(x,
                                                        increment,
                                                        unreported) :
                increment.share() * (exact->displacement(x) * outward_normal)) *
             outward_normal;
    if (condition.function)
      return condition.displacement_increment(x, increment, unreported);
    return increment.share() * exact->displacement(x);
  }



  double
  ImplicitBoundary::fit_prescribed_displacement(
    const Context                              &context,
    const LoadIncrement                        &increment,
    TrilinosWrappers::SparseMatrix             &mass,
    LinearAlgebra::distributed::Vector<double> &prescribed) const
  {
    const BoundaryCurves  &curves = context.curves;
    const BackgroundGrid  &grid   = context.grid;
    const Q1CellKernel    &kernel = context.kernel;
    const ExactSolution   *exact  = context.exact_solution;
    constexpr unsigned int n      = Q1CellKernel::dofs_per_cell;
    const MPI_Comm         comm   = grid.mpi_communicator();
    const QGauss<1>        gauss(std::max(points_along, 4u));

    // Which DoFs the boundary meets: all others are zero.
    LinearAlgebra::distributed::Vector<double> touched(
      grid.locally_owned_dofs(), grid.locally_relevant_dofs(), comm);
    CurvePieceValues values(grid, gauss);
    const auto       pieces = values.pieces(
      curves, [](const BoundaryCurve &curve, const CurveCondition *condition) {
        return is_ibm_support(curve, condition) &&
               condition->kind == CurveCondition::Kind::displacement;
      });
    std::vector<types::global_dof_index> dof_indices(n);
    for (const auto &piece : pieces)
      {
        piece.owned_cell->get_dof_indices(dof_indices);
        for (const auto i : dof_indices)
          touched(i) = 1;
      }
    touched.compress(VectorOperation::max);
    touched.update_ghost_values();

    AffineConstraints<double> constraints(grid.locally_relevant_dofs());
    for (const auto i : grid.locally_relevant_dofs())
      if (touched(i) == 0.)
        constraints.add_line(i);
    constraints.close();

    // Boundary mass matrix and right-hand side of eq. 36.
    mass = 0;
    TrilinosWrappers::MPI::Vector rhs(grid.locally_owned_dofs(), comm);
    FullMatrix<double>            cell_matrix(n, n);
    Vector<double>                cell_rhs(n);
    for (const auto &piece : pieces)
      {
        values.reinit(piece);
        cell_matrix = 0;
        cell_rhs    = 0;
        for (unsigned int q = 0; q < gauss.size(); ++q)
          {
            const double       ds = values.JxW(q);
            const Point<2>    &st = values.local_coordinates(q);
            const Tensor<1, 2> ua = prescribed_increment(*piece.condition,
                                                         exact,
                                                         values.position(q),
                                                         values.normal(q),
                                                         increment);
            for (unsigned int i = 0; i < n; ++i)
              {
                const Tensor<1, 2> Ni = kernel.shape_value(i, st);
                cell_rhs[i] += Ni * ua * ds;
                for (unsigned int j = 0; j < n; ++j)
                  cell_matrix(i, j) += Ni * kernel.shape_value(j, st) * ds;
              }
          }
        constraints.distribute_local_to_global(
          cell_matrix, cell_rhs, values.dof_indices(), mass, rhs);
      }
    // Rows of DoFs the boundary does not meet: identity.
    for (const auto i : grid.locally_owned_dofs())
      if (touched(i) == 0.)
        mass.add(i, i, 1.);
    mass.compress(VectorOperation::add);
    rhs.compress(VectorOperation::add);
    // A boundary along the middle of a row of cells sees only one
    // combination of the values above and below it: the least-squares
    // system M d = b is singular there (and nearly so where the boundary is
    // nearly parallel to the grid). Any of its solutions gives the same
    // displacement (the grid field w absorbs what d^a adds inside the body).
    // Iterated Tikhonov finds one: factorise A = M + a diag(M) once, then
    // d += A^-1 (b - M d); each pass shrinks the shift a brings by a / (a +
    // lambda) in every direction with eigenvalue lambda of M, and leaves
    // the least weighted norm in the null space.
    TrilinosWrappers::MPI::Vector shift(grid.locally_owned_dofs(), comm);
    for (const auto i : grid.locally_owned_dofs())
      if (touched(i) != 0.)
        shift(i) = 1e-8 * mass.diag_element(i);
    for (const auto i : grid.locally_owned_dofs())
      if (shift(i) != 0.)
        mass.add(i, i, shift(i));
    mass.compress(VectorOperation::add);
    shift.compress(VectorOperation::insert);

    TrilinosWrappers::MPI::Vector  solution(grid.locally_owned_dofs(), comm);
    TrilinosWrappers::MPI::Vector  correction(solution), residual(solution);
    SolverControl                  control(1, 0);
    TrilinosWrappers::SolverDirect solver(
      control,
      TrilinosWrappers::SolverDirect::AdditionalData(false, "Amesos_Mumps"));
    solver.initialize(mass);
    solver.solve(solution, rhs);
    for (unsigned int pass = 0; pass < 4; ++pass)
      {
        // b - M d = b - A d + a diag(M) d
        mass.vmult(residual, solution);
        residual.sadd(-1., 1., rhs);
        correction = solution;
        correction.scale(shift);
        residual += correction;
        solver.solve(correction, residual);
        solution += correction;
      }
    constraints.distribute(solution);

    prescribed.reinit(grid.locally_owned_dofs(),
                      grid.locally_relevant_dofs(),
                      comm);
    for (const auto i : grid.locally_owned_dofs())
      prescribed(i) = solution(i);
    prescribed.update_ghost_values();

    // Root mean square of the fit along the boundary.
    double                    error2 = 0, length = 0;
    Q1CellKernel::LocalVector da;
    for (const auto &piece : pieces)
      {
        values.reinit(piece);
        for (unsigned int i = 0; i < n; ++i)
          da[i] = prescribed(values.dof_indices()[i]);
        for (unsigned int q = 0; q < gauss.size(); ++q)
          {
            const double       ds = values.JxW(q);
            const Tensor<1, 2> misfit =
              kernel.displacement(da, values.local_coordinates(q)) -
              prescribed_increment(*piece.condition,
                                   exact,
                                   values.position(q),
                                   values.normal(q),
                                   increment);
            error2 += misfit.norm_square() * ds;
            length += ds;
          }
      }
    error2 = Utilities::MPI::sum(error2, comm);
    length = Utilities::MPI::sum(length, comm);
    return length > 0 ? std::sqrt(error2 / length) : 0.;
  }



  double
  ImplicitBoundary::support_displacement(
    const BoundaryCurves                                &curves,
    const BackgroundGrid                                &grid,
    const Point<2>                                      &x,
    const std::function<Tensor<1, 2>(const Point<2> &)> &field,
    Tensor<1, 2>                                        &w) const
  {
    const double delta = band_width(grid);
    const auto   ij    = grid.cell_index(x);
    // The nearest IBM support among the pieces in the point's cell.
    double                smallest = std::numeric_limits<double>::max();
    double                phi_min  = 0;
    Tensor<1, 2>          n_min;
    Point<2>              foot;
    const CurveCondition *nearest = nullptr;
    for (const auto &curve : curves.get_curves())
      for (const auto &piece : curve.pieces)
        {
          if (piece.cell != ij)
            continue;
          const CurveCondition *condition =
            curve.condition_of_segment(piece.segment);
          if (!is_ibm_support(curve, condition))
            continue;
          // Closest point on the piece: samples, then Newton on (C - x).C'.
          const BSplineCurve &spline = *curve.spline;
          double              u_best = piece.u_begin, d_best = smallest;
          const unsigned int  samples = 8;
          for (unsigned int k = 0; k <= samples; ++k)
            {
              const double u =
                piece.u_begin + (piece.u_end - piece.u_begin) * k / samples;
              const double d = spline.value(u).distance(x);
              if (d < d_best)
                {
                  d_best = d;
                  u_best = u;
                }
            }
          double u = u_best;
          for (unsigned int it = 0; it < 20; ++it)
            {
              const Tensor<1, 2> r  = spline.value(u) - x;
              const Tensor<1, 2> d1 = spline.derivative(u);
              const double       g  = r * d1;
              const double       dg = d1 * d1 + r * spline.second_derivative(u);
              if (dg <= 0)
                break;
              const double next =
                std::min(std::max(u - g / dg, piece.u_begin), piece.u_end);
              if (std::abs(next - u) < 1e-15)
                break;
              u = next;
            }
          const double distance = spline.value(u).distance(x);
          if (distance < smallest)
            {
              smallest = distance;
              n_min    = -spline.outward_normal(u);
              phi_min  = (x - spline.value(u)) * n_min;
              foot     = spline.value(u);
              nearest  = condition;
            }
        }
    if (nearest == nullptr || phi_min >= delta)
      return 1.;

    const double D = d_function(phi_min, delta);
    if (formulation == Formulation::consistent)
      {
        Tensor<1, 2> w_b = field(foot);
        if (nearest->prescribes_displacement())
          w_b -= prescribed_increment(
            *nearest, last_exact, foot, -n_min, last_increment);
        if (nearest->holds_normal_component_only())
          w -= (1 - D) * (w_b * n_min) * n_min;
        else
          w -= (1 - D) * w_b;
        // A point on a face of the grid (where a curve ends on a grid-face
        // support, as the smooth footing's base on the symmetry line) may
        // be carried across it by round-off in n alone: the grid field
        // holds it on the face, the correction along a normal tilted by
        // 1e-16 does not. Such round-off (up to 1e-9 h) is taken back; a
        // real departure is left for MaterialPoints::move to report.
        const double tolerance = 1e-9 * grid.min_cell_size();
        for (unsigned int k = 0; k < 2; ++k)
          {
            const double below = grid.lower_left()[k] - (x[k] + w[k]);
            const double above = (x[k] + w[k]) - grid.upper_right()[k];
            if (below > 0 && below <= tolerance)
              w[k] += below;
            else if (above > 0 && above <= tolerance)
              w[k] -= above;
          }
        return D;
      }
    if (nearest->holds_normal_component_only())
      w -= (1 - D) * (w * n_min) * n_min;
    else
      w *= D;
    return D;
  }
} // namespace bsmpm
