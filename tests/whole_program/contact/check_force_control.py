#!/usr/bin/env python3
"""A rigid body under a prescribed force, its motion solved for
(doc/contact.md, "Rigid bodies under a force"), against the same body
moved by a prescribed displacement.

1. The displacement-driven run (the scene as it is, at np = 1) gives the
   force F on the body and its displacement u.
2. The same scene with 'Rigid body 1/Displacement = <x>; free' and a
   Force that passes through minus the forces of 1. at the load steps'
   factors (linear in t between them) must give, at every step, the same
   displacement (to --tolerance, relative: the Newton tolerance's scale),
   the force on the body equal to minus the applied one, and, with
   --width, the same contact half-width at the end (the far end of the last
   touching piece in contact-NNNN.csv: Hertz's disc). Each step then solves
   the problem of the displacement-driven step (the points move between
   steps, so a force linear in t would not: the elastic footing in two
   steps moved 1.6e-4 less than the displacement that gave its force).
3. With --np 2: the force-driven run at np = 2 must equal that at np = 1.
4. With --bad-input: contradictory input (a component with both a
   Displacement and a Force) is refused with a message, and so is a force
   that pulls the body off the soil ('nothing resists').
5. With --check-tangent: the force-driven run compares the contact's
   tangent, with the body's bordered terms, with central differences
   (Contact/Check tangent): the largest relative difference must stay
   below 1e-6.
"""
import argparse
import csv
import glob
import os
import pathlib
import sys
import tempfile

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[2]))
from bsmpm_run import run  # noqa: E402  (tests/bsmpm_run.py)

parser = argparse.ArgumentParser(description=__doc__)
parser.add_argument("--bsmpm", required=True)
parser.add_argument("--prm", required=True)
parser.add_argument("--np", type=int, default=1)
parser.add_argument("--set", action="append", default=[])
parser.add_argument("--tolerance", type=float, default=1e-6)
parser.add_argument("--width", action="store_true",
                    help="compare the contact half-width too")
parser.add_argument("--bad-input", action="store_true")
parser.add_argument("--check-tangent", action="store_true")
args = parser.parse_args()
problems = []


def body(settings, np=1, expect_success=True):
    with tempfile.TemporaryDirectory() as directory:
        summary, result = run(args.bsmpm, args.prm, np, args.set + settings,
                              directory, output=True, check=expect_success)
        if not expect_success:
            return result
        for line in result.stdout.splitlines():
            if "touched nothing" in line:
                print(line.strip())
        q = summary["steps"][-1]["quantities"]
        width = None
        if args.width:
            files = sorted(glob.glob(os.path.join(directory,
                                                  "contact-*.csv")))
            rows = [r for r in csv.DictReader(open(files[-1]))
                    if r["body"] == "1"]
            width = max(float(r["x"]) + float(r["length"]) / 2
                        for r in rows)
        iterations = [len(s["newton_residuals"]) for s in summary["steps"]
                      if "newton_residuals" in s]
        steps = [(s["load_factor"], s["quantities"]) for s in summary["steps"]]
        return q, width, iterations, steps


def describe(name, result):
    q, width, iterations, _ = result
    text = (f"{name}: displacement ({q['rigid_body_1_displacement_x']:.9g}, "
            f"{q['rigid_body_1_displacement_y']:.9g}) m, force "
            f"({q['rigid_body_1_force_x']:.9g}, "
            f"{q['rigid_body_1_force_y']:.9g}) N/m")
    if width is not None:
        text += f", half-width {width:.9g} m"
    if iterations:
        text += f", Newton iterations per step {iterations}"
    print(text)


# The output of the last step only (the contact pressures for --width).
settings = ["Output/Interval=1000000"]
driven = body(settings)
describe("displacement-driven", driven)
q = driven[0]
u_x = q["rigid_body_1_displacement_x"]
force_y = q["rigid_body_1_force_y"]
# The applied force: minus the measured force at each step's load factor,
# linear in between (from zero at t = 0).
knots = [(0.0, 0.0)] + [(t, -s["rigid_body_1_force_y"])
                        for t, s in driven[3]]
