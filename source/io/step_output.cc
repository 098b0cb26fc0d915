#include <deal.II/base/mpi.h>

#include <deal.II/numerics/data_out.h>

#include <bsmpm/io/curve_output.h>
#include <bsmpm/io/point_output.h>
#include <bsmpm/io/step_output.h>

#include <algorithm>
#include <sstream>

namespace bsmpm
{
  StepOutput::StepOutput(OutputWriter         &output,
                         const BackgroundGrid &grid,
                         const MaterialPoints &points,
                         const BoundaryCurves &boundary_curves,
                         const NeumannLoads   &neumann_loads,
                         const SupportMethods &supports)
    : output(output)
    , grid(grid)
    , points(points)
    , boundary_curves(boundary_curves)
    , neumann_loads(neumann_loads)
    , supports(supports)
  {}



  void
  StepOutput::write(const unsigned int step,
                    const double       load_factor,
                    const LinearAlgebra::distributed::Vector<double> &increment,
                    const std::vector<double> &fill_fractions,
                    const std::vector<double> &support_qualities) const
  {
    DataOut<2> grid_out;
    grid_out.attach_dof_handler(grid.dof_handler());
    std::vector<DataComponentInterpretation::DataComponentInterpretation>
      vector_field(2, DataComponentInterpretation::component_is_part_of_vector);
    grid_out.add_data_vector(increment,
                             std::vector<std::string>(2,
                                                      "displacement_increment"),
                             DataOut<2>::type_dof_data,
                             vector_field);
    Vector<float> fill(fill_fractions.begin(), fill_fractions.end());
    Vector<float> subdomain(grid.triangulation().n_active_cells());
    for (const auto &cell : grid.triangulation().active_cell_iterators())
      if (cell->is_locally_owned())
        subdomain[cell->active_cell_index()] = cell->subdomain_id();
    grid_out.add_data_vector(fill, "material_fraction");
    Vector<float> quality(support_qualities.begin(), support_qualities.end());
    for (auto &q : quality)
      q = std::max(q, 0.f);
    grid_out.add_data_vector(quality, "support_quality");
    grid_out.add_data_vector(subdomain, "subdomain");
    grid_out.build_patches();
    grid_out.set_flags(output.vtk_flags());
    output.write_series("grid", step, load_factor, grid_out);

    write_points(step, load_factor);
    if (!boundary_curves.empty())
      write_curves(step, load_factor);
    if (contact != nullptr)
      {
        const std::vector<std::vector<Point<2>>> outlines = contact->outlines();
        output.write_serial_series("rigid_bodies",
                                   step,
                                   load_factor,
                                   [&](std::ostream &out) {
                                     CurveOutput::write_outlines(out, outlines);
                                   });
      }

    output.write_collections();
  }



  void
  StepOutput::write_contact_tractions(const unsigned int step) const
  {
    if (contact == nullptr)
      return;
    std::ostringstream tractions;
    contact->write_tractions(tractions, grid.mpi_communicator());
    output.write_root_file("contact-" + Utilities::int_to_string(step, 4) +
                             ".csv",
                           [&](std::ostream &out) { out << tractions.str(); });
  }



  void
  StepOutput::write_points(const unsigned int step,
                           const double       load_factor) const
  {
    const PointOutput points_out(points, output.vtk_flags());
    output.write_series(
      "points",
      step,
      load_factor,
      [&](std::ostream &out) { points_out.write_vtu(out); },
      [&](std::ostream &out, const std::vector<std::string> &pieces) {
        points_out.write_pvtu_record(out, pieces);
      });
  }



  void
  StepOutput::write_curves(const unsigned int step,
                           const double       load_factor) const
  {
    const MPI_Comm communicator = grid.mpi_communicator();
    // Gauss points live where their cells do: gather them for the file.
    std::vector<double> local;
    for (const auto &g : neumann_loads.quadrature_points())
      local.insert(
        local.end(),
        {g.position[0], g.position[1], g.traction[0], g.traction[1], g.weight});
    std::vector<NeumannLoads::QuadraturePoint> gauss;
    for (const auto &part : Utilities::MPI::gather(communicator, local, 0))
      for (std::size_t i = 0; i + 4 < part.size(); i += 5)
        gauss.push_back({Point<2>(part[i], part[i + 1]),
                         Tensor<1, 2>({part[i + 2], part[i + 3]}),
                         part[i + 4]});
    local.clear();
    for (const auto &b : supports.band_points())
      local.insert(local.end(),
                   {b.position[0], b.position[1], b.d_function, b.weight});
    std::vector<SupportMethod::BandPoint> band;
    for (const auto &part : Utilities::MPI::gather(communicator, local, 0))
      for (std::size_t i = 0; i + 3 < part.size(); i += 4)
        band.push_back(
          {Point<2>(part[i], part[i + 1]), part[i + 2], part[i + 3], 0, {}});
    output.write_serial_series(
      "curves", step, load_factor, [this](std::ostream &out) {
        CurveOutput::write_curves(out, boundary_curves);
      });
    output.write_serial_series(
      "curve_points", step, load_factor, [&](std::ostream &out) {
        CurveOutput::write_points(out, boundary_curves, gauss, band);
      });
  }
} // namespace bsmpm
