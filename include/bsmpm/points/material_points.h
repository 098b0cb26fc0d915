#ifndef bsmpm_material_points_h
#define bsmpm_material_points_h

#include <deal.II/base/symmetric_tensor.h>

#include <deal.II/lac/la_parallel_vector.h>

#include <deal.II/particles/particle_handler.h>

#include <bsmpm/geometry/background_grid.h>
#include <bsmpm/geometry/body_region.h>
#include <bsmpm/materials/material.h>
#include <bsmpm/points/material_point_layout.h>
#include <bsmpm/points/q1_cell_kernel.h>

#include <algorithm>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace bsmpm
{
  using namespace dealii;

  /**
   * The material points (MPs): the quadrature points of the method, which
   * carry the state of the body through the load steps. They live in a
   * Particles::ParticleHandler, so that sorting into cells and MPI ownership
   * come from deal.II; their state is stored as particle properties.
   *
   * Zero-volume points are boundary tracking points: they move with the body
   * but never enter the stiffness or the internal force.
   */
  class MaterialPoints
  {
  public:
    /** Offsets of the state in the properties of a particle. */
    struct Property
    {
      static constexpr unsigned int volume           = 0;
      static constexpr unsigned int stress           = 1; ///< xx, yy, xy
      static constexpr unsigned int strain           = 4; ///< xx, yy, xy
      static constexpr unsigned int displacement     = 7; ///< total, x, y
      static constexpr unsigned int initial_position = 9; ///< x, y
      /** Value of the IBM D-function at the point in the last step (1 away
       * from supports). */
      static constexpr unsigned int d_function   = 11;
      static constexpr unsigned int n_properties = 12;
      /** The state of a nonlinear constitutive model, stored only when the
       * scene's model needs it (n_properties_inelastic properties). */
      static constexpr unsigned int elastic_strain = 12; ///< xx, yy, zz, xy
      static constexpr unsigned int plastic_strain = 16; ///< equivalent
      static constexpr unsigned int stress_zz      = 17;
      static constexpr unsigned int yielded        = 18; ///< 1 if plastic
      /** Quadrature weight of the point in this step (its volume, or the
       * moment-fitted weight in a cut cell, CutCellQuadrature). */
      static constexpr unsigned int weight = 19;
      /** Deformation gradient F of the point's motion since the start
       * (xx, xy, yx, yy; F_zz = 1 in plane strain) and det F: the
       * kinematics of finite strain; in small strain a record of the
       * points' motion. */
      static constexpr unsigned int deformation_gradient = 20;
      static constexpr unsigned int det_F                = 24;
      /** The body the point belongs to, 0 .. n - 1 (Bodies). */
      static constexpr unsigned int body                   = 25;
      static constexpr unsigned int n_properties_inelastic = 26;
    };

    /** Result of moving the points by one increment. */
    struct MoveReport
    {
      /** Points (over all processes) that would leave the grid. */
      types::particle_index n_left_grid = 0;
      /** Where one of them would go. */
      Point<2> example;
      /** Largest total displacement and stress (Frobenius) norms of points
       * with volume, over all processes: the scales of the solution. */
      double max_displacement = 0;
      double max_stress       = 0;
      /** Largest displacement increment of a point with volume. */
      double max_increment = 0;
      /** Points whose increment is not finite (NaN or inf). */
      types::particle_index n_non_finite = 0;
      /** Support quality (GhostPenalty) of the cell that the example point
       * left, if the qualities were given; -1 otherwise. */
      double example_quality = -1;
    };

    /** With @p inelastic_state, every point also stores the state of a
     * nonlinear constitutive model (Property::elastic_strain and after). */
    explicit MaterialPoints(const BackgroundGrid &grid,
                            const bool            inelastic_state = false);

    /** Whether the points store the state of a nonlinear constitutive
     * model; to be set before generate(). */
    void
    store_inelastic_state(const bool inelastic_state)
    {
      n_point_properties = inelastic_state ? Property::n_properties_inelastic :
                                             Property::n_properties;
    }

    /** Number of properties per point. */
    unsigned int
    n_properties() const
    {
      return n_point_properties;
    }

    /**
     * Creates the material points of @p layout in @p region, except those
     * for which @p excluded (if given) is true. Throws if a point lies
     * outside the grid or if the region holds no point.
     */
    void
    generate(const MaterialPointLayout                   &layout,
             const BodyRegion                            &region,
             const std::function<bool(const Point<2> &)> &excluded = {});

    /**
     * After generate(): adds the points of a further body, number @p body
     * (from 1; Property::body, which the points store with the state of a
     * nonlinear model), of @p layout in @p region, except where
     * @p excluded. Their ids follow the earlier bodies' candidates, so
     * that they too are partition-independent; or, for a body built by a
     * later stage, from @p first_id, which reserve_ids() kept for it.
     * Returns how many points it added. Throws (naming @p section) if the
     * region holds no point.
     */
    types::particle_index
    add_body(const MaterialPointLayout                   &layout,
             const BodyRegion                            &region,
             const unsigned int                           body,
             const std::string                           &section,
             const std::function<bool(const Point<2> &)> &excluded = {},
             const std::optional<types::particle_index>  &first_id = {});

    /** Keeps the ids of the candidates of @p layout for a body that a
     * later stage builds (add_body()), so that the ids of the points made
     * after it do not depend on when it is built. Returns the first. */
    types::particle_index
    reserve_ids(const MaterialPointLayout &layout);

    /** Counts the material points again (those with a volume): after the
     * points were read from a checkpoint, which may hold bodies built or
     * material excavated since the start. */
    void
    count_material_points();

    /**
     * The moments of the points' masses (their volumes times the density
     * of their body, set_densities()) in every locally owned cell, by
     * active_cell_index(): where bodies of several densities share a
     * cell, the body force is integrated from these.
     */
    void
    compute_mass_moments(std::vector<CellMoments> &moments) const;

    /** The density of every body, by Property::body (one entry with one
     * body): what compute_mass_moments() and global_mass() weigh the
     * points' volumes with. */
    void
    set_densities(const std::vector<double> &densities)
    {
      body_densities = densities;
    }

    /** The mass of all points, over all processes. */
    double
    global_mass() const;

    /**
     * Adds zero-volume tracking points at @p positions (the same list on
     * every process) and returns their particle ids, in order.
     */
    std::vector<types::particle_index>
    add_tracking_points(const std::vector<Point<2>> &positions);

    const Particles::ParticleHandler<2> &
    particle_handler() const
    {
      return particles;
    }
    Particles::ParticleHandler<2> &
    particle_handler()
    {
      return particles;
    }

    /** Number of points with volume, over all processes. */
    types::particle_index
    n_global_material_points() const
    {
      return n_material_points;
    }

    /** Sum of the volumes of all points. */
    double
    global_volume() const;

    /**
     * The volume and stress moments of every locally owned cell, indexed by
     * active_cell_index(); zero for other cells.
     */
    void
    compute_cell_moments(std::vector<CellMoments> &moments) const;

    /**
     * Modifies the displacement increment @p w of a point at @p x near a
     * support and returns the D-function there (see ImplicitBoundary);
     * @p field gives the grid increment anywhere in the point's cell.
     */
    using SupportFunction = std::function<
      double(const Point<2>                                      &x,
             const std::function<Tensor<1, 2>(const Point<2> &)> &field,
             Tensor<1, 2>                                        &w)>;

    /**
     * Applies the grid increment @p increment (with ghost values) to every
     * point: strain, stress, total displacement and position (paper eqs 5-8).
     * With @p prescribed (nodal values d^a of prescribed displacements, or
     * nullptr), the increment is u = w + M d^a and the strain B (d + d^a).
     * In the cells flagged in @p support_cells (by active_cell_index),
     * @p support modifies w. @p cell_quality (by active_cell_index, if
     * given) is reported for a point that leaves the grid. The points are not
     * re-sorted into cells; see sort_into_cells(). Without
     * @p update_stress the stress is left alone (a nonlinear model has
     * stored it already, ConstitutiveUpdate::commit()), without
     * @p update_strain the strain (finite strain: commit() stores the
     * logarithmic strain). With a B-bar @p kernel, @p cell_moments (by
     * active_cell_index, those the system was assembled with) give each
     * cell's centroid, where the stress takes its volumetric strain; the
     * stored strain stays the points' own.
     */
    MoveReport
    move(const Q1CellKernel                               &kernel,
         const LinearElasticMaterial                      &material,
         const LinearAlgebra::distributed::Vector<double> &increment,
         const LinearAlgebra::distributed::Vector<double> *prescribed = nullptr,
         const std::vector<bool>        *support_cells                = nullptr,
         const SupportFunction          &support                      = {},
         const std::vector<double>      *cell_quality                 = nullptr,
         const bool                      update_stress                = true,
         const bool                      update_strain                = true,
         const std::vector<CellMoments> *cell_moments = nullptr);

    /** Finds the cell and owner of every point after move(). */
    void
    sort_into_cells();

    /**
     * The outer layer of material points along a straight polyline (its
     * vertices @p corners, closed or not): along each side, the points with
     * volume nearest to it on its left, ordered along it. Returns their ids,
     * the same on every process; for a closed polyline each corner point
     * appears once.
     */
    std::vector<types::particle_index>
    outer_layer(const std::vector<Point<2>> &corners, const bool closed) const;

    /** The positions of the points @p ids, in that order, on every
     * process. */
    std::vector<Point<2>>
    locations(const std::vector<types::particle_index> &ids) const;

    /** Multiplies the volume of the points with ids @p ids by @p factor
     * (the same list on every process); a repeated id is scaled once per
     * occurrence. */
    void
    scale_volumes(const std::vector<types::particle_index> &ids,
                  const double                              factor);

    /** Gives every point the stress @p stress at its position and, where
     * the points store the state of a nonlinear model, the elastic strain
     * @p compliance : stress that carries it (InitialStress). */
    void
    set_stress(
      const std::function<SymmetricTensor<2, 3>(const Point<2> &,
                                                const unsigned int)> &stress,
      const std::vector<SymmetricTensor<4, 3>> &compliances);

    /**
     * Removes the material points (with volume) for which @p inside is true
     * at their position (Excavation). Returns how many were removed on all
     * processes.
     */
    types::particle_index
    remove_points(const std::function<bool(const Point<2> &)> &inside);

    /** Sets the total displacements of all points to zero (a stage that
     * measures its own displacements); positions, strains, stresses and
     * state stay. */
    void
    reset_displacements();

    /**
     * Marks the points with ids @p ids (the same list on every process) as
     * tracked: their current positions are available, in this order, from
     * tracked_positions() at any time, at no extra pass over the points.
     */
    void
    track(const std::vector<types::particle_index> &ids);

    /** Number of tracked points (the list given to track()). */
    unsigned int
    n_tracked() const
    {
      return n_tracked_slots;
    }

    /**
     * For the tracked points, by slot: whether the point belongs to a rigid
     * support and, if so, its increment in the next move() in place of the
     * body's (BoundaryCurves::rigid_support_increments()).
     */
    void
    set_rigid_increments(
      const std::vector<std::pair<bool, Tensor<1, 2>>> &increments)
    {
      rigid_increments = increments;
    }

    /** The constitutive state of a tracked point that finite strain needs
     * at the boundary: elastic strain (xx, yy, zz, xy), equivalent plastic
     * strain and det F (zero strains and det F = 1 for a linear model in
     * small strain, whose points store no state). */
    using TrackedState = std::array<double, 6>;

    /**
     * All properties of the tracked points in the slots @p slots (the same
     * list on every process), gathered from the processes that own them:
     * one vector of n_properties() values per slot, on every process.
     */
    std::vector<std::vector<double>>
    tracked_properties(const std::vector<unsigned int> &slots) const;

    /**
     * Adds zero-volume tracking points at @p positions with the properties
     * @p properties (n_properties() values each, the volume set to zero;
     * the same lists on every process) and appends them to the tracked
     * list. Returns their slots.
     */
    std::vector<unsigned int>
    add_tracked_points(const std::vector<Point<2>>            &positions,
                       const std::vector<std::vector<double>> &properties);

    /** The tracked list (ids by slot, the slots of removed points
     * included) and the next free id, as a string of bytes: what a
     * checkpoint keeps of a run whose curves gained or lost points
     * (BoundaryCurves::chain_state()). */
    std::string
    tracking_state() const;

    /** Takes back a tracking_state(), after the points were read from the
     * same checkpoint. */
    void
    restore_tracking(const std::string &state);

    /**
     * Removes the tracked points in the slots @p slots (the same list on
     * every process) from the points. Their slots stay in the tracked list,
     * unused: the other slots keep their numbers.
     */
    void
    remove_tracked_points(const std::vector<unsigned int> &slots);

    /** Current positions and stresses of the tracked points, in the order
     * given to track(), on every process (zero in the slots of removed
     * points); with @p states their constitutive states too, with
     * @p displacements their total displacements (Property::displacement,
     * which a stage may reset). */
    void
    tracked_states(std::vector<Point<2>>     &positions,
                   std::vector<Voigt>        &stresses,
                   std::vector<TrackedState> *states        = nullptr,
                   std::vector<Tensor<1, 2>> *displacements = nullptr) const;

    /** Whether a point with volume lies in @p cell. */
    bool
    holds_material(const DoFHandler<2>::active_cell_iterator &cell) const;

    /**
     * The mean properties of the points with volume in the face neighbours
     * of @p cell, owned or ghost (if none holds material, the diagonal
     * neighbours), weighted by their volumes; empty if none of them holds
     * material. The state of the neighbourhood for a cell of
     * the body that holds no point (ConstitutiveUpdate): exact wherever
     * the state is uniform. Needs exchange_neighbourhood_state() after the
     * points last changed.
     */
    std::vector<double>
    neighbourhood_mean_properties(
      const DoFHandler<2>::active_cell_iterator &cell) const;

    /**
     * For every one of @p positions (the same list on every process): the
     * mean properties of the points with volume within @p radius of it,
     * weighted by their volumes, over all processes (collective); empty
     * where no such point is. The state of the material next to a
     * boundary point made where there was none (an excavation's face).
     */
    std::vector<std::vector<double>>
    mean_properties_near(const std::vector<Point<2>> &positions,
                         const double                 radius) const;

    /**
     * Sums the volume-weighted properties of the points of every owned
     * cell and sends them to the processes that hold the cell as a ghost
     * (collective), for neighbourhood_mean_properties(): a cell next to the
     * partition's edge must borrow the same state as it would in a serial
     * run.
     */
    void
    exchange_neighbourhood_state();

    /**
     * Finds which owned and ghost cells hold material (collective), for
     * boundary_strain() and boundary_gradient(): a zero-volume point next
     * to a ghost cell must take the same neighbour's field as it would on
     * the process that owns that cell, or the result would depend on the
     * partition. move() calls it itself; call it after the points changed
     * cells and before the other two.
     */
    void
    find_material_cells();

    /**
     * The strain increment of the grid field @p increment (with ghost
     * values; plus @p prescribed if given) for a zero-volume point at local
     * coordinates @p st of @p cell, a cell without material: the strain of
     * the nearest face neighbour that holds material, its affine field
     * extended to the point (a boundary point on a grid line is sorted into
     * the cell above or right of it, and a boundary that has just entered a
     * cell leaves a sliver whose outer vertices hold nothing); @p cell's own
     * if no neighbour does.
     */
    Voigt
    boundary_strain(
      const Q1CellKernel                               &kernel,
      const DoFHandler<2>::active_cell_iterator        &cell,
      const Point<2>                                   &st,
      const LinearAlgebra::distributed::Vector<double> &increment,
      const LinearAlgebra::distributed::Vector<double> *prescribed) const;

    /** The displacement gradient of the same field as boundary_strain():
     * grad u, row = component. */
    Tensor<2, 2>
    boundary_gradient(
      const Q1CellKernel                               &kernel,
      const DoFHandler<2>::active_cell_iterator        &cell,
      const Point<2>                                   &st,
      const LinearAlgebra::distributed::Vector<double> &increment,
      const LinearAlgebra::distributed::Vector<double> *prescribed) const;

    /** The nodal values of @p increment plus @p prescribed (if given) on
     * the DoFs of @p cell, whose indices @p dof_indices receives. */
    static Q1CellKernel::LocalVector
    cell_increment(const DoFHandler<2>::active_cell_iterator        &cell,
                   const LinearAlgebra::distributed::Vector<double> &increment,
                   const LinearAlgebra::distributed::Vector<double> *prescribed,
                   std::vector<types::global_dof_index> &dof_indices);

    /** Names of the properties in the points' ParaView files (PointOutput). */
    static std::vector<std::string>
    property_names(const unsigned int n_properties = Property::n_properties);

  private:
    /** "(x, y)", for messages. */
    static std::string
    format_point(const Point<2> &p);

    /** Inserts one point if its cell is locally owned; returns whether. */
    bool
    insert(const Point<2>             &position,
           const double                volume,
           const types::particle_index id,
           const unsigned int          body = 0);

    /** The cell whose field boundary_strain() extends to a point at @p st
     * of @p cell, and the point's local coordinates in it. */
    std::pair<DoFHandler<2>::active_cell_iterator, Point<2>>
    boundary_source(const DoFHandler<2>::active_cell_iterator &cell,
                    const Point<2>                            &st) const;

    /** The nodal values of @p increment (plus @p prescribed, if given) of
     * the cell that boundary_source() finds for a point at @p st of
     * @p cell, and the point's local coordinates in it. */
    std::pair<Q1CellKernel::LocalVector, Point<2>>
    boundary_increment(
      const DoFHandler<2>::active_cell_iterator        &cell,
      const Point<2>                                   &st,
      const LinearAlgebra::distributed::Vector<double> &increment,
      const LinearAlgebra::distributed::Vector<double> *prescribed) const;

    /** Whether each owned and ghost cell holds material, by
     * active_cell_index() (find_material_cells()). */
    std::vector<bool> material_cells;

    /** Per owned and ghost cell (global active cell index c), the sums
     * sum_p V_p q_p of the properties q of its points at c W + k and their
     * volume sum_p V_p at c W + W - 1, W the number of properties plus
     * one (exchange_neighbourhood_state()). */
    LinearAlgebra::distributed::Vector<double> neighbourhood_sums;

    /** Whether neighbourhood_sums holds the points as they are. */
    bool neighbourhood_current = false;

    /** Records position and stress of a point if it is tracked. */
    /** The density of the point with @p props (set_densities()). */
    double
    density(const ArrayView<const double> &props) const
    {
      return body_densities.size() == 1 ?
               body_densities[0] :
               body_densities[static_cast<unsigned int>(props[Property::body])];
    }

    /** Inserts the points of @p layout in @p region with ids from
     * @p first_id on, with Property::body = @p body; returns how many
     * were inserted over all processes. */
    types::particle_index
    insert_body(const MaterialPointLayout                   &layout,
                const BodyRegion                            &region,
                const unsigned int                           body,
                const std::function<bool(const Point<2> &)> &excluded,
                const types::particle_index                  first_id);

    void
    record_if_tracked(const types::particle_index   id,
                      const Point<2>               &x,
                      const ArrayView<const double> properties);

    const BackgroundGrid         &grid;
    unsigned int                  n_point_properties;
    Particles::ParticleHandler<2> particles;
    types::particle_index         n_material_points = 0;
    types::particle_index         next_id           = 0;
    std::vector<double>           body_densities    = {0.};

    /** By tracked slot: set_rigid_increments(). */
    std::vector<std::pair<bool, Tensor<1, 2>>> rigid_increments;
    /** Whether a particle id is in the tracked list: a bit per id, so
     * that the test in the loops over all points costs little memory. */
    std::vector<bool> is_tracked;
    /** (id, slot in the tracked list) of the tracked points, by id. */
    std::vector<std::pair<types::particle_index, unsigned int>> tracked_slots;

    /** Slot of particle @p id in the tracked list, or invalid. */
    unsigned int
    tracked_slot(const types::particle_index id) const
    {
      if (id >= is_tracked.size() || !is_tracked[id])
        return numbers::invalid_unsigned_int;
      return std::lower_bound(tracked_slots.begin(),
                              tracked_slots.end(),
                              id,
                              [](const auto                 &entry,
                                 const types::particle_index i) {
                                return entry.first < i;
                              })
        ->second;
    }
    /** Length of the tracked list given to track() and extended by
     * add_tracked_points(). */
    unsigned int n_tracked_slots = 0;
    /** Refills tracked_local from every locally owned point. */
    void
    record_tracked_points();
    /** State of the locally owned tracked points: slot, x, y, stress, the
     * TrackedState and the total displacement. */
    std::vector<std::array<double, 14>> tracked_local;
  };
} // namespace bsmpm

#endif