expression = repr(knots[-1][1])
for (t0, f0), (t1, f1) in reversed(list(zip(knots, knots[1:]))):
    expression = (f"if(t <= {t1!r}, {f0!r} + ({f1!r} - {f0!r}) * "
                  f"(t - {t0!r}) / ({t1!r} - {t0!r}), {expression})")
forced_settings = settings + [
    f"Rigid body 1/Displacement={u_x!r}*t; free",
    f"Rigid body 1/Force=0; {expression}"]
forced = body(forced_settings + (["Contact/Check tangent=true"]
                                 if args.check_tangent else []))
describe("force-driven", forced)
qf = forced[0]
if args.check_tangent:
    error = qf["contact_tangent_error"]
    print(f"contact tangent against central differences: largest relative "
          f"difference {error:.3g}")
    if not error < 1e-6:
        problems.append("the contact tangent differs from the differences")

for (t, sd), (_, sf) in zip(driven[3], forced[3]):
    u = sd["rigid_body_1_displacement_y"]
    difference = abs(sf["rigid_body_1_displacement_y"] - u)
    print(f"t = {t:.4g}: displacement {sf['rigid_body_1_displacement_y']:.9g}"
          f" against {u:.9g} m, difference {difference:.3g} "
          f"({difference / abs(u):.3g} relative); force on the body "
          f"{sf['rigid_body_1_force_y']:.9g}, applied "
          f"{sf['rigid_body_1_applied_force_y']:.9g} N/m")
    if not difference <= args.tolerance * abs(u):
        problems.append(f"t = {t}: the force-driven body does not move as "
                        f"far as the displacement-driven one")
    balance = abs(sf["rigid_body_1_force_y"] +
                  sf["rigid_body_1_applied_force_y"])
    if not balance <= args.tolerance * abs(sd["rigid_body_1_force_y"]) or \
            abs(sf["rigid_body_1_applied_force_y"] +
                sd["rigid_body_1_force_y"]) > \
            1e-12 * abs(sd["rigid_body_1_force_y"]):
        problems.append(f"t = {t}: the contact force does not balance the "
                        f"applied force")
if len(forced[3]) != len(driven[3]):
    problems.append("the runs have different numbers of steps")
if args.width and abs(forced[1] - driven[1]) > 1e-9:
    problems.append("the half-widths differ")

if args.np > 1:
    parallel = body(forced_settings, np=args.np)
    describe(f"force-driven, np = {args.np}", parallel)
    qp = parallel[0]
    for key in ["rigid_body_1_displacement_y", "rigid_body_1_force_y"]:
        if abs(qp[key] - qf[key]) > 1e-8 * abs(qf[key]):
            problems.append(f"{key} at np = {args.np} differs from np = 1")

if args.bad_input:
    result = body(["Rigid body 1/Displacement=0; -0.1*t",
                   "Rigid body 1/Force=0; -100*t"], expect_success=False)
    message = result.stdout + result.stderr
    print("both a Displacement and a Force:",
          message.strip().splitlines()[-1] if message.strip() else "")
    if result.returncode == 0 or \
            "either displacement-controlled" not in message:
        problems.append("a component with both a Displacement and a Force "
                        "was not refused")
    result = body(["Rigid body 1/Displacement=0; free",
                   f"Rigid body 1/Force=0; {abs(force_y)!r}*t"],
                  expect_success=False)
    message = result.stdout + result.stderr
    print("a force away from the body:",
          message.strip().splitlines()[-1] if message.strip() else "")
    if result.returncode == 0 or "nothing resists" not in message:
        problems.append("a force that pulls the body away was not refused")

for p in problems:
    print("FAIL:", p)
sys.exit(1 if problems else 0)
