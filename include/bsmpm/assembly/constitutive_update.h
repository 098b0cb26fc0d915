#ifndef bsmpm_constitutive_update_h
#define bsmpm_constitutive_update_h

#include <deal.II/base/parameter_handler.h>

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/la_parallel_vector.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <bsmpm/assembly/cell_scatter.h>
#include <bsmpm/geometry/background_grid.h>
#include <bsmpm/materials/constitutive_model.h>
#include <bsmpm/materials/material.h>
#include <bsmpm/points/material_points.h>
#include <bsmpm/points/q1_cell_kernel.h>

#include <array>
#include <memory>
#include <vector>

namespace bsmpm
{
  using namespace dealii;

  /**
   * A constitutive model at the material points, integrated point by point:
   * its share of the Newton system of a load step, and the update of the
   * points' state once the step has converged (doc/newton.md,
   * doc/finite-strain.md).
   *
   * The material's whole contribution comes from the points, each with its
   * quadrature weight w_p (the moment-fitted weight in cut cells, else its
   * volume). In small strain, for the increment d with strain increments
   * de_p = B_p d,
   *
   *   f_int(d) = sum_p w_p B_p^T sigma(eps_e,n + de_p),
   *   K_T(d)   = sum_p w_p B_p^T D_p B_p,
   *
   * D_p the algorithmic tangent. With B-bar, B_p is replaced by the
   * modified strain columns (xx, yy, zz, engineering xy) whose volumetric
   * part is the mean over the points of the cell.
   *
   * In finite strain (updated Lagrangian on the configuration at the start
   * of the step) the increment gives every point a relative deformation
   * gradient f_p = 1 + grad_n(u); the trial elastic state is
   * b_e^tr = f b_e,n f^T, the model returns the Kirchhoff stress tau of
   * eps^tr = ln(b_e^tr) / 2, and
   *
   *   f_int,a = sum_p (w_p / J_n,p) tau_p g_a,p,   g_a = f^-T grad_n N_a,
   *
   * with the consistent tangent derived in doc/finite-strain.md. With
   * B-bar the volumetric part of ln f is replaced by that at the points'
   * centroid (F-bar). The body force then acts on the points' masses.
   */
  class ConstitutiveUpdate
  {
  public:
    /** The entries "Volumetric strain" and "Kinematics" of section
     * "Material". */
    static void
    declare_parameters(ParameterHandler &prm);

    /**
     * The update that @p model needs with the kinematics and volumetric
     * strain of section "Material": null for a linear model in small
     * strain, which the linear system integrates itself, unless
     * @p newton (something else, contact or several bodies, needs Newton
     * iterations). B-bar (F-bar) applies where a nonlinear model needs it,
     * @p nonlinear_bodies (another body's model is nonlinear) included,
     * and to linear elasticity in small strain without @p contact, whose
     * pressures a mean per cell makes alternate. Throws if finite strain
     * is asked of a @p material that is not in plane strain.
     */
    static std::unique_ptr<ConstitutiveUpdate>
    create(ParameterHandler            &prm,
           const ConstitutiveModel     &model,
           const LinearElasticMaterial &material,
           const bool                   newton           = false,
           const bool                   contact          = false,
           const bool                   nonlinear_bodies = false);

    /** Whether "Material/Volumetric strain" is B-bar: what the linear path
     * (Q1CellKernel) takes when create() returns no update. */
    static bool
    uses_b_bar(ParameterHandler &prm);

    enum class Kinematics
    {
      small_strain,
      finite_strain
    };

    /**
     * With @p b_bar, the volumetric strain of every point is replaced by
     * the mean over the points of its cell (B-bar, doc/newton.md; F-bar in
     * finite strain), which keeps isochoric plastic flow from locking the
     * Q1 grid.
     */
    ConstitutiveUpdate(const ConstitutiveModel &model,
                       const bool               b_bar,
                       const Kinematics         kinematics);

    Kinematics
    kinematics() const
    {
      return point_kinematics;
    }

