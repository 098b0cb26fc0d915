#ifndef bsmpm_rigid_body_motion_h
#define bsmpm_rigid_body_motion_h

#include <deal.II/base/exceptions.h>
#include <deal.II/base/index_set.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/tensor.h>

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/lac/vector.h>

#include <bsmpm/contact/rigid_body.h>

#include <boost/serialization/vector.hpp>

#include <array>
#include <map>
#include <string>
#include <vector>

namespace bsmpm
{
  using namespace dealii;

  /** A force-controlled component of a rigid body that no contact
   * resists (RigidBodyMotion::bordered_correction()). */
  DeclException1(ExcUnresistedMotion, std::string, << arg1);



  /**
   * Where the rigid bodies are within a load increment, and the unknowns
   * of the bodies whose translation is force-controlled (doc/contact.md,
   * "Rigid bodies under a force").
   *
   * A prescribed component of a body's translation is its expression of
   * the load factor. A free component c is an unknown of the Newton
   * iterations besides the grid's displacement increment du: the body is
   * in equilibrium when the contact forces on it balance the applied force,
   *
   *   r_c(du, c) = F_applied(t) + F_contact(du, c) = 0.
   *
   * The unknowns are not DoFs of the grid's system: the contact adds to
   * the Newton system [K B; G H] [du; dc] = [R; r_c] the column B (the
   * grid forces' derivative by c, minus), the row G (the body's force's
   * derivative by du, minus) and the small block H, held here. Block
   * elimination solves it with the grid's matrix alone: K X = R,
   * K Y_k = B_k, then (H - G Y) dc = r_c - G X and du = X - Y dc.
   */
  class RigidBodyMotion
  {
  public:
    /** A force-controlled component: body and direction (0: x, 1: y). */
    struct Unknown
    {
      unsigned int body;
      unsigned int component;
    };

    /** Starts with the bodies in their places at load factor 0. */
    void
    initialize(const std::vector<RigidBody> &bodies);

    /** Whether any body has a force-controlled component. */
    bool
    has_unknowns() const
    {
      return !unknowns.empty();
    }

    const std::vector<Unknown> &
    get_unknowns() const
    {
      return unknowns;
    }

    /** The unknown of component @p d of body @p b, or -1. */
    int
    unknown_of(const unsigned int b, const unsigned int d) const
    {
      return index[b][d];
    }

    /**
     * Places the bodies for the load increment from load factor @p from to
     * @p to: prescribed components by their expressions, free ones where
     * the last converged increment left them and, as the start of the
     * Newton iterations, moved by the last converged increment's motion
     * scaled to this one.
     */
    void
    begin_increment(const std::vector<RigidBody> &bodies,
                    const double                  from,
                    const double                  to);

    /** The translation of body @p b at the increment's start. */
    const Tensor<1, 2> &
    start(const unsigned int b) const
    {
      return start_place[b];
    }

    /** The translation of body @p b at the increment's end (for a free
     * component: the Newton iterations' present value). */
    const Tensor<1, 2> &
    end(const unsigned int b) const
    {
      return end_place[b];
    }

    /** The free components' values at the increment's end, in the order
     * of get_unknowns(). */
    Vector<double>
    values() const;

    /** The free components' values at the increment's start. */
    Vector<double>
    start_values() const;

    /** Sets the free components' values at the increment's end. */
    void
    set_values(const Vector<double> &c);

    /** Adds @p factor @p dc to the free components at the increment's end. */
    void
    add(const double factor, const Vector<double> &dc);

    /** Moves body @p b at the increment's end by @p shift (in its free
     * components: the others of @p shift must be zero) before the Newton
     * iterations, to touch what it must rest on. The shift is no part of
     * the motion that predicts the next increment. */
    void
    approach(const unsigned int b, const Tensor<1, 2> &shift);

    /** Adds @p text to what the step's log says of the bodies' start (a
     * body moved to touch). */
    void
    note(const std::string &text)
    {
      notes += (notes.empty() ? "" : "; ") + text;
    }

