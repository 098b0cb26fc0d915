#!/usr/bin/env python3
"""Iterative refinement of the direct solver (LinearSolver::solve's accuracy).

1. Newton corrections are refined only while their residual is above a
   thousandth of the Newton tolerance's force: the plastic strip footing
   (h = 0.125, 0.02 m in 4 steps, direct solver), whose back-substitutions
   leave round-off (about 1e-14 of |R_k|), takes no refinement step in any
   of its corrections (it took 18 when every solve was refined as far as
   the factors reduce the residual).
2. A linear solve is still refined as far as that goes: the square of 1b
   with a band of 1e-8 h (an ill-conditioned system, doc/stability.md)
   takes at least one refinement step.
"""
import argparse
import pathlib
import sys

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1]))
from bsmpm_run import run  # noqa: E402  (tests/bsmpm_run.py)

parser = argparse.ArgumentParser(description=__doc__)
parser.add_argument("--bsmpm", required=True)
parser.add_argument("--prm-directory", required=True)
args = parser.parse_args()
problems = []


def steps(prm, settings):
    """The steps of summary.json of a run of @p prm with @p settings."""
    summary, result = run(args.bsmpm, pathlib.Path(args.prm_directory, prm),
                          settings=["Output/Interval=0",
                                    "Linear solver/Method=direct"] + settings,
                          output=True, check=False)
    if result.returncode != 0:
        problems.append(f"{prm}: exit code {result.returncode}: "
                        f"{result.stderr[-1000:]}")
        return []
    return summary["steps"]


footing = steps("strip-footing.prm",
                ["Background grid/Cell size=0.125", "Loading/Load steps=4",
                 "Boundary curves/Curve 1/Condition 2=117-160: "
                 "displacement 0; -0.02"])
corrections = sum(len(s["newton_corrections"]) for s in footing)
refined = sum(s["refinement_steps"] for s in footing)
print(f"footing: {corrections} Newton corrections, {refined} refinement steps")
if corrections == 0:
    problems.append("footing: no Newton correction was solved")
if refined != 0:
    problems.append("footing: Newton corrections were refined below the "
                    "accuracy they need")

square = steps("square-compression-ibm.prm",
               ["Implicit boundary/Relative band width=1e-8"])
refined = sum(s["refinement_steps"] for s in square)
print(f"square, band 1e-8 h: {refined} refinement steps, relative residual "
      f"{[s['relative_residual'] for s in square]}")
if square and refined == 0:
    problems.append("square: the linear solve was not refined")

for p in problems:
    print("FAILED:", p)
sys.exit(1 if problems else 0)
