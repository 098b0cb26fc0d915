#include <deal.II/base/data_out_base.h>

#include <bsmpm/io/curve_output.h>

namespace bsmpm
{
  namespace CurveOutput
  {
    namespace
    {
      using Range =
        std::tuple<unsigned int,
                   unsigned int,
                   std::string,
                   DataComponentInterpretation::DataComponentInterpretation>;

      template <int dim>
      void
      write(std::ostream                                  &out,
            const std::vector<DataOutBase::Patch<dim, 2>> &patches,
            const std::vector<std::string>                &names,
            const std::vector<Range>                      &vectors)
      {
        DataOutBase::VtkFlags flags;
        DataOutBase::write_vtu(patches, names, vectors, flags, out);
      }
    } // namespace



    void
    write_curves(std::ostream         &out,
                 const BoundaryCurves &curves,
                 const unsigned int    samples)
    {
      // One line patch per sample interval, with data at both ends.
      std::vector<DataOutBase::Patch<1, 2>> patches;
      const auto                           &all = curves.get_curves();
      for (unsigned int c = 0; c < all.size(); ++c)
        {
          const BSplineCurve &spline = *all[c].spline;
          for (unsigned int k = 0; k < spline.n_segments(); ++k)
            {
              const auto range = spline.segment_parameters(k);
              for (unsigned int i = 0; i < samples; ++i)
                {
                  DataOutBase::Patch<1, 2> patch;
                  patch.reference_cell = ReferenceCells::Line;
                  patch.n_subdivisions = 1;
                  patch.data.reinit(3, 2);
                  for (unsigned int end = 0; end < 2; ++end)
                    {
                      const double u =
                        range[0] + (range[1] - range[0]) * (i + end) / samples;
                      const Tensor<1, 2> n = spline.outward_normal(u);
                      patch.vertices[end]  = spline.value(u);
                      patch.data(0, end)   = c + 1;
                      patch.data(1, end)   = n[0];
                      patch.data(2, end)   = n[1];
                    }
                  patch.patch_index = patches.size();
                  patches.push_back(patch);
                }
            }
        }
      write(out,
            patches,
            {"curve", "outward_normal", "outward_normal"},
            {Range(1,
                   2,
                   "outward_normal",
                   DataComponentInterpretation::component_is_part_of_vector)});
    }



    void
    write_outlines(std::ostream                             &out,
                   const std::vector<std::vector<Point<2>>> &outlines)
    {
      std::vector<DataOutBase::Patch<1, 2>> patches;
      for (unsigned int b = 0; b < outlines.size(); ++b)
        for (unsigned int i = 0; i + 1 < outlines[b].size(); ++i)
          {
            DataOutBase::Patch<1, 2> patch;
            patch.reference_cell = ReferenceCells::Line;
            patch.n_subdivisions = 1;
            patch.data.reinit(1, 2);
            for (unsigned int end = 0; end < 2; ++end)
              {
                patch.vertices[end] = outlines[b][i + end];
                patch.data(0, end)  = b + 1;
              }
            patch.patch_index = patches.size();
            patches.push_back(patch);
          }
      write(out, patches, {"body"}, {});
    }



    void
    write_points(std::ostream                                     &out,
                 const BoundaryCurves                             &curves,
                 const std::vector<NeumannLoads::QuadraturePoint> &gauss_points,
                 const std::vector<ImplicitBoundary::BandPoint>   &band_points)
    {
      std::vector<DataOutBase::Patch<0, 2>> patches;
      const auto                            add = [&](const Point<2>     &x,
                           const int           kind,
                           const int           curve,
                           const Tensor<1, 2> &traction,
                           const double        D = 1.) {
        DataOutBase::Patch<0, 2> patch;
        patch.vertices[0] = x;
        patch.data.reinit(5, 1);
        patch.data(0, 0)  = kind;
        patch.data(1, 0)  = curve;
        patch.data(2, 0)  = traction[0];
        patch.data(3, 0)  = traction[1];
        patch.data(4, 0)  = D;
        patch.patch_index = patches.size();
        patches.push_back(patch);
      };

      const auto &all = curves.get_curves();
      for (unsigned int c = 0; c < all.size(); ++c)
        {
          for (const auto &x : all[c].positions)
            add(x, 0, c + 1, Tensor<1, 2>());
          for (const auto &piece : all[c].pieces)
            add(all[c].spline->value(piece.u_begin), 1, c + 1, Tensor<1, 2>());
        }
      for (const auto &g : gauss_points)
        add(g.position, 2, 0, g.traction);
      for (const auto &b : band_points)
        add(b.position, 3, 0, Tensor<1, 2>(), b.d_function);

      write(out,
            patches,
            {"kind", "curve", "traction", "traction", "d_function"},
            {Range(2,
                   3,
                   "traction",
                   DataComponentInterpretation::component_is_part_of_vector)});
    }
  } // namespace CurveOutput
} // namespace bsmpm
