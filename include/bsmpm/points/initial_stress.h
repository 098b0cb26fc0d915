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
   *
   * Several bodies stacked as horizontal layers (Bodies) each carry their
   * own weight and K0: sigma_yy is the weight of all layers above a point,
   * the horizontal stresses the point's layer's K0 times it.
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

    /** A body as a horizontal layer: its material, its constitutive model
     * (the at-rest coefficient, the yield check) and its heights. */
    struct Layer
    {
      const LinearElasticMaterial *material;
      const ConstitutiveModel     *model;
      double                       bottom, top;
      /** Whether the layer is there from the start (not built by a later
       * stage: no weight, no stress). */
      bool present = true;
    };

    /**
     * Makes the stress field for the @p layers (one per body, by body
     * number: the region's lowest and highest point; a single body is one
     * layer) under @p gravity. The highest layer reaches up to the ground
     * surface, the lowest down without end. Refuses gravity that is not
     * vertical and downwards, a plane-stress material, and a K0 that puts
     * a layer outside its model's yield surface (checked at its top and
     * bottom: the stress is affine in depth within a layer, and a convex
     * yield function is largest at the ends of that line).
     */
    void
    initialize(const std::vector<Layer> &layers, const Tensor<1, 2> &gravity);

    /** The stress at @p x in body @p body (xx, yy, zz, xy as a tensor in
     * 3D); zero above the ground surface. */
    SymmetricTensor<2, 3>
    stress(const Point<2> &x, const unsigned int body = 0) const;

    /** Gives the points their initial stress and, where they store the
     * state of a nonlinear model, the elastic strain of it (their body's
     * model's elastic compliance). */
    void
    apply(MaterialPoints &points) const;

    /** K0 in use in body @p body (after initialize()). */
    double
    k0(const unsigned int body = 0) const
    {
      return coefficients[body];
    }

  private:
    bool        k0_procedure = false;
    std::string surface_text = "auto";
    std::string k0_text      = "auto";
    double      surface      = 0;
    /** The given K0 (k0_text not auto). */
    double given_k0 = 0;
    /** Per layer, by body: its heights (the highest up to the surface,
     * the lowest without end below), unit weight and K0, and the elastic
     * compliance of its model. */
    std::vector<double> bottoms, tops, unit_weights, coefficients;
    std::vector<SymmetricTensor<4, 3>> compliances;

    /** -sigma_yy at height @p y: the weight of the layers above it. */
    double
    overburden(const double y) const;
  };
} // namespace bsmpm

#endif
