#!/usr/bin/env python3
"""Constant-stress patch tests on a rotated square, whatever the point layout.

A 100 mm square rotated by 0, 15, 30, 45 and 60 degrees on a grid of 10 mm
cells, its boundary four B-splines through tracking points, in two load
steps (the second one integrates the stresses of the first), for every
layout a user would pick (per cell 1..8, a lattice, cell centroids):

  (a) pressure 8 kPa on one side, rollers on the other three (the lower left
      corner of the square stays put);
  (b) a linear displacement field imposed on the whole boundary;
  (c) rollers on two adjacent sides (bottom, left) and a prescribed normal
      displacement on the other two (`normal displacement <un>` on the
      right, un an expression of x, y: the normal component u . n of a
      uniform strain with the square's own axes as principal directions,
      outward normal; `normal displacement exact` on the top): the
      tangential components are free on all four sides. Three layouts
      (per cell 2, lattice, cell centroid): the cases above cover the
      others.

The layouts of a case and angle run in one or two bsmpm processes, with
--sweep over the layout or the points per cell (each run a scene of its
own, in its own output directory): a Debug process takes about as long to
start as this small scene to run.

The supports by the implicit boundary method (delta/h = 1e-6, or with
--band default the default band of 1e-2: the consistent formulation is
exact whatever the band, corners of two displacement supports included) or
by Nitsche's method. The exact stress is constant, so the discrete one must be
too, up to round-off times the condition number: every relative stress error
R_sigma_* <= 1e-8 (implicit boundary) or <= 1e-10 (Nitsche). The cut cells
make this hold: their stiffness takes the exact moments of the part of the
cell inside the square, their stresses are integrated by fitted weights.

Usage: patch_tests.py --bsmpm BSMPM --method ibm|nitsche [--angles ...]
       [--all-layouts CASES] [--full-angle A] [--band default|WIDTH]
"""

import argparse
import json
import math
import os
import pathlib
import shutil
import sys
import tempfile

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[2]))
from bsmpm_run import run  # noqa: E402  (tests/bsmpm_run.py)

E, NU, P = 1e6, 0.25, 8000.0


