#!/usr/bin/env python3
"""Hertz's line contact of an elastic disc on a rigid flat (plane strain).

Reads the last contact-NNNN.csv and summary.json of a run of
prm/hertz-disc.prm (a quarter disc of radius R, symmetric about x = 0 and
about its horizontal diameter, pressed by a rigid flat): the force per unit
length on the whole disc is P = 2 |F_y| (two quarters make the lower half,
whose reaction the flat carries), and Hertz's half-width and pressure are

    a = sqrt(4 P R (1 - nu^2) / (pi E)),
    p(x) = 2 P / (pi a^2) sqrt(a^2 - x^2).

Prints the contact half-width against a, and the relative L2 error of the
pressure of the contact pieces (constant on each) over the pieces and the
Hertz zone; with --max-width-error and --max-pressure-error, exits 1 if
they are exceeded.
"""
import argparse
import csv
import glob
import json
import math
import os
import sys

parser = argparse.ArgumentParser()
parser.add_argument("directory")
parser.add_argument("--radius", type=float, default=1.0)
parser.add_argument("--youngs-modulus", type=float, default=1e6)
parser.add_argument("--poissons-ratio", type=float, default=0.3)
parser.add_argument("--max-width-error", type=float)
parser.add_argument("--max-pressure-error", type=float)
args = parser.parse_args()

with open(os.path.join(args.directory, "summary.json")) as f:
    summary = json.load(f)
last = summary["steps"][-1]["quantities"]
P = 2 * abs(last["rigid_body_1_force_y"])
E, nu, R = args.youngs_modulus, args.poissons_ratio, args.radius
a = math.sqrt(4 * P * R * (1 - nu**2) / (math.pi * E))
p0 = 2 * P / (math.pi * a)

files = sorted(glob.glob(os.path.join(args.directory, "contact-*.csv")))
rows = [r for r in csv.DictReader(open(files[-1])) if r["body"] == "1"]
pieces = [(float(r["x"]), float(r["pressure"]), float(r["length"]))
          for r in rows]
# Half-width: the far end of the last piece in contact.
width = max(x + L / 2 for x, p, L in pieces)


def hertz(x):
    return p0 * math.sqrt(max(0.0, 1 - (x / a) ** 2))


error = sum(L * (p - hertz(x)) ** 2 for x, p, L in pieces)
norm = sum(L * hertz(x) ** 2 for x, p, L in pieces)
# Where Hertz has pressure but no piece touches.
covered = width
if covered < a:
    n = 200
    for i in range(n):
        x = covered + (a - covered) * (i + 0.5) / n
        error += (a - covered) / n * hertz(x) ** 2
        norm += (a - covered) / n * hertz(x) ** 2
relative = math.sqrt(error / norm)
print(f"P = {P:.6g} N/m, a_Hertz = {a:.6g}, p0 = {p0:.6g}")
print(f"contact half-width {width:.6g} ({len(pieces)} pieces), "
      f"error {width - a:+.3g} ({(width - a) / a:+.2%})")
print(f"pressure L2 error {relative:.3g}")
ok = True
if args.max_width_error is not None and abs(width - a) > args.max_width_error:
    print(f"FAIL: half-width error above {args.max_width_error}")
    ok = False
if args.max_pressure_error is not None and relative > args.max_pressure_error:
    print(f"FAIL: pressure error above {args.max_pressure_error}")
    ok = False
sys.exit(0 if ok else 1)
