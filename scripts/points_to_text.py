"""Writes the material points of one points-NNNN.pvtu of a bsmpm run as a
text file of columns x, y, body, equivalent plastic strain, volume (run with
pvpython; scripts/plot_bodies.py draws it).

Usage: pvpython points_to_text.py points-NNNN.pvtu OUTPUT.txt
"""
import sys

import numpy as np
from paraview import servermanager, simple
from vtk.numpy_interface import dataset_adapter as dsa

reader = simple.XMLPartitionedUnstructuredGridReader(FileName=[sys.argv[1]])
reader.UpdatePipeline()
data = dsa.WrapDataObject(servermanager.Fetch(reader))
points = np.array(data.Points)
np.savetxt(sys.argv[2], np.column_stack(
    [points[:, 0], points[:, 1]] +
    [np.array(data.PointData[name]) for name in
     ("body", "equivalent_plastic_strain", "volume")]))
