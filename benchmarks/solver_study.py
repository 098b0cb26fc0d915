#!/usr/bin/env python3
"""CG iteration counts of bsmpm's linear solver against the cell size,
the fill fraction of cut cells and the stopping tolerance (doc/benchmarks.md).

  h:          scene 4a (plate with a hole, 8^2 points per cell, one step)
              at h = 2^-3 .. 2^-7, and the column [0,1]^2 under its own
              weight (4^2 points per cell, 3 load steps) at 32^2 .. 256^2
              cells;
  fill:       a square on 128 x 192 cells whose top row of cells holds a
              sliver of height f h (one point per cell, its centroid),
              f = 1 .. 1e-10, default stabilisation (ghost penalty);
  tolerance:  the errors of 4a and of the column at every h for the
              relative tolerances 1e-4 .. 1e-12 and the automatic one:
              how far each moves the errors from those of the 1e-12 solve.

Every run forces the method of --method, "cg amg" (ML, the default here, as
in the tables of doc/benchmarks.md) or "cg gmg" (the geometric multigrid),
also below the automatic threshold. Prints tables in Markdown; --csv DIR
writes them as CSV too.

Usage: solver_study.py --bsmpm BUILD/bsmpm [--only h,fill,tolerance]
                       [--method "cg amg"|"cg gmg"]
"""
import argparse
import csv
import os
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
PRM = os.path.join(ROOT, "prm")
sys.path.insert(0, os.path.join(ROOT, "tests"))
from bsmpm_run import run as run_bsmpm  # noqa: E402  (tests/bsmpm_run.py)

PLATE = [os.path.join(PRM, "plate-with-hole-neumann.prm")]
COLUMN = [os.path.join(PRM, "column-self-weight.prm"),
          "--set", "Background grid/Cell size=0",
          "--set", "Background grid/Upper right corner=1, 1",
          "--set", "Body region/Upper right corner=1, 1",
          "--set", "Exact solution/Column/Height=1",
          "--set", "Material points/Points per cell=4",
          "--set", "Loading/Load steps=3"]


METHOD = "cg amg"


def run(bsmpm, args, sets, directory):
    """summary.json of a run of @p args (a parameter file and --set
    assignments) with @p sets."""
    return run_bsmpm(bsmpm, args[0], arguments=args[1:], directory=directory,
                     settings=sets + [f"Linear solver/Method={METHOD}",
                                      "Output/Interval=0",
                                      "Output/Timing summary=false"])


def iterations(summary):
    return [step["iterations"] for step in summary["steps"]]


def cases():
    for k in range(3, 8):
        h = 2.0 ** -k
        yield ("4a", f"2^-{k}", PLATE, [f"Background grid/Cell size={h!r}"])
    for n in (32, 64, 128, 256):
        yield ("column", f"{n}^2", COLUMN,
               [f"Background grid/Cells per direction={n}, {n}"])


def study_h(bsmpm, tmp, tables):
    rows = []
    for scene, size, args, sets in cases():
        s = run(bsmpm, args, sets, os.path.join(tmp, "h"))
        rows.append([scene, size, s["n_dofs"], " ".join(map(str, iterations(s))),
                     f"{s['steps'][-1]['relative_residual']:.1e}"])
    tables["h"] = (["scene", "h", "DoFs", "CG iterations per step",
                    "residual"], rows)


def study_fill(bsmpm, tmp, tables):
    rows = []
    h = 1.0 / 128
    for f in ["1", "1e-1", "1e-2", "1e-4", "1e-6", "1e-8", "1e-10"]:
        top = 1 - h + float(f) * h if f != "1" else 1.0
        sets = ["Background grid/Upper right corner=1, 1.5",
                "Background grid/Cells per direction=128, 192",
                f"Body region/Upper right corner=1, {top!r}",
                "Linear solver/Estimate condition number=false"]
        s = run(bsmpm, [os.path.join(PRM, "square-sliver.prm")], sets,
                os.path.join(tmp, "fill"))
        rows.append([f, s["n_dofs"], " ".join(map(str, iterations(s))),
                     f"{s['steps'][-1]['relative_residual']:.1e}"])
    tables["fill"] = (["fill f of the top row", "DoFs",
                       "CG iterations per step", "residual"], rows)


def study_tolerance(bsmpm, tmp, tables):
    rows = []
    tolerances = ["1e-4", "1e-6", "1e-8", "automatic", "1e-10"]
    for scene, size, args, sets in cases():
        exact = run(bsmpm, args, sets + ["Linear solver/Tolerance=1e-12"],
                    os.path.join(tmp, "t"))
        row = [scene, size]
        for t in tolerances:
            s = run(bsmpm, args, sets + [f"Linear solver/Tolerance={t}"],
                    os.path.join(tmp, "t"))
            # How far the errors moved, relative to themselves.
            moved = max(abs(s["errors"][k] - exact["errors"][k]) /
                        abs(exact["errors"][k])
                        for k in ("L2_u", "L2_sigma", "max_A_u", "max_A_v")
                        if k in exact["errors"] and exact["errors"][k] > 1e-12)
            row.append(f"{moved:.0e} ({sum(iterations(s))})")
        row.append(f"- ({sum(iterations(exact))})")
        rows.append(row)
    tables["tolerance"] = (["scene", "h"] + tolerances + ["1e-12"], rows)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--bsmpm", required=True)
    parser.add_argument("--only", default="h,fill,tolerance")
    parser.add_argument("--csv")
    parser.add_argument("--method", default="cg amg",
                        choices=["cg amg", "cg gmg"])
    args = parser.parse_args()
    global METHOD
    METHOD = args.method
    tables = {}
    with tempfile.TemporaryDirectory() as tmp:
        for name in args.only.split(","):
            {"h": study_h, "fill": study_fill,
             "tolerance": study_tolerance}[name](args.bsmpm, tmp, tables)
    for name, (header, rows) in tables.items():
        print(f"\n{name}:\n")
        print("| " + " | ".join(header) + " |")
        print("|" + "---|" * len(header))
        for row in rows:
            print("| " + " | ".join(map(str, row)) + " |")
        if args.csv:
            os.makedirs(args.csv, exist_ok=True)
            with open(os.path.join(args.csv, f"solver_{name}.csv"), "w",
                      newline="") as f:
                csv.writer(f).writerows([header] + rows)


if __name__ == "__main__":
    main()
