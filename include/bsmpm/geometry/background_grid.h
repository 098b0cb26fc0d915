#ifndef bsmpm_background_grid_h
#define bsmpm_background_grid_h

#include <deal.II/base/index_set.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>

#include <deal.II/distributed/tria.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/mapping_cartesian.h>

#include <deal.II/lac/affine_constraints.h>

#include <algorithm>
#include <array>
#include <string>
#include <vector>

namespace bsmpm
{
  using namespace dealii;

  /**
   * The background grid: an axis-aligned rectangle of equal Q1 cells,
   * distributed with p4est, with the vector Q1 element and its DoFs. The grid
   * never moves: material points move through it and it is reset every load
   * step (paper Sec. 2).
   *
   * Because all cells are equal, the cell holding a point and that point's
   * local coordinates are computed directly, never searched for.
   */
  class BackgroundGrid
  {
  public:
    /** A support condition on one of the four faces of the rectangle. */
    enum class FaceCondition
    {
      free,
      fixed, ///< both displacement components zero
      roller ///< normal component zero, tangential free
    };

    using cell_iterator = DoFHandler<2>::active_cell_iterator;

    explicit BackgroundGrid(const MPI_Comm communicator);

    static void
    declare_parameters(ParameterHandler &prm);
    void
    parse_parameters(ParameterHandler &prm);

    /** Builds the triangulation and distributes the DoFs. With
     * @p saved_triangulation (a file of Triangulation::save(), see
     * Checkpoint), the refinement and partition are loaded from it, with the
     * data attached to its cells. */
    void
    create(const std::string &saved_triangulation = "");

    const parallel::distributed::Triangulation<2> &
    triangulation() const
    {
      return tria;
    }
    const DoFHandler<2> &
    dof_handler() const
    {
      return dofs;
    }
    const FESystem<2> &
    fe() const
    {
      return finite_element;
    }
    const Mapping<2> &
    mapping() const
    {
      return cartesian_mapping;
    }
    const IndexSet &
    locally_owned_dofs() const
    {
      return owned_dofs;
    }
    const IndexSet &
    locally_relevant_dofs() const
    {
      return relevant_dofs;
    }
    MPI_Comm
    mpi_communicator() const
    {
      return communicator;
    }

    const Point<2> &
    lower_left() const
    {
      return corner_lower;
    }
    const Point<2> &
    upper_right() const
    {
      return corner_upper;
    }
    const Tensor<1, 2> &
    cell_size() const
    {
      return h;
    }
    /** Smaller of the two cell side lengths. */
    double
    min_cell_size() const
    {
      return std::min(h[0], h[1]);
    }
    unsigned int
    n_cells(const unsigned int direction) const
    {
      return cells[direction];
    }

    /** Whether @p p lies in the closed rectangle of the grid. */
    bool
    contains(const Point<2> &p) const;

    /** @p p, moved onto the grid's rectangle in each direction in which it
     * lies outside by less than @p fraction of a cell; else as it is. */
    Point<2>
    pulled_onto(Point<2> p, const double fraction) const;

    /**
     * Index (i, j) of the cell that holds @p p, which must lie in the grid.
     * A point on a grid line belongs to the cell above / to the right of it,
     * except on the upper and right edges of the grid.
     */
    std::array<unsigned int, 2>
    cell_index(const Point<2> &p) const
    {
      Assert(contains(p), ExcMessage("Point outside the grid."));
      // Between the clamps the quotient is positive: truncation is floor.
      std::array<unsigned int, 2> ij;
      for (unsigned int d = 0; d < 2; ++d)
        {
          const double x = (p[d] - corner_lower[d]) / h[d];
          ij[d]          = !(x > 0.)     ? 0u :
                           x >= cells[d] ? cells[d] - 1 :
                                           static_cast<unsigned int>(x);
        }
      return ij;
    }

    /** Local coordinates of @p p in the cell with index @p ij. */
    Point<2>
    local_coordinates(const Point<2>                    &p,
                      const std::array<unsigned int, 2> &ij) const
    {
      return Point<2>((p[0] - corner_lower[0]) / h[0] - ij[0],
                      (p[1] - corner_lower[1]) / h[1] - ij[1]);
    }

    /** Lower left vertex of the cell with index @p ij. */
    Point<2>
    cell_origin(const std::array<unsigned int, 2> &ij) const
    {
      return Point<2>(corner_lower[0] + ij[0] * h[0],
                      corner_lower[1] + ij[1] * h[1]);
    }

    /** Index of an active cell of the triangulation. */
    std::array<unsigned int, 2>
    cell_index(const cell_iterator &cell) const
    {
      return cell_index(cell->center());
    }

    /**
     * The locally owned cell with index @p ij, or an invalid (end) iterator
     * if another process owns it.
     */
    cell_iterator
    locally_owned_cell(const std::array<unsigned int, 2> &ij) const
    {
      return owned_cell_lookup[ij[1] * cells[0] + ij[0]];
    }

    /**
     * The process that owns the cell with index @p ij (any cell of the grid,
     * also artificial ones): a table of one entry per cell, filled when the
     * grid is created.
     */
    types::subdomain_id
    owner(const std::array<unsigned int, 2> &ij) const
    {
      return cell_owners[ij[1] * cells[0] + ij[0]];
    }

    /** The position of the cell with index @p ij in locally_owned_cells(),
     * or numbers::invalid_unsigned_int if another process owns it. */
    unsigned int
    owned_position(const std::array<unsigned int, 2> &ij) const
    {
      return owned_positions[ij[1] * cells[0] + ij[0]];
    }

    /** The locally owned cells with their indices (i, j), in the order of
     * the triangulation's active cells. */
    const std::vector<std::pair<cell_iterator, std::array<unsigned int, 2>>> &
    locally_owned_cells() const
    {
      return owned_cells;
    }

    /** Adds the support conditions of the grid faces to @p constraints. */
    void
    make_face_constraints(AffineConstraints<double> &constraints) const;

    /** Whether any grid face carries a support condition. */
    bool
    has_face_conditions() const;

    /** The support condition of face @p f: 0 left, 1 right, 2 bottom,
     * 3 top. */
    FaceCondition
    face_condition(const unsigned int f) const
    {
      return face_conditions[f];
    }

  private:
    MPI_Comm                                communicator;
    parallel::distributed::Triangulation<2> tria;
    FESystem<2>                             finite_element;
    MappingCartesian<2>                     cartesian_mapping;
    DoFHandler<2>                           dofs;
    IndexSet                                owned_dofs;
    IndexSet                                relevant_dofs;

    Point<2>                     corner_lower, corner_upper;
    std::array<unsigned int, 2>  cells = {{1, 1}};
    Tensor<1, 2>                 h;
    std::array<FaceCondition, 4> face_conditions; // left, right, bottom, top

    std::vector<cell_iterator>       owned_cell_lookup;
    std::vector<types::subdomain_id> cell_owners;
    std::vector<unsigned int>        owned_positions;
    std::vector<std::pair<cell_iterator, std::array<unsigned int, 2>>>
      owned_cells;
  };
} // namespace bsmpm

#endif
