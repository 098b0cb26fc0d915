#ifndef bsmpm_contact_nodes_h
#define bsmpm_contact_nodes_h

#include <deal.II/base/mpi.h>
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <bsmpm/contact/contact_pieces.h>
#include <bsmpm/contact/rigid_body.h>
#include <bsmpm/contact/rigid_body_motion.h>
#include <bsmpm/geometry/background_grid.h>

#include <array>
#include <vector>

namespace bsmpm
{
  using namespace dealii;

  /**
   * 'Contact/Pressure = at grid lines' (doc/contact.md, "Contact
   * pressures"): the nodes of the contact pressure along the curves, one
   * where a curve crosses a grid line (or a free stretch ends), and the
   * Gauss points that each of them integrates over.
   *
   * The pressure is linear along the curve between neighbouring nodes (in
   * the curve's parameter): node a has the hat function phi_a, one on it,
   * zero at its neighbours, and holds one pressure for its weighted gap
   * G_a = sum_q phi_a(X_q) w_q g_q over the weight W_a = sum_q phi_a(X_q)
   * w_q (a mortar pairing: as many pressures as the curve crosses grid
   * lines, fewer than the bilinear displacement has values on the curve,
   * so that they cannot over-constrain it). A node's Gauss points lie in
   * the two cells on either side of its crossing.
   *
   * Only the places of a curve that face the body (their outward normal
   * against the outline's, at the increment's start) or already
   * penetrate it take part: a stretch round a corner of the body does not
   * dilute the gap of the face that touches.
   *
   * The points are this process's (in its locally owned cells), the nodes
   * are those of all processes, numbered alike on every process (by body,
   * curve and crossing), with W_a summed in a fixed order (by node, then
   * by cell): np > 1 gives the serial nodes bit for bit.
   */
  class ContactNodes
  {
  public:
    /** A Gauss point of a candidate piece, in a locally owned cell. */
    struct GaussPoint
    {
      unsigned int                body    = 0;
      unsigned int                curve   = 0;
      unsigned int                feature = 0;
      std::array<unsigned int, 2> cell    = {{0, 0}};
      /** X_q, on the curve of the increment's start. */
      Point<2> position;
      /** w_q: the length it stands for. */
      double weight = 0;
      /** The traction of the last increment at X_q (ContactHistory). */
      Tensor<1, 2> previous;
      /** The nodes of the crossings before and after it along the
       * curve, and their hat functions there, phi_a(X_q) (the last two
       * unused: numbers::invalid_unsigned_int). */
      std::array<unsigned int, 4> nodes;
      std::array<double, 4>       shape;
    };

    /** A node: its key and its weight. */
    struct Node
    {
      unsigned int body  = 0;
      unsigned int curve = 0;
      /** The crossing: its parameter on the curve. */
      double key = 0;
      /** W_a = sum_q N_a(X_q) w_q over the points of all processes. */
      double weight = 0;
      /** The augmented Lagrangian's multiplier (zero for the penalty). */
      double multiplier = 0;
    };

    /** A curve's point (a knot of its spline) that lies in a candidate
     * piece: where the tractions are kept for the next increment
     * (ContactHistory::store_points()). */
    struct CurvePoint
    {
      unsigned int                body    = 0;
      unsigned int                curve   = 0;
      unsigned int                index   = 0;
      unsigned int                feature = 0;
      std::array<unsigned int, 2> cell    = {{0, 0}};
      Point<2>                    position;
      std::array<unsigned int, 4> nodes;
      std::array<double, 4>       shape;
    };

    /**
     * The nodes of the Gauss points of @p pieces (this process's candidate
     * pieces, contact_pieces.h: one per cell, curve and part of the
     * outline), each Gauss point taken with the part of the outline it
     * faces; @p curves for the curves' points in the pieces. Collective.
     */
    void
    reinit(const std::vector<ContactPiece> &pieces,
           const BoundaryCurves            &curves,
           const std::vector<RigidBody>    &bodies,
           const RigidBodyMotion           &motion,
           const BackgroundGrid            &grid);

    const std::vector<GaussPoint> &
    points() const
    {
      return gauss_points;
    }

    const std::vector<Node> &
    nodes() const
    {
      return all_nodes;
    }

    std::vector<Node> &
    nodes()
    {
      return all_nodes;
    }

    const std::vector<CurvePoint> &
    curve_points() const
    {
      return knots;
    }

    /** The cells that hold Gauss points, of all processes (the same list on
     * every process): the contact's stiffness couples each with the cells
     * round it (ContactPattern). */
    const std::vector<std::array<unsigned int, 2>> &
    cells() const
    {
      return all_cells;
    }

    /** The augmented Lagrangian's start: each node's multiplier the
     * weighted mean of the normal pressure of the last increment
     * (ContactHistory) over its points. Collective. */
    void
    initialize_multipliers(const std::vector<RigidBody> &bodies,
                           const RigidBodyMotion        &motion,
                           const MPI_Comm                communicator);

    /** Node @p a's augmented Lagrangian multiplier becomes @p value. */
    void
    set_multiplier(const unsigned int a, const double value)
    {
      all_nodes[a].multiplier = value;
    }

  private:
    /** The node of crossing @p key of @p curve with @p body among
     * all_nodes, or invalid_unsigned_int. */
    unsigned int
    find(const unsigned int body,
         const unsigned int curve,
         const double       key) const;

    /** The nodes and hat functions at parameter share @p phi of @p piece
     * (after all_nodes stands). */
    void
    locate(const ContactPiece          &piece,
           const double                 phi,
           std::array<unsigned int, 4> &nodes,
           std::array<double, 4>       &shape) const;

    std::vector<GaussPoint>                  gauss_points;
    std::vector<Node>                        all_nodes;
    std::vector<CurvePoint>                  knots;
    std::vector<std::array<unsigned int, 2>> all_cells;
    /** The grid's cells in x: a cell's number is i + j cells_per_row. */
    unsigned int cells_per_row = 1;
  };
} // namespace bsmpm

#endif
