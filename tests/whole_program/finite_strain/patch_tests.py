#!/usr/bin/env python3
"""Finite-strain patch tests with a free side that crosses grid lines.

A square in plane strain (Hencky, E = 1e6 Pa, nu = 0.3) on a grid of 0.25 m
cells, rollers on the grid's left and bottom faces, a follower pressure on
its top curve and its right side a free curve (issue 26, item 3;
doc/finite-strain.md, "Cells the points fill unevenly"):

  compression: a 0.9 m square, pressure 480559 Pa: lambda_y = 0.7, the free
               side moves from x = 0.9 to 1.049 (across x = 1), the top
               from 0.9 to 0.63 (across 0.75);
  stretch:     a 0.8 m square, pressure -248173 Pa (tension): lambda_y =
               1.3, the free side moves from 0.8 to 0.715 (across 0.75),
               the top from 0.8 to 1.04 (across 1).

The deformation is homogeneous and Hencky elasticity path independent, so
every point must carry sigma_yy = -p, sigma_xx = sigma_xy = 0 after any
number of load steps, with every layout (one point per cell too: such a
cell is integrated by the four points of its exact moments with the
point's state, ConstitutiveUpdate::cell_system()): the relative stress
errors R and
the mean absolute errors over |p| must stay below the Newton tolerance's
reach (bound 1e-8). Before the cells whose points carry only their area
were completed by the exact moments (ConstitutiveUpdate::cell_system) the
compression was off by percents.

The same deformations imposed through supports on the B-spline curves
(doc/finite-strain.md, "Supports in finite strain"), by the implicit
boundary method (the default) and by Nitsche's method:

  compression, stretch: the top curve's normal displacement (-0.27 m,
               +0.24 m) instead of the pressure, the rest as above;
  shear:       simple shear u = (0.4 y, 0) of the square [0.3, 1.2]^2
               imposed as a displacement on its whole boundary (one closed
               curve; no face supports): the left side moves from x = 0.3
               across 0.5 and 0.75, the right one across 1.25 and 1.5.
               Exact: sigma = mu ln(b), b = F F^T, F = [[1, 0.4], [0, 1]].

Before the supports' terms took the stress of the step's deformation (they
paired the increment with the elastic stiffness and the stress of the
step's start) these were off by up to about 1e-2. Before an iterate that
inverts a point was left out of the system (an infinite |R| for the line
search) the IBM runs in 1 or 2 steps and several one-point runs aborted in
a Debug build on a NaN force.

Usage: patch_tests.py --bsmpm BSMPM
"""

import argparse
import math
import os
import pathlib
import sys
import tempfile

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[2]))
from bsmpm_run import run  # noqa: E402  (tests/bsmpm_run.py)

BOUND = 1e-8

CASES = {
    # name: (side of the square, pressure on the top)
    "compression": (0.9, 480559.0),
    "stretch": (0.8, -248173.0),
}

E, NU = 1e6, 0.3
MU = E / (2 * (1 + NU))
# Supports on the curves: the top's normal displacement (compression,
# stretch), or simple shear of SHEAR_BOX by SHEAR_GAMMA.
NORMAL_DISPLACEMENT = {"compression": -0.27, "stretch": 0.24}
SHEAR_GAMMA = 0.4
SHEAR_BOX = (0.3, 1.2)


def exact_stress(case):
    """Cauchy stress (xx, yy, xy) of the homogeneous deformation imposed
    through the supports (plane strain, Hencky)."""
    if case == "shear":
        # b = F F^T for F = [[1, g], [0, 1]]; det b = 1, so tau = sigma =
        # 2 mu eps = mu ln(b) (trace-free).
        g = SHEAR_GAMMA
        bxx, byy, bxy = 1 + g * g, 1.0, g
        m, r = (bxx + byy) / 2, math.hypot((bxx - byy) / 2, bxy)
        l1, l2 = m + r, m - r
        e1 = ((bxx - l2) / (l1 - l2), (byy - l2) / (l1 - l2), bxy / (l1 - l2))
        ln1, ln2 = math.log(l1), math.log(l2)
        log_b = [ln2 + (ln1 - ln2) * e1[0], ln2 + (ln1 - ln2) * e1[1],
                 (ln1 - ln2) * e1[2]]
        return tuple(MU * v for v in log_b)
    side = CASES[case][0]
    ly = (side + NORMAL_DISPLACEMENT[case]) / side
    ey = math.log(ly)
    ex = -NU / (1 - NU) * ey
    tau_yy = E / (1 - NU * NU) * ey
    return (0.0, tau_yy / (math.exp(ex) * ly), 0.0)


