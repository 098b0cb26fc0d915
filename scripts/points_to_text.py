"""Writes the material points of one points-NNNN.pvtu of a bsmpm run as a
text file of columns x, y, body, equivalent plastic strain, volume; or, given
a curves-NNNN.vtu, the points along the boundary curves as columns x, y
(run with pvpython; scripts/plot_bodies.py draws them).

Usage: pvpython points_to_text.py points-NNNN.pvtu OUTPUT.txt
       pvpython points_to_text.py curves-NNNN.vtu OUTPUT.txt
"""
import sys

import numpy as np
from paraview import servermanager, simple
from vtk.numpy_interface import dataset_adapter as dsa

curves = sys.argv[1].endswith(".vtu")
reader = (simple.XMLUnstructuredGridReader if curves else
          simple.XMLPartitionedUnstructuredGridReader)(FileName=[sys.argv[1]])
reader.UpdatePipeline()
data = dsa.WrapDataObject(servermanager.Fetch(reader))
points = np.array(data.Points)
columns = [points[:, 0], points[:, 1]]
if not curves:
    columns += [np.array(data.PointData[name]) for name in
                ("body", "equivalent_plastic_strain", "volume")]
np.savetxt(sys.argv[2], np.column_stack(columns))
