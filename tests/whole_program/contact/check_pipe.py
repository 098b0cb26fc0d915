#!/usr/bin/env python3
"""A rigid pipe pushed into clay (prm/pipe-penetration.prm): the run must
complete at every --np given with no increment accepted stalled, the
penetration resistance V / (D c_u) = 2 F_y / (D c_u) must not fall by more
than --max-dip (relative) from one step to the next (a smooth curve; the
clay's resistance grows with the depth), and the runs at several np must
give the same force to --agree. A smooth circle's tractions are normal to
it: their moment about its centre must vanish (to 1e-9 of F D).
Prints V / (D c_u) and the contact length per step.

Usage: check_pipe.py --bsmpm B --prm prm/pipe-penetration.prm
         [--np 1 2] [--set ...]
"""
import argparse
import pathlib
import sys

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[2]))
from bsmpm_run import run  # noqa: E402  (tests/bsmpm_run.py)

parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
parser.add_argument("--bsmpm", required=True)
parser.add_argument("--prm", required=True)
parser.add_argument("--np", type=int, nargs="+", default=[1])
parser.add_argument("--diameter", type=float, default=1.0)
parser.add_argument("--shear-strength", type=float, default=10.0)
parser.add_argument("--max-dip", type=float, default=0.02)
parser.add_argument("--agree", type=float, default=1e-6)
parser.add_argument("--set", action="append", default=[])
args = parser.parse_args()
problems = []
scale = 2 / (args.diameter * args.shear_strength)

forces = {}
for np in args.np:
    summary, result = run(args.bsmpm, args.prm, np,
                          ["Output/Interval=0"] + args.set,
                          output=True, check=False)
    if result.returncode != 0 or summary is None:
        problems.append(f"np = {np}: exit code {result.returncode}: "
                        f"{result.stderr[-1000:]}")
        continue
    steps = summary["steps"]
    if len(steps) != summary["load_steps"]:
        problems.append(f"np = {np}: {len(steps)} of "
                        f"{summary['load_steps']} steps")
    stalled = [s["step"] for s in steps if s.get("stalled_increments", 0)]
    if stalled:
        problems.append(f"np = {np}: stalled increments accepted in steps "
                        f"{stalled}")
    V = [scale * s["quantities"]["rigid_body_1_force_y"] for s in steps]
    forces[np] = V
    print(f"np = {np}: V / (D c_u) and contact length (m) per step")
    print(" ".join(f"{v:.3f}/{s['quantities']['rigid_body_1_contact_length']:.2f}"
                   for v, s in zip(V, steps)))
    # The scene's pipe is a smooth circle unless a --set gives it friction
    # or another shape.
    if not any(("Friction=" in s and not s.endswith("=smooth")) or
               ("Shape=" in s and not s.endswith("=circle"))
               for s in args.set):
        worst = max(abs(s["quantities"]["rigid_body_1_moment"]) /
                    (args.diameter * max(abs(s["quantities"]["rigid_body_1_force_x"]),
                                         abs(s["quantities"]["rigid_body_1_force_y"])))
                    for s in steps)
        print(f"np = {np}: largest |M| / (|F| D) about the centre {worst:.1e}")
        if worst > 1e-9:
            problems.append(f"np = {np}: the smooth pipe's tractions have a "
                            f"moment about its centre ({worst:.1e} of F D)")
    dips = [(s["step"], round(b / a - 1, 4))
            for s, a, b in zip(steps[1:], V, V[1:]) if b < (1 - args.max_dip) * a]
    if dips:
        problems.append(f"np = {np}: the resistance falls by more than "
                        f"{args.max_dip:.0%} at steps {dips}")

runs = list(forces.items())
for np, V in runs[1:]:
    first = runs[0][1]
    for k, (a, b) in enumerate(zip(first, V)):
        if abs(a - b) > args.agree * abs(a):
            problems.append(f"np = {np}, step {k + 1}: {b} against {a} at "
                            f"np = {runs[0][0]}")
            break

for p in problems:
    print("FAIL:", p)
sys.exit(1 if problems else 0)
