"""Opens a run's ParaView files with ParaView's own readers (pvpython) and
checks that every series loads, has the expected arrays and is not empty.

Usage: pvpython open_output.py <output directory>
"""
import os
import sys

from paraview import simple

directory = sys.argv[1]
expected = {
    "points.pvd": ["volume", "stress_xx", "displacement", "d_function"],
    "grid.pvd": ["displacement_increment"],
    "curves.pvd": ["outward_normal", "curve"],
    "curve_points.pvd": ["kind", "traction", "d_function"],
}
failed = False
for name, arrays in expected.items():
    reader = simple.PVDReader(FileName=os.path.join(directory, name))
    times = reader.TimestepValues
    n_steps = len(times) if hasattr(times, "__len__") else 1
    for time in (times if hasattr(times, "__len__") else [times]):
        reader.UpdatePipeline(time)
        data = simple.servermanager.Fetch(reader)
        block = data.GetBlock(0) if data.IsA("vtkMultiBlockDataSet") else data
        n_points = block.GetNumberOfPoints()
        present = [block.GetPointData().GetArrayName(i)
                   for i in range(block.GetPointData().GetNumberOfArrays())]
        missing = [a for a in arrays if a not in present]
        if n_points == 0 or missing:
            print(f"{name} at t = {time}: {n_points} points, missing {missing}")
            failed = True
    print(f"{name}: {n_steps} steps read")

reader = simple.PVDReader(FileName=os.path.join(directory, "solution.pvd"))
reader.UpdatePipeline()
print("solution.pvd: read")
print("FAILED" if failed else "all series open")
sys.exit(1 if failed else 0)
