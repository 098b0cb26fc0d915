#ifndef bsmpm_support_method_h
#define bsmpm_support_method_h

#include <deal.II/base/parameter_handler.h>

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/la_parallel_vector.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/lac/vector.h>

#include <bsmpm/boundary/boundary_curves.h>
#include <bsmpm/boundary/curve_piece_values.h>
#include <bsmpm/boundary/support_stress.h>
#include <bsmpm/geometry/background_grid.h>
#include <bsmpm/materials/material.h>
#include <bsmpm/points/q1_cell_kernel.h>
#include <bsmpm/verification/exact_solution.h>

#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace bsmpm
{
  using namespace dealii;

  /**
   * A way of imposing the supports of the boundary curves (fixed, roller,
   * prescribed displacement) on the grid's field, which does not conform to
   * the curves: the implicit boundary method (ImplicitBoundary), Nitsche's
   * method (NitscheBoundary), and what comes next (a mortar or a penalty
   * support). Each curve names its method ("Boundary curves/Curve k/
   * Dirichlet method"); the method imposes the supports of those curves.
   *
   * SystemAssembly and Scene hold every registered method in a list
   * (SupportMethods) and call each in turn for
   * - its terms in the system K du = r of a load increment (assemble()),
   *   also of one curve alone, for that curve's reaction (SupportReaction);
   * - in finite strain, its terms that depend on the stress of the step's
   *   deformation, per Newton iteration (add_finite_strain_terms());
   * - the cells its supports cross (mark_cells()), which hold their DoFs
   *   even without material;
   * - where the method changes the displacement near the curve (the
   *   implicit boundary method's band), the displacement of a material
   *   point there when the points move (support_displacement()), and the
   *   band's quadrature points (band_points(): output and the points' share
   *   of the Newton system);
   * - where the method imposes a prescribed displacement through nodal
   *   values fitted by least squares, that fit
   *   (fit_prescribed_displacement()).
   *
   * A method registers itself with BSMPM_REGISTER_SUPPORT_METHOD in its own
   * source file under the value of "Dirichlet method" that selects it
   * (the pattern of the constitutive models): this interface knows no
   * method. Its parameters are in a subsection of its own.
   */
  class SupportMethod
  {
  public:
    /** What the terms of every support method are made of. */
    struct Context
    {
      const BoundaryCurves        &curves;
      const BackgroundGrid        &grid;
      const Q1CellKernel          &kernel;
      const LinearElasticMaterial &material;
      /** The scene's exact solution (prescribed data "... exact"), or
       * nullptr. */
      const ExactSolution *exact_solution;
      /** Whether the points follow the finite-strain kinematics. */
      bool finite_strain;
    };

    /** A quadrature point of a support's band near the curve, kept for
     * output and for the tangent of nonlinear materials
     * (ConstitutiveUpdate::SupportBandPoint). */
    struct BandPoint
    {
      Point<2>     position;
      double       d_function;
      double       weight;
      unsigned int cell_index;         // active_cell_index()
      Point<2>     reference_position; // in that cell
    };

    /** A method registered as @p name, the value of "Dirichlet method"
     * that selects it: it imposes the supports of the curves whose
     * "Dirichlet method" is @p name. */
    SupportMethod(const std::string &name);

    virtual ~SupportMethod() = default;

    virtual void
    parse_parameters(ParameterHandler &prm) = 0;

    /** The value of "Dirichlet method" that selects the method; also the
     * name of its timer section. */
    const std::string &
    name() const
    {
      return method_name;
    }

    /** Whether this method imposes the supports of @p curve. */
    bool
    imposes(const BoundaryCurve &curve) const
    {
      return curve.dirichlet_method == method_name;
    }

    /** Whether any curve has a support that this method imposes. */
    bool
    used_by(const BoundaryCurves &curves) const
    {
      return curves.has_supports(method_name);
    }

    /** The pieces in locally owned cells of this method's supports (of
     * the curve @p only alone unless nullptr), for @p values. */
    std::vector<LocallyOwnedCurvePiece>
    supported_pieces(const CurvePieceValues &values,
                     const BoundaryCurves   &curves,
                     const BoundaryCurve    *only) const
    {
      return values.pieces(curves,
                           CurvePieceValues::supports_by(method_name, only));
    }

    /**
     * Adds the method's terms of all its supports on locally owned cells to
     * @p matrix and @p rhs, through @p constraints, for the load increment
     * @p increment (the prescribed displacements imposed by their change
     * over it).
     * @p prescribed: the nodal values of a fitted prescribed displacement
     * (fit_prescribed_displacement()), or nullptr. With a B-bar kernel,
     * @p moments (by active_cell_index) give each cell's centroid. With
     * @p only, the supports of that curve alone.
     */
    virtual void
    assemble(const Context                                    &context,
             const LoadIncrement                              &increment,
             const LinearAlgebra::distributed::Vector<double> *prescribed,
             const std::vector<CellMoments>                   *moments,
             const AffineConstraints<double>                  &constraints,
             TrilinosWrappers::SparseMatrix                   &matrix,
             TrilinosWrappers::MPI::Vector                    &rhs,
             const BoundaryCurve *only = nullptr) = 0;

    /**
     * Finite strain: the method's terms that depend on the stress of the
     * step's increment @p increment (with ghost values), @p stress giving
     * the material's response, as internal forces into @p internal_force
     * and, unless nullptr, their derivative into @p tangent, through
     * @p constraints. With @p only, that curve's supports alone.
     */
    virtual void
    add_finite_strain_terms(
      const Context                                    &context,
      const LinearAlgebra::distributed::Vector<double> &increment,
      const SupportStress                              &stress,
      const AffineConstraints<double>                  &constraints,
      TrilinosWrappers::SparseMatrix                   *tangent,
      TrilinosWrappers::MPI::Vector                    &internal_force,
      const BoundaryCurve *only = nullptr) const = 0;

    /**
     * Sets @p cells[c] for every locally owned cell c (by
     * active_cell_index()) that a support of this method crosses; with
     * @p both_components_only only supports that hold both components.
     */
    virtual void
    mark_cells(const BackgroundGrid &grid,
               const BoundaryCurves &curves,
               const bool            both_components_only,
               std::vector<bool>    &cells) const;

    /** Whether the method changes the displacement of the material points
     * near its supports (support_displacement()). */
    virtual bool
    displaces_points() const
    {
      return false;
    }

    /**
     * The displacement increment @p w of a point at @p x (before it moves)
     * whose grid increment it is, where this method changes it near a
     * support; @p field is the grid increment anywhere in the point's cell.
     * Returns the factor of the D-function there (1 where the method does
     * not act, and leaves @p w).
     */
    virtual double
    support_displacement(
      const BoundaryCurves                                &curves,
      const BackgroundGrid                                &grid,
      const Point<2>                                      &x,
      const std::function<Tensor<1, 2>(const Point<2> &)> &field,
      Tensor<1, 2>                                        &w) const;

    /** The band points of the last assemble() on this process (none for
     * a method without a band). */
    virtual const std::vector<BandPoint> &
    band_points() const;

    /** Whether the method imposes prescribed displacements of @p curves
     * through nodal values fitted by least squares. */
    virtual bool
    fits_prescribed_displacement(const BoundaryCurves &curves) const;

    /**
     * Those nodal values for the prescribed displacement's change over
     * @p increment into @p prescribed; @p mass is a matrix with the system's sparsity
     * pattern, used as work space. Returns the root mean square misfit
     * along the supports. Only if fits_prescribed_displacement().
     */
    virtual double
    fit_prescribed_displacement(
      const Context                              &context,
      const LoadIncrement                        &increment,
      TrilinosWrappers::SparseMatrix             &mass,
      LinearAlgebra::distributed::Vector<double> &prescribed) const;

  protected:
    /**
     * Where a stress in the cell of @p piece takes its volumetric strain
     * (Q1CellKernel::stress_column()): with a B-bar kernel, whose
     * @p moments (by active_cell_index) are given, at the centroid of the
     * cell's material, as the points' stiffness does; without (nullptr),
     * at the stress's own point (no value).
     */
    static std::optional<Point<2>>
    bbar_point(const std::vector<CellMoments> *moments,
               const LocallyOwnedCurvePiece   &piece);

    /** What a method adds on one piece of its supports: given @p values
     * reinit()ed on the piece, its terms into @p cell_matrix and
     * @p cell_vector (zero on entry), on the DoFs of the piece's cell. */
    using PieceTerms = std::function<void(const CurvePieceValues &values,
                                          FullMatrix<double>     &cell_matrix,
                                          Vector<double>         &cell_vector)>;

    /**
     * The loop that the terms of every support method share, assemble()'s
     * and add_finite_strain_terms()': over the pieces of this method's
     * supports in locally owned cells (of the curve @p only alone unless
     * nullptr), with the Gauss points @p along each piece, @p piece_terms
     * per piece, its cell's terms added through @p constraints to
     * @p vector and, unless nullptr, to @p matrix.
     */
    void
    add_piece_terms(const Context                   &context,
                    const Quadrature<1>             &along,
                    const BoundaryCurve             *only,
                    const AffineConstraints<double> &constraints,
                    TrilinosWrappers::SparseMatrix  *matrix,
                    TrilinosWrappers::MPI::Vector   &vector,
                    const PieceTerms                &piece_terms) const;

  private:
    const std::string method_name;
  };



  /** A support method of class @p Method made from the parameters of
   * @p prm: the registry's maker (BSMPM_REGISTER_SUPPORT_METHOD). */
  template <class Method>
  std::unique_ptr<SupportMethod>
  create_support_method(ParameterHandler &prm)
  {
    auto method = std::make_unique<Method>();
    method->parse_parameters(prm);
    return method;
  }

  /**
   * One support method as the registry knows it: how its parameters are
   * declared, and how it is made from them.
   */
  struct SupportMethodEntry
  {
    void (*declare_parameters)(ParameterHandler &prm);
    std::unique_ptr<SupportMethod> (*create)(ParameterHandler &prm);
  };

  /**
   * Adds a support method to the registry under @p name, the value of
   * "Boundary curves/Curve k/Dirichlet method" that selects it. Called
   * before main() by BSMPM_REGISTER_SUPPORT_METHOD. Returns true.
   */
  bool
  register_support_method(const std::string        &name,
                          const SupportMethodEntry &entry);

  /** The registered support methods by name, in alphabetical order. */
  const std::map<std::string, SupportMethodEntry> &
  registered_support_methods();

  /** Their names, separated by '|': the values of "Dirichlet method". */
  std::string
  support_method_names();
} // namespace bsmpm

/**
 * Registers the SupportMethod @p classname under the "Dirichlet method"
 * value @p name. @p classname needs a default constructor and static
 * declare_parameters(ParameterHandler &); it is made by
 * create_support_method(). Use it once, inside namespace bsmpm of the
 * method's source file.
 */
#define BSMPM_REGISTER_SUPPORT_METHOD(classname, name)                       \
  namespace                                                                  \
  {                                                                          \
    const bool classname##_is_registered = ::bsmpm::register_support_method( \
      name,                                                                  \
      {&classname::declare_parameters,                                       \
       &::bsmpm::create_support_method<classname>});                         \
  }

#endif
