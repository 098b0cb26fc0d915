#!/usr/bin/env python3
"""Hertz's line contact of an elastic disc on a rigid flat (plane strain).

A run of prm/hertz-disc.prm (a quarter disc of radius R, symmetric about
x = 0 and about its horizontal diameter, pressed by a rigid flat) gives the
force on the flat per unit length of the quarter; the whole disc carries
P = 2 |F_y| (two quarters make the lower half, whose reaction the flat
carries), and Hertz's half-width and pressure are

    a = sqrt(4 P R (1 - nu^2) / (pi E)),
    p(x) = 2 P / (pi a^2) sqrt(a^2 - x^2).

With a directory: prints the contact half-width against a and the relative
L2 error of the pressure (each row of contact-NNNN.csv, a touching piece or,
with mortar pressures, a Gauss point, taken at its pressure over its
length, against Hertz's, and Hertz's pressure where no row touches). The
half-width is the far end of the last row that touches (gap <= 0): with
mortar pressures the pressure, linear between the crossings, reaches past
the touching points to the next crossing.

With --bsmpm and --prm: runs the scene at the cell sizes of --cells (two
tracking points per cell along the arc) and fails unless at every size the
half-width is within one tracking-point spacing of a and the pressure error
below --max-pressure-error, and the pressure error falls from each size to
the next; with --max-tangent-error, also the contact's tangent against
central differences (Contact/Check tangent) at every Newton iteration.
"""
import argparse
import csv
import glob
import json
import math
import os
import pathlib
import sys
import tempfile

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[2]))
from bsmpm_run import run  # noqa: E402  (tests/bsmpm_run.py)


def evaluate(directory, R, E, nu):
    with open(os.path.join(directory, "summary.json")) as f:
        summary = json.load(f)
    last = summary["steps"][-1]["quantities"]
    P = 2 * abs(last["rigid_body_1_force_y"])
    a = math.sqrt(4 * P * R * (1 - nu**2) / (math.pi * E))
    p0 = 2 * P / (math.pi * a)

    def hertz(x):
        return p0 * math.sqrt(max(0.0, 1 - (x / a) ** 2))

    files = sorted(glob.glob(os.path.join(directory, "contact-*.csv")))
    rows = [r for r in csv.DictReader(open(files[-1])) if r["body"] == "1"]
    pieces = [(float(r["x"]), float(r["pressure"]), float(r["length"]))
              for r in rows]
    # Half-width: the far end of the last row that touches.
    width = max(float(r["x"]) + float(r["length"]) / 2 for r in rows
                if float(r["gap"]) <= 1e-9)
    n = 200
    error = 0.0
    for x, p, L in pieces:
        for i in range(n):
            error += L / n * (p - hertz(x - L / 2 + L * (i + 0.5) / n)) ** 2
    reach = max(x + L / 2 for x, p, L in pieces)
    if reach < a:
        for i in range(n):
            error += (a - reach) / n * hertz(
                reach + (a - reach) * (i + 0.5) / n) ** 2
    norm = sum(a / n * hertz(a * (i + 0.5) / n) ** 2 for i in range(n))
    print(f"P = {P:.6g} N/m, a_Hertz = {a:.6g}, p0 = {p0:.6g}; "
          f"contact half-width {width:.6g} ({len(pieces)} pieces), "
          f"error {width - a:+.3g} ({(width - a) / a:+.2%}); "
          f"pressure L2 error {math.sqrt(error / norm):.3g}")
    return width, a, math.sqrt(error / norm), last


parser = argparse.ArgumentParser(description=__doc__)
parser.add_argument("directory", nargs="?")
parser.add_argument("--bsmpm")
parser.add_argument("--prm")
parser.add_argument("--np", type=int, default=1)
parser.add_argument("--cells", type=int, nargs="+", default=[32, 64],
                    help="cells per unit length (1/h) of the runs")
parser.add_argument("--max-pressure-error", type=float, default=0.2)
parser.add_argument("--max-tangent-error", type=float)
parser.add_argument("--set", action="append", default=[],
                    help="a further --set of the runs")
parser.add_argument("--radius", type=float, default=1.0)
parser.add_argument("--youngs-modulus", type=float, default=1e6)
parser.add_argument("--poissons-ratio", type=float, default=0.3)
args = parser.parse_args()
R, E, nu = args.radius, args.youngs_modulus, args.poissons_ratio

if args.directory:
    evaluate(args.directory, R, E, nu)
    sys.exit(0)

problems = []
errors = []
for cells in args.cells:
    # Two tracking points per cell along the arc (as the scene: 101 at
    # h = 1/32).
    n_points = 1 + 100 * cells // 32
    spacing = math.pi / 2 * R / (n_points - 1)
    with tempfile.TemporaryDirectory() as directory:
        check = ([] if args.max_tangent_error is None
                 else ["Contact/Check tangent=true"])
        run(args.bsmpm, args.prm, args.np,
            [f"Background grid/Cell size={1 / cells}",
             f"Boundary curves/Curve 1/Number of points={n_points}"]
            + check + args.set,
            directory)
        print(f"h = 1/{cells}, {n_points} points along the arc: ", end="")
        width, a, error, last = evaluate(directory, R, E, nu)
    if args.max_tangent_error is not None:
        tangent = last.get("contact_tangent_error", float("inf"))
        checks = last.get("contact_tangent_checks", 0)
        print(f"  tangent against central differences: {tangent:.3g} "
              f"({int(checks)} checks)")
        if not (checks > 0 and tangent <= args.max_tangent_error):
            problems.append(f"h = 1/{cells}: tangent error {tangent} "
                            f"({checks} checks) above "
                            f"{args.max_tangent_error}")
    errors.append(error)
    if abs(width - a) > spacing:
        problems.append(f"h = 1/{cells}: half-width off by more than the "
                        f"tracking-point spacing {spacing:.4g}")
    if error > args.max_pressure_error:
        problems.append(f"h = 1/{cells}: pressure error {error:.3g} above "
                        f"{args.max_pressure_error}")
for coarse, fine in zip(errors, errors[1:]):
    if not fine < coarse:
        problems.append(f"the pressure error does not fall: {errors}")
for p in problems:
    print("FAIL:", p)
sys.exit(1 if problems else 0)
