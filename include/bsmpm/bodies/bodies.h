#ifndef bsmpm_bodies_h
#define bsmpm_bodies_h

#include <deal.II/base/parameter_handler.h>

#include <bsmpm/geometry/body_region.h>
#include <bsmpm/materials/constitutive_model.h>
#include <bsmpm/materials/material.h>
#include <bsmpm/points/material_point_layout.h>
#include <bsmpm/points/material_points.h>

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace bsmpm
{
  using namespace dealii;

  /**
   * The bodies of a scene beyond the first (doc/bodies.md): subsections
   * "Body 2" .. "Body 4", each with a Name (empty: no such body) and its
   * own "Body region", "Material" and "Material points", read by the same
   * classes as the first body's, which the top level of the parameter file
   * describes (the short form of a scene with one body).
   *
   * The bodies share the grid's field: where they meet they are bonded
   * (no slip, no gap). Every point belongs to one body (its
   * MaterialPoints::Property::body, 0 for the first) and is integrated with
   * that body's constitutive model and density.
   */
  class Bodies
  {
  public:
    /** Most bodies in a scene, the first included. */
    static constexpr unsigned int max_bodies = 4;

    /** One further body. */
    struct Body
    {
      std::string           name;
      BodyRegion            region;
      MaterialPointLayout   layout;
      LinearElasticMaterial material;
      /** Its constitutive model (Material/Constitutive model). */
      std::shared_ptr<const ConstitutiveModel> model;
      /** Its parameter section, for messages: "Body 2". */
      std::string section;
      /** The stage that builds it (Stages/Stage k/Construction); 1: there
       * from the start. */
      unsigned int stage = 1;
    };

    /** Declares "Body 2" .. "Body 4". */
    static void
    declare_parameters(ParameterHandler &prm);

    /** Reads the bodies whose Name is not empty, their strengths divided by
     * @p strength_factor (StrengthReduction). They must come in order: a
     * Body k with a name needs Body k - 1 to have one. */
    void
    parse_parameters(ParameterHandler &prm, const double strength_factor);

    /** The further bodies, in order (body number 1, 2, ...: the points'
     * Property::body). */
    const std::vector<Body> &
    further() const
    {
      return bodies;
    }

    /** Whether the scene has more than one body. */
    bool
    several() const
    {
      return !bodies.empty();
    }

    /** Records which stage builds which body: @p names_by_stage[k - 1]
     * are the names that Stages/Stage k/Construction gives. Refuses an
     * unknown name, stage 1 and a body built twice. */
    void
    build_in_stages(
      const std::vector<std::vector<std::string>> &names_by_stage);

    /** Whether a stage after the first builds a body. */
    bool
    built_later() const;

    /**
     * The region the boundary curves refer to ("region edge") and are
     * completed round: the rectangle that the bodies fill together where
     * every body's region is an axis-aligned rectangle and their areas add
     * up to that of their bounding box (layers), else nothing (the curves
     * then lie on the first body's edges, @p first_region, and are not
     * completed). With one body, @p first_region. Only the bodies there
     * from the start count: those built later have no curves.
     */
    std::optional<BodyRegion>
    filled_rectangle(const BodyRegion &first_region) const;

    /** Whether the bodies fill a rectangle (filled_rectangle()) as
     * horizontal layers: each as wide as the rectangle. */
    bool
    horizontal_layers(const BodyRegion &first_region) const;

    /**
     * Whether @p p lies in the region of a body before body @p k (from 1:
     * a further body; the first body's region is @p first_region): a
     * point of the layout on an edge that two bodies share belongs to the
     * earlier body, so that the material is not counted twice. Earlier:
     * built in an earlier stage, or in the same with a lower number.
     */
    bool
    in_earlier_body(const Point<2>    &p,
                    const unsigned int k,
                    const BodyRegion  &first_region) const;

    /**
     * Refuses regions that overlap: a point of one body (of @p points,
     * over all processes) inside the region of another, not on its edge,
     * the first body's region being @p first_region. Bodies may meet
     * along their edges. The bodies that later stages build are checked
     * by the points their layouts will give them on @p grid.
     */
    void
    check_overlaps(const MaterialPoints &points,
                   const BackgroundGrid &grid,
                   const BodyRegion     &first_region,
                   const MPI_Comm        communicator) const;

    /**
     * Adds to @p quantities, for every body k (1 the first), its number
     * of points "body_k_points", their volume "body_k_volume", their
     * largest displacement "body_k_max_displacement" and how many yield
     * "body_k_yielded_points" (0 for a body not built yet). Collective
     * over @p communicator.
     */
    void
    record(const MaterialPoints          &points,
           const MPI_Comm                 communicator,
           std::map<std::string, double> &quantities) const;

  private:
    std::vector<Body> bodies;
  };
} // namespace bsmpm

#endif