    /**
     * A quadrature point of the part of a cell where a support carries its
     * own elastic stiffness in place of the points' (the implicit boundary's
     * band, doc/newton.md "Supports in the tangent"), in the cell's
     * reference coordinates.
     */
    struct SupportBandPoint
    {
      Point<2> st;
      double   weight;
    };
    /** Those points by active_cell_index(). */
    using SupportBands = std::vector<std::vector<SupportBandPoint>>;

    /** Whether the material's tangent is symmetric: where the model's is
     * (F-bar in finite strain keeps it so, add_finite_strain_point()). */
    bool
    symmetric_tangent() const
    {
      return symmetric_tangents;
    }

    /**
     * The models of the further bodies (Bodies), in order: a point of body
     * k > 0 (MaterialPoints::Property::body) responds with @p models[k -
     * 1], a point of body 0 with the model given to the constructor. A
     * point of another body than the first enters the cell's sums with its
     * own elastic tangent, the cells whose points stay elastic (the
     * moments' shortcut) hold the first body's points only.
     */
    void
    set_further_bodies(const std::vector<const ConstitutiveModel *> &models);

    /** Finite strain: the gravity @p gravity times its load multiplier
     * @p multiplier, which assemble() integrates over the points' masses
     * (per unit reference volume rho_0 lambda g, rho_0 the density of the
     * point's body, set_densities()). */
    void
    set_body_force(const double multiplier, const Tensor<1, 2> &gravity)
    {
      gravity_multiplier = multiplier;
      body_gravity       = gravity;
    }

    /** The density of every body (by MaterialPoints::Property::body; one
     * entry with one body). */
    void
    set_densities(const std::vector<double> &densities)
    {
      body_densities = densities;
    }

    /**
     * With @p moments (by active_cell_index(), from
     * CutCellQuadrature::correct_cell_moments(); kept by the caller), the
     * points carry quadrature weights of their own (Property::weight) and
     * the cells' exact moments complete what these weights miss (see
     * cell_system()); with nullptr the points integrate with their volumes.
     */
    void
    use_cut_cell_quadrature(const std::vector<CellMoments> *moments)
    {
      quadrature_weights = moments != nullptr;
      exact_moments      = moments;
    }

    /**
     * Whether the cells' exact moments complete the points' weights and
     * the cells of the body without points are integrated here (virtual
     * points, cell_system() and assemble()), and B-bar/F-bar take the exact
     * centroid: with the cut-cell quadrature in finite strain. Not yet in
     * small strain, where the virtual points' averaged plastic states kept
     * Newton from converging on the strip footing (doc/finite-strain.md).
     */
    bool
    completes_moments() const
    {
      return exact_moments != nullptr &&
             point_kinematics == Kinematics::finite_strain;
    }

    /** What assemble() found, on this process. */
    struct AssemblyCount
    {
      /** Locally owned points with volume that yield. */
      unsigned long long yielded = 0;
      /**
       * Cells left out because the increment inverts one of their points
       * (det f <= 0, finite strain): the increment is no admissible state,
       * it has no finite residual, and the Newton iteration must take a
       * shorter step (SystemAssembly::newton_system() then returns an
       * infinite |R|, which the line search backs away from).
       */
      unsigned long long inverted_cells = 0;
    };

    /** The points' volume and its first moments in a cell: where B-bar
     * takes the cell's mean volumetric strain (their centroid). */
    struct VolumeMoments
    {
      double v = 0, vs = 0, vt = 0;

      void
      add(const Point<2> &st, const double volume)
      {
        v += volume;
        vs += volume * st[0];
        vt += volume * st[1];
      }
    };

