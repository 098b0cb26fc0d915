#include <bsmpm/base/exception_message.h>
#include <bsmpm/bodies/bodies.h>

namespace bsmpm
{
  namespace
  {
    std::string
    body_section(const unsigned int k)
    {
      return "Body " + std::to_string(k);
    }



    /** Whether @p p lies inside @p region and not on its edge: the points
     * a tiny step away in eight directions lie in it too. */
    bool
    strictly_inside(const BodyRegion &region, const Point<2> &p)
    {
      const BoundingBox<2> box = region.bounding_box();
      const double step = 1e-9 * box.get_boundary_points().first.distance(
                                   box.get_boundary_points().second);
      if (!region.contains(p))
        return false;
      for (const int dx : {-1, 0, 1})
        for (const int dy : {-1, 0, 1})
          if ((dx != 0 || dy != 0) &&
              !region.contains(p +
                               step * Tensor<1, 2>({double(dx), double(dy)})))
            return false;
      return true;
    }
  } // namespace



  void
  Bodies::declare_parameters(ParameterHandler &prm)
  {
    for (unsigned int k = 2; k <= max_bodies; ++k)
      {
        prm.enter_subsection(body_section(k));
        prm.declare_entry(
          "Name",
          "",
          Patterns::Anything(),
          "A further body (doc/bodies.md), which takes part when it has a "
          "name (e.g. clay, sand, footing); the first body is the one of the "
          "top-level sections Body region, Material and Material points. The "
          "subsections Body region, Material (its elastic constants, density "
          "and constitutive model, not Kinematics or Volumetric strain, which "
          "the top-level Material sets for all bodies) and Material points "
          "describe it as those of the first body do. Bodies meet bonded: "
          "they share the grid's displacement field. Their regions must not "
          "overlap.");
        BodyRegion::declare_parameters(prm);
        LinearElasticMaterial::declare_parameters(prm);
        MaterialPointLayout::declare_parameters(prm);
        prm.leave_subsection();
      }
  }



  void
  Bodies::parse_parameters(ParameterHandler &prm, const double strength_factor)
  {
    bodies.clear();
    bool gap = false;
    for (unsigned int k = 2; k <= max_bodies; ++k)
      {
        prm.enter_subsection(body_section(k));
        const std::string name = prm.get("Name");
        if (name.empty())
          {
            gap = true;
            prm.leave_subsection();
            continue;
          }
        try
          {
            AssertThrow(!gap,
                        ExcMessage("Name: " + body_section(k - 1) +
                                   " has no name; number the bodies from 2 "
                                   "on without a gap."));
            Body body;
            body.name    = name;
            body.section = body_section(k);
            body.region.parse_parameters(prm);
            body.material.parse_parameters(prm);
            std::unique_ptr<ConstitutiveModel> model =
              create_constitutive_model(prm);
            if (strength_factor != 1.)
              model = model->with_reduced_strength(strength_factor);
            body.model = std::move(model);
            body.layout.parse_parameters(prm);
            bodies.push_back(std::move(body));
          }
        catch (const ExceptionBase &e)
          {
            prm.leave_subsection();
            // The message names the body's section.
            AssertThrow(false,
                        ExcMessage(body_section(k) + "/" + message_of(e)));
          }
        prm.leave_subsection();
      }
  }



  std::optional<BodyRegion>
  Bodies::filled_rectangle(const BodyRegion &first_region) const
  {
    if (bodies.empty())
      return first_region;
    std::vector<const BodyRegion *> regions{&first_region};
    for (const Body &body : bodies)
      regions.push_back(&body.region);
    BoundingBox<2> box  = first_region.bounding_box();
    double         area = 0;
    for (const BodyRegion *region : regions)
      {
        if (region->shape() != BodyRegion::Shape::rectangle)
          return std::nullopt;
        box.merge_with(region->bounding_box());
        area += region->area();
      }
    const auto [lower_left, upper_right] = box.get_boundary_points();
    const double box_area =
      (upper_right[0] - lower_left[0]) * (upper_right[1] - lower_left[1]);
    if (std::abs(area - box_area) > 1e-12 * box_area)
      return std::nullopt;
    return BodyRegion::rectangle(lower_left, upper_right);
  }



  bool
  Bodies::horizontal_layers(const BodyRegion &first_region) const
  {
    const std::optional<BodyRegion> filled = filled_rectangle(first_region);
    if (!filled)
      return false;
    const auto whole   = filled->bounding_box().get_boundary_points();
    const auto as_wide = [&](const BodyRegion &region) {
      const auto box = region.bounding_box().get_boundary_points();
      return box.first[0] == whole.first[0] && box.second[0] == whole.second[0];
    };
    if (!as_wide(first_region))
      return false;
    for (const Body &body : bodies)
      if (!as_wide(body.region))
        return false;
    return true;
  }



  bool
  Bodies::in_earlier_body(const Point<2>    &p,
                          const unsigned int k,
                          const BodyRegion  &first_region) const
  {
    if (first_region.contains(p))
      return true;
    for (unsigned int j = 1; j < k; ++j)
      if (bodies[j - 1].region.contains(p))
        return true;
    return false;
  }



  void
  Bodies::check_overlaps(const MaterialPoints &points,
                         const BodyRegion     &first_region,
                         const MPI_Comm        communicator) const
  {
    using Property = MaterialPoints::Property;
    std::vector<const BodyRegion *> regions{&first_region};
    std::vector<std::string>        sections{"Body region"};
    for (const Body &body : bodies)
      {
        regions.push_back(&body.region);
        sections.push_back(body.section + "/Body region");
      }
    // The first overlap found on this process: (body, other body), or
    // (n, n) for none; the smallest pair over all processes is reported.
    const unsigned int n     = regions.size();
    unsigned int       found = n * n;
    for (const auto &particle : points.particle_handler())
      {
        const auto props = particle.get_properties();
        if (props[Property::volume] == 0.)
          continue;
        const unsigned int b = static_cast<unsigned int>(props[Property::body]);
        for (unsigned int j = 0; j < n; ++j)
          if (j != b && strictly_inside(*regions[j], particle.get_location()))
            found = std::min(found, b * n + j);
      }
    found = Utilities::MPI::min(found, communicator);
    AssertThrow(found == n * n,
                ExcMessage(sections[found / n] + " and " + sections[found % n] +
                           " overlap: bodies may meet along their edges but "
                           "not share material."));
  }
} // namespace bsmpm
