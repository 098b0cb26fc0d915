#ifndef bsmpm_nodal_contact_terms_h
#define bsmpm_nodal_contact_terms_h

#include <deal.II/base/mpi.h>
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/la_parallel_vector.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/lac/vector.h>

#include <bsmpm/contact/contact_law.h>
#include <bsmpm/contact/contact_nodes.h>
#include <bsmpm/contact/contact_terms.h>
#include <bsmpm/contact/rigid_body.h>
#include <bsmpm/contact/rigid_body_motion.h>
#include <bsmpm/geometry/background_grid.h>
#include <bsmpm/points/q1_cell_kernel.h>

#include <array>
#include <optional>
#include <vector>

namespace bsmpm
{
  using namespace dealii;

  /** A change of one DoF of the increment (or of a body's translation:
   * DoF n + 2 body + component, n the grid's DoFs), for central
   * differences. */
  struct ContactPerturbation
  {
    types::global_dof_index dof   = numbers::invalid_dof_index;
    double                  delta = 0;
  };



  /**
   * The contact's share of the Newton system with mortar pressures: one
   * pressure per node, a crossing of a curve with a grid line
   * (ContactNodes; doc/contact.md, "Mortar pressures").
   *
   * At the increment du a Gauss point X_q of a node's pieces moves to
   * x_q = X_q + du(X_q) and has the gap g_q to the part of the outline it
   * faces, its normal n_q and tangent t_q = (-n_y, n_x). With phi_a the
   * node's hat function along the curve, node a sums over the points of
   * all processes
   *
   *   G_a = sum_q w_q phi_a g_q,   c_a = dG_a/du = sum_q w_q phi_a n_q . N_i,
   *
   * and applies the contact law (ContactLaw) to its mean gap G_a / W_a:
   * p_a = max(0, -eps G_a / W_a). Its potential W_a p_a^2 / (2 eps) gives
   * the force p_a c_a, so that the curve carries the continuous pressure
   * p(x) = sum_a p_a phi_a(x), and the stiffness eps / W_a c_a c_a^T
   * (semi-smooth: the node is active or not at every Newton iteration)
   * plus -sum_q w_q p(x_q) (t . N_i)(t . N_j) / rho where the outline
   * turns. Friction likewise per node, on the mean of the trial
   * tractions (t_prev - eps (du - du_body)) . t_q of its points: tau_a,
   * the force tau_a d_a with d_a = sum_q w_q phi_a t_q . N_i. A body's
   * translation enters as two more DoFs with the shapes -e_x, -e_y (as in
   * ContactTerms): the bordered terms of a force-controlled body.
   *
   * c_a has entries on the DoFs of the two cells on either side of its
   * crossing: the stiffness couples DoFs two cells apart (ContactPattern
   * widens the tangent's pattern). Every process gathers the nodes' sums
   * of all processes (summed by node, then by cell: np > 1 gives the
   * serial sums bit for bit) and adds the rows of the DoFs it owns.
   */
  class NodalContactTerms
  {
  public:
    /** The cell's DoFs and the body's translation. */
    static constexpr unsigned int n_dofs = ContactTerms::n_dofs;

    /** What contact does at a Gauss point of this process. */
    struct PointState
    {
      /** The grid DoFs of the point's cell. */
      std::array<types::global_dof_index, Q1CellKernel::dofs_per_cell> dofs;
      /** Shape values on the cell's DoFs and the body's translation. */
      ContactTerms::ShapeValues N;
      /** Where it is after the increment, relative to the body. */
      Point<2>     x;
      SurfacePoint surface;
      /** p(x) = sum_a p_a N_a(X), tau(x) likewise. */
      double pressure   = 0;
      double tangential = 0;
      /** Whether one of its nodes takes part (or slides). */
      bool active  = false;
      bool sliding = false;

      /** The traction on the curve, p n + tau t with t = (-n_y, n_x). */
      Tensor<1, 2>
      traction() const
      {
        const Tensor<1, 2> &n = surface.normal;
        return pressure * n + tangential * Tensor<1, 2>({-n[1], n[0]});
      }
    };

    /** What contact does at a node (the same on every process). */
    struct NodeState
    {
      /** G_a, sum w N t_prev . t, sum w N (du - du_body) . t. */
      double gap      = 0;
      double previous = 0;
      double slip     = 0;
      /** The DoFs of the node's vectors, ascending (a body's translation
       * numbered n_dofs + 2 body + component), and per DoF c_a, d_a and
       * where the outline turns the derivatives of the previous traction
       * and of the slip by the turning of t (doc/contact.md). */
      std::vector<types::global_dof_index> dofs;
      std::vector<std::array<double, 4>>   vectors;
      ContactLaw::Traction                 traction;
    };

    /** The whole contact at one increment. */
    struct State
    {
      std::vector<PointState> points;
      std::vector<NodeState>  nodes;
      /** Whether the stiffness is symmetric (nothing slides, no friction
       * where the outline turns). */
      bool symmetric = true;
    };


    /** What contact does at the increment @p increment (ghosted;
     * @p prescribed as for the points), with the laws of @p terms.
     * Collective. */
    static State
    evaluate(const ContactTerms                               &terms,
             const ContactNodes                               &nodes,
             const std::vector<RigidBody>                     &bodies,
             const RigidBodyMotion                            &motion,
             const BackgroundGrid                             &grid,
             const Q1CellKernel                               &kernel,
             const LinearAlgebra::distributed::Vector<double> &increment,
             const LinearAlgebra::distributed::Vector<double> *prescribed,
             const ContactPerturbation &perturbation = ContactPerturbation());

    /** Node @p a's force on its DoFs (@p force) and its stiffness
     * (@p stiffness, minus the force's derivative) on its DoFs, @p weight
     * its W_a. Zero if it does not take part. */
    static void
    node_terms(const NodeState    &node,
               const double        weight,
               Vector<double>     &force,
               FullMatrix<double> &stiffness);

    /** A point's share of the stiffness where the outline turns (the
     * turning of n and t in c_a and d_a) on the n_dofs DoFs of its cell
     * and body; false if none. */
    static bool
    point_terms(const ContactNodes::GaussPoint &point,
                const PointState               &state,
                FullMatrix<double>             &stiffness);

    /** 'Contact/Check tangent': the largest difference of the stiffness of
     * @p state (at @p increment) from central differences of the nodes'
     * forces by every DoF (and body translation) of the active nodes,
     * relative to the stiffness's largest entry; none where a difference
     * crosses a kink of the law (a node starts or stops touching or
     * sliding). Collective: ten evaluations per DoF, for small checks. */
    static std::optional<double>
    relative_error(const ContactTerms                               &terms,
                   const ContactNodes                               &nodes,
                   const std::vector<RigidBody>                     &bodies,
                   const RigidBodyMotion                            &motion,
                   const BackgroundGrid                             &grid,
                   const Q1CellKernel                               &kernel,
                   const LinearAlgebra::distributed::Vector<double> &increment,
                   const LinearAlgebra::distributed::Vector<double> *prescribed,
                   const State                                      &state);

    /** Adds the force and stiffness of @p state to @p force and
     * @p tangent (the rows of this process's DoFs) and, for bodies under a
     * force, the bordered terms to @p motion. */
    static void
    add_newton_terms(const State                     &state,
                     const ContactNodes              &nodes,
                     const BackgroundGrid            &grid,
                     const AffineConstraints<double> &constraints,
                     RigidBodyMotion                 &motion,
                     TrilinosWrappers::SparseMatrix  &tangent,
                     TrilinosWrappers::MPI::Vector   &force);
  };
} // namespace bsmpm

#endif
