#!/usr/bin/env python3
"""The face of an excavation as a boundary curve (doc/stages.md,
"Excavation"): the column of prm/column-excavated.prm, ground at rest (K0)
with a free closed curve round it, whose top is excavated down to a height
H'. The column below heaves by rho g d y / M at height y (d = 8 - H', M the
constrained modulus) and carries -rho g (H' - y).

1. Small strain, the face at several heights, on grid lines and inside
   cells: the probe's heave and vertical stress to round-off.
2. Finite strain (the same curve): within --finite-tolerance of them.
3. Released over 4 steps (small strain, the face inside a cell): the
   first step heaves a quarter of the whole to round-off (the rest starts
   in balance, the cut cells along the new face included).
4. A tunnel (a B-spline circle of radius 0.3 m inside the column): a new
   closed curve round the hole, the area removed the circle's within 1e-3
   at h = 0.125. Resumed from the checkpoint after it (finite strain, the
   top excavated next), the run ends where the run left alone ends, to the
   last digit.
5. A round pit (Excavation edge = B-spline through 12 points on a circle
   of radius 0.4 m centred on the column's top): the area removed is the
   half disc's within 3e-3 at h = 0.125 and 1e-3 at h = 0.0625.
6. Refused, naming the parameter: a region that reaches into the body
   between two points of the curve, a region through the column's middle
   (it would cross the curve twice), and a region that takes a stretch of
   a curve with a condition that would then hold on the face.
"""
import argparse
import math
import os
import pathlib
import sys
import tempfile

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[2]))
from bsmpm_run import check_relative, run  # noqa: E402  (tests/bsmpm_run.py)

parser = argparse.ArgumentParser(description=__doc__)
parser.add_argument("--bsmpm", required=True)
parser.add_argument("--prm", required=True)
parser.add_argument("--np", type=int, default=1)
parser.add_argument("--heights", default="7.9,6.7,6.5,6.33,3.3")
parser.add_argument("--finite-tolerance", type=float, default=0.01)
parser.add_argument("--parts", default="1,2,3,4,5,6")
args = parser.parse_args()
parts = {int(p) for p in args.parts.split(",")}

g, H, y_probe = 9.81, 8.0, 2.5
E, nu, rho = 1e7, 0.3, 2000.0
M = E * (1 - nu) / ((1 + nu) * (1 - 2 * nu))
problems = []


def region(top):
    return f"Stages/Stage 2/Excavation=-1, {top}; 2, {top}; 2, 11; -1, 11"


def check(what, value, expected, tolerance):
    check_relative(problems, what, value, expected, tolerance)


def column(top, settings=(), tolerance=1e-10, label="small strain"):
    summary = run(args.bsmpm, args.prm, args.np,
                  [region(top)] + list(settings))
    q = summary["quantities"]
    heave = rho * g * (H - top) * y_probe / M
    check(f"{label}, face at {top} m: heave at y = {y_probe}",
          q["probe_displacement_y"], heave, tolerance)
    check(f"{label}, face at {top} m: sigma_yy at y = {y_probe}",
          q["probe_stress_yy"], -rho * g * (top - y_probe), tolerance)
    if q.get("curve1_points_inserted", 0) == 0:
        problems.append(f"{label}, face at {top} m: no point of the face "
                        "joined the curve")


if 1 in parts:
    for top in [float(t) for t in args.heights.split(",")]:
        column(top)
if 2 in parts:
    column(6.7, ["Material/Kinematics=finite strain"], args.finite_tolerance,
           "finite strain")
if 3 in parts:
    summary = run(args.bsmpm, args.prm, args.np,
                  [region(6.7), "Stages/Stage 2/Load steps=4"])
    first = summary["steps"][1]["quantities"]["probe_displacement_y"]
    check("4 steps: heave after the first", first,
          rho * g * (H - 6.7) * y_probe / M / 4, 1e-10)
if 4 in parts:
    tunnel = "; ".join(f"{0.5 + 0.3 * math.cos(math.pi * i / 6):.12g}, "
                       f"{4 + 0.3 * math.sin(math.pi * i / 6):.12g}"
                       for i in range(12))
    summary = run(args.bsmpm, args.prm, args.np, [
        "Background grid/Cell size=0.125",
        f"Stages/Stage 2/Excavation={tunnel}",
        "Stages/Stage 2/Excavation edge=B-spline"])
    check("tunnel, h = 0.125: area removed",
          1.0 * H - summary["quantities"]["body_area"],
          math.pi * 0.3 ** 2, 1e-3)
    if summary["quantities"].get("curve2_points", 0) < 8:
        problems.append("tunnel: no curve round the hole")
    with tempfile.TemporaryDirectory() as directory:
        settings = ["Material/Kinematics=finite strain",
                    "Stages/Number of stages=3",
                    f"Stages/Stage 2/Excavation={tunnel}",
                    "Stages/Stage 2/Excavation edge=B-spline",
                    "Stages/Stage 3/Load steps=2",
                    "Stages/Stage 3/Load factor=0",
                    "Stages/Stage 3/" + region(6.7).split("/", 2)[2],
                    "Output/Checkpoint interval=1"]
        whole = run(args.bsmpm, args.prm, args.np, settings,
                    directory=directory)
        resumed = run(args.bsmpm, None, args.np, directory=directory,
                      arguments=["--resume",
                                 os.path.join(directory, "checkpoint-2")])
        same = (whole["quantities"] == resumed["quantities"] and
                whole["errors"] == resumed["errors"])
        print(f"resumed after the tunnel: "
              f"{'the same end' if same else 'a different end'}")
        if not same:
            problems.append("resumed after the tunnel: a different end")
if 5 in parts:
    circle = "; ".join(f"{0.5 + 0.4 * math.cos(math.pi * i / 6):.12g}, "
                       f"{H + 0.4 * math.sin(math.pi * i / 6):.12g}"
                       for i in range(12))
    for h, tolerance in ((0.125, 3e-3), (0.0625, 1e-3)):
        summary = run(args.bsmpm, args.prm, args.np, [
            f"Background grid/Cell size={h}",
            f"Stages/Stage 2/Excavation={circle}",
            "Stages/Stage 2/Excavation edge=B-spline"])
        check(f"round pit, h = {h}: area removed",
              1.0 * H - summary["quantities"]["body_area"],
              math.pi * 0.4 ** 2 / 2, tolerance)
if 6 in parts:
    refusals = [
        ("a notch between two points", ["Stages/Stage 2/Excavation=-0.1, "
                                        "3.2; 0.3, 3.2; 0.3, 3.6; -0.1, 3.6"],
         "between two points"),
        ("a slice through the middle", ["Stages/Stage 2/Excavation=-1, 3; "
                                        "2, 3; 2, 4; -1, 4"],
         "more than once"),
        ("a loaded stretch", ["Boundary curves/Curve 1/Condition=pressure "
                              "1000", region(6.7)], "would then hold"),
    ]
    for what, settings, text in refusals:
        summary, result = run(args.bsmpm, args.prm, args.np, settings,
                              output=True, check=False)
        message = result.stderr.strip().splitlines()[-1:] or [""]
        print(f"{what}: exit {result.returncode}, {message[0][:200]}")
        if result.returncode != 1 or text not in result.stderr or \
                "Stages/Stage 2/Excavation" not in result.stderr:
            problems.append(f"{what}: not refused with '{text}'")

if problems:
    print("FAILED:", "; ".join(problems))
    sys.exit(1)
print("OK")
