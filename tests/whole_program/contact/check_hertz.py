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
L2 error of the pressure. With pressures at the grid lines (the default)
contact-NNNN.csv has a row per crossing of the curve with a grid line, its
pressure the lumped projection int phi_k p ds / int phi_k ds of the
tractions onto the crossing's hat function: they are compared with Hertz's
pressure projected on the same hat functions (weighted by the rows'
lengths), and the half-width is the a whose Hertz profile (same force),
projected alike, fits the rows best. Otherwise (--pressure or --set
"Contact/Pressure=...": per cell, mortar) each row, a touching piece or a
Gauss point, is taken at its pressure over its length against Hertz's, and
Hertz's pressure where no row touches; the half-width is the far end of the
last row that touches (gap <= 0).

With --bsmpm and --prm: runs the scene at the cell sizes of --cells (two
tracking points per cell along the arc) and fails unless at every size the
pressure error is below --max-pressure-error and the half-width within
--max-width-error of a (at the crossings) or within one tracking-point
spacing of a with the error falling from each size to the next (pieces,
Gauss points); with --max-tangent-error, also the contact's tangent against
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


def hertz_profile(P, a):
    p0 = 2 * P / (math.pi * a)
    return lambda x: p0 * math.sqrt(max(0.0, 1 - (x / a) ** 2))


def projected(p, xs, k, n=400):
    """The lumped projection int phi_k p dx / int phi_k dx of p onto the
    hat function of crossing k between its neighbours (mirrored about
    x = 0, the line of symmetry)."""
    lo = xs[k - 1] if k > 0 else -xs[k + 1]
    hi = xs[k + 1] if k + 1 < len(xs) else 2 * xs[k] - xs[k - 1]
    num = den = 0.0
    for lo_, hi_, up in ((lo, xs[k], True), (xs[k], hi, False)):
        for i in range(n):
            x = lo_ + (hi_ - lo_) * (i + 0.5) / n
            w = (x - lo_) / (hi_ - lo_) if up else (hi_ - x) / (hi_ - lo_)
            num += w * p(abs(x)) * (hi_ - lo_) / n
            den += w * (hi_ - lo_) / n
    return num / den


def evaluate_crossings(rows, P, a):
    """Pressures at the grid lines: one row per crossing of the curve with
    a grid line, its pressure the lumped projection of the tractions
    (length W_k = int phi_k ds). Compared with Hertz's pressure projected
    on the same hat functions; the half-width is the a whose Hertz
    profile (same force), so projected, fits the rows best."""
    curves = {}
    for r in rows:
        curves.setdefault(r["curve"], []).append(r)
    arc = max(curves.values(),
              key=lambda c: sum(float(r["pressure"]) * float(r["length"])
                                for r in c))
    arc = sorted((float(r["x"]), float(r["pressure"]), float(r["length"]))
                 for r in arc)
    xs = [x for x, _, _ in arc]

    def misfit(b):
        profile = hertz_profile(P, b)
        return sum(L * (p - projected(profile, xs, k)) ** 2
                   for k, (x, p, L) in enumerate(arc))

    lo, hi = 0.5 * a, 1.5 * a
    g = (math.sqrt(5) - 1) / 2
    for _ in range(40):
        m1, m2 = hi - g * (hi - lo), lo + g * (hi - lo)
        if misfit(m1) < misfit(m2):
            hi = m2
        else:
            lo = m1
    width = (lo + hi) / 2
    profile = hertz_profile(P, a)
    error = norm = 0.0
    for k, (x, p, L) in enumerate(arc):
        exact = projected(profile, xs, k)
        error += L * (p - exact) ** 2
        norm += L * exact ** 2
    touching = sum(1 for _, p, _ in arc if p > 0)
    return width, math.sqrt(error / norm), f"{touching} crossings press"


