#ifndef bsmpm_constitutive_update_h
#define bsmpm_constitutive_update_h

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/la_parallel_vector.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <bsmpm/background_grid.h>
#include <bsmpm/constitutive_model.h>
#include <bsmpm/material_points.h>
#include <bsmpm/q1_cell_kernel.h>

namespace bsmpm
{
  using namespace dealii;

  /**
   * A nonlinear constitutive model at the material points (small strain):
   * its share of the Newton system of a load step, and the update of the
   * points' state once the step has converged (doc/newton.md).
   *
   * The material's whole contribution comes from the points, each with its
   * quadrature weight w_p (the moment-fitted weight in cut cells, else its
   * volume): for the increment d with strain increments de_p = B_p d,
   *
   *   f_int(d) = sum_p w_p B_p^T sigma(eps_e,n + de_p),
   *   K_T(d)   = sum_p w_p B_p^T D_p B_p,
   *
   * D_p the algorithmic tangent. With B-bar, B_p is replaced by the
   * modified strain columns (xx, yy, zz, engineering xy) whose volumetric
   * part is the mean over the points of the cell.
   */
  class ConstitutiveUpdate
  {
  public:
    /**
     * With @p b_bar, the volumetric strain of every point is replaced by
     * the mean over the points of its cell (B-bar, doc/newton.md), which
     * keeps isochoric plastic flow from locking the Q1 grid.
     */
    ConstitutiveUpdate(const ConstitutiveModel &model, const bool b_bar);

    /** Whether the points carry quadrature weights of their own
     * (Property::weight, set by CutCellQuadrature); else their volume. */
    void
    use_quadrature_weights(const bool use)
    {
      quadrature_weights = use;
    }

    /**
     * Adds K_T to @p tangent and f_int to @p internal_force for the
     * increment @p increment (with ghost values) and, if given, the
     * prescribed nodal values @p prescribed, through @p constraints.
     * Neither is compressed. Returns the number of locally owned points with
     * volume that yield.
     */
    unsigned long long
    assemble(const MaterialPoints                             &points,
             const BackgroundGrid                             &grid,
             const Q1CellKernel                               &kernel,
             const LinearAlgebra::distributed::Vector<double> &increment,
             const LinearAlgebra::distributed::Vector<double> *prescribed,
             const AffineConstraints<double>                  &constraints,
             TrilinosWrappers::SparseMatrix                   &tangent,
             TrilinosWrappers::MPI::Vector &internal_force) const;

    /**
     * Stores the state at the end of the step in every point (tracking
     * points too): elastic strain, equivalent plastic strain, stress
     * (in-plane and zz) and the yield flag. Call it before
     * MaterialPoints::move(), which then leaves the stress alone. Returns
     * the number of points with volume that yielded, over all processes.
     */
    unsigned long long
    commit(MaterialPoints                                   &points,
           const BackgroundGrid                             &grid,
           const Q1CellKernel                               &kernel,
           const LinearAlgebra::distributed::Vector<double> &increment,
           const LinearAlgebra::distributed::Vector<double> *prescribed) const;

    /** Voigt form (xx, yy, zz, xy; engineering shear) of a 3D tangent. */
    static Tensor<2, 4>
    voigt_tangent(const SymmetricTensor<4, 3> &tangent);

  private:
    /** How the strain of the points of one cell is computed. */
    struct CellStrain
    {
      /** Standard strain of the cell: e[0] + s e[1] + t e[2]. */
      std::array<Voigt, 3> coefficients;
      /** B-bar: the local coordinates where the cell's mean volumetric
       * strain is taken (the points' centroid). */
      bool     use_b_bar = false;
      Point<2> centroid;
    };

    CellStrain
    cell_strain(
      const Q1CellKernel                                           &kernel,
      const Particles::ParticleHandler<2>::particle_iterator_range &points,
      const Q1CellKernel::LocalVector                              &d) const;

    /** Standard in-plane columns @p B and the (B-bar) strain columns
     * (xx, yy, zz, engineering xy) @p B_bar at @p st. */
    static void
    strain_columns(const Q1CellKernel          &kernel,
                   const CellStrain            &strain,
                   const Point<2>              &st,
                   std::array<Voigt, 8>        &B,
                   std::array<Tensor<1, 4>, 8> &B_bar);

    /** The model's response to the strain increment @p de (xx, yy, zz,
     * engineering xy) of the point with properties @p props; @p state
     * returns the updated state. */
    ConstitutiveResponse
    respond(const ArrayView<const double> &props,
            const Tensor<1, 4>            &de,
            ConstitutiveState             &state) const;

    const ConstitutiveModel &model;
    const bool               b_bar;
    bool                     quadrature_weights = false;
  };
} // namespace bsmpm

#endif
