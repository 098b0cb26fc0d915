#ifndef bsmpm_point_output_h
#define bsmpm_point_output_h

#include <deal.II/base/data_out_base.h>

#include <bsmpm/points/material_points.h>

#include <ostream>
#include <string>
#include <tuple>
#include <vector>

namespace bsmpm
{
  using namespace dealii;

  /**
   * The material points for ParaView, written straight from the particle
   * handler: a VTK XML unstructured grid of one vertex per locally owned
   * point with the fields id, the properties (MaterialPoints::
   * property_names(); displacement and initial_position as vectors), in
   * the layout, order and zlib encoding of deal.II's DataOutBase::write_vtu,
   * so that the files are those Particles::DataOut wrote. It does not build
   * deal.II's patches (one heap-allocated table per point, copied again
   * while writing): the arrays are compressed one at a time as they are
   * read from the points, so the memory it needs beyond the points is the
   * compressed size of one array.
   */
  class PointOutput
  {
  public:
    /** @p flags: the compression level; time, cycle and units are not
     * written. */
    PointOutput(const MaterialPoints        &points,
                const DataOutBase::VtkFlags &flags);

    /** This process's points as one .vtu piece. */
    void
    write_vtu(std::ostream &out) const;

    /** The .pvtu record of the pieces @p pieces (one per process). */
    void
    write_pvtu_record(std::ostream                   &out,
                      const std::vector<std::string> &pieces) const;

  private:
    using Range =
      std::tuple<unsigned int,
                 unsigned int,
                 std::string,
                 DataComponentInterpretation::DataComponentInterpretation>;

    /** Writes one array of @p n_components floats per point, @p fill
     * writing a point's values to its second argument. */
    template <typename Fill>
    void
    write_point_array(std::ostream      &out,
                      const unsigned int n_components,
                      const Fill        &fill) const;

    const Particles::ParticleHandler<2> &particles;
    const DataOutBase::VtkFlags          flags;
    /** "id" and the property names: property i is field i + 1. */
    const std::vector<std::string> field_names;
    /** The fields written as vectors, as in DataOutInterface. */
    const std::vector<Range> vectors;
  };
} // namespace bsmpm

#endif
