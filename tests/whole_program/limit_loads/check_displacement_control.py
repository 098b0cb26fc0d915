#!/usr/bin/env python3
"""Runs a load-ramped scene under displacement control (Loading/Control =
displacement) and checks that it passes its limit load: exit code 0, status
'completed', every step done (no limit load declared), and the load factor
of the last steps, those whose settlement is past the collapse, within the
bounds of the limit load factor, as a plateau. The step table is not
compared (see check_limit_load.py)."""
import argparse
import pathlib
import sys

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[2]))
from bsmpm_run import run  # noqa: E402  (tests/bsmpm_run.py)

parser = argparse.ArgumentParser(description=__doc__)
parser.add_argument("--bsmpm", required=True)
parser.add_argument("--prm", required=True)
parser.add_argument("--lower", type=float, required=True)
parser.add_argument("--upper", type=float, required=True)
parser.add_argument("--plateau-steps", type=int, required=True,
                    help="how many last steps must lie within the bounds")
args = parser.parse_args()

summary, result = run(args.bsmpm, args.prm, output=True, check=False,
                      cwd=pathlib.Path(args.prm).parent)
print(result.stdout[-3000:])
if result.returncode != 0:
    sys.exit(f"exit code {result.returncode}: {result.stderr}")

problems = []
if summary["status"] != "completed":
    problems.append(f"status {summary['status']}")
if "limit_load_factor" in summary["quantities"]:
    problems.append("a limit load was declared: the run stopped at it")
steps = summary["steps"]
if len(steps) != summary["load_steps"]:
    problems.append(f"{len(steps)} of {summary['load_steps']} steps done")
factors = [s["load_factor"] for s in steps]
print("load factors per step:", " ".join(f"{f:.4f}" for f in factors))
plateau = factors[-args.plateau_steps:]
if len(plateau) < args.plateau_steps:
    problems.append("too few steps for the plateau")
for f in plateau:
    if not args.lower <= f <= args.upper:
        problems.append(f"load factor {f} of the plateau outside "
                        f"[{args.lower}, {args.upper}]")
for problem in problems:
    print(problem)
sys.exit(1 if problems else 0)
