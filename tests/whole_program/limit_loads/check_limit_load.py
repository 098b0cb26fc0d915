#!/usr/bin/env python3
"""Runs a load-ramped scene that must collapse and checks its record: exit
code 0, status 'completed', a limit_load_factor within the bounds given,
inside its own bracket, with a reason. The step table is not compared: the
Newton iterations of a failing increment beyond the limit diverge, and their
residuals differ with round-off from run to run."""
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
parser.add_argument("--set", action="append", default=[],
                    help="a parameter assignment passed on to bsmpm")
parser.add_argument("--np", type=int, default=1,
                    help="processes (mpirun) for the run")
args = parser.parse_args()

summary, result = run(args.bsmpm, args.prm, args.np, args.set, output=True,
                      check=False, cwd=pathlib.Path(args.prm).parent)
print(result.stdout[-2000:])
if result.returncode != 0:
    sys.exit(f"exit code {result.returncode}: {result.stderr}")

q = summary["quantities"]
problems = []
if summary["status"] != "completed":
    problems.append(f"status {summary['status']}")
if "limit_load_factor" not in q:
    problems.append("no limit_load_factor: the collapse was not detected")
else:
    factor = q["limit_load_factor"]
    if not args.lower <= factor <= args.upper:
        problems.append(f"limit_load_factor {factor} outside "
                        f"[{args.lower}, {args.upper}]")
    if not q["limit_load_lower"] <= factor < q["limit_load_upper"]:
        problems.append("limit_load_factor outside its bracket")
    if not summary.get("limit_load_reason"):
        problems.append("no limit_load_reason")
    print(f"limit load factor {factor}, bracket [{q['limit_load_lower']}, "
          f"{q['limit_load_upper']}]: {summary.get('limit_load_reason')}")
for problem in problems:
    print(problem)
sys.exit(1 if problems else 0)
