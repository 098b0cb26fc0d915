#ifndef bsmpm_exact_solution_h
#define bsmpm_exact_solution_h

#include <deal.II/base/function.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/symmetric_tensor.h>

#include <bsmpm/materials/material.h>

#include <memory>
#include <string>

namespace bsmpm
{
  using namespace dealii;

  /**
   * A closed-form small-strain solution that a scene is checked against, as
   * a Function<2> of the initial position X with five components:
   * displacement u, v and stress sigma_xx, sigma_yy, sigma_xy.
   *
   * All of bsmpm's exact solutions live in this file and are chosen by name
   * in the "Exact solution" section of a scene:
   * - column under self weight: 1D strain under gravity, fixed base;
   * - constant stress: a homogeneous stress, optionally in a rotated frame
   *   (the square compression tests, paper Sec. 4.1);
   * - lame cylinder: internally pressurised thick cylinder (paper Sec. 4.3);
   * - kirsch plate: infinite plate with a circular hole under far-field
   *   tension (paper Sec. 4.4, eqs 42-46).
   */
  class ExactSolution : public Function<2>
  {
  public:
    ExactSolution()
      : Function<2>(5)
    {}

    virtual Tensor<1, 2>
    displacement(const Point<2> &X) const = 0;

    virtual SymmetricTensor<2, 2>
    stress(const Point<2> &X) const = 0;

    /** Traction sigma n on a surface with outward unit normal @p n. */
    Tensor<1, 2>
    traction(const Point<2> &X, const Tensor<1, 2> &n) const
    {
      return stress(X) * n;
    }

    /** A short description with the solution's derived figures (printed). */
    virtual std::string
    description() const = 0;

    double
    value(const Point<2> &X, const unsigned int component) const override;

    void
    vector_value(const Point<2> &X, Vector<double> &values) const override;

    static void
    declare_parameters(ParameterHandler &prm);

    /**
     * Creates the solution named in the "Exact solution" section, or returns
     * nullptr for "none". @p gravity is the acceleration of the Loading
     * section (used by the column); @p finite_strain selects the
     * finite-strain solution where there is one (the column).
     */
    static std::unique_ptr<ExactSolution>
    create(ParameterHandler            &prm,
           const LinearElasticMaterial &material,
           const Tensor<1, 2>          &gravity,
           const bool                   finite_strain = false);
  };



  /** Elastic column under its own weight: fixed base, free top, rollers on
   * the sides, so that eps_xx = 0 and u_y depends on y only. */
  class ColumnUnderSelfWeight : public ExactSolution
  {
  public:
    /** With @p finite_strain, the column of Hencky material in finite
     * strain (doc/finite-strain.md): the stress is the same function of
     * the initial height, the displacement follows through Lambert's W. */
    ColumnUnderSelfWeight(const LinearElasticMaterial &material,
                          const double                 unit_weight_y,
                          const double                 base,
                          const double                 height,
                          const bool                   finite_strain = false);
    Tensor<1, 2>
    displacement(const Point<2> &X) const override;
    SymmetricTensor<2, 2>
    stress(const Point<2> &X) const override;
    std::string
    description() const override;

  private:
    double b_y, base, height, constrained_modulus, lateral_ratio;
    bool   finite_strain;
  };



  /** Homogeneous stress (given in a frame rotated by @p angle) with zero
   * displacement at @p fixed_point and no rigid rotation. */
  class ConstantStress : public ExactSolution
  {
  public:
    ConstantStress(const LinearElasticMaterial &material,
                   const Voigt                 &stress_in_frame,
                   const double                 angle,
                   const Point<2>              &fixed_point);
    Tensor<1, 2>
    displacement(const Point<2> &X) const override;
    SymmetricTensor<2, 2>
    stress(const Point<2> &X) const override;
    std::string
    description() const override;

  private:
    SymmetricTensor<2, 2> sigma, epsilon;
    Point<2>              fixed_point;
  };



  /** Lame's thick cylinder under inner pressure p, traction-free outside. */
  class LameCylinder : public ExactSolution
  {
  public:
    /** If @p inner_displacement is positive, the pressure is the one that
     * moves the inner radius outwards by that much. */
    LameCylinder(const LinearElasticMaterial &material,
                 const Point<2>              &center,
                 const double                 inner_radius,
                 const double                 outer_radius,
                 const double                 pressure,
                 const double                 inner_displacement);
    Tensor<1, 2>
    displacement(const Point<2> &X) const override;
    SymmetricTensor<2, 2>
    stress(const Point<2> &X) const override;
    std::string
    description() const override;

    double
    pressure() const
    {
      return p;
    }
    const Point<2> &
    axis() const
    {
      return center;
    }
    /** Radial displacement at radius @p r. */
    double
    radial_displacement(const double r) const;

  private:
    Point<2> center;
    double   a, b, p;
    double   E, nu;
    bool     plane_strain;
  };



  /** Kirsch's infinite plate with a hole of radius r_i under far-field
   * tension S along x (Timoshenko and Goodier; paper eqs 42-46). */
  class KirschPlate : public ExactSolution
  {
  public:
    KirschPlate(const LinearElasticMaterial &material,
                const Point<2>              &center,
                const double                 hole_radius,
                const double                 far_field_stress);
    Tensor<1, 2>
    displacement(const Point<2> &X) const override;
    SymmetricTensor<2, 2>
    stress(const Point<2> &X) const override;
    std::string
    description() const override;

  private:
    Point<2> center;
    double   a, S, mu, kappa;
  };
} // namespace bsmpm

#endif