def evaluate_pieces(rows, P, a):
    """One row per touching piece (one pressure per cell) or Gauss point
    (mortar pressures), taken at its pressure over its length against
    Hertz's, and Hertz's pressure where no row touches; the half-width is
    the far end of the last row that touches (gap <= 0)."""
    hertz = hertz_profile(P, a)
    pieces = [(float(r["x"]), float(r["pressure"]), float(r["length"]))
              for r in rows]
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
    return width, math.sqrt(error / norm), f"{len(pieces)} pieces"


def evaluate(directory, R, E, nu, crossings):
    with open(os.path.join(directory, "summary.json")) as f:
        summary = json.load(f)
    last = summary["steps"][-1]["quantities"]
    P = 2 * abs(last["rigid_body_1_force_y"])
    a = math.sqrt(4 * P * R * (1 - nu**2) / (math.pi * E))
    p0 = 2 * P / (math.pi * a)
    files = sorted(glob.glob(os.path.join(directory, "contact-*.csv")))
    rows = [r for r in csv.DictReader(open(files[-1])) if r["body"] == "1"]
    width, error, what = (evaluate_crossings if crossings else
                          evaluate_pieces)(rows, P, a)
    print(f"P = {P:.6g} N/m, a_Hertz = {a:.6g}, p0 = {p0:.6g}; "
          f"contact half-width {width:.6g} ({what}), "
          f"error {width - a:+.3g} ({(width - a) / a:+.2%}); "
          f"pressure L2 error {error:.3g}")
    return width, a, error, last


parser = argparse.ArgumentParser(description=__doc__)
parser.add_argument("directory", nargs="?")
parser.add_argument("--bsmpm")
parser.add_argument("--prm")
parser.add_argument("--np", type=int, default=1)
parser.add_argument("--cells", type=int, nargs="+", default=[32, 64],
                    help="cells per unit length (1/h) of the runs")
parser.add_argument("--max-pressure-error", type=float, default=0.2)
parser.add_argument("--max-tangent-error", type=float)
parser.add_argument("--max-width-error", type=float, default=0.02,
                    help="pressures at the grid lines: the half-width's "
                    "allowed relative error")
parser.add_argument("--set", action="append", default=[],
                    help="a further --set of the runs")
parser.add_argument("--radius", type=float, default=1.0)
parser.add_argument("--youngs-modulus", type=float, default=1e6)
parser.add_argument("--poissons-ratio", type=float, default=0.3)
parser.add_argument("--pressure", default="at grid lines",
                    help="the run's Contact/Pressure (with a directory)")
args = parser.parse_args()
R, E, nu = args.radius, args.youngs_modulus, args.poissons_ratio
pressure = args.pressure
for setting in args.set:
    key, _, value = setting.partition("=")
    if key.strip() == "Contact/Pressure":
        pressure = value.strip()
crossings = pressure in ("at grid lines", "automatic")

if args.directory:
    evaluate(args.directory, R, E, nu, crossings)
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
        width, a, error, last = evaluate(directory, R, E, nu, crossings)
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
    if crossings and abs(width - a) > args.max_width_error * a:
        problems.append(f"h = 1/{cells}: half-width off by more than "
                        f"{args.max_width_error:.1%}")
    if not crossings and abs(width - a) > spacing:
        problems.append(f"h = 1/{cells}: half-width off by more than the "
                        f"tracking-point spacing {spacing:.4g}")
    if error > args.max_pressure_error:
        problems.append(f"h = 1/{cells}: pressure error {error:.3g} above "
                        f"{args.max_pressure_error}")
# Piece by piece the error includes the contact's edge, which refinement
# resolves; at the crossings both sides are projected alike, and what is
# left is the pressures' alternation (doc/contact.md), which need not fall.
for coarse, fine in zip(errors, errors[1:]):
    if not crossings and not fine < coarse:
        problems.append(f"the pressure error does not fall: {errors}")
for p in problems:
    print("FAIL:", p)
sys.exit(1 if problems else 0)
