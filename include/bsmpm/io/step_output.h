#ifndef bsmpm_step_output_h
#define bsmpm_step_output_h

#include <deal.II/lac/la_parallel_vector.h>

#include <bsmpm/boundary/boundary_curves.h>
#include <bsmpm/boundary/neumann_loads.h>
#include <bsmpm/boundary/support_methods.h>
#include <bsmpm/contact/curve_contact.h>
#include <bsmpm/geometry/background_grid.h>
#include <bsmpm/io/output_writer.h>
#include <bsmpm/points/material_points.h>

#include <vector>

namespace bsmpm
{
  using namespace dealii;

  /**
   * The ParaView files of one load step, written through an OutputWriter:
   * the series grid (displacement increment, material fraction, support
   * quality and subdomain of every cell), points and, where the scene has
   * boundary curves, curves and curve_points (the curves with their
   * traction Gauss points and support band points); and, after every load
   * step whatever the ParaView interval, the contact tractions.
   */
  class StepOutput
  {
  public:
    StepOutput(OutputWriter         &output,
               const BackgroundGrid &grid,
               const MaterialPoints &points,
               const BoundaryCurves &boundary_curves,
               const NeumannLoads   &neumann_loads,
               const SupportMethods &supports);

    /**
     * Writes load step @p step at load factor @p load_factor and rewrites
     * the collections. @p fill_fractions and @p support_qualities: one
     * value per active cell (those of locally owned cells are written).
     */
    void
    write(const unsigned int                                step,
          const double                                      load_factor,
          const LinearAlgebra::distributed::Vector<double> &increment,
          const std::vector<double>                        &fill_fractions,
          const std::vector<double> &support_qualities) const;

    /** Also writes the outlines of the rigid bodies of @p contact (series
     * rigid_bodies), and lets write_contact_tractions() write its
     * tractions. */
    void
    show_contact(const CurveContact &curve_contact)
    {
      contact = &curve_contact;
    }

    /** Writes the contact tractions along the curves after load step
     * @p step (contact-NNNN.csv, CurveContact::write_tractions()) if the
     * scene has rigid bodies. Called after every load step, whatever
     * Output/Interval: they are figures of the run, as summary.json's, not
     * ParaView's. Collective. */
    void
    write_contact_tractions(const unsigned int step) const;

  private:
    void
    write_points(const unsigned int step, const double load_factor) const;

    void
    write_curves(const unsigned int step, const double load_factor) const;

    OutputWriter         &output;
    const BackgroundGrid &grid;
    const MaterialPoints &points;
    const BoundaryCurves &boundary_curves;
    const NeumannLoads   &neumann_loads;
    const SupportMethods &supports;
    const CurveContact   *contact = nullptr;
  };
} // namespace bsmpm

#endif