    /** What the last begin_increment() did beyond the prediction (empty if
     * nothing), and forgets it. */
    std::string
    take_notes()
    {
      std::string text;
      std::swap(text, notes);
      return text;
    }

    /**
     * Zeroes the bordered terms before the contact adds those of a Newton
     * system: the columns and rows live on the grid's DoFs
     * @p locally_owned. @p stiffness_scale: the stiffness of contact over
     * one cell (penalty times cell size), to judge a singular H - G Y.
     */
    void
    reset_bordered_terms(const IndexSet &locally_owned,
                         const MPI_Comm  communicator,
                         const double    stiffness_scale);

    /** The column B_k: -d(grid force)/dc_k (condensed like a load). */
    TrilinosWrappers::MPI::Vector &
    column(const unsigned int k)
    {
      return columns[k];
    }

    const TrilinosWrappers::MPI::Vector &
    column(const unsigned int k) const
    {
      return columns[k];
    }

    /** The row G_k: -d(F_contact)_k/du. */
    TrilinosWrappers::MPI::Vector &
    row(const unsigned int k)
    {
      return rows[k];
    }

    /** The block H: -d(F_contact)/dc (this process's share until
     * finish_bordered_terms()). */
    FullMatrix<double> &
    block()
    {
      return h_block;
    }

    /** The contact force on the bodies in the free components (this
     * process's share until finish_bordered_terms()). */
    Vector<double> &
    contact_force()
    {
      return force_on_body;
    }

    /** Sums the bordered terms over processes and forms the residual
     * r_c = F_applied(t) + F_contact with the load factor @p t that the
     * increment ends at. Collective. */
    void
    finish_bordered_terms(const std::vector<RigidBody> &bodies, const double t);

    /** |r_c| of the last finish_bordered_terms(). */
    double
    residual_norm() const
    {
      return residual.l2_norm();
    }

    const Vector<double> &
    get_residual() const
    {
      return residual;
    }

    /**
     * The correction dc of the bordered Newton system from X = K^-1 R and
     * Y_k = K^-1 B_k: (H - G Y) dc = r_c - G X. Throws with the body and
     * component if H - G Y is singular: a free component that no contact
     * resists. Collective.
     */
    Vector<double>
    bordered_correction(
      const TrilinosWrappers::MPI::Vector              &X,
      const std::vector<TrilinosWrappers::MPI::Vector> &Y) const;

    /** After the increment converged: its end is the next one's start,
     * and its motion the next prediction. */
    void
    accept();

    /** Adds rigid_body_N_applied_force_x/y of the bodies with a free
     * component at load factor @p t. */
    void
    record(const std::vector<RigidBody>  &bodies,
           const double                   t,
           std::map<std::string, double> &quantities) const;

    /** What a load step leaves for the next (the places and the free
     * components' motion), for checkpoints. */
    template <class Archive>
    void
    serialize(Archive &archive, const unsigned int)
    {
      archive &start_place &end_place &solved_start &solved_end &last_motion
        &last_delta;
    }

  private:
    std::vector<Unknown>            unknowns;
    std::vector<std::array<int, 2>> index;
    /** Per body, for messages: its parameter section, and whether its
     * surface is frictional. */
    std::vector<std::string> sections;
    std::vector<bool>        frictional;

    std::vector<Tensor<1, 2>> start_place, end_place;
    /** The free components' part of the places (zero elsewhere). */
    std::vector<Tensor<1, 2>> solved_start, solved_end;
    /** The free components' motion of the last converged increment and
     * that increment's load factor increment. */
    std::vector<Tensor<1, 2>> last_motion;
    /** The shifts of approach() in this increment. */
    std::vector<Tensor<1, 2>> approaches;
    double                    last_delta = 0, delta = 0;
    std::string               notes;

    std::vector<TrilinosWrappers::MPI::Vector> columns, rows;
    FullMatrix<double>                         h_block;
    Vector<double>                             force_on_body, residual;
    double                                     scale        = 0;
    MPI_Comm                                   communicator = MPI_COMM_SELF;
  };
} // namespace bsmpm

#endif