def support_scene(case, method, layout, steps, directory):
    """The parameter file of one run whose deformation the curves'
    supports impose by @p method (implicit boundary or nitsche)."""
    sxx, syy, sxy = exact_stress(case)
    text = scene("compression" if case == "shear" else case, layout, steps,
                 directory)
    lines = text.splitlines()
    start = lines.index("subsection Boundary curves")
    end = lines.index("subsection Exact solution")
    method_line = f"    set Dirichlet method = {method}"
    if case == "shear":
        low, high = SHEAR_BOX
        curves = [
            "subsection Boundary curves",
            "  subsection Curve 1",
            "    set Points           = region edge",
            "    set Edge             = boundary",
            "    set Number of points = 5",
            f"    set Condition        = displacement {SHEAR_GAMMA}*y; 0",
            method_line,
            "  end",
            "end",
        ]
        lines = [l for l in lines if "set Left   = roller" not in l
                 and "set Bottom = roller" not in l]
        start = lines.index("subsection Boundary curves")
        end = lines.index("subsection Exact solution")
        body = lines.index("subsection Body region")
        lines[body + 2] = f"  set Lower left corner  = {low}, {low}"
        lines[body + 3] = f"  set Upper right corner = {high}, {high}"
    else:
        curves = lines[start:end]
        k = curves.index("    set Condition        = "
                         f"pressure {CASES[case][1]!r}")
        curves[k] = ("    set Condition        = normal displacement "
                     f"{NORMAL_DISPLACEMENT[case]!r}")
        curves.insert(k + 1, method_line)
    lines[start:end] = curves
    k = lines.index("  subsection Constant stress")
    lines[k + 1] = f"    set Stress = {sxx!r}, {syy!r}, {sxy!r}"
    return "\n".join(lines) + "\n"


