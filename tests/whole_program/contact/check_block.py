#!/usr/bin/env python3
"""Coulomb friction on a rigid plane (tests/whole_program/contact/block_on_plane.prm).

1. Stick: the block on a plane inclined by theta with tan(theta) = 0.2 <
   mu = 0.3 stays: the run converges and the force on the plane equals the
   block's weight, in size (rho |g| A) and direction; its moment about the
   plane's centroid is that of a force through the block's centroid (the
   weight's line of action), to 1 % of |F| times their distance.
2. The same on a rough plane: nothing slides.
3. Slip: the plane is dragged sideways by 0.02 m under the block (gravity
   upright) while the grid's left face holds the block's left side: the
   whole base slides, and the plane's tangential force is mu times its
   normal force, the weight.
4. No equilibrium: on an incline with tan(theta) = 0.5 > mu nothing holds
   the block (a quasi-static run cannot follow it sliding away): the run
   must fail with a message, not hang or crash, and say that a body that
   only friction holds has no quasi-static equilibrium.
5. Newton iterations made to fail (a residual tolerance of 1e-30, no
   cuts, no stalled iterate accepted) where friction cannot be the cause:
   the block on the level frictional plane (the pressure holds its weight)
   and the block held at its side on a smooth plane. The run fails, and its
   message must not speak of friction.
6. The plane under the block held at its side, pushed sideways by a force
   (force-controlled) beyond what friction holds: the run fails, saying
   that the frictional surface slides.
"""
import argparse
import math
import pathlib
import sys

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[2]))
from bsmpm_run import run  # noqa: E402  (tests/bsmpm_run.py)

parser = argparse.ArgumentParser(description=__doc__)
parser.add_argument("--bsmpm", required=True)
parser.add_argument("--prm", required=True)
parser.add_argument("--np", type=int, default=1)
args = parser.parse_args()
rho, mu = 1000.0, 0.3
problems = []


def case(name, settings, expect_success=True):
    summary, result = run(args.bsmpm, args.prm, args.np, settings,
                          output=True, check=False)
    if not expect_success:
        print(f"{name}: exit code {result.returncode}; "
              f"{result.stderr.strip()[-300:]}")
        if result.returncode == 0:
            problems.append(f"{name}: the run did not fail")
        return result.stderr
    if result.returncode != 0:
        problems.append(f"{name}: exit code {result.returncode}: "
                        f"{result.stdout[-1500:]} {result.stderr}")
        return None
    q = summary["steps"][-1]["quantities"]
    q["body_area"] = summary["quantities"].get("body_area", q.get("body_area"))
    print(f"{name}: force ({q['rigid_body_1_force_x']:.8g}, "
          f"{q['rigid_body_1_force_y']:.8g}) N/m, contact "
          f"{q['rigid_body_1_contact_length']:.6g} m, sliding "
          f"{q['rigid_body_1_sliding_length']:.6g} m")
    return q


def check_weight(name, q, g):
    weight = rho * math.hypot(*g) * q["body_area"]
    force = math.hypot(q["rigid_body_1_force_x"], q["rigid_body_1_force_y"])
    angle = math.atan2(q["rigid_body_1_force_x"], -q["rigid_body_1_force_y"])
    print(f"  |F| / (rho |g| A) - 1 = {force / weight - 1:.2e}, direction "
          f"off by {angle - math.atan2(g[0], -g[1]):.2e} rad")
    if abs(force / weight - 1) > 1e-3:
        problems.append(f"{name}: the force is not the weight")
    if abs(angle - math.atan2(g[0], -g[1])) > 1e-6:
        problems.append(f"{name}: the force is not along gravity")


def check_moment(name, q):
    # The block's centroid (0, 0.35) less the plane's (0, -0.45): the
    # weight's line of action passes through the block's, and so does the
    # force of the block on the plane (the block moves by about a
    # millimetre, a tenth of the tolerance).
    arm = (0.0, 0.8)
    fx, fy = q["rigid_body_1_force_x"], q["rigid_body_1_force_y"]
    expected = arm[0] * fy - arm[1] * fx
    moment = q["rigid_body_1_moment"]
    print(f"  moment about the plane's centroid {moment:.6g} N m/m, "
          f"through the block's centroid {expected:.6g}")
    if abs(moment - expected) > 0.01 * math.hypot(fx, fy) * math.hypot(*arm):
        problems.append(f"{name}: the force does not act through the "
                        "block's centroid")


g = (1.92339, -9.61694)
q = case("stick, frictional", [])
if q:
    check_weight("stick, frictional", q, g)
    check_moment("stick, frictional", q)
q = case("stick, rough", ["Rigid body 1/Friction=rough"])
if q:
    check_weight("stick, rough", q, g)
    if q["rigid_body_1_sliding_length"] != 0:
        problems.append("stick, rough: a rough plane let the block slide")

drag = ["Loading/Gravity=0, -9.81",
        "Background grid/Lower left corner=-0.4, -0.5",
        "Background grid/Upper right corner=1.1, 1",
        "Background grid/Face conditions/Left=roller",
        "Rigid body 1/Displacement=0.02*t; 0"]
q = case("slip, dragged plane", drag)
if q:
    # Both forces on the plane point back and down.
    ratio = q["rigid_body_1_force_x"] / q["rigid_body_1_force_y"]
    print(f"  F_T / F_N = {ratio:.10g} (mu = {mu})")
    if abs(ratio - mu) > 1e-8:
        problems.append(f"slip: F_T / F_N = {ratio} is not mu")
    if abs(q["rigid_body_1_sliding_length"] -
           q["rigid_body_1_contact_length"]) > 1e-12:
        problems.append("slip: not the whole base slides")
    check_weight("slip, dragged plane",
                 {**q, "rigid_body_1_force_x": 0.0}, (0.0, -9.81))

HINT = "a body that only friction holds has no quasi-static equilibrium"
message = case("no equilibrium", ["Loading/Gravity=4.38577, -8.77154"],
               expect_success=False)
if HINT not in message:
    problems.append("no equilibrium: the message does not say that only "
                    "friction holds the block")

stopped = ["Nonlinear solver/Maximum iterations=2",
           "Nonlinear solver/Residual tolerance=1e-30",
           "Nonlinear solver/Stall tolerance=0",
           "Nonlinear solver/Maximum step cuts=0"]
for name, settings in [
        ("stopped, level frictional plane", ["Loading/Gravity=0, -9.81"]),
        ("stopped, smooth plane, block held at its side",
         drag[:4] + ["Rigid body 1/Friction=smooth"])]:
    message = case(name, stopped + settings, expect_success=False)
    if HINT in message:
        problems.append(f"{name}: the message blames friction")

message = case("pushed beyond friction",
               drag[:4] + ["Rigid body 1/Displacement=free; 0",
                           "Rigid body 1/Force=2000*t; 0"],
               expect_success=False)
if "a frictional one across that direction that the force makes slide" \
        not in message:
    problems.append("pushed beyond friction: the message does not say "
                    "that the frictional surface slides")

for p in problems:
    print("FAIL:", p)
sys.exit(1 if problems else 0)
