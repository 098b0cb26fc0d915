#!/usr/bin/env python3
"""Runs a scene serially and with mpirun -np N (for each N of --np, against
the one serial run) and checks that every error and quantity of
summary.json agrees to a relative tolerance.

"Agree" means: as fields. Any change in the order of operations (the
partition, the pivoting of the direct solver) moves the solution by about
cond(K) times the machine epsilon, and an error that is itself small against
the solution magnifies that. So absolute errors (A_*, max_A_*) are compared
relative to the scale of their field (max_displacement, max_stress of the
serial run), and normalised errors (R_*, L2_*) absolutely; quantities
relative to themselves, except the components of a vector or tensor
(..._x, ..._y, ..._xx, ..._xy, ..._yy), which are compared relative to the
largest component of the same name: a shear stress or a sideways force
that is zero but for round-off is no worse for being at 1e-16 in one run
and 1e-14 in the other. The places of maxima (max_A_u_at_x, ...) are not
compared: among round-off-level errors the largest is an arbitrary one.
The number of points that yielded may differ by one in two hundred
(--yield-tolerance): without hardening a point that stays on the yield
surface has a trial yield function of zero to round-off, and counts as
yielding (f > 0) in one run and not in the other; every field is still
compared.

--repeat runs the parallel case twice and requires the same bits in both
(errors, quantities and every step's record in summary.json).
"""
import argparse
import pathlib
import sys

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[2]))
from bsmpm_run import run  # noqa: E402  (tests/bsmpm_run.py)


def scale_of(name, quantities):
    if name.startswith(("A_", "max_A_")):
        return quantities["max_stress" if "sigma" in name else "max_displacement"]
    if name.startswith(("R_", "L2_")):
        return 1.0
    return None


COMPONENTS = ("_xx", "_xy", "_yy", "_x", "_y")


def component_scale(name, quantities):
    """The largest component of the vector or tensor that @p name is a
    component of, or None if it is none."""
    for suffix in COMPONENTS:
        if name.endswith(suffix):
            stem = name[:-len(suffix)]
            members = [v for k, v in quantities.items()
                       if k[len(stem):] in COMPONENTS and k.startswith(stem)
                       and isinstance(v, (int, float))]
            return max(abs(v) for v in members)
    return None


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--bsmpm", required=True)
    parser.add_argument("--prm", required=True)
    parser.add_argument("--np", type=int, nargs="+", default=[2],
                        help="numbers of processes, each compared with the "
                        "serial run")
    parser.add_argument("--tolerance", type=float, default=1e-10)
    parser.add_argument("--yield-tolerance", type=float, default=0.005)
    parser.add_argument("--repeat", action="store_true",
                        help="run the parallel case twice as well: both "
                        "runs must give the same bits in every error, "
                        "quantity and Newton residual of every step")
    parser.add_argument("--set", action="append", default=[])
    args = parser.parse_args()

    settings = args.set + ["Output/Interval=0", "Output/Timing summary=false"]
    serial = run(args.bsmpm, args.prm, 1, settings)
    failed = False
    for np in args.np:
        parallel = run(args.bsmpm, args.prm, np, settings)
        again = run(args.bsmpm, args.prm, np, settings) if args.repeat else None
        failed |= compare(serial, parallel, again, np, args)
    print("serial and parallel runs agree" if not failed else "MISMATCH")
    return 1 if failed else 0


def compare(serial, parallel, again, np, args):
    """Whether the run at @p np processes (and @p again, its repetition)
    fails to give the serial results; prints every comparison."""
    failed = False
    if again is not None:
        # One run must give the bits of the next (equal, not close: a
        # difference of round-off grows where a decision flips on it).
        for section in ("errors", "quantities"):
            differ = sorted(k for k in set(parallel[section]) | set(again[section])
                            if parallel[section].get(k) != again[section].get(k))
            if differ:
                print(f"np={np} run twice: {section} differ: " +
                      ", ".join(f"{k} {parallel[section].get(k)!r} "
                                f"{again[section].get(k)!r}" for k in differ[:4]))
                failed = True
        for a, b in zip(parallel["steps"], again["steps"]):
            if a != b:
                print(f"np={np} run twice: step {a['step']} differs")
                failed = True
                break
        if not failed:
            print(f"np={np} run twice: the same bits")
    for key in ("n_cells", "n_dofs", "n_material_points", "n_tracking_points"):
        if serial[key] != parallel[key]:
            print(f"{key}: serial {serial[key]} != parallel {parallel[key]}")
            failed = True

    for section in ("errors", "quantities"):
        a, b = serial[section], parallel[section]
        if set(a) != set(b):
            print(f"{section}: different names {sorted(a)} vs {sorted(b)}")
            failed = True
            continue
        for name in sorted(a):
            if "_at_" in name:
                continue  # where a maximum occurs: arbitrary among ties
            reference = scale_of(name, serial["quantities"]) if section == "errors" else None
            if reference is None and section == "quantities":
                reference = component_scale(name, a)
            if reference is None:
                reference = max(abs(a[name]), abs(b[name]))
            difference = abs(a[name] - b[name])
            if name == "yielded_points":
                ok = difference <= max(1, args.yield_tolerance * a[name])
            else:
                ok = difference <= args.tolerance * reference
            print(f"{section}/{name}: serial {a[name]:.15e} np={np} "
                  f"{b[name]:.15e} {'ok' if ok else 'DIFFERENT'}")
            failed |= not ok
    return failed


if __name__ == "__main__":
    sys.exit(main())