def scene(angle, layout, case, method, directory, band="1e-6"):
    """The parameter file of one patch test."""
    a = math.radians(angle)
    cx = cy = 0.075

    def corner(x, y):
        return (cx + math.cos(a) * x - math.sin(a) * y,
                cy + math.sin(a) * x + math.cos(a) * y)

    lower_left = corner(-0.05, -0.05)
    cos_a, sin_a = math.cos(a), math.sin(a)
    if case == "pressure":
        # Rollers on three sides: strain only along the square's own y.
        stress = (-NU / (1 - NU) * P, -P, 0.0)
        conditions = {"top": "pressure 8000", "bottom": "roller",
                      "right": "roller", "left": "roller"}
    elif case == "normal":
        # Principal stresses along the square's axes (rollers carry no
        # shear). On the right side (outward normal (cos a, sin a)),
        # u . n = eps_xx (x' - x'_0) with x' the coordinate along the
        # square's x axis and x'_0 that of the fixed lower left corner: an
        # expression of the current position, as the exact solution is
        # (a constant would strain the second load step's longer square
        # less).
        stress = (-3000.0, 5000.0, 0.0)
        eps_xx = (1 + NU) / E * ((1 - NU) * stress[0] - NU * stress[1])
        un = (f"{eps_xx!r} * ((x - {lower_left[0]!r}) * {cos_a!r} + "
              f"(y - {lower_left[1]!r}) * {sin_a!r})")
        conditions = {"bottom": "roller", "left": "roller",
                      "right": f"normal displacement {un}",
                      "top": "normal displacement exact"}
    else:
        stress = (-3000.0, 5000.0, 2000.0)
        conditions = {side: "displacement exact"
                      for side in ("top", "bottom", "right", "left")}
    dirichlet = "nitsche" if method == "nitsche" else "implicit boundary"

    lines = [
        "set Scene name = patch",
        "subsection Background grid",
        "  set Lower left corner  = 0, 0",
        "  set Upper right corner = 0.15, 0.15",
        "  set Cells per direction = 15, 15",
        "end",
        "subsection Material",
        f"  set Young's modulus = {E}",
        f"  set Poisson's ratio = {NU}",
        "  set Model = plane strain",
        "end",
        "subsection Loading",
        "  set Load steps = 2",
        "end",
        "subsection Body region",
        "  set Shape = rotated rectangle",
        f"  set Center = {cx}, {cy}",
        "  set Width = 0.1",
        "  set Height = 0.1",
        f"  set Angle = {angle}",
        "end",
        "subsection Material points",
    ]
    # Every layout's own parameter is set, so that a --sweep of the layout
    # or of the points per cell gives each run the scene it would have alone.
    kind, n = layout.split()[0], layout.split()[-1]
    lines += [f"  set Layout = {'per cell' if kind == 'per' else layout}",
              f"  set Points per cell = {n if kind == 'per' else 2}",
              "  set Lattice points = 37, 37"]
    lines += ["end", "subsection Boundary curves"]
    for k, side in enumerate(("bottom", "right", "top", "left")):
        lines += [f"  subsection Curve {k + 1}",
                  "    set Points = region edge",
                  f"    set Edge = {side}",
                  "    set Number of points = 11",
                  f"    set Condition = {conditions[side]}",
                  f"    set Dirichlet method = {dirichlet}",
                  "  end"]
    lines += [
        "end",
    ]
    if band != "default":
        lines += ["subsection Implicit boundary",
                  f"  set Relative band width = {band}",
                  "end"]
    lines += [
        "subsection Exact solution",
        "  set Name = constant stress",
        "  subsection Constant stress",
        f"    set Stress = {stress[0]!r}, {stress[1]!r}, {stress[2]!r}",
        f"    set Angle = {angle}",
        f"    set Fixed point = {lower_left[0]!r}, {lower_left[1]!r}",
        "  end",
        "end",
        "subsection Output",
        f"  set Directory = {directory}",
        "  set Interval = 0",
        "  set Timing summary = false",
        "end",
    ]
    return "\n".join(lines) + "\n"


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--bsmpm", required=True)
    parser.add_argument("--method", choices=["ibm", "nitsche"], required=True)
    parser.add_argument("--angles", default="0,15,30,45,60")
    parser.add_argument("--all-layouts", default="pressure,displacement",
                        help="the cases run with every layout; the others "
                             "with per cell 2, lattice and cell centroid")
    parser.add_argument("--full-angle", type=float, default=None,
                        help="run the --all-layouts cases with every layout "
                             "at this angle only (default: at every angle)")
    parser.add_argument("--band", default="1e-6",
                        help="relative band width of the implicit boundary "
                             "method, or 'default'")
    args = parser.parse_args()

    bound = 1e-8 if args.method == "ibm" else 1e-10
    layouts = [f"per cell {n}" for n in range(1, 9)] + ["lattice",
                                                       "cell centroid"]
    few_layouts = ["per cell 2", "lattice", "cell centroid"]
    # The runs of a row go through one process each per --sweep (bsmpm runs
    # a scene once per value, each in its own output directory): a Debug
    # process spends about as long starting (loading deal.II and its
    # libraries) as it takes for this small scene. Each entry: the layout
    # of the parameter file, the sweep, the layouts of its runs in order.
    full_row = [("per cell 1",
                 "Material points/Points per cell=" +
                 ",".join(str(n) for n in range(1, 9)), layouts[:8]),
                ("lattice", "Material points/Layout=lattice,cell centroid",
                 layouts[8:])]
    few_row = [("per cell 2",
                "Material points/Layout=per cell,lattice,cell centroid",
                few_layouts)]
    all_layouts_for = args.all_layouts.split(",")
    failures, worst = [], 0.0
    with tempfile.TemporaryDirectory() as tmp:
        prm = os.path.join(tmp, "patch.prm")
        out = os.path.join(tmp, "output")
        for angle in [float(a) for a in args.angles.split(",")]:
            for case in ("pressure", "displacement", "normal"):
                row = []
                full = case in all_layouts_for and (
                    args.full_angle is None or angle == args.full_angle)
                for first, sweep, names in (full_row if full else few_row):
                    with open(prm, "w") as f:
                        f.write(scene(angle, first, case, args.method, out,
                                      args.band))
                    shutil.rmtree(out, ignore_errors=True)
                    # Each run of the sweep writes into out/sweep-<k>.
                    _, result = run(args.bsmpm, prm, arguments=["--sweep",
                                                                sweep],
                                    directory=out, output=True, check=False)
                    ended = 0
                    for k, layout in enumerate(names):
                        summary = os.path.join(out, f"sweep-{k}",
                                               "summary.json")
                        if not os.path.isfile(summary):
                            # The run of this layout did not end (the
                            # process stopped in it or before).
                            failures.append(f"{angle} {case} {layout}: exit "
                                            f"{result.returncode}: "
                                            f"{result.stderr.strip()[-300:]}")
                            row.append("  fail ")
                            continue
                        ended += 1
                        with open(summary) as f:
                            errors = json.load(f)["errors"]
                        error = max(errors[key] for key in errors
                                    if key.startswith("R_sigma"))
                        worst = max(worst, error)
                        row.append(f"{error:7.1e}")
                        if not error <= bound:
                            failures.append(f"{angle} {case} {layout}: "
                                            f"R_sigma {error:.2e} > "
                                            f"{bound:.0e}")
                    if result.returncode != 0 and ended == len(names):
                        failures.append(f"{angle} {case} {sweep}: exit "
                                        f"{result.returncode}: "
                                        f"{result.stderr.strip()[-300:]}")
                print(f"{angle:4.0f} deg {case:12s} " + " ".join(row),
                      flush=True)
    print(f"layouts: {', '.join(layouts)} (cases other than "
          f"{', '.join(all_layouts_for)}: {', '.join(few_layouts)})")
    print(f"worst R_sigma {worst:.2e} (bound {bound:.0e})")
    for failure in failures:
        print("FAILED:", failure)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
