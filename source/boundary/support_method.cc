#include <bsmpm/boundary/support_method.h>

namespace bsmpm
{
  namespace
  {
    std::map<std::string, SupportMethodEntry> &
    support_method_registry()
    {
      static std::map<std::string, SupportMethodEntry> methods;
      return methods;
    }
  } // namespace



  SupportMethod::SupportMethod(const std::string &name)
    : method_name(name)
  {}



  void
  SupportMethod::mark_cells(const BackgroundGrid &grid,
                            const BoundaryCurves &curves,
                            const bool            both_components_only,
                            std::vector<bool>    &cells) const
  {
    curves.mark_support_cells(grid, method_name, both_components_only, cells);
  }



  double
  SupportMethod::support_displacement(
    const BoundaryCurves &,
    const BackgroundGrid &,
    const Point<2> &,
    const std::function<Tensor<1, 2>(const Point<2> &)> &,
    Tensor<1, 2> &) const
  {
    return 1.;
  }



  const std::vector<SupportMethod::BandPoint> &
  SupportMethod::band_points() const
  {
    static const std::vector<BandPoint> none;
    return none;
  }



  bool
  SupportMethod::fits_prescribed_displacement(const BoundaryCurves &) const
  {
    return false;
  }



  double
  SupportMethod::fit_prescribed_displacement(
    const Context &,
    const LoadIncrement &,
    TrilinosWrappers::SparseMatrix &,
    LinearAlgebra::distributed::Vector<double> &) const
  {
    Assert(false,
           ExcMessage("Support method '" + method_name +
                      "' fits no prescribed displacement."));
    return 0.;
  }



  std::optional<Point<2>>
  SupportMethod::bbar_point(const std::vector<CellMoments> *moments,
                            const LocallyOwnedCurvePiece   &piece)
  {
    if (moments == nullptr)
      return std::nullopt;
    return Q1CellKernel::centroid(
      (*moments)[piece.owned_cell->active_cell_index()]);
  }



  void
  SupportMethod::add_piece_terms(const Context                   &context,
                                 const Quadrature<1>             &along,
                                 const BoundaryCurve             *only,
                                 const AffineConstraints<double> &constraints,
                                 TrilinosWrappers::SparseMatrix  *matrix,
                                 TrilinosWrappers::MPI::Vector   &vector,
                                 const PieceTerms &piece_terms) const
  {
    constexpr unsigned int n = Q1CellKernel::dofs_per_cell;
    FullMatrix<double>     cell_matrix(n, n);
    Vector<double>         cell_vector(n);
    CurvePieceValues       values(context.grid, along);
    for (const auto &piece : supported_pieces(values, context.curves, only))
      {
        values.reinit(piece);
        cell_matrix = 0;
        cell_vector = 0;
        piece_terms(values, cell_matrix, cell_vector);
        if (matrix != nullptr)
          constraints.distribute_local_to_global(
            cell_matrix, cell_vector, values.dof_indices(), *matrix, vector);
        else
          constraints.distribute_local_to_global(cell_vector,
                                                 values.dof_indices(),
                                                 vector);
      }
  }



  bool
  register_support_method(const std::string        &name,
                          const SupportMethodEntry &entry)
  {
    Assert(support_method_registry().count(name) == 0,
           ExcMessage("Two support methods are called '" + name + "'."));
    support_method_registry()[name] = entry;
    return true;
  }



  const std::map<std::string, SupportMethodEntry> &
  registered_support_methods()
  {
    return support_method_registry();
  }



  std::string
  support_method_names()
  {
    std::string names;
    for (const auto &[name, entry] : support_method_registry())
      names += (names.empty() ? "" : "|") + name;
    return names;
  }
} // namespace bsmpm
