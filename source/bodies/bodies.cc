#include <bsmpm/base/exception_message.h>
#include <bsmpm/bodies/bodies.h>

#include <algorithm>
#include <cmath>

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



  void
  Bodies::build_in_stages(
    const std::vector<std::vector<std::string>> &names_by_stage)
  {
    for (Body &body : bodies)
      body.stage = 1;
    for (unsigned int k = 1; k <= names_by_stage.size(); ++k)
      for (const std::string &name : names_by_stage[k - 1])
        {
          const std::string where =
            "Stages/Stage " + std::to_string(k) + "/Construction = " + name;
          const auto body =
            std::find_if(bodies.begin(), bodies.end(), [&](const Body &b) {
              return b.name == name;
            });
          if (body == bodies.end())
            {
              std::string names;
              for (const Body &b : bodies)
                names += (names.empty() ? "" : ", ") + b.name;
              AssertThrow(false,
                          ExcMessage(where +
                                     ": no further body has that name (they "
                                     "are: " +
                                     (names.empty() ? "none" : names) +
                                     "; the first body is there from the "
                                     "start)."));
            }
          AssertThrow(k > 1,
                      ExcMessage(where +
                                 ": stage 1 starts the analysis, with every "
                                 "body there; build it in a later stage."));
          AssertThrow(body->stage == 1,
                      ExcMessage(where + ": " + body->section +
                                 " is built by stage " +
                                 std::to_string(body->stage) + " already."));
          body->stage = k;
        }
  }



  bool
  Bodies::built_later() const
  {
    return std::any_of(bodies.begin(), bodies.end(), [](const Body &body) {
      return body.stage > 1;
    });
  }



  std::optional<BodyRegion>
  Bodies::filled_rectangle(const BodyRegion &first_region) const
  {
    std::vector<const BodyRegion *> regions{&first_region};
    for (const Body &body : bodies)
      if (body.stage == 1)
        regions.push_back(&body.region);
    if (regions.size() == 1)
      return first_region;
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
      if (body.stage == 1 && !as_wide(body.region))
        return false;
    return true;
  }



  bool
  Bodies::in_earlier_body(const Point<2>    &p,
                          const unsigned int k,
                          const BodyRegion  &first_region) const
  {
    // Earlier: built in an earlier stage, or in the same one with a lower
    // number (the first body is there from the start).
    const auto stage_of = [this](const unsigned int j) {
      return j == 0 ? 1u : bodies[j - 1].stage;
    };
    const auto region_of = [&](const unsigned int j) -> const BodyRegion & {
      return j == 0 ? first_region : bodies[j - 1].region;
    };
    for (unsigned int j = 0; j <= bodies.size(); ++j)
      if (j != k &&
          (stage_of(j) < stage_of(k) ||
           (stage_of(j) == stage_of(k) && j < k)) &&
          region_of(j).contains(p))
        return true;
    return false;
  }



  void
  Bodies::check_overlaps(const MaterialPoints &points,
                         const BackgroundGrid &grid,
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
    const auto         test  = [&](const unsigned int b, const Point<2> &p) {
      for (unsigned int j = 0; j < n; ++j)
        if (j != b && strictly_inside(*regions[j], p))
          found = std::min(found, b * n + j);
    };
    for (const auto &particle : points.particle_handler())
      {
        const auto props = particle.get_properties();
        if (props[Property::volume] != 0.)
          test(static_cast<unsigned int>(props[Property::body]),
               particle.get_location());
      }
    // The bodies that later stages build, by the points they will have.
    for (unsigned int k = 1; k <= bodies.size(); ++k)
      if (bodies[k - 1].stage > 1)
        bodies[k - 1].layout.for_each_point(
          grid,
          bodies[k - 1].region,
          [&](const MaterialPointLayout::CellIndex &ij) {
            return grid.locally_owned_cell(ij) != grid.dof_handler().end();
          },
          [&](const Point<2> &p, double, unsigned long) {
            if (!in_earlier_body(p, k, first_region))
              test(k, p);
          });
    found = Utilities::MPI::min(found, communicator);
    AssertThrow(found == n * n,
                ExcMessage(sections[found / n] + " and " + sections[found % n] +
                           " overlap: bodies may meet along their edges but "
                           "not share material."));
  }



  void
  Bodies::record(const MaterialPoints          &points,
                 const MPI_Comm                 communicator,
                 std::map<std::string, double> &quantities) const
  {
    using Property       = MaterialPoints::Property;
    const unsigned int n = bodies.size() + 1;
    // Per body: points, volume, yielded points (sums); the largest
    // displacement (maximum).
    std::vector<double> sums(3 * n), largest(n);
    for (const auto &particle : points.particle_handler())
      {
        const auto props = particle.get_properties();
        if (props[Property::volume] == 0.)
          continue;
        const unsigned int b = static_cast<unsigned int>(props[Property::body]);
        sums[3 * b] += 1;
        sums[3 * b + 1] += props[Property::volume];
        sums[3 * b + 2] += props[Property::yielded] > 0 ? 1 : 0;
        largest[b] = std::max(largest[b],
                              std::hypot(props[Property::displacement],
                                         props[Property::displacement + 1]));
      }
    Utilities::MPI::sum(sums, communicator, sums);
    Utilities::MPI::max(largest, communicator, largest);
    for (unsigned int b = 0; b < n; ++b)
      {
        const std::string key      = "body_" + std::to_string(b + 1) + "_";
        quantities[key + "points"] = sums[3 * b];
        quantities[key + "volume"] = sums[3 * b + 1];
        quantities[key + "yielded_points"]   = sums[3 * b + 2];
        quantities[key + "max_displacement"] = largest[b];
      }
  }
} // namespace bsmpm