    /**
     * What a cell's points give once per load increment, so that the
     * Newton systems of the increment need none of them while the cell
     * stays elastic (small strain; doc/newton.md, "Cells that stay
     * elastic"). With the strain increment of the cell affine,
     * de(s, t) = E_0 + s E_s + t E_t, and every point elastic, the stress
     * of point p is D_e (e_n,p + de_p) and the sums of cell_system() are
     *
     *   S_a = D_e (sum_p w_p m_a e_n,p + sum_b M_ab E_b),   H_ab = M_ab D_e,
     *
     * m = (1, s, t). Every point is elastic if the largest |de| over the
     * box of the points' (s, t) stays below the smallest of their
     * ConstitutiveModel::elastic_reach().
     */
    struct ElasticCell
    {
      /** The smallest elastic reach of the points with weight; 0: the
       * cell takes the point-by-point path. */
      double reach = 0;
      /** The box of the points' reference coordinates: centre, half
       * widths. */
      Point<2> centre;
      double   half_width_s = 0, half_width_t = 0;
      /** M_ab = sum_p w_p m_a m_b, in the order of cell_system()'s H. */
      double M[6] = {};
      /** sum_p w_p m_a e_n,p, the stored elastic strains (xx, yy, zz,
       * engineering xy). */
      double strain_moments[3][4] = {};
      /** B-bar's centroid. */
      VolumeMoments volume;
    };
    /** By active_cell_index(). */
    using ElasticCells = std::vector<ElasticCell>;

    /**
     * The ElasticCell of every locally owned cell, for the points as they
     * are (call it at the start of each load increment: commit() and
     * MaterialPoints::move() make them stale). Empty in finite strain.
     */
    void
    prepare_elastic_cells(const MaterialPoints &points,
                          const BackgroundGrid &grid,
                          ElasticCells         &cells) const;

    /**
     * Adds K_T to @p tangent and f_int to @p internal_force for the
     * increment @p increment (with ghost values) and, if given, the
     * prescribed nodal values @p prescribed, through @p constraints.
     * Neither is compressed; @p scatter serves @p tangent (see CellScatter:
     * the cells' positions in it are kept between assemblies). A cell whose
     * points the increment inverts adds nothing and is counted instead
     * (never a NaN in the system). With @p bands, the tangent of a cell
     * crossed by a support's band is stiffened there (cell_system()).
     */
    AssemblyCount
    assemble(const MaterialPoints                             &points,
             const BackgroundGrid                             &grid,
             const Q1CellKernel                               &kernel,
             const LinearAlgebra::distributed::Vector<double> &increment,
             const LinearAlgebra::distributed::Vector<double> *prescribed,
             const AffineConstraints<double>                  &constraints,
             TrilinosWrappers::SparseMatrix                   &tangent,
             TrilinosWrappers::MPI::Vector                    &internal_force,
             CellScatter                                      &scatter,
             const SupportBands                               *bands = nullptr,
             const ElasticCells *elastic_cells = nullptr) const;

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

    /**
     * How much of its elastic stiffness the material keeps round each grid
     * vertex in the state that the last commit() stored, by DoF (both
     * DoFs of a vertex hold its value, with ghost values); nullptr before
     * the first commit(). For vertex v with DoFs v_x, v_y it is
     *
     *   rho_v = lambda_min(K_vv(D)) / lambda_min(K_vv(D_e)),
     *
     * K_vv(D) = sum_p w_p B_v,p^T D B_v,p the 2x2 block of v in the
     * tangent of the points round v, with their algorithmic tangents D_p
     * at the end of the step, and K_vv(D_e) the same with the elastic
     * tangent: 1 where every point round v responds elastically (exactly:
     * the same sums), towards 0 where the points are perfectly plastic and
     * their flow takes the one direction in which they would hold v (the
     * upper vertex of a cut cell whose points lie near its bottom).
     * GhostPenalty::cell_qualities scales the support quality by it.
     */
    const LinearAlgebra::distributed::Vector<double> *
    support_stiffness_ratios() const
    {
      return stiffness_ratio.size() > 0 ? &stiffness_ratio : nullptr;
    }

    /** Sets the ratios of support_stiffness_ratios() as a resumed run
     * takes them from its checkpoint (with ghost values): what the last
     * commit() before it left, which the next load step's support
     * qualities depend on. Const as commit() is, which computes them. */
    void
    restore_support_stiffness_ratios(
      const LinearAlgebra::distributed::Vector<double> &ratios) const
    {
      stiffness_ratio = ratios;
    }

