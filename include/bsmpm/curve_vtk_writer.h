#ifndef bsmpm_curve_vtk_writer_h
#define bsmpm_curve_vtk_writer_h

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <bsmpm/boundary_curves.h>
#include <bsmpm/implicit_boundary.h>
#include <bsmpm/neumann_loads.h>

#include <string>
#include <vector>

namespace bsmpm
{
  using namespace dealii;

  /**
   * Writes the boundary curves for ParaView with VTK's XML PolyData writer:
   * the splines as finely sampled polylines with their outward normals, and
   * the points that define and integrate them (boundary points, the cuts by
   * the grid, the Gauss points of the loads with their tractions).
   */
  namespace CurveVtkWriter
  {
    /** Polylines of all curves, @p samples points per Bezier segment. */
    void
    write_curves(const std::string &   file,
                 const BoundaryCurves &curves,
                 const unsigned int    samples = 16);

    /**
     * Vertices with a "kind" field: 0 boundary point, 1 cut of a curve by a
     * grid line, 2 Gauss point of a load (with its traction vector), 3
     * quadrature point of an IBM band (with its D-function value).
     */
    void
    write_points(const std::string &                                 file,
                 const BoundaryCurves &                              curves,
                 const std::vector<NeumannLoads::QuadraturePoint> &gauss_points,
                 const std::vector<ImplicitBoundary::BandPoint> &    band_points);
  } // namespace CurveVtkWriter
} // namespace bsmpm

#endif
