#ifndef bsmpm_constitutive_model_h
#define bsmpm_constitutive_model_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>

#include <array>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace bsmpm
{
  using namespace dealii;

  /**
   * What a material point keeps of its constitutive model between load
   * steps.
   */
  struct ConstitutiveState
  {
    /** Elastic strain: the small-strain elastic strain, or the logarithmic
     * elastic strain ln(b_e)/2 in finite strain. In plane strain its zz
     * component is carried. */
    SymmetricTensor<2, 3> elastic_strain;
    /** Accumulated equivalent plastic strain, sum of sqrt(2/3) |d eps_p|. */
    double equivalent_plastic_strain = 0;
  };



  /**
   * What update() returns.
   */
  struct ConstitutiveResponse
  {
    /** Cauchy stress (small strain) or Kirchhoff stress (finite strain). */
    SymmetricTensor<2, 3> stress;
    /** Algorithmic tangent d stress / d trial elastic strain (minor
     * symmetries; without major symmetry for non-associated flow). */
    SymmetricTensor<4, 3> tangent;
    /** Whether the step returned to the yield surface. If not, the
     * tangent is the model's elastic_tangent() (ConstitutiveUpdate sums
     * the points that do not yield with it, as the linear kernel does). */
    bool yielded = false;
  };



  /**
   * A constitutive model in three dimensions, usable for small strain
   * (trial elastic strain in, Cauchy stress out) and for finite strain by
   * the Hencky/exponential-map route (trial logarithmic elastic strain
   * ln(b_e^tr)/2 in, Kirchhoff stress out): for isotropic models with
   * Hencky elasticity both are the same map (doc/materials.md, Sec. 1).
   *
   * Each model has its own parameter subsection of "Material"; the elastic
   * constants are the section's "Young's modulus" and "Poisson's ratio".
   * update() is const and thread-safe.
   */
  class ConstitutiveModel
  {
  public:
    ConstitutiveModel(const double youngs_modulus, const double poissons_ratio);
    virtual ~ConstitutiveModel() = default;

    /**
     * On entry state.elastic_strain is the TRIAL elastic strain and
     * state.equivalent_plastic_strain the converged one of the last step;
     * on exit both are the returned (updated) values.
     */
    virtual ConstitutiveResponse
    update(ConstitutiveState &state) const = 0;

    /**
     * update() as the small-strain Newton system of a plane-strain point
     * needs it (ConstitutiveUpdate::cell_system() and commit()): the same
     * return and the same numbers, the stress as (xx, yy, zz, xy) in
     * @p stress, and the algorithmic tangent in Voigt form (rows xx, yy,
     * zz, xy; columns the same with the engineering shear, as
     * ConstitutiveUpdate::voigt_tangent() makes it) in @p tangent, row by
     * row, but only where the step yields: a step that does not yield has
     * elastic_tangent(), which the caller takes once per cell, and
     * @p tangent is left as it is. Returns whether the step yields. The
     * state's xz and yz strains are zero (plane strain).
     *
     * Most points of a Newton system do not yield, and update() builds
     * them the 36-entry rank-4 tangent all the same: the models override
     * this with an elastic check that builds none. The default calls
     * update().
     */
    virtual bool
    plane_strain_update(ConstitutiveState      &state,
                        std::array<double, 4>  &stress,
                        std::array<double, 16> &tangent) const;

    /**
     * How far the trial elastic strain may move from that of @p state (in
     * the norm of the strain tensor) with the step staying elastic: every
     * trial strain e with |e - state.elastic_strain| < elastic_reach(state)
     * has the stress elastic_tangent() : e and does not yield. A cell whose
     * points all stay within their reach is then integrated from moments
     * of their strains, without a return map per point (doc/newton.md,
     * "Cells that stay elastic"). 0, the default, promises nothing;
     * infinity for linear elasticity.
     */
    virtual double
    elastic_reach(const ConstitutiveState &state) const;

    /** The stress of @p response as (xx, yy, zz, xy) and, if it yielded,
     * its tangent in Voigt form (plane_strain_update()). */
    static void
    plane_strain_response(const ConstitutiveResponse &response,
                          std::array<double, 4>      &stress,
                          std::array<double, 16>     &tangent);

    /** Yield function: <= 0 for admissible stresses; -infinity for linear
     * elasticity. */
    virtual double
    yield_function(const SymmetricTensor<2, 3> &stress,
                   const double                 eq_plastic_strain) const;

    /** Tangent of an elastic step (for the linear elastic model in plane
     * stress: with sigma_zz = 0 condensed). */
    virtual SymmetricTensor<4, 3>
    elastic_tangent() const;

    /** The ratio K0 of horizontal to vertical stress in level ground at
     * rest (InitialStress): nu / (1 - nu), that of an elastic layer under
     * its own weight, unless the model knows better. */
    virtual double
    at_rest_coefficient() const
    {
      return poissons_ratio() / (1. - poissons_ratio());
    }
    /** True for linear elasticity: no state, stress linear in the strain,
     * so that the code may keep its linear fast path. */
    virtual bool
    is_linear() const;

    /** Whether the algorithmic tangent has the major symmetry (false for
     * non-associated flow), so that CG can solve the Newton systems. */
    virtual bool
    symmetric_tangent() const
    {
      return true;
    }

    /** The name as given in "Material/Constitutive model". */
    virtual std::string
    name() const = 0;

    /**
     * The same model with its strength divided by @p factor (> 0), for the
     * strength reduction method (doc/limit-loads.md): von Mises divides the
     * yield stress (and the hardening modulus), Drucker-Prager the cohesion
     * and the tangents of the friction and dilation angles. The default
     * refuses: a model without a strength has no factor of safety.
     */
    virtual std::unique_ptr<ConstitutiveModel>
    with_reduced_strength(const double factor) const;

    double
    youngs_modulus() const
    {
      return E;
    }
    double
    poissons_ratio() const
    {
      return nu;
    }
    double
    shear_modulus() const
    {
      return mu;
    }
    double
    bulk_modulus() const
    {
      return kappa;
    }

  protected:
    /** D^e : eps = K tr(eps) 1 + 2 mu dev(eps). */
    SymmetricTensor<2, 3>
    elastic_stress(const SymmetricTensor<2, 3> &elastic_strain) const;

    /** elastic_stress() of a plane-strain elastic strain (xz = yz = 0) as
     * (xx, yy, zz, xy), with the deviator @p e of it at hand: the same
     * numbers as K tr(eps) 1 + 2 mu e. */
    void
    plane_strain_elastic_stress(const SymmetricTensor<2, 3> &eps,
                                const SymmetricTensor<2, 3> &e,
                                std::array<double, 4>       &stress) const
    {
      const double p = kappa * trace(eps);
      stress[0]      = p + 2. * mu * e[0][0];
      stress[1]      = p + 2. * mu * e[1][1];
      stress[2]      = p + 2. * mu * e[2][2];
      stress[3]      = 2. * mu * e[0][1];
    }

    /** The three-dimensional isotropic stiffness K 1 (x) 1 + 2 mu I_d. */
    const SymmetricTensor<4, 3> &
    isotropic_stiffness() const
    {
      return stiffness_3d;
    }

    /** The entry of the deviatoric projector I_d = 1/2 (d_ik d_jl + d_il
     * d_jk) - d_ij d_kl / 3 between deal.II's stored pairs @p r and @p c of
     * a symmetric 3x3 tensor, (00, 11, 22, 01, 02, 12): delta_rc - 1/3
     * between normal components, delta_rc / 2 between shear components. */
    static double
    deviatoric_projector(const unsigned int r, const unsigned int c)
    {
      return r < 3 && c < 3 ? (r == c ? 2. / 3. : -1. / 3.) : r == c ? 0.5 : 0.;
    }

    /** t += a I_d + b n (x) n, written entry by entry (deal.II's
     * outer_product of symmetric tensors is slow). */
    static void
    add_deviatoric_terms(SymmetricTensor<4, 3>       &t,
                         const double                 a,
                         const double                 b,
                         const SymmetricTensor<2, 3> &n);

    double                E;
    double                nu;
    double                mu;
    double                kappa;
    SymmetricTensor<4, 3> stiffness_3d;
  };



  /**
   * Eigenvalues and orthonormal eigenvectors of a symmetric tensor (Jacobi's
   * method), in descending order, and the assembly of isotropic tensor
   * functions and of their derivatives from principal values
   * (doc/materials.md, Sec. 5).
   */
  class SpectralDecomposition
  {
  public:
    explicit SpectralDecomposition(const SymmetricTensor<2, 3> &x);

    /** sum_A y_A n_A (x) n_A. */
    SymmetricTensor<2, 3>
    assemble(const std::array<double, 3> &y) const;

    /**
     * d y / d x = sum_AB dy_dx[A][B] M_A (x) M_B
     *             + sum_{A<B} rho_AB W_AB (x) W_AB,
     * with spin moduli rho = {rho_01, rho_02, rho_12}.
     */
    SymmetricTensor<4, 3>
    assemble_tangent(const Tensor<2, 3>          &dy_dx,
                     const std::array<double, 3> &rho) const;

    /** The difference quotient (y_a - y_b) / (x_a - x_b), replaced by its
     * limit (limit_a + limit_b) / 2 where the gap is below about the cube
     * root of the machine epsilon times max(|x_a|, |x_b|). */
    static double
    spin_modulus(const double x_a,
                 const double x_b,
                 const double y_a,
                 const double y_b,
                 const double limit_a,
                 const double limit_b);

    std::array<double, 3>       values;
    std::array<Tensor<1, 3>, 3> vectors;
  };



  /**
   * f(x) = sum_A f(x_A) n_A (x) n_A of a symmetric tensor and its derivative
   * d f(x) / d x, robust for equal and nearly equal eigenvalues. With f = ln
   * it gives the logarithmic strain ln(b)/2 (times 2) and d ln(b) / d b of
   * the finite-strain tangent; with f = exp, b_e = exp(2 eps_e).
   */
  std::pair<SymmetricTensor<2, 3>, SymmetricTensor<4, 3>>
  isotropic_tensor_function(const SymmetricTensor<2, 3>         &x,
                            const std::function<double(double)> &f,
                            const std::function<double(double)> &df);

  /** What every model is made from: the elastic constants of "Material"
   * and the plane idealisation. */
  struct ElasticConstants
  {
    double youngs_modulus;
    double poissons_ratio;
    bool   plane_stress;
  };

  /**
   * One constitutive model as the registry knows it: what "Material/
   * Constitutive model" documents for it, whether it may be used in plane
   * stress, and how its parameters are declared and read (in the subsection
   * "Material", each model in a subsection of its own).
   */
  struct ConstitutiveModelEntry
  {
    std::string description;
    bool        plane_stress;
    void (*declare_parameters)(ParameterHandler &prm);
    std::unique_ptr<ConstitutiveModel> (
      *create)(ParameterHandler &prm, const ElasticConstants &elastic);
  };

  /**
   * Adds a model to the registry under @p name, the value of "Material/
   * Constitutive model" that selects it. Called before main() by
   * BSMPM_REGISTER_CONSTITUTIVE_MODEL in the model's own source file, so
   * that this interface knows no model (the pattern of ASPECT's
   * ASPECT_REGISTER_MATERIAL_MODEL). Returns true.
   */
  bool
  register_constitutive_model(const std::string            &name,
                              const ConstitutiveModelEntry &entry);

  /** The names of the registered models, in alphabetical order. */
  std::vector<std::string>
  constitutive_model_names();

  /**
   * Declares "Material/Constitutive model" (a selection among the
   * registered models) and the parameters of every registered model. Call
   * it at the top level: it enters "Material" itself.
   * LinearElasticMaterial::declare_parameters() calls it.
   */
  void
  declare_constitutive_parameters(ParameterHandler &prm);

  /**
   * The model chosen in "Material/Constitutive model", with the elastic
   * constants and the plane model of "Material" (checked as
   * LinearElasticMaterial does). Refuses a model that needs plane strain in
   * plane stress.
   */
  std::unique_ptr<ConstitutiveModel>
  create_constitutive_model(ParameterHandler &prm);

  /**
   * Throws unless the constitutive model @p name can be used with the
   * two-dimensional idealisation (plasticity needs plane strain).
   */
  void
  check_constitutive_model_compatibility(const std::string &name,
                                         const bool         plane_stress);
} // namespace bsmpm

/**
 * Registers the ConstitutiveModel @p classname under the parameter value
 * @p name (see register_constitutive_model()). @p classname needs
 * static declare_parameters(ParameterHandler &) and
 * static create(ParameterHandler &, const ElasticConstants &). Use it once,
 * inside namespace bsmpm of the model's source file.
 */
#define BSMPM_REGISTER_CONSTITUTIVE_MODEL(classname,                        \
                                          name,                             \
                                          plane_stress,                     \
                                          description)                      \
  namespace                                                                 \
  {                                                                         \
    const bool classname##_is_registered =                                  \
      ::bsmpm::register_constitutive_model(name,                            \
                                           {description,                    \
                                            plane_stress,                   \
                                            &classname::declare_parameters, \
                                            &classname::create});           \
  }

#endif
