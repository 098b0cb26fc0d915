#include <bsmpm/points/initial_stress.h>
#include <bsmpm/points/material_points.h>

#include <cmath>
#include <limits>
#include <sstream>

namespace bsmpm
{
  void
  InitialStress::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Initial stress");
    prm.declare_entry(
      "Kind",
      "none",
      Patterns::Selection("none|K0 procedure"),
      "none: the body starts unstressed, and gravity comes on with the "
      "load steps. K0 procedure: level ground starts in the state of a "
      "laterally confined layer under its own weight (doc/stages.md): "
      "sigma_yy = -gamma (Ground surface - y), gamma = Material/Density "
      "times |Loading/Gravity|, the horizontal stresses K0 sigma_yy, no "
      "shear; gravity is then on from the start.");
    prm.declare_entry("Ground surface",
                      "auto",
                      Patterns::Anything(),
                      "K0 procedure: the height y of the level ground "
                      "surface in m; auto: the top of the body region.");
    prm.declare_entry("K0",
                      "auto",
                      Patterns::Anything(),
                      "K0 procedure: the ratio of horizontal to vertical "
                      "stress; auto: nu / (1 - nu) (linear elastic, von "
                      "Mises), 1 - sin(phi) (Drucker-Prager).");
    prm.leave_subsection();
  }



  void
  InitialStress::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Initial stress");
    k0_procedure = prm.get("Kind") == "K0 procedure";
    surface_text = Utilities::trim(prm.get("Ground surface"));
    k0_text      = Utilities::trim(prm.get("K0"));
    prm.leave_subsection();
    const auto number = [](const std::string &text, const std::string &name) {
      std::istringstream in(text);
      double             value = 0;
      in >> value;
      AssertThrow(!in.fail() && in.eof() && std::isfinite(value),
                  ExcMessage("Initial stress/" + name + " = '" + text +
                             "': give a number, or auto."));
      return value;
    };
    if (surface_text != "auto")
      surface = number(surface_text, "Ground surface");
    if (k0_text != "auto")
      {
        given_k0 = number(k0_text, "K0");
        AssertThrow(given_k0 >= 0,
                    ExcMessage("Initial stress/K0 = " + k0_text +
                               ": a ratio of stresses, at least 0."));
      }
  }



  void
  InitialStress::initialize(const std::vector<Layer> &layers,
                            const Tensor<1, 2>       &gravity)
  {
    if (!k0_procedure)
      return;
    double highest = -std::numeric_limits<double>::infinity();
    double lowest  = std::numeric_limits<double>::infinity();
    for (const Layer &layer : layers)
      {
        if (!layer.present)
          continue;
        AssertThrow(layer.material->model() !=
                      LinearElasticMaterial::Model::plane_stress,
                    ExcMessage("Initial stress/Kind = K0 procedure is for "
                               "ground in plane strain; Material/Model is "
                               "plane stress."));
        AssertThrow(gravity[0] == 0 && gravity[1] < 0 &&
                      layer.material->density() > 0,
                    ExcMessage("Initial stress/Kind = K0 procedure needs the "
                               "weight of the ground: Material/Density > 0 "
                               "and Loading/Gravity vertical and downwards "
                               "(0, -g)."));
        highest = std::max(highest, layer.top);
        lowest  = std::min(lowest, layer.bottom);
      }
    if (surface_text == "auto")
      surface = highest;
    bottoms.clear();
    tops.clear();
    unit_weights.clear();
    coefficients.clear();
    compliances.clear();
    for (const Layer &layer : layers)
      {
        bottoms.push_back(layer.bottom == lowest ?
                            -std::numeric_limits<double>::infinity() :
                            layer.bottom);
        tops.push_back(layer.top == highest ?
                         std::numeric_limits<double>::infinity() :
                         layer.top);
        unit_weights.push_back(
          layer.present ? -layer.material->density() * gravity[1] : 0.);
        coefficients.push_back(
          k0_text == "auto" ? layer.model->at_rest_coefficient() : given_k0);
        compliances.push_back(invert(layer.model->elastic_tangent()));
      }

    // The stress is affine in depth within a layer; a convex yield
    // function is largest at an end of that line: the layer's top (or the
    // surface) or its bottom.
    for (unsigned int b = 0; b < layers.size(); ++b)
      {
        if (!layers[b].present)
          continue;
        const ConstitutiveModel &model = *layers[b].model;
        const double             upper = std::min(surface, layers[b].top);
        const double             lower = std::min(upper, layers[b].bottom);
        const double             f =
          model.yield_function(stress(Point<2>(0., lower), b), 0.);
        if (!(f > 0))
          continue;
        // Where along the depth it crosses the surface (f(0) <= 0).
        const double f0 =
          model.yield_function(stress(Point<2>(0., upper), b), 0.);
        const double depth =
          (surface - upper) + (upper - lower) * (f0 < 0 ? -f0 / (f - f0) : 0.);
        std::ostringstream message;
        message << "Initial stress: K0 = " << coefficients[b]
                << " puts the ground deeper than " << depth
                << " m below the surface y = " << surface
                << " outside the yield surface of the " << model.name()
                << " material (at y = " << lower << ", the yield function is "
                << f
                << " > 0): the material cannot carry that state at rest. "
                   "Give a K0 nearer 1 (Initial stress/K0), or let a first "
                   "stage bring the ground's weight (Stages).";
        AssertThrow(false, ExcMessage(message.str()));
      }
  }



  double
  InitialStress::overburden(const double y) const
  {
    double weight = 0;
    for (unsigned int b = 0; b < unit_weights.size(); ++b)
      weight +=
        unit_weights[b] *
        std::max(0., std::min(surface, tops[b]) - std::max(y, bottoms[b]));
    return weight;
  }



  SymmetricTensor<2, 3>
  InitialStress::stress(const Point<2> &x, const unsigned int body) const
  {
    SymmetricTensor<2, 3> sigma;
    const double          sigma_v = -overburden(x[1]);
    sigma[0][0]                   = coefficients[body] * sigma_v;
    sigma[1][1]                   = sigma_v;
    sigma[2][2]                   = coefficients[body] * sigma_v;
    return sigma;
  }



  void
  InitialStress::apply(MaterialPoints &points) const
  {
    if (!k0_procedure)
      return;
    points.set_stress([&](const Point<2>    &x,
                          const unsigned int body) { return stress(x, body); },
                      compliances);
  }
} // namespace bsmpm