    /** Voigt form (xx, yy, zz, xy; engineering shear) of a 3D tangent. */
    static Tensor<2, 4>
    voigt_tangent(const SymmetricTensor<4, 3> &tangent);

    /** A point of a cell as the cell's system sees it. */
    struct PointView
    {
      Point<2>                st;
      ArrayView<const double> props;
    };

    /**
     * The internal force (minus the body force in finite strain) @p f and
     * the tangent @p K (both set, not added to) of the points @p cell_points
     * of one cell for the local increment @p d. Returns how many points
     * with volume yield. If the increment inverts a point of the cell
     * (det f <= 0 in finite strain, at a point or, with F-bar, at the
     * centroid), @p f is NaN (the caller must not assemble it: see
     * assemble()). Used by assemble(); public for the tests.
     *
     * With the cell's exact moments @p exact_moments (and quadrature
     * weights), where the points' weights miss its area or first moments
     * (a cut cell whose points carry its area only), two virtual points
     * with the points' mean state complete them: the exact area at the
     * exact centroid, minus the points' weight at their centroid. Then the
     * force of a homogeneous deformation is that of the exact geometry, as
     * in the linear path (doc/cut-cells.md, doc/finite-strain.md). A cell
     * with a single point is integrated instead by four points of its
     * exact moments with that point's state (a one-point rule would leave
     * the cell's hourglass modes without stiffness).
     *
     * With @p band (small strain), the quadrature points of an implicit
     * boundary band in the cell: the band's terms (ImplicitBoundary) replace
     * the regular elastic energy there by that of the band's field, which
     * holds the support like a penalty of order E / delta. With a material
     * that yields, the points' energy is not the elastic one the band takes
     * out, and the sum is indefinite where they yield (CG fails, Newton's
     * correction stops descending, steps are cut). So the band is an elastic
     * layer: two virtual points per band point, with the points' mean state,
     * put the elastic material in (+w) and take the points' material out
     * (-w). Where the mean state responds elastically they cancel to the
     * last bit; where it yields they add int_band Bbar^T (C - D) Bbar >= 0,
     * and force and tangent stay consistent (doc/newton.md).
     */
    unsigned int
    cell_system(const Q1CellKernel                  &kernel,
                const std::vector<PointView>        &cell_points,
                const Q1CellKernel::LocalVector     &d,
                FullMatrix<double>                  &K,
                Vector<double>                      &f,
                const CellMoments                   *exact_moments = nullptr,
                const std::vector<SupportBandPoint> *band = nullptr) const;

    /** The ElasticCell of the points @p cell_points of one cell (small
     * strain). */
    ElasticCell
    elastic_cell(const std::vector<PointView> &cell_points) const;

    /**
     * cell_system() without the points, for a cell whose points all stay
     * elastic under the local increment @p d (see ElasticCell): K and f
     * (set) from @p cell's moments; false, and neither set, where that is
     * not certain. Used by assemble(); public for the tests.
     */
    bool
    elastic_cell_system(const Q1CellKernel              &kernel,
                        const ElasticCell               &cell,
                        const Q1CellKernel::LocalVector &d,
                        FullMatrix<double>              &K,
                        Vector<double>                  &f,
                        const CellMoments *exact_moments = nullptr) const;

    /**
     * Finite strain at a point of a support (ImplicitBoundary's band,
     * NitscheBoundary's curve points; doc/finite-strain.md, "Supports in
     * finite strain"): the first Piola stress of the configuration at the
     * step's start, P = tau f^-T / J_n, of a point with the properties
     * @p props (elastic and plastic strain, det F as of the step's start)
     * under the relative deformation gradient @p f (f_zz = 1), and its
     * derivative @p A, A[i][j][k][l] = d P_ij / d f_kl. The same trial
     * state and return as the points' (without F-bar). Returns false, P
     * and A unset, if det f <= 0.
     */
    bool
    first_piola_stress(const ArrayView<const double> &props,
                       const Tensor<2, 2>            &f,
                       Tensor<2, 2>                  &P,
                       Tensor<4, 2>                  &A) const;

  private:
    using Property = MaterialPoints::Property;

