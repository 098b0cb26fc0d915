#include <bsmpm/curve_vtk_writer.h>

#include <vtkCellArray.h>
#include <vtkDoubleArray.h>
#include <vtkIntArray.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyLine.h>
#include <vtkSmartPointer.h>
#include <vtkXMLPolyDataWriter.h>

namespace bsmpm
{
  namespace CurveVtkWriter
  {
    namespace
    {
      vtkSmartPointer<vtkDoubleArray>
      vector_array(const char *name)
      {
        auto array = vtkSmartPointer<vtkDoubleArray>::New();
        array->SetName(name);
        array->SetNumberOfComponents(3);
        return array;
      }

      void
      write(const std::string &file, vtkPolyData *data)
      {
        auto writer = vtkSmartPointer<vtkXMLPolyDataWriter>::New();
        writer->SetFileName(file.c_str());
        writer->SetInputData(data);
        writer->SetDataModeToBinary();
        AssertThrow(writer->Write() == 1,
                    ExcMessage("Output: cannot write the file '" + file + "'."));
      }
    } // namespace



    void
    write_curves(const std::string &   file,
                 const BoundaryCurves &curves,
                 const unsigned int    samples)
    {
      auto points  = vtkSmartPointer<vtkPoints>::New();
      auto lines   = vtkSmartPointer<vtkCellArray>::New();
      auto normals = vector_array("outward_normal");
      auto ids     = vtkSmartPointer<vtkIntArray>::New();
      ids->SetName("curve");

      const auto &all = curves.get_curves();
      for (unsigned int c = 0; c < all.size(); ++c)
        {
          const BSplineCurve &spline = *all[c].spline;
          auto                line   = vtkSmartPointer<vtkPolyLine>::New();
          for (unsigned int k = 0; k < spline.n_segments(); ++k)
            {
              const auto   range = spline.segment_parameters(k);
              const bool   last  = k + 1 == spline.n_segments();
              for (unsigned int i = 0; i < samples + (last ? 1 : 0); ++i)
                {
                  const double u =
                    range[0] + (range[1] - range[0]) * i / samples;
                  const Point<2>     x = spline.value(u);
                  const Tensor<1, 2> n = spline.outward_normal(u);
                  line->GetPointIds()->InsertNextId(
                    points->InsertNextPoint(x[0], x[1], 0.));
                  normals->InsertNextTuple3(n[0], n[1], 0.);
                  ids->InsertNextValue(c + 1);
                }
            }
          if (spline.is_closed())
            line->GetPointIds()->InsertNextId(
              line->GetPointIds()->GetId(0));
          lines->InsertNextCell(line);
        }

      auto data = vtkSmartPointer<vtkPolyData>::New();
      data->SetPoints(points);
      data->SetLines(lines);
      data->GetPointData()->AddArray(normals);
      data->GetPointData()->AddArray(ids);
      write(file, data);
    }



    void
    write_points(const std::string &                                file,
                 const BoundaryCurves &                             curves,
                 const std::vector<NeumannLoads::QuadraturePoint> &gauss_points,
                 const std::vector<ImplicitBoundary::BandPoint> &   band_points)
    {
      auto points   = vtkSmartPointer<vtkPoints>::New();
      auto vertices = vtkSmartPointer<vtkCellArray>::New();
      auto traction = vector_array("traction");
      auto kind     = vtkSmartPointer<vtkIntArray>::New();
      kind->SetName("kind");
      auto curve_id = vtkSmartPointer<vtkIntArray>::New();
      curve_id->SetName("curve");
      auto d_function = vtkSmartPointer<vtkDoubleArray>::New();
      d_function->SetName("d_function");

      const auto add = [&](const Point<2> &x, const int k, const int c,
                           const Tensor<1, 2> &t, const double D = 1.) {
        const vtkIdType id = points->InsertNextPoint(x[0], x[1], 0.);
        vertices->InsertNextCell(1, &id);
        kind->InsertNextValue(k);
        curve_id->InsertNextValue(c);
        traction->InsertNextTuple3(t[0], t[1], 0.);
        d_function->InsertNextValue(D);
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

      auto data = vtkSmartPointer<vtkPolyData>::New();
      data->SetPoints(points);
      data->SetVerts(vertices);
      data->GetPointData()->AddArray(kind);
      data->GetPointData()->AddArray(curve_id);
      data->GetPointData()->AddArray(traction);
      data->GetPointData()->AddArray(d_function);
      write(file, data);
    }
  } // namespace CurveVtkWriter
} // namespace bsmpm
