#!/usr/bin/env python3
"""A smooth rigid wall moved away from a clay face under gravity
(wall_moved_away.prm): the run must complete with every load step at most
--max-iterations Newton iterations (augmented Lagrangian solves included);
after the last step the clay must touch the wall along one contiguous
stretch of the face (the rows of contact-NNNN.csv, a piece of curve each,
at most 1.5 --cell-size apart along it), from near its foot up to below its top (the top has
left the wall), the force on the wall must push it away from the clay
(F_x > 0), and no pressure may exceed --max-pressure (a spike on a short
piece).

Usage: check_wall.py --bsmpm B --prm wall_moved_away.prm [--set ...]
"""
import argparse
import csv
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
parser.add_argument("--cell-size", type=float, default=0.5)
parser.add_argument("--max-iterations", type=int, default=60)
parser.add_argument("--max-pressure", type=float, default=180.)
parser.add_argument("--set", action="append", default=[])
args = parser.parse_args()
problems = []

with tempfile.TemporaryDirectory() as directory:
    summary = run(args.bsmpm, args.prm, args.np,
                  ["Output/Timing summary=false"] + args.set, directory)
    steps = summary["steps"]
    last = steps[-1]
    with open(os.path.join(directory,
                           f"contact-{last['step']:04d}.csv")) as f:
        rows = [{k: float(v) for k, v in r.items()} for r in csv.DictReader(f)]

iterations = [len(s["newton_residuals"]) for s in steps]
print("Newton iterations per step:", iterations)
if len(steps) != 20:
    problems.append(f"{len(steps)} load steps, not 20")
if max(iterations) > args.max_iterations:
    problems.append(f"a step took {max(iterations)} Newton iterations "
                    f"(at most {args.max_iterations})")

q = last["quantities"]
force = q["rigid_body_1_force_x"]
# The face is vertical: a row is a piece of it, about a cell high, and
# its touching part spans about its length in y.
rows.sort(key=lambda r: r["y"])
spans = [(r["y"] - r["length"] / 2, r["y"] + r["length"] / 2) for r in rows]
gaps = [b["y"] - a["y"] for a, b in zip(rows, rows[1:])]
print(f"wall moved {q['rigid_body_1_displacement_x']:.3f} m: force "
      f"{force:.2f} kN/m, contact length {q['rigid_body_1_contact_length']:.3f}"
      f" m in {len(rows)} rows from y = {spans[0][0]:.3f} to "
      f"{spans[-1][1]:.3f} m, rows up to {max(gaps, default=0):.3f} m apart, "
      f"largest pressure {max(r['pressure'] for r in rows):.1f} kPa")
if force <= 0:
    problems.append("the clay does not push the wall")
if max(gaps, default=0) > 1.5 * args.cell_size:
    problems.append("the touching part is not one stretch")
if spans[0][0] > 1.0 or spans[-1][1] > 4.5:
    problems.append("the touching stretch is not the lower part of the face")
if max(r["pressure"] for r in rows) > args.max_pressure:
    problems.append("a pressure spike")

for p in problems:
    print("FAIL:", p)
sys.exit(1 if problems else 0)
