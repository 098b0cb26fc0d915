#include <deal.II/base/exceptions.h>

#include <deal.II/lac/lapack_full_matrix.h>
#include <deal.II/lac/vector.h>

#include <bsmpm/linear_algebra/geometric_multigrid.h>
#include <bsmpm/linear_algebra/vertex_patch_smoother.h>

#include <Epetra_Vector.h>

#include <algorithm>
#include <cmath>

namespace bsmpm
{
  namespace
  {
    /** @p block's inverse, row by row, appended to @p inverse: Cholesky
     * for a symmetric block, LU for an unsymmetric one (GMRES), and the
     * pseudo-inverse of its SVD where that fails (a singular block, or a
     * symmetric one that is not positive definite): the null space then
     * gets no correction from this patch. */
    void
    append_inverse(const LAPACKFullMatrix<double> &block,
                   std::vector<double>            &inverse)
    {
      const unsigned int n       = block.m();
      double             largest = 0., asymmetry = 0.;
      for (unsigned int i = 0; i < n; ++i)
        for (unsigned int j = 0; j < n; ++j)
          {
            largest = std::max(largest, std::abs(block(i, j)));
            asymmetry =
              std::max(asymmetry, std::abs(block(i, j) - block(j, i)));
          }
      LAPACKFullMatrix<double> factor(block);
      const bool               symmetric = asymmetry <= 1e-12 * largest;
      if (symmetric)
        factor.set_property(LAPACKSupport::symmetric);
      bool inverted = true;
      try
        {
          factor.invert();
        }
      catch (const ExceptionBase &)
        {
          inverted = false;
        }
      if (inverted && symmetric)
        {
          // potri fills one triangle only; deal.II 9.4 mirrors it, but a
          // symmetric copy costs nothing at this size.
          for (unsigned int i = 0; i < n; ++i)
            for (unsigned int j = 0; j < n; ++j)
              inverse.push_back(i <= j ? factor(i, j) : factor(j, i));
          return;
        }
      if (inverted)
        {
          for (unsigned int i = 0; i < n; ++i)
            for (unsigned int j = 0; j < n; ++j)
              inverse.push_back(factor(i, j));
          return;
        }
      // Singular (or indefinite and symmetric): the pseudo-inverse, by
      // columns of unit vectors.
      LAPACKFullMatrix<double> svd(block);
      svd.compute_inverse_svd(1e-12);
      Vector<double>      unit(n), column(n);
      std::vector<double> columns(n * n);
      for (unsigned int j = 0; j < n; ++j)
        {
          unit    = 0.;
          unit[j] = 1.;
          svd.vmult(column, unit);
          for (unsigned int i = 0; i < n; ++i)
            columns[i * n + j] = column[i];
        }
      inverse.insert(inverse.end(), columns.begin(), columns.end());
    }
  } // namespace



