"""Opens a run's ParaView files with ParaView's own readers (pvpython) and
checks that every series loads at every written step, is not empty, has the
expected arrays with finite values, and that solution.pvd opens as a whole.

Usage: pvpython open_output.py [--curves] [--every-step] <output directory>

--curves: the scene has boundary curves, so curves.pvd and
          curve_points.pvd must be there too (otherwise they must not).
--every-step: the run wrote every load step (Output/Interval = 1), so
              every series must hold load_steps + 1 steps (summary.json),
              the initial state included.
"""
import argparse
import json
import math
import os
import sys
import xml.etree.ElementTree as ElementTree

from paraview import simple

parser = argparse.ArgumentParser()
parser.add_argument("directory")
parser.add_argument("--curves", action="store_true")
parser.add_argument("--every-step", action="store_true")
args = parser.parse_args()
n_steps = None
if args.every_step:
    with open(os.path.join(args.directory, "summary.json")) as f:
        n_steps = json.load(f)["load_steps"] + 1

expected = {
    "points.pvd": ["volume", "stress_xx", "displacement", "d_function"],
    "grid.pvd": ["displacement_increment", "material_fraction"],
}
curve_series = {
    "curves.pvd": ["outward_normal", "curve"],
    "curve_points.pvd": ["kind", "traction", "d_function"],
}
if args.curves:
    expected.update(curve_series)

failures = []
for name in curve_series:
    if not args.curves and os.path.exists(os.path.join(args.directory, name)):
        failures.append(f"{name} written by a scene without curves")


def datasets(pvd):
    """The file names a .pvd collection lists, in order."""
    root = ElementTree.parse(pvd).getroot()
    return [d.get("file") for d in root.iter("DataSet")]


for name, arrays in expected.items():
    path = os.path.join(args.directory, name)
    if not os.path.exists(path):
        failures.append(f"{name} missing")
        continue
    files = datasets(path)
    if n_steps is not None and len(files) != n_steps:
        failures.append(f"{name}: {len(files)} steps, expected {n_steps}")
    reader = simple.PVDReader(FileName=path)
    times = reader.TimestepValues
    times = list(times) if hasattr(times, "__len__") else [times]
    if len(times) != len(files):
        failures.append(f"{name}: ParaView sees {len(times)} of "
                        f"{len(files)} steps")
    for time in times:
        reader.UpdatePipeline(time)
        data = simple.servermanager.Fetch(reader)
        block = data.GetBlock(0) if data.IsA("vtkMultiBlockDataSet") else data
        if block is None or block.GetNumberOfPoints() == 0:
            failures.append(f"{name} at t = {time}: no points")
            continue
        point_data = block.GetPointData()
        present = [point_data.GetArrayName(i)
                   for i in range(point_data.GetNumberOfArrays())]
        missing = [a for a in arrays if a not in present]
        if missing:
            failures.append(f"{name} at t = {time}: missing arrays {missing}")
        for i in range(point_data.GetNumberOfArrays()):
            array = point_data.GetArray(i)
            for c in range(array.GetNumberOfComponents()):
                low, high = array.GetRange(c)
                if not (math.isfinite(low) and math.isfinite(high)):
                    failures.append(f"{name} at t = {time}: array "
                                    f"{array.GetName()} is not finite")
    print(f"{name}: {len(times)} steps read")

# The whole collection, every part at the last time.
reader = simple.PVDReader(FileName=os.path.join(args.directory,
                                                "solution.pvd"))
reader.UpdatePipeline(max(reader.TimestepValues)
                      if hasattr(reader.TimestepValues, "__len__")
                      else reader.TimestepValues)
print("solution.pvd: read")

for f in failures:
    print("FAILED:", f)
print("FAILED" if failures else "all series open")
sys.exit(1 if failures else 0)
