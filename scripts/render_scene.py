"""Renders the last load step of a bsmpm run with ParaView (run with
pvbatch): the material points at their deformed places coloured by a field,
the boundary curves drawn over them in black, optionally the initial curves
in grey.

Usage: pvbatch render_scene.py OUTPUT_DIRECTORY FIELD PNG [TITLE]
"""
import os
import sys

from paraview import simple

directory, field, png = sys.argv[1], sys.argv[2], sys.argv[3]
title = sys.argv[4] if len(sys.argv) > 4 else field

points = simple.PVDReader(FileName=os.path.join(directory, "points.pvd"))
last = points.TimestepValues[-1] if hasattr(points.TimestepValues, "__len__") \
    else points.TimestepValues
# A scene without boundary curves writes no curves.pvd.
has_curves = os.path.exists(os.path.join(directory, "curves.pvd"))
if has_curves:
    curves = simple.PVDReader(FileName=os.path.join(directory, "curves.pvd"))
    # The initial curves: the same series held at time 0.
    first = simple.ForceTime(Input=simple.PVDReader(
        FileName=os.path.join(directory, "curves.pvd")))
    first.ForcedTime = 0.0
    first.IgnorePipelineTime = 1

view = simple.CreateRenderView()
view.ViewSize = [1400, 900]
view.ViewTime = last
view.OrientationAxesVisibility = 0
view.Background = [1, 1, 1]
view.UseColorPaletteForBackground = 0

shown = simple.Show(points, view)
shown.SetRepresentationType("Points")
shown.PointSize = 3
simple.ColorBy(shown, ("POINTS", field))
lut = simple.GetColorTransferFunction(field)
lut.ApplyPreset("Jet", True)
shown.RescaleTransferFunctionToDataRange(True, False)
bar = simple.GetScalarBar(lut, view)
bar.Title = title
bar.ComponentTitle = ""
bar.TitleColor = [0, 0, 0]
bar.LabelColor = [0, 0, 0]
shown.SetScalarBarVisibility(view, True)

# The initial boundary (grey) and the deformed one (black).
if has_curves:
    initial = simple.Show(first, view)
    initial.SetRepresentationType("Wireframe")
    initial.AmbientColor = initial.DiffuseColor = [0.6, 0.6, 0.6]
    initial.LineWidth = 2
    initial.ColorArrayName = [None, ""]
    deformed = simple.Show(curves, view)
    deformed.SetRepresentationType("Wireframe")
    deformed.AmbientColor = deformed.DiffuseColor = [0, 0, 0]
    deformed.LineWidth = 3
    deformed.ColorArrayName = [None, ""]

view.InteractionMode = "2D"
simple.ResetCamera(view)
view.CameraParallelScale *= 1.05
simple.SaveScreenshot(png, view, ImageResolution=[1400, 900])
print(f"wrote {png}")