def scene(case, layout, steps, directory):
    """The parameter file of one run."""
    side, p = CASES[case]
    lines = [
        "set Scene name = finite-strain-patch",
        "subsection Background grid",
        "  set Lower left corner  = 0, 0",
        "  set Upper right corner = 2, 2",
        "  set Cell size          = 0.25",
        "  subsection Face conditions",
        "    set Left   = roller",
        "    set Bottom = roller",
        "  end",
        "end",
        "subsection Material",
        "  set Young's modulus = 1e6",
        "  set Poisson's ratio = 0.3",
        "  set Model           = plane strain",
        "  set Kinematics      = finite strain",
        "end",
        "subsection Loading",
        f"  set Load steps = {steps}",
        "end",
        "subsection Body region",
        "  set Shape              = rectangle",
        "  set Lower left corner  = 0, 0",
        f"  set Upper right corner = {side}, {side}",
        "end",
        "subsection Material points",
    ]
    kind, n = layout.split()[0], layout.split()[-1]
    if kind == "per":
        lines += ["  set Layout = per cell", f"  set Points per cell = {n}"]
    elif kind == "lattice":
        lines += ["  set Layout = lattice", f"  set Lattice points = {n}, {n}"]
    else:
        lines += ["  set Layout = cell centroid"]
    lines += [
        "end",
        "subsection Boundary curves",
        "  subsection Curve 1",
        "    set Points           = region edge",
        "    set Edge             = top",
        "    set Number of points = 5",
        f"    set Condition        = pressure {p!r}",
        "  end",
        "  subsection Curve 2",
        "    set Points           = region edge",
        "    set Edge             = right",
        "    set Number of points = 5",
        "  end",
        "end",
        "subsection Exact solution",
        "  set Name = constant stress",
        "  subsection Constant stress",
        f"    set Stress = 0, {-p!r}, 0",
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
    parser.add_argument("--only", default="",
                        help="run only the runs whose description holds "
                        "this text (e.g. nitsche)")
    parser.add_argument("--run", action="append", default=[],
                        help="instead of the test's runs, the run "
                        "'CASE;SUPPORT;LAYOUT;STEPS' (e.g. "
                        "'compression;implicit boundary;per cell 3;1'); "
                        "may be repeated")
    args = parser.parse_args()

    # (case, support, layout, load steps): every layout a user would pick
    # for a square (per cell 1 to 4 points per direction, a lattice, cell
    # centroids; polar needs an annulus sector) and 1, 2, 4, 5, 6 and 10
    # load steps, spread over the cases and supports so that each layout
    # meets each support somewhere (about 30 s of CPU in a Debug build).
    runs = [("compression", "pressure", "per cell 1", 10),
            ("compression", "pressure", "per cell 2", 10),
            ("compression", "pressure", "per cell 3", 6),
            ("compression", "pressure", "per cell 4", 2),
            ("compression", "pressure", "lattice 9", 6),
            ("compression", "pressure", "cell centroid", 10),
            ("stretch", "pressure", "per cell 1", 5),
            ("stretch", "pressure", "per cell 3", 4),
            ("stretch", "pressure", "cell centroid", 1),
            ("compression", "implicit boundary", "per cell 1", 5),
            ("compression", "implicit boundary", "per cell 2", 10),
            ("compression", "implicit boundary", "per cell 3", 1),
            ("compression", "implicit boundary", "per cell 3", 2),
            ("compression", "implicit boundary", "lattice 9", 2),
            ("stretch", "implicit boundary", "per cell 2", 5),
            ("stretch", "implicit boundary", "cell centroid", 10),
            ("shear", "implicit boundary", "per cell 1", 2),
            ("shear", "implicit boundary", "per cell 2", 5),
            ("shear", "implicit boundary", "per cell 3", 1),
            ("shear", "implicit boundary", "per cell 4", 5),
            ("compression", "nitsche", "per cell 1", 10),
            ("compression", "nitsche", "per cell 3", 5),
            ("compression", "nitsche", "per cell 4", 1),
            ("stretch", "nitsche", "per cell 2", 1),
            ("stretch", "nitsche", "lattice 9", 5),
            ("shear", "nitsche", "per cell 2", 10),
            ("shear", "nitsche", "cell centroid", 2)]
    if args.run:
        runs = [(c, sup, lay, int(n)) for c, sup, lay, n in
                (r.split(";") for r in args.run)]
    if args.only:
        runs = [r for r in runs if args.only in " ".join(map(str, r))]
    failures, worst = [], 0.0
    with tempfile.TemporaryDirectory() as tmp:
        prm = os.path.join(tmp, "patch.prm")
        out = os.path.join(tmp, "output")
        for case, support, layout, steps in runs:
            with open(prm, "w") as f:
                if support == "pressure":
                    f.write(scene(case, layout, steps, out))
                else:
                    f.write(support_scene(case, support, layout, steps, out))
            summary, result = run(args.bsmpm, prm, directory=out,
                                  output=True, check=False)
            name = (f"{case:12s} {support:17s} {layout:14s} "
                    f"{steps:3d} steps")
            if result.returncode != 0:
                failures.append(f"{name}: exit {result.returncode}: "
                                f"{result.stderr.strip()[-300:]}")
                print(f"{name}: fail", flush=True)
                continue
            errors = summary["errors"]
            if support == "pressure":
                p = abs(CASES[case][1])
                error = max(errors["R_sigma_yy"], errors["A_sigma_xx"] / p,
                            errors["A_sigma_xy"] / p)
            else:
                scale = max(abs(v) for v in exact_stress(case))
                error = max(errors["A_sigma_" + c] / scale
                            for c in ("xx", "yy", "xy"))
            worst = max(worst, error)
            no_points = summary.get("quantities", summary).get(
                "body_cells_no_points", 0)
            # Newton iterations of the accepted attempts, and load steps
            # cut.
            newton = sum(len(step.get("newton_residuals", [0])) - 1
                         for step in summary.get("steps", []))
            cuts = sum(step.get("increments", 1) - 1
                       for step in summary.get("steps", []))
            print(f"{name}: stress error {error:7.1e} "
                  f"(body cells without points at the end {no_points:g}, "
                  f"Newton iterations {newton}, cuts {cuts})",
                  flush=True)
            if not error <= BOUND:
                failures.append(f"{name}: stress error {error:.2e} > "
                                f"{BOUND:.0e}")
    print(f"worst stress error {worst:.2e} (bound {BOUND:.0e})")
    for failure in failures:
        print("FAILED:", failure)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
