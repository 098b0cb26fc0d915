#!/usr/bin/env python3
"""A rigid body under a prescribed force, its motion solved for
(doc/contact.md, "Rigid bodies under a force"), against the same body
moved by a prescribed displacement.

1. The displacement-driven run (the scene as it is, at np = 1) gives the
   force F on the body and its displacement u.
2. The same scene with 'Rigid body 1/Displacement = <x>; free' and
   'Force = 0; -F*t' (the applied force balances the contact's) must give
   the same displacement u (to --tolerance, relative: the Newton
   tolerance's scale), the force on the body equal to minus the applied one,
   and, with --width, the same contact half-width (the far end of the last
   touching piece in contact-NNNN.csv: Hertz's disc).
3. With --np 2: the force-driven run at np = 2 must equal that at np = 1.
4. With --bad-input: contradictory input (a component with both a
   Displacement and a Force) is refused with a message, and so is a force
   that pulls the body away from everything ('nothing supports it').
5. With --check-tangent: the force-driven run compares the contact's
   tangent, with the body's bordered terms, with central differences
   (Contact/Check tangent): the largest relative difference must stay
   below 1e-6.
"""
import argparse
import csv
import glob
import json
import os
import pathlib
import subprocess
import sys
import tempfile

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


def run(settings, np=1, expect_success=True):
    with tempfile.TemporaryDirectory() as directory:
        command = ([] if np == 1 else
                   ["mpirun", "--allow-run-as-root", "--oversubscribe",
                    "-np", str(np)])
        command += [str(pathlib.Path(args.bsmpm).resolve()),
                    str(pathlib.Path(args.prm).resolve()),
                    "--set", f"Output/Directory={directory}"]
        for s in args.set + settings:
            command += ["--set", s]
        result = subprocess.run(command, capture_output=True, text=True)
        if not expect_success:
            return result
        if result.returncode != 0:
            sys.exit(f"{settings}, np = {np}: exit code {result.returncode}: "
                     f"{result.stdout[-2000:]} {result.stderr}")
        for line in result.stdout.splitlines():
            if "touched nothing" in line:
                print(line.strip())
        summary = json.loads((pathlib.Path(directory) / "summary.json")
                             .read_text())
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
        return q, width, iterations


def describe(name, result):
    q, width, iterations = result
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
driven = run(settings)
describe("displacement-driven", driven)
q = driven[0]
u_x = q["rigid_body_1_displacement_x"]
force_y = q["rigid_body_1_force_y"]
forced_settings = settings + [
    f"Rigid body 1/Displacement={u_x!r}*t; free",
    f"Rigid body 1/Force=0; {-force_y!r}*t"]
forced = run(forced_settings + (["Contact/Check tangent=true"]
                                 if args.check_tangent else []))
describe("force-driven", forced)
qf = forced[0]
if args.check_tangent:
    error = qf["contact_tangent_error"]
    print(f"contact tangent against central differences: largest relative "
          f"difference {error:.3g}")
    if not error < 1e-6:
        problems.append("the contact tangent differs from the differences")

u = q["rigid_body_1_displacement_y"]
difference = abs(qf["rigid_body_1_displacement_y"] - u)
print(f"displacement difference {difference:.3g} m "
      f"({difference / abs(u):.3g} relative)")
if not difference <= args.tolerance * abs(u):
    problems.append("the force-driven body does not move as far as the "
                    "displacement-driven one")
balance = abs(qf["rigid_body_1_force_y"] + qf["rigid_body_1_applied_force_y"])
print(f"force on the body {qf['rigid_body_1_force_y']:.9g}, applied "
      f"{qf['rigid_body_1_applied_force_y']:.9g} N/m")
if not balance <= args.tolerance * abs(force_y) or \
        abs(qf["rigid_body_1_applied_force_y"] + force_y) > \
        1e-12 * abs(force_y):
    problems.append("the contact force does not balance the applied force")
if args.width and abs(forced[1] - driven[1]) > 1e-9:
    problems.append("the half-widths differ")

if args.np > 1:
    parallel = run(forced_settings, np=args.np)
    describe(f"force-driven, np = {args.np}", parallel)
    qp = parallel[0]
    for key in ["rigid_body_1_displacement_y", "rigid_body_1_force_y"]:
        if abs(qp[key] - qf[key]) > 1e-8 * abs(qf[key]):
            problems.append(f"{key} at np = {args.np} differs from np = 1")

if args.bad_input:
    result = run(["Rigid body 1/Displacement=0; -0.1*t",
                  "Rigid body 1/Force=0; -100*t"], expect_success=False)
    message = result.stdout + result.stderr
    print("both a Displacement and a Force:",
          message.strip().splitlines()[-1] if message.strip() else "")
    if result.returncode == 0 or \
            "either displacement- or force-controlled" not in message:
        problems.append("a component with both a Displacement and a Force "
                        "was not refused")
    result = run(["Rigid body 1/Displacement=0; free",
                  f"Rigid body 1/Force=0; {abs(force_y)!r}*t"],
                 expect_success=False)
    message = result.stdout + result.stderr
    print("a force away from the body:",
          message.strip().splitlines()[-1] if message.strip() else "")
    if result.returncode == 0 or "nothing supports it" not in message:
        problems.append("a force that pulls the body away was not refused")

for p in problems:
    print("FAIL:", p)
sys.exit(1 if problems else 0)
