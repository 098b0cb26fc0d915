#ifndef bsmpm_initial_stress_h
#define bsmpm_initial_stress_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>
#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>

#include <bsmpm/materials/constitutive_model.h>
#include <bsmpm/materials/material.h>

namespace bsmpm
{
  using namespace dealii;

  class MaterialPoints;

  /**
   * The stress the ground starts with (section "Initial stress",
   * doc/stages.md): the K0 procedure for level ground. Below the ground
   * surface y_s the vertical stress is the weight of the material above,
   * sigma_yy = -gamma (y_s - y), gamma = density |gravity|, and the
   * horizontal ones (in the plane and out of it) are K0 times it, with no
   * shear: the state of a laterally confined layer under its own weight.
   * K0 is given, or the model's at-rest coefficient
   * (ConstitutiveModel::at_rest_coefficient(): nu / (1 - nu) for an
   * elastic or von Mises material, Jaky's 1 - sin(phi) for Drucker-Prager).
   *
   * The body force is then on from the start: the stress balances it, and
   * the loads of the stages come on top (LoadStages). On level ground with
   * K0 = nu / (1 - nu) an elastic body is in the state that a gravity stage
   * gives, without its displacements. A ground that is not level, or a
   * K0 the material cannot carry (refused at setup), wants a gravity stage
   * instead.
   */
  class InitialStress
  {
  public:
    static void
    declare_parameters(ParameterHandler &prm);

    void
    parse_parameters(ParameterHandler &prm);

    bool
    enabled() const
    {
      return k0_procedure;
    }

    /**
     * Makes the stress field for a body whose highest point is at
     * @p top and lowest at @p bottom (the body region's bounding box), of
     * @p material under @p gravity, with @p model for the at-rest
     * coefficient. Refuses gravity that is not vertical and downwards, a
     * plane-stress material, and a K0 that puts the body outside the
     * model's yield surface (checked at the surface and at the bottom:
     * the stress is proportional to depth, and a convex yield function is
     * largest at the ends of that line).
     */
    void
    initialize(const double                 top,
               const double                 bottom,
               const LinearElasticMaterial &material,
               const Tensor<1, 2>          &gravity,
               const ConstitutiveModel     &model);

    /** The stress at @p x (xx, yy, zz, xy as a tensor in 3D); zero above
     * the ground surface. */
    SymmetricTensor<2, 3>
    stress(const Point<2> &x) const;

    /** Gives the points their initial stress and, where they store the
     * state of a nonlinear model, the elastic strain of it (@p model's
     * elastic compliance). */
    void
    apply(MaterialPoints &points, const ConstitutiveModel &model) const;

    /** K0 in use (after initialize()). */
    double
    k0() const
    {
      return coefficient;
    }

  private:
    bool        k0_procedure = false;
    std::string surface_text = "auto";
    std::string k0_text      = "auto";
    double      surface      = 0;
    double      unit_weight  = 0;
    double      coefficient  = 0;
  };
} // namespace bsmpm

#endif