    /** The @p n_points points of a cell as cell_system() takes them. */
    static void
    gather_points(
      const Particles::ParticleHandler<2>::particle_iterator_range &range,
      const unsigned int                                            n_points,
      std::vector<PointView>                                       &views);

    /** How the strain of the points of one cell is computed. */
    struct CellStrain
    {
      /** Standard strain of the cell: e[0] + s e[1] + t e[2]. */
      std::array<Voigt, 3> coefficients;
      /** B-bar: the local coordinates where the cell's mean volumetric
       * strain is taken (the points' centroid). */
      bool     use_b_bar = false;
      Point<2> centroid;
      /** B-bar, small strain: the volumetric strain of each shape function
       * column at the centroid, the same for every point of the cell. */
      std::array<double, 8> centroid_volumetric;
      /** F-bar: ln det f at the centroid and the spatial gradients of the
       * shape functions there. */
      double                      log_det_centroid = 0;
      std::array<Tensor<1, 2>, 8> centroid_gradients;
      /** F-bar: the increment inverts the cell at the centroid. */
      bool inverted = false;
      /** The small-strain (B-bar) strain columns (xx, yy, zz,
       * engineering xy) of the shape functions are affine in the cell,
       * column i at (s, t) being
       * columns[0][i] + s columns[1][i] + t columns[2][i] (in finite
       * strain too: commit() weighs the vertices' stiffness with them),
       * and, in small strain, so is the strain increment of the cell's d,
       * increment[0] + s increment[1] + t increment[2]. */
      std::array<std::array<Tensor<1, 4>, 8>, 3> columns;
      std::array<Tensor<1, 4>, 3>                increment;
    };

    /** The strain of the cell's points; with B-bar its mean volumetric
     * part is taken at the points' centroid, or at the exact centroid of
     * @p exact_moments with the cut-cell quadrature. */
    CellStrain
    cell_strain(const Q1CellKernel              &kernel,
                const std::vector<PointView>    &cell_points,
                const Q1CellKernel::LocalVector &d,
                const CellMoments               *exact_moments) const;

    /** The same for the points' volume moments @p volume. */
    CellStrain
    cell_strain(const Q1CellKernel              &kernel,
                const VolumeMoments             &volume,
                const Q1CellKernel::LocalVector &d,
                const CellMoments               *exact_moments) const;

    /**
     * Small strain: K and f (set) from the sums of cell_system(), H_ab of
     * the points that yield (if @p plastic), the scalar moments M_ab of
     * those that do not, and S_a of all.
     */
    void
    system_from_moments(const CellStrain &strain,
                        const double (&H)[6][16],
                        const bool plastic,
                        const double (&M)[6],
                        const double (&S)[3][4],
                        FullMatrix<double> &K,
                        Vector<double>     &f) const;

    /** What the finite-strain kinematics give at one point. */
    struct FiniteStrainPoint
    {
      /** Relative deformation gradient f, its determinant, and the
       * spatial gradients g_i = f^-T grad_n N_i. */
      Tensor<2, 2>                f;
      double                      det_f = 1;
      std::array<Tensor<1, 2>, 8> gradients;
      /** Trial b_e (in-plane block). */
      Tensor<2, 2> trial_b;
      /** d ln(b_e^tr) / d b_e^tr on in-plane tensors, as a matrix on the
       * components (xx, yy, xy) (see InPlaneFunction). */
      Tensor<2, 3> log_derivative;
    };

    /** B-bar/F-bar: the centroid of @p strain and what is taken there
     * (cell_strain()); leaves use_b_bar false for a cell without
     * volume. */
    void
    centroid_strain(const Q1CellKernel              &kernel,
                    const VolumeMoments             &volume,
                    const Q1CellKernel::LocalVector &d,
                    const CellMoments               *exact_moments,
                    CellStrain                      &strain) const;

