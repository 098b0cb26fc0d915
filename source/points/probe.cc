#include <deal.II/base/utilities.h>

#include <bsmpm/base/parameter_tools.h>
#include <bsmpm/points/probe.h>

namespace bsmpm
{
  void
  Probe::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Probe");
    prm.declare_entry("Point",
                      "",
                      Patterns::Anything(),
                      "Initial position of a zero-volume point that moves "
                      "with the body and whose displacement is reported as "
                      "quantities <name>_displacement_x, _y and "
                      "<name>_deflection (= -displacement_y); empty: none.");
    prm.declare_entry("Name",
                      "probe",
                      Patterns::Anything(),
                      "Name of the probe.");
    prm.leave_subsection();
  }



  void
  Probe::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Probe");
    has_point = !Utilities::trim(prm.get("Point")).empty();
    if (has_point)
      initial_position = ParameterTools::get_point(prm, "Point");
    name = prm.get("Name");
    prm.leave_subsection();
  }



  void
  Probe::add_to(MaterialPoints                     &points,
                std::vector<types::particle_index> &tracked)
  {
    slot = tracked.size();
    tracked.push_back(points.add_tracking_points({initial_position})[0]);
  }



  void
  Probe::record(const MaterialPoints          &points,
                std::map<std::string, double> &quantities) const
  {
    std::vector<Point<2>>     positions;
    std::vector<Voigt>        stresses;
    std::vector<Tensor<1, 2>> displacements;
    points.tracked_states(positions, stresses, nullptr, &displacements);
    // The point's own record, which a stage may restart from zero.
    const Tensor<1, 2> u                 = displacements[slot];
    quantities[name + "_displacement_x"] = u[0];
    quantities[name + "_displacement_y"] = u[1];
    quantities[name + "_deflection"]     = -u[1];
    const Voigt &sigma                   = stresses[slot];
    quantities[name + "_stress_xx"]      = sigma[0];
    quantities[name + "_stress_yy"]      = sigma[1];
    quantities[name + "_stress_xy"]      = sigma[2];
  }
} // namespace bsmpm
