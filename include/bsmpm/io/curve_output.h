#ifndef bsmpm_curve_output_h
#define bsmpm_curve_output_h

#include <bsmpm/boundary/boundary_curves.h>
#include <bsmpm/boundary/implicit_boundary.h>
#include <bsmpm/boundary/neumann_loads.h>

#include <ostream>
#include <vector>

namespace bsmpm
{
  using namespace dealii;

  /**
   * The boundary curves for ParaView, as VTK XML unstructured grids written
   * by deal.II's DataOutBase: the splines as finely sampled polylines with
   * their outward normals, and the points that define and integrate them.
   * (Debian's paraview package conflicts with libvtk9-dev, so bsmpm does not
   * build against VTK.)
   */
  namespace CurveOutput
  {
    /** Polylines of all curves, @p samples points per Bezier segment;
     * fields: curve (1-based), outward_normal. */
    void
    write_curves(std::ostream         &out,
                 const BoundaryCurves &curves,
                 const unsigned int    samples = 16);

    /** Closed polylines (the outlines of rigid bodies); field: body
     * (1-based). */
    void
    write_outlines(std::ostream                             &out,
                   const std::vector<std::vector<Point<2>>> &outlines);

    /**
     * Vertices with a field "kind": 0 boundary point, 1 cut of a curve by a
     * grid line, 2 Gauss point of a load (with its traction), 3 quadrature
     * point of an IBM band (with its D-function value).
     */
    void
    write_points(std::ostream                                     &out,
                 const BoundaryCurves                             &curves,
                 const std::vector<NeumannLoads::QuadraturePoint> &gauss_points,
                 const std::vector<ImplicitBoundary::BandPoint>   &band_points);
  } // namespace CurveOutput
} // namespace bsmpm

#endif