    /** f and the trial elastic strain (into @p state) of a point at @p st
     * with properties @p props; with F-bar, @p strain's centroid sets the
     * volumetric part. */
    FiniteStrainPoint
    finite_strain_trial(const Q1CellKernel              &kernel,
                        const CellStrain                &strain,
                        const Point<2>                  &st,
                        const ArrayView<const double>   &props,
                        const Q1CellKernel::LocalVector &d,
                        const Tensor<2, 2>              *gradient,
                        ConstitutiveState               &state) const;

    /** The (B-bar) strain increment (xx, yy, zz, engineering xy) at
     * @p st of the local increment that @p strain was made for (small
     * strain). */
    static Tensor<1, 4>
    strain_increment(const CellStrain &strain, const Point<2> &st)
    {
      return strain.increment[0] + st[0] * strain.increment[1] +
             st[1] * strain.increment[2];
    }

    /** The model's response to the strain increment @p de (xx, yy, zz,
     * engineering xy) of the point with properties @p props
     * (ConstitutiveModel::plane_strain_update(): the stress, the Voigt
     * tangent only if the point yields, which it returns); @p state
     * returns the updated state. Inline (below): called for every point of
     * every Newton system, where the call cost about as much as filling the
     * state. */
    bool
    respond(const ArrayView<const double> &props,
            const Tensor<1, 4>            &de,
            ConstitutiveState             &state,
            std::array<double, 4>         &stress,
            std::array<double, 16>        &tangent) const;

    /** The stored elastic strain of @p props plus the strain increment
     * @p de (xx, yy, zz, engineering xy) into @p e: the trial strain of
     * small strain. Inline (below). */
    static void
    trial_strain(const ArrayView<const double> &props,
                 const Tensor<1, 4>            &de,
                 SymmetricTensor<2, 3>         &e);

    /** Small strain: the stress @p sigma (xx, yy, zz, xy) of the elastic
     * material at the stored elastic strain of @p props plus @p de,
     * whatever the point's state (the elastic layer of a support's band in
     * cell_system()). */
    void
    elastic_stress(const ArrayView<const double> &props,
                   const Tensor<1, 4>            &de,
                   std::array<double, 4>         &sigma) const;

    /**
     * Finite strain: adds the point at @p st with properties @p props and
     * weight @p w to the force @p f and the tangent @p K of its cell for
     * the local increment @p d (doc/finite-strain.md), with @p state as
     * work space; @p yielded says whether it yields. False, and nothing
     * added, if the increment inverts the point (det f <= 0).
     */
    bool
    add_finite_strain_point(const Q1CellKernel              &kernel,
                            const CellStrain                &strain,
                            const Point<2>                  &st,
                            const ArrayView<const double>   &props,
                            const double                     w,
                            const Q1CellKernel::LocalVector &d,
                            ConstitutiveState               &state,
                            FullMatrix<double>              &K,
                            Vector<double>                  &f,
                            bool                            &yielded) const;

    /**
     * The only point with weight of @p cell_points where cell_system()
     * integrates the cell by the four points of the exact moments
     * @p exact_moments with that point's state (finite strain with the
     * cut-cell quadrature); nullptr otherwise.
     *
     * One point in a cell (one point per cell, or a cut cell the body has
     * just entered): a one-point rule holds none of the cell's hourglass
     * modes (their strain vanishes at the point), so Newton's tangent is
     * singular and the curves' tracking points, which the hourglass modes
     * move, wander (doc/finite-strain.md). The four points of
     * PointMoments::exact_four_point_rule() with the one point's state are
     * exact for a homogeneous state (the integrand is affine), and their
     * tangent holds every deformation mode of the cell.
     */
    const PointView *
    single_point(const std::vector<PointView> &cell_points,
                 const CellMoments            *exact_moments) const;

    /** At most two virtual points of a cell: reference coordinates and
     * weights (a fixed array: cell_system() makes them for every cut cell
     * of every Newton system). */
    struct VirtualPoints
    {
      std::array<Point<2>, 2> st;
      std::array<double, 2>   weight;
      unsigned int            n = 0;

      void
      add(const Point<2> &point, const double w)
      {
        st[n]     = point;
        weight[n] = w;
        ++n;
      }
    };

