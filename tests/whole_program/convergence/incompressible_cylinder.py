#!/usr/bin/env python3
"""The thick cylinder (Lame) at nu = 0.499 against nu = 0.25: no locking.

Runs prm/thick-cylinder.prm (linear elastic, inner pressure, plane strain)
at every cell size of a refinement study, with default settings apart from
the Poisson's ratio, and requires at every h that L2_u, L2_sigma and the
inner radius error at nu = 0.499 stay within FACTOR (2) of those at
nu = 0.25. The standard strain (`--set "Material/Volumetric strain =
standard"`, the linear kernel before B-bar) locks: at h = 0.25 L2_u 4.6e-1
against 8.1e-3 (doc/b-bar.md).

Usage: incompressible_cylinder.py --bsmpm BSMPM --prm PRM
       [--sizes 0.25,0.125,0.0625] [--set "Section/Name=value" ...]
"""

import argparse
import pathlib
import sys

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[2]))
from bsmpm_run import run  # noqa: E402  (tests/bsmpm_run.py)

FACTOR = 2.0
MEASURES = ("L2_u", "L2_sigma", "inner_radius_error")


def cylinder(bsmpm, prm, nu, h, extra):
    summary = run(bsmpm, prm, settings=[f"Material/Poisson's ratio={nu}",
                                        f"Background grid/Cell size={h}",
                                        "Output/Interval=0"] + extra)
    values = dict(summary["errors"])
    values["inner_radius_error"] = summary["quantities"]["inner_radius_error"]
    return values


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--bsmpm", required=True)
    parser.add_argument("--prm", required=True)
    parser.add_argument("--sizes", default="0.25,0.125,0.0625")
    parser.add_argument("--nu", default="0.25,0.499",
                        help="reference first, then the nearly "
                             "incompressible ones")
    parser.add_argument("--set", action="append", default=[])
    args = parser.parse_args()

    nus = args.nu.split(",")
    failures = []
    print(f"{'nu':>6} {'h':>7} " + " ".join(f"{m:>19}" for m in MEASURES))
    for h in args.sizes.split(","):
        reference = None
        for nu in nus:
            values = cylinder(args.bsmpm, args.prm, nu, h, args.set)
            print(f"{nu:>6} {h:>7} " +
                  " ".join(f"{values[m]:19.3e}" for m in MEASURES),
                  flush=True)
            if reference is None:
                reference = values
                continue
            for m in MEASURES:
                if not values[m] <= FACTOR * reference[m]:
                    failures.append(
                        f"nu {nu}, h {h}: {m} {values[m]:.3e} > "
                        f"{FACTOR} x {reference[m]:.3e} (nu {nus[0]})")
    for failure in failures:
        print("FAILED:", failure)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
