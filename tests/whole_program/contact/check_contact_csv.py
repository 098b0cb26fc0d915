#!/usr/bin/env python3
"""The contact tractions along the curves (contact-NNNN.csv) after every
load step with ParaView output off (Output/Interval = 0): the block of
block_on_plane.prm on the plane inclined by tan(theta) = 0.2, two load
steps, partly sliding at the ends of its base.

Checks for each step: the file exists (and no ParaView file does); each
row names body 1 and the block's Curve 1; the rows' tractions sum to the
force on the rigid body that summary.json records, F = -sum (p_N n + t_T t)
length with t = (-n_y, n_x), to 1e-9 of it; the rows that slide add up to
its sliding length (sliding_length) and all rows to its contact length.

Usage: check_contact_csv.py --bsmpm B --prm block_on_plane.prm [--np N]
"""
import argparse
import csv
import math
import os
import pathlib
import sys
import tempfile

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[2]))
from bsmpm_run import run  # noqa: E402  (tests/bsmpm_run.py)

parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
parser.add_argument("--bsmpm", required=True)
parser.add_argument("--prm", required=True)
parser.add_argument("--np", type=int, default=1)
args = parser.parse_args()
problems = []

COLUMNS = ["body", "curve", "x", "y", "normal_x", "normal_y", "gap",
           "pressure", "tangential_traction", "length", "sliding",
           "sliding_length"]

with tempfile.TemporaryDirectory() as directory:
    summary = run(args.bsmpm, args.prm, args.np,
                  ["Output/Interval=0", "Output/Timing summary=false"],
                  directory)
    paraview = [f for f in os.listdir(directory)
                if f.endswith((".vtu", ".pvtu", ".pvd"))]
    if paraview:
        problems.append(f"ParaView files with Output/Interval = 0: "
                        f"{paraview[:3]}")
    for step in summary["steps"]:
        q = step["quantities"]
        name = f"contact-{step['step']:04d}.csv"
        path = os.path.join(directory, name)
        if not os.path.isfile(path):
            problems.append(f"no {name}")
            continue
        with open(path) as f:
            reader = csv.DictReader(f)
            if reader.fieldnames != COLUMNS:
                problems.append(f"{name}: columns {reader.fieldnames}")
                continue
            rows = [{k: float(v) for k, v in r.items()} for r in reader]
        if not rows or any(r["body"] != 1 or r["curve"] != 1 for r in rows):
            problems.append(f"{name}: no rows, or rows of another body or "
                            f"curve")
            continue
        force = [0.0, 0.0]
        for r in rows:
            n = (r["normal_x"], r["normal_y"])
            t = (-n[1], n[0])
            for d in range(2):
                force[d] -= (r["pressure"] * n[d] +
                             r["tangential_traction"] * t[d]) * r["length"]
        recorded = (q["rigid_body_1_force_x"], q["rigid_body_1_force_y"])
        error = math.hypot(force[0] - recorded[0], force[1] - recorded[1]) / \
            math.hypot(*recorded)
        contact = sum(r["length"] for r in rows)
        sliding = sum(r["sliding_length"] for r in rows)
        print(f"step {step['step']}: {len(rows)} rows, force from the rows "
              f"({force[0]:.10g}, {force[1]:.10g}) N/m, recorded "
              f"({recorded[0]:.10g}, {recorded[1]:.10g}): relative difference "
              f"{error:.2e}; contact {contact:.6g} m, sliding {sliding:.6g} m")
        if error > 1e-9:
            problems.append(f"{name}: the rows' force differs from "
                            f"summary.json's by {error:.2e}")
        if abs(contact - q["rigid_body_1_contact_length"]) > 1e-9 or \
                abs(sliding - q["rigid_body_1_sliding_length"]) > 1e-9:
            problems.append(f"{name}: the rows' lengths are not summary.json's")
        if sliding == 0:
            problems.append(f"{name}: nothing slides (partial slip expected)")

for p in problems:
    print("FAIL:", p)
sys.exit(1 if problems else 0)