    /** The virtual points that complete the moments of the points'
     * weights W, Ws, Wt to the cell's exact moments @p exact_moments, if
     * cell_system() completes them: the exact area at the exact centroid,
     * minus W at the points' centroid. */
    VirtualPoints
    completion_points(const CellMoments *exact_moments,
                      const double       W,
                      const double       Ws,
                      const double       Wt) const;

    /** The mean properties of @p cell_points, weighted as they integrate
     * (their weights sum to @p W): the state of cell_system()'s virtual
     * points. */
    std::vector<double>
    mean_state(const std::vector<PointView> &cell_points, const double W) const;

    /** The weight a point of @p props integrates with: its fitted weight
     * with the cut-cell quadrature, else its volume; zero for a point that
     * holds no material (no volume), which the sums skip. */
    double
    integration_weight(const ArrayView<const double> &props) const;

    const ConstitutiveModel &model;
    /** The model of every body (the first: model), and the Voigt form of
     * its elastic tangent; one entry with a single body. */
    std::vector<const ConstitutiveModel *> body_models;
    std::vector<Tensor<2, 4>>              body_voigt;
    /** Whether every body's model has a symmetric tangent. */
    bool symmetric_tangents;

    /** The model of the point with @p props. */
    const ConstitutiveModel &
    model_of(const ArrayView<const double> &props) const
    {
      return body_models.size() == 1 ?
               model :
               *body_models[static_cast<unsigned int>(props[Property::body])];
    }

    /** Whether the point with @p props belongs to another body than the
     * first; then its elastic Voigt tangent, row by row, into
     * @p tangent. */
    bool
    other_body_tangent(const ArrayView<const double> &props,
                       std::array<double, 16>        &tangent) const
    {
      if (body_models.size() == 1)
        return false;
      const unsigned int b = static_cast<unsigned int>(props[Property::body]);
      if (b == 0)
        return false;
      for (unsigned int r = 0; r < 4; ++r)
        for (unsigned int c = 0; c < 4; ++c)
          tangent[4 * r + c] = body_voigt[b][r][c];
      return true;
    }

    const bool b_bar;
    /** The model's elastic tangent in Voigt form (voigt_tangent()). */
    const Tensor<2, 4> elastic_voigt;
    const Kinematics   point_kinematics;
    bool               quadrature_weights = false;
    /** See use_cut_cell_quadrature(). */
    const std::vector<CellMoments> *exact_moments      = nullptr;
    double                          gravity_multiplier = 0;
    Tensor<1, 2>                    body_gravity;
    std::vector<double>             body_densities = {0.};

    /** The body force per unit reference volume at the point with
     * @p props (set_body_force()). */
    Tensor<1, 2>
    body_force_at(const ArrayView<const double> &props) const
    {
      const double density =
        body_densities.size() == 1 ?
          body_densities[0] :
          body_densities[static_cast<unsigned int>(props[Property::body])];
      return gravity_multiplier * density * body_gravity;
    }
    /** See support_stiffness_ratios(). */
    mutable LinearAlgebra::distributed::Vector<double> stiffness_ratio;
  };



  inline bool
  ConstitutiveUpdate::respond(const ArrayView<const double> &props,
                              const Tensor<1, 4>            &de,
                              ConstitutiveState             &state,
                              std::array<double, 4>         &stress,
                              std::array<double, 16>        &tangent) const
  {
    trial_strain(props, de, state.elastic_strain);
    state.equivalent_plastic_strain = props[Property::plastic_strain];
    return model_of(props).plane_strain_update(state, stress, tangent);
  }



  inline void
  ConstitutiveUpdate::trial_strain(const ArrayView<const double> &props,
                                   const Tensor<1, 4>            &de,
                                   SymmetricTensor<2, 3>         &e)
  {
    e[0][0] = props[Property::elastic_strain] + de[0];
    e[1][1] = props[Property::elastic_strain + 1] + de[1];
    e[2][2] = props[Property::elastic_strain + 2] + de[2];
    e[0][1] = props[Property::elastic_strain + 3] + de[3] / 2;
    e[0][2] = e[1][2] = 0;
  }
} // namespace bsmpm

#endif
