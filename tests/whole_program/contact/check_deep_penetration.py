#!/usr/bin/env python3
"""The deep penetration of doc/contact.md: the rough rigid footing of
prm/strip-footing-rigid.prm pushed into von Mises soil in finite strain,
1.075 m (u/B = 0.5) over 100 load steps, the grid raised to y = 5.5 m.

--steps N runs the first N of those load steps only (the footing moved
N * 0.01075 m in N steps of the same size). The run must complete at every
--np given, every step without a cut increment (--no-cuts), the contact
length at every step at least --length times its mean over the run (the
footing keeps its contact), and the runs at several np agree in the force
to --agree.
Prints per step q = F_y / (B/2) (kPa), the contact length and the points
inserted / removed on the curves.

--repeat runs the last np twice and requires the same bits in both.

Suite: h = 0.125, 4 steps, np 1 and 2, the defaults (in finite strain the
pressures at the grid lines). By hand, the full run (doc/contact.md, "Deep
penetration": it completes at h = 0.25 and 0.125, not at 0.0625):

  python3 tests/whole_program/contact/check_deep_penetration.py \
    --bsmpm build/bsmpm \
    --prm prm/strip-footing-rigid.prm --cell-size 0.125 --steps 100 --np 1 2
"""
import argparse
import pathlib
import sys

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[2]))
from bsmpm_run import run  # noqa: E402  (tests/bsmpm_run.py)

parser = argparse.ArgumentParser(description=__doc__)
parser.add_argument("--bsmpm", required=True)
parser.add_argument("--prm", required=True)
parser.add_argument("--cell-size", type=float, default=0.125)
parser.add_argument("--steps", type=int, default=100)
parser.add_argument("--np", type=int, nargs="+", default=[1])
parser.add_argument("--no-cuts", action="store_true")
parser.add_argument("--length", type=float, default=0.5,
                    help="the least contact length allowed, as a fraction "
                    "of the run's mean (a footing that loses its contact)")
parser.add_argument("--agree", type=float, default=1e-6,
                    help="relative difference of the forces between np")
parser.add_argument("--repeat", action="store_true",
                    help="run the last --np a second time: both runs must "
                    "give the same bits in every step's quantities and "
                    "Newton residuals")
parser.add_argument("--set", action="append", default=[])
args = parser.parse_args()
half_width = 1.075
problems = []


def penetration(np):
    summary, result = run(
        args.bsmpm, args.prm, np,
        ["Output/Interval=0", "Material/Kinematics=finite strain",
         "Background grid/Upper right corner=4, 5.5",
         f"Background grid/Cell size={args.cell_size}",
         f"Loading/Load steps={args.steps}",
         f"Rigid body 1/Displacement=0; {-0.01075 * args.steps}*t"]
        + args.set, output=True, check=False)
    if result.returncode != 0 or summary is None:
        problems.append(f"np = {np}: exit code {result.returncode}: "
                        f"{result.stderr[-1500:]}")
    return summary


summaries = {np: penetration(np) for np in args.np}
for np, summary in summaries.items():
    if summary is None:
        continue
    steps = summary["steps"]
    print(f"np = {np}: {summary['status']}, {len(steps)} steps")
    print("step  u/B    q (kPa)  contact (m)  increments  newton  "
          "inserted/removed")
    for s in steps:
        q = s["quantities"]
        inserted = sum(v for k, v in q.items() if k.endswith("_inserted"))
        removed = sum(v for k, v in q.items() if k.endswith("_removed"))
        print(f"{s['step']:4d}  {0.01075 * s['step'] / 2.15:.3f}  "
              f"{q['rigid_body_1_force_y'] / half_width:8.2f}  "
              f"{q['rigid_body_1_contact_length']:.3f}  "
              f"{s['increments']:10d}  "
              f"{len(s.get('newton_residuals', [])):6d}  "
              f"{int(inserted)}/{int(removed)}")
    if len(steps) != args.steps:
        problems.append(f"np = {np}: {len(steps)} of {args.steps} steps")
    if args.no_cuts:
        cut = [s["step"] for s in steps if s["increments"] != 1]
        if cut:
            problems.append(f"np = {np}: steps {cut} were cut")
    lengths = [s["quantities"]["rigid_body_1_contact_length"] for s in steps]
    mean = sum(lengths) / max(1, len(lengths))
    # The length moves by up to a piece as the touching stretch gains or
    # loses one (doc/contact.md); a footing that loses its contact falls
    # far below its mean.
    short = [(s["step"], round(l, 3)) for s, l in zip(steps, lengths)
             if l < args.length * mean]
    if short:
        problems.append(f"np = {np}: contact length below {args.length} "
                        f"of its mean {mean:.3f}: {short}")

runs = [s for s in summaries.values() if s is not None]
for other, np in zip(runs[1:], list(summaries)[1:]):
    for a, b in zip(runs[0]["steps"], other["steps"]):
        fa = a["quantities"]["rigid_body_1_force_y"]
        fb = b["quantities"]["rigid_body_1_force_y"]
        if abs(fa - fb) > args.agree * abs(fa):
            problems.append(f"np = {np}, step {a['step']}: force {fb} "
                            f"against {fa} at np = {args.np[0]}")
            break

if args.repeat and summaries[args.np[-1]] is not None:
    # One run must give the bits of the next: every quantity and Newton
    # residual of every step (MUMPS on two processes added its fronts in
    # the order their messages arrived: two runs parted by 5e-15 .. 3e-13
    # within steps 1 .. 4, doc/contact.md).
    first, again = summaries[args.np[-1]], penetration(args.np[-1])
    if again is not None:
        for a, b in zip(first["steps"], again["steps"]):
            keys = set(a["quantities"]) | set(b["quantities"])
            differ = sorted(k for k in keys
                            if a["quantities"].get(k) != b["quantities"].get(k))
            if differ or a["newton_residuals"] != b["newton_residuals"]:
                problems.append(
                    f"np = {args.np[-1]} run twice: step {a['step']} differs "
                    f"in {differ[:4]}, Newton residuals "
                    f"{'differ' if a['newton_residuals'] != b['newton_residuals'] else 'equal'}"
                    f" (force {a['quantities'].get('rigid_body_1_force_y')!r}"
                    f" against {b['quantities'].get('rigid_body_1_force_y')!r})")
                break
        if len(first["steps"]) != len(again["steps"]):
            problems.append(f"np = {args.np[-1]} run twice: "
                            f"{len(first['steps'])} and {len(again['steps'])} steps")

if problems:
    sys.exit("\n".join(problems))
print("OK")