  void
  VertexPatchSmoother::initialize(
    const Epetra_CrsMatrix                         &matrix,
    const Epetra_Map                               &map,
    const std::vector<std::array<unsigned int, 3>> &place,
    const unsigned int                              nx,
    const unsigned int                              ny,
    const Patch                                     patch)
  {
    const int n_local = map.NumMyElements();
    AssertThrow(place.size() == static_cast<std::size_t>(n_local),
                ExcMessage("Vertex patch smoother: one place per unknown."));

    // The matrix row of each local unknown, and whether it couples.
    std::vector<int>  row(n_local);
    std::vector<bool> coupled(n_local);
    for (int k = 0; k < n_local; ++k)
      {
        row[k] = matrix.LRID(map.GID(k));
        AssertThrow(row[k] >= 0,
                    ExcMessage("Vertex patch smoother: an unknown of the "
                               "level is not a row of its matrix."));
        coupled[k] = couples_off_diagonal(matrix, row[k]);
      }

    // The local coupled unknown at each vertex and component, -1 if none.
    const std::size_t nv = std::size_t(nx + 1) * (ny + 1);
    std::vector<int>  at_vertex(2 * nv, -1);
    for (int k = 0; k < n_local; ++k)
      if (coupled[k])
        at_vertex[2 * (place[k][0] + std::size_t(nx + 1) * place[k][1]) +
                  place[k][2]] = k;

    // Anchors and the vertex ranges of their patches.
    // Anchors (vertices or cells) and the vertex range [i - below, i +
    // above] of their patches, clipped to the grid.
    const bool         by_vertex = patch == Patch::vertex;
    const unsigned int ax        = by_vertex ? nx + 1 : nx,
                       ay        = by_vertex ? ny + 1 : ny;
    const unsigned int below     = patch == Patch::cell ? 0 : 1;
    const unsigned int above     = patch == Patch::large ? 2 : 1;
    patch_start.assign(1, 0);
    patch_unknowns.clear();
    std::vector<bool> in_patch(n_local, false);
    for (unsigned int j = 0; j < ay; ++j)
      for (unsigned int i = 0; i < ax; ++i)
        {
          const unsigned int i0    = i > below ? i - below : 0;
          const unsigned int j0    = j > below ? j - below : 0;
          const unsigned int i1    = std::min(i + above, nx);
          const unsigned int j1    = std::min(j + above, ny);
          const std::size_t  first = patch_unknowns.size();
          for (unsigned int b = j0; b <= j1; ++b)
            for (unsigned int a = i0; a <= i1; ++a)
              for (unsigned int c = 0; c < 2; ++c)
                {
                  const int k =
                    at_vertex[2 * (a + std::size_t(nx + 1) * b) + c];
                  if (k >= 0)
                    patch_unknowns.push_back(k);
                }
          // vmult() gathers a patch into arrays of 64 (at most 32 here).
          AssertThrow(patch_unknowns.size() - first <= 64, ExcInternalError());
          if (patch_unknowns.size() > first)
            {
              for (std::size_t q = first; q < patch_unknowns.size(); ++q)
                in_patch[patch_unknowns[q]] = true;
              patch_start.push_back(patch_unknowns.size());
            }
        }

    // The blocks A_p and their inverses.
    inverse_start.assign(1, 0);
    inverses.clear();
    std::vector<int>    position(n_local, -1);
    std::vector<double> inverse_scratch;
    for (std::size_t p = 0; p + 1 < patch_start.size(); ++p)
      {
        const unsigned int n        = patch_start[p + 1] - patch_start[p];
        const int         *unknowns = &patch_unknowns[patch_start[p]];
        for (unsigned int a = 0; a < n; ++a)
          position[unknowns[a]] = a;
        LAPACKFullMatrix<double> block(n, n);
        for (unsigned int a = 0; a < n; ++a)
          {
            int     entries;
            double *values;
            int    *columns;
            matrix.ExtractMyRowView(row[unknowns[a]], entries, values, columns);
            for (int e = 0; e < entries; ++e)
              {
                const int k = map.LID(matrix.GCID(columns[e]));
                if (k >= 0 && position[k] >= 0)
                  block(a, position[k]) += values[e];
              }
          }
        for (unsigned int a = 0; a < n; ++a)
          position[unknowns[a]] = -1;
        append_inverse(block, inverse_scratch);
        inverses.insert(inverses.end(),
                        inverse_scratch.begin(),
                        inverse_scratch.end());
        inverse_scratch.clear();
        inverse_start.push_back(inverses.size());
      }

    // Point Jacobi for the rest.
    single_unknowns.clear();
    single_inverse.clear();
    Epetra_Vector diagonal(matrix.RowMap());
    AssertThrow(matrix.ExtractDiagonalCopy(diagonal) == 0,
                ExcMessage("Vertex patch smoother: no diagonal."));
    for (int k = 0; k < n_local; ++k)
      if (!in_patch[k])
        {
          single_unknowns.push_back(k);
          const double d = diagonal[row[k]];
          single_inverse.push_back(d != 0. ? 1. / d : 0.);
        }
  }



  void
  VertexPatchSmoother::vmult(TrilinosWrappers::MPI::Vector       &dst,
                             const TrilinosWrappers::MPI::Vector &src) const
  {
    const Epetra_Vector &r = *src.trilinos_vector()(0);
    Epetra_Vector       &x = *dst.trilinos_vector()(0);
    x.PutScalar(0.);
    double local_r[64], local_x[64];
    for (std::size_t p = 0; p + 1 < patch_start.size(); ++p)
      {
        const std::size_t n        = patch_start[p + 1] - patch_start[p];
        const int        *unknowns = &patch_unknowns[patch_start[p]];
        const float      *inverse  = &inverses[inverse_start[p]];
        for (std::size_t a = 0; a < n; ++a)
          local_r[a] = r[unknowns[a]];
        for (std::size_t a = 0; a < n; ++a)
          {
            double sum = 0.;
            for (std::size_t b = 0; b < n; ++b)
              sum += inverse[a * n + b] * local_r[b];
            local_x[a] = sum;
          }
        for (std::size_t a = 0; a < n; ++a)
          x[unknowns[a]] += local_x[a];
      }
    for (std::size_t s = 0; s < single_unknowns.size(); ++s)
      x[single_unknowns[s]] = single_inverse[s] * r[single_unknowns[s]];
  }
} // namespace bsmpm
