#ifndef bsmpm_probe_h
#define bsmpm_probe_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>

#include <bsmpm/points/material_points.h>

#include <map>
#include <string>
#include <vector>

namespace bsmpm
{
  using namespace dealii;

  /**
   * An optional zero-volume point (section "Probe") that moves with the
   * body and whose displacement and stress are reported after every load
   * step: a load-displacement curve at a place of the scene's choosing.
   */
  class Probe
  {
  public:
    static void
    declare_parameters(ParameterHandler &prm);

    void
    parse_parameters(ParameterHandler &prm);

    /** Initial position. */
    const Point<2> &
    position() const
    {
      return initial_position;
    }

    /** Whether the scene has a probe. */
    bool
    enabled() const
    {
      return has_point;
    }

    /** Its slot in MaterialPoints' tracked list (add_to()). */
    unsigned int
    tracked_slot() const
    {
      return slot;
    }

    /** Adds the probe to @p points as a tracking point and its id to
     * @p tracked, the list that MaterialPoints::track() is then given. */
    void
    add_to(MaterialPoints &points, std::vector<types::particle_index> &tracked);

    /** Sets the quantities <name>_displacement_x, _y, <name>_deflection
     * (= -displacement_y) and <name>_stress_xx, _yy, _xy in @p quantities
     * from the probe's tracked state in @p points. */
    void
    record(const MaterialPoints          &points,
           std::map<std::string, double> &quantities) const;

  private:
    std::string name;
    Point<2>    initial_position;
    bool        has_point = false;
    /** Position of the probe in the tracked list. */
    unsigned int slot = 0;
  };
} // namespace bsmpm

#endif
