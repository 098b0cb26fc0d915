#!/usr/bin/env python3
"""Rigid bodies given as closed B-splines (Shape = spline) against the
same outlines given exactly, on tests/whole_program/contact/cylinder_on_block.prm.

1. A flat punch: the spline through the corners of a rectangle and the
   midpoints of its edges is the rectangle (straight on both sides of each
   corner, so the corners are kept sharp and the edges stay straight): its
   force must equal the polygon's to --exact-tolerance.
2. A cylinder: splines through 12, 24 and 48 points on the circle must
   come closer to the circle's force as the points get denser, the densest
   within --curved-tolerance of it.
3. --np 2: the spline cylinder's force must equal the serial one.
"""
import argparse
import math
import pathlib
import sys

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[2]))
from bsmpm_run import run  # noqa: E402  (tests/bsmpm_run.py)

parser = argparse.ArgumentParser(description=__doc__)
parser.add_argument("--bsmpm", required=True)
parser.add_argument("--prm", required=True)
parser.add_argument("--np", type=int, default=1)
parser.add_argument("--exact-tolerance", type=float, default=1e-9)
parser.add_argument("--curved-tolerance", type=float, default=1e-4)
args = parser.parse_args()
problems = []


def force(settings, np=1):
    steps = run(args.bsmpm, args.prm, np, settings)["steps"]
    return [s["quantities"]["rigid_body_1_force_y"] for s in steps]


def points(list_of_xy):
    return "; ".join(f"{x:.17g}, {y:.17g}" for x, y in list_of_xy)


def relative(a, b):
    return max(abs(x - y) for x, y in zip(a, b)) / max(abs(y) for y in b)


# 1. Flat punch 0.3 m wide (half of it, on the symmetry line), 5 mm in.
corners = [(-1, 0.5), (0.3, 0.5), (0.3, 1.0), (-1, 1.0)]
punch = ["Rigid body 1/Displacement=0; -0.005*t"]
polygon = force(punch + ["Rigid body 1/Shape=polygon",
                         f"Rigid body 1/Vertices={points(corners)}"])
with_midpoints = []
for k, c in enumerate(corners):
    d = corners[(k + 1) % 4]
    with_midpoints += [c, ((c[0] + d[0]) / 2, (c[1] + d[1]) / 2)]
spline = force(punch + ["Rigid body 1/Shape=spline",
                        f"Rigid body 1/Vertices={points(with_midpoints)}"])
difference = relative(spline, polygon)
print(f"flat punch: polygon {polygon[-1]:.10g}, spline {spline[-1]:.10g} "
      f"N/m, relative difference {difference:.2e}")
if difference > args.exact_tolerance:
    problems.append(f"the spline punch differs from the polygon by "
                    f"{difference:.2e}")

# 2. The cylinder (the scene's circle) against splines through points on it.
circle = force([])
differences = []
for n in [12, 24, 48]:
    on_circle = [(0.5 * math.cos(2 * math.pi * i / n),
                  1 + 0.5 * math.sin(2 * math.pi * i / n)) for i in range(n)]
    settings = ["Rigid body 1/Shape=spline",
                f"Rigid body 1/Vertices={points(on_circle)}"]
    spline = force(settings)
    differences.append(relative(spline, circle))
    print(f"cylinder: circle {circle[-1]:.10g}, spline through {n} points "
          f"{spline[-1]:.10g} N/m, relative difference {differences[-1]:.2e}")
    if n == 48 and args.np > 1:
        parallel = force(settings, args.np)
        d = relative(parallel, spline)
        print(f"  np = {args.np}: {parallel[-1]:.10g} N/m, relative "
              f"difference to np = 1 {d:.2e}")
        if d > 1e-8:
            problems.append(f"np = {args.np} differs from np = 1 by {d:.2e}")
for coarse, fine in zip(differences, differences[1:]):
    if not fine < coarse:
        problems.append(f"denser splines do not come closer: {differences}")
if differences[-1] > args.curved_tolerance:
    problems.append(f"the spline through 48 points is {differences[-1]:.2e} "
                    f"off the circle")
for p in problems:
    print("FAIL:", p)
sys.exit(1 if problems else 0)
