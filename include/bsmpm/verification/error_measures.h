#ifndef bsmpm_error_measures_h
#define bsmpm_error_measures_h

#include <bsmpm/geometry/b_spline_curve.h>
#include <bsmpm/points/material_points.h>
#include <bsmpm/verification/exact_solution.h>

#include <map>
#include <string>
#include <vector>

namespace bsmpm
{
  /**
   * Errors of the material-point solution against an exact one, evaluated at
   * the initial position of every point with volume (paper eqs 37-40):
   *
   * - R_u, R_v, R_sigma_xx, R_sigma_yy, R_sigma_xy: volume-weighted means of
   *   the pointwise relative errors |h - a| / |a|; a component is left out
   *   when its exact value vanishes at some point.
   * - A_u, A_v, A_sigma_xx, A_sigma_yy, A_sigma_xy: volume-weighted means of
   *   the absolute errors; max_A_u, max_A_v: their maxima, and
   *   max_A_u_at_x, ..._y (and for v) the initial position of the point
   *   where each occurs.
   * - L2_u, L2_sigma: relative L2 errors over the points,
   *   sqrt(sum V |h - a|^2 / sum V |a|^2), with the Frobenius norm for the
   *   stress.
   *
   * The exact solution is a function of the initial positions, so the
   * weights are the initial volumes: with @p finite_strain, V / det F.
   */
  std::map<std::string, double>
  compute_errors(const MaterialPoints &points,
                 const ExactSolution  &exact,
                 const MPI_Comm        communicator,
                 const bool            finite_strain = false);

  /** A boundary curve as the radius errors see it: where its points
   * started and the spline through them now. */
  struct BoundaryArc
  {
    const std::vector<Point<2>> &initial_points;
    const BSplineCurve          &deformed;
  };

  /**
   * Radii of the deformed boundary arcs of a Lame cylinder (paper Sec. 4.3):
   * for each curve whose initial points lie on a circle about the axis,
   * 1000 points equally spaced in the curve parameter are sampled on the
   * deformed curve and their distances r to the axis compared with the exact
   * deformed radius R = r0 + u_r(r0). Returns, for the innermost and the
   * outermost such curve, inner_/outer_radius (mean r) and
   * inner_/outer_radius_error (mean |r - R| / R).
   */
  std::map<std::string, double>
  compute_radius_errors(const std::vector<BoundaryArc> &curves,
                        const LameCylinder             &lame);
} // namespace bsmpm

#endif
