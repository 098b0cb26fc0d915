#!/usr/bin/env python3
"""Runs a bsmpm scene over a refinement series and reports errors and rates.

Each run overrides one parameter (e.g. the cell size) with --set and reads the
run's summary.json. Rates are log(e_{k-1}/e_k) / |log(x_{k-1}/x_k)| for the
refined parameter x: positive when the error falls. With --min-rate NAME=RATE the script fails unless the
rate between the last two runs of error NAME is at least RATE, which makes it
a test. With --csv it writes one row per run.

Example:
  scripts/convergence_study.py --bsmpm build/bsmpm \
      --prm prm/column-self-weight.prm \
      --parameter "Background grid/Cell size" --values 0.5,0.25,0.125 \
      --errors L2_u,L2_sigma --min-rate L2_u=1.9
"""
import argparse
import csv
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(
    os.path.abspath(__file__))), "tests"))
from bsmpm_run import run as run_bsmpm  # noqa: E402  (tests/bsmpm_run.py)


def run(args, value, index):
    """summary.json of the run with the refined parameter at @p value, the
    @p index-th of the series."""
    settings = [f"{args.parameter}={value}", "Output/Interval=0",
                "Output/Timing summary=false"] + args.set
    for vary in args.vary:
        name, values = vary.split("=", 1)
        settings.append(f"{name}={values.split(';')[index]}")
    return run_bsmpm(args.bsmpm, args.prm, args.mpirun, settings)


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--bsmpm", required=True)
    parser.add_argument("--prm", required=True)
    parser.add_argument("--parameter", required=True,
                        help="parameter to refine, as Section/Name")
    parser.add_argument("--values", required=True,
                        help="comma-separated values, coarse to fine")
    parser.add_argument("--errors", default="L2_u,L2_sigma",
                        help="comma-separated error or quantity names to report")
    parser.add_argument("--set", action="append", default=[],
                        help="further overrides, as for bsmpm --set")
    parser.add_argument("--vary", action="append", default=[],
                        help="Section/Name=v1;v2;...: a parameter that changes "
                             "along with the refined one (one value per run)")
    parser.add_argument("--min-rate", action="append", default=[],
                        help="NAME=RATE: require this rate between the last two runs")
    parser.add_argument("--csv", help="write a CSV with one row per run")
    parser.add_argument("--mpirun", type=int, default=1)
    parser.add_argument("--repeat", type=int, default=1,
                        help="run each point this many times and keep the "
                             "fastest (wall times per phase from that run)")
    args = parser.parse_args()

    values = [v.strip() for v in args.values.split(",")]
    names = [n.strip() for n in args.errors.split(",")]
    rows = []
    for i, value in enumerate(values):
        runs = [run(args, value, i) for k in range(args.repeat)]
        summary = min(runs, key=lambda s: s["timing"]["total"])
        results = dict(summary["errors"])
        results.update(summary["quantities"])
        rows.append({"value": float(value),
                     "n_dofs": summary["n_dofs"],
                     "n_material_points": summary["n_material_points"],
                     "time": summary["timing"]["total"],
                     **{n: results.get(n, float("nan")) for n in names},
                     **{"time " + phase: t
                        for phase, t in summary["timing"].items()
                        if phase != "total"}})

    header = f"{args.parameter:>28} {'dofs':>8} {'points':>9}"
    for n in names:
        header += f" {n:>14} {'rate':>6}"
    print(header)
    rates = {n: [] for n in names}
    for i, row in enumerate(rows):
        line = f"{row['value']:>28.6g} {row['n_dofs']:>8} {row['n_material_points']:>9}"
        for n in names:
            rate = float("nan")
            if i > 0 and row[n] > 0 and rows[i - 1][n] > 0:
                # Positive when the error falls, whichever way the
                # parameter runs (cell size down, points per cell up).
                rate = (math.log(rows[i - 1][n] / row[n]) /
                        abs(math.log(rows[i - 1]["value"] / row["value"])))
            rates[n].append(rate)
            line += f" {row[n]:>14.6e} {rate:>6.2f}"
        print(line)

    if args.csv:
        fields = []
        for row in rows:
            fields += [k for k in row if k not in fields]
        with open(args.csv, "w", newline="") as f:
            writer = csv.DictWriter(f, fieldnames=fields, restval=0.0)
            writer.writeheader()
            writer.writerows(rows)

    failed = False
    for requirement in args.min_rate:
        name, minimum = requirement.split("=")
        rate = rates[name][-1]
        ok = rate >= float(minimum)
        print(f"rate of {name} between the last two runs: {rate:.3f} "
              f"(required >= {minimum}): {'passed' if ok else 'FAILED'}")
        failed |= not ok
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
