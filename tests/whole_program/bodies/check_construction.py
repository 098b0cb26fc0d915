#!/usr/bin/env python3
"""Bodies built by stages (doc/stages.md, "Construction"): the column of
prm/column-built-in-lifts.prm, ground at rest (K0) with two lifts of fill
built on it, in one-dimensional compression. A lift of height H_k and
density rho_k settles the ground's top by

    rho_k g H_k H / M,   M = E (1 - nu) / ((1 + nu) (1 - 2 nu)),

H the ground's height (the lift adds rho_k g H_k to the vertical stress
all through the ground below it).

1. The scene: lift 1, built in one step on the ground's unmoved points,
   to round-off; after lift 2 (on points that lift 1 moved), within
   --moved-tolerance; every body's points and volume in summary.json
   (none before it is built).
2. Lift 1's weight grows with its stage: built in 4 steps, the settlement
   after each is the share s = 1/4 .. 1 of the whole within
   --moved-tolerance (the points move between the steps), and no point of
   lift 1 exists in stage 1 (built_points).
3. The ground's weight by a gravity stage instead of K0: the stage gives
   the exact settlement of self-weight, rho g H^2 / (2 M); lift 1 then
   meets points that the weight moved, within --moved-tolerance.
4. Resumed from the checkpoint between the stages and from one inside the
   building of lift 2, the run ends where the run left alone ends, to
   round-off.
5. In finite strain, both lifts within 2 %.
6. Resumed between the stages with lift 2's density and points changed,
   the run ends where the run with them from the start ends; a change to
   lift 1, already built, is refused.
"""
import argparse
import pathlib
import sys
import tempfile

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[2]))
from bsmpm_run import check_relative, run  # noqa: E402  (tests/bsmpm_run.py)

parser = argparse.ArgumentParser(description=__doc__)
parser.add_argument("--bsmpm", required=True)
parser.add_argument("--prm", required=True)
parser.add_argument("--np", type=int, default=1)
parser.add_argument("--moved-tolerance", type=float, default=0.01)
parser.add_argument("--parts", default="1,2,3,4,5,6",
                    help="which of the checks above to run")
args = parser.parse_args()
parts = {int(p) for p in args.parts.split(",")}

g, H = 9.81, 8.0
E, nu, rho = 1e7, 0.3, 2000.0           # the ground
lifts = [(1800.0, 2.0), (1800.0, 1.0)]  # (density, height) of lift 1, 2
M = E * (1 - nu) / ((1 + nu) * (1 - 2 * nu))
settlement = [-r * g * h * H / M for r, h in lifts]

problems = []


def check(what, value, expected, tolerance):
    check_relative(problems, what, value, expected, tolerance)


def surface(summary):
    return [s["quantities"]["surface_displacement_y"]
            for s in summary["steps"]]


def scene_as_it_is():
    """1. The scene as it is; each body's points and volume in
    summary.json, none before it is built."""
    summary = run(args.bsmpm, args.prm, args.np, ["Output/Interval=0"])
    u = surface(summary)
    check("lift 1 built in one step", u[1], settlement[0], 1e-10)
    check("lift 2 on the moved points", u[2], sum(settlement),
          args.moved_tolerance)
    expected = {1: (128, 8.0), 2: (32, 2.0), 3: (16, 1.0)}
    for step, built in ((0, (1,)), (1, (1, 2)), (2, (1, 2, 3))):
        q = summary["steps"][step]["quantities"]
        for body, (points, volume) in expected.items():
            found = (q[f"body_{body}_points"], q[f"body_{body}_volume"])
            wanted = (points, volume) if body in built else (0, 0)
            if abs(found[0] - wanted[0]) > 0 or \
                    abs(found[1] - wanted[1]) > 1e-12 * volume:
                problems.append(f"step {step + 1}: body {body} has "
                                f"{found}, not {wanted}")


def weight_over_the_stage():
    """2. Lift 1's weight over four steps."""
    summary = run(args.bsmpm, args.prm, args.np,
                  ["Output/Interval=0", "Stages/Number of stages=2",
                   "Body 3/Name=", "Stages/Stage 2/Load steps=4"])
    u = surface(summary)
    for i in range(1, 5):
        check(f"lift 1 at s = {i}/4", u[i], settlement[0] * i / 4,
              args.moved_tolerance)
    built = [s["quantities"].get("built_points", 0)
             for s in summary["steps"]]
    if built[0] != 0 or built[-1] <= 0:
        problems.append(f"built_points {built}: none in stage 1, "
                        "lift 1's after")


def after_a_gravity_stage():
    """3. The ground's weight by a gravity stage."""
    u = surface(run(args.bsmpm, args.prm, args.np,
                    ["Output/Interval=0", "Initial stress/Kind=none",
                     "Stages/Number of stages=2", "Body 3/Name="]))
    check("the ground's own weight", u[0], -rho * g * H * H / (2 * M),
          1e-10)
    check("lift 1 after the weight", u[1] - u[0], settlement[0],
          3 * args.moved_tolerance)


# Checkpoints after every step, lift 2 built over three steps.
CHECKPOINTED = ["Output/Interval=0", "Output/Checkpoint interval=1",
                "Stages/Stage 3/Load steps=3"]


def checkpointed_run(directory):
    """The settlement at the end of the checkpointed run in directory."""
    return surface(run(args.bsmpm, args.prm, args.np, CHECKPOINTED,
                       directory))[-1]


def resumed():
    """4. Resumed between the stages and inside the building of lift 2."""
    with tempfile.TemporaryDirectory() as directory:
        whole = checkpointed_run(directory)
        for checkpoint in ("checkpoint-2", "checkpoint-3"):
            summary = run(args.bsmpm, None, args.np, directory=directory,
                          arguments=["--resume", f"{directory}/{checkpoint}"])
            check(f"resumed from {checkpoint}", surface(summary)[-1], whole,
                  1e-12)
            if summary["steps"][-1]["quantities"]["built_points"] != 48:
                problems.append(f"{checkpoint}: built_points")


def changed_on_resume():
    """6. A body not built yet changes on the resume, one built may not."""
    with tempfile.TemporaryDirectory() as directory:
        whole = checkpointed_run(directory)
        # Lift 2 is not built yet at the end of stage 2: its material and
        # points may change on the resume, as if they had been so from the
        # start; lift 1's may not.
        lift_2 = ["Body 3/Material/Density=3600",
                  "Body 3/Material points/Points per cell=3"]
        changed = surface(run(args.bsmpm, args.prm, args.np,
                              CHECKPOINTED + lift_2))[-1]
        summary = run(args.bsmpm, None, args.np, directory=directory,
                      arguments=["--resume", f"{directory}/checkpoint-2",
                                 *[a for s in lift_2 for a in ("--set", s)]])
        check("resumed with lift 2 changed", surface(summary)[-1], changed,
              1e-12)
        check("lift 2 twice as heavy", changed - whole, settlement[1],
              args.moved_tolerance)
        _, result = run(args.bsmpm, None, args.np, directory=directory,
                        arguments=["--resume", f"{directory}/checkpoint-2",
                                   "--set", "Body 2/Material/Density=1"],
                        output=True, check=False)
        if result.returncode == 0 or "is in stage 2" not in result.stderr:
            problems.append("a change to lift 1 on the resume after it was "
                            "built was not refused")


def finite_strain():
    """5. In finite strain (the ground's K0 stress makes it a little
    stiffer than M: measured 0.97 % less settlement)."""
    u = surface(run(args.bsmpm, args.prm, args.np,
                    ["Output/Interval=0", "Material/Kinematics=finite strain"]))
    check("lift 1 in finite strain", u[1], settlement[0], 0.02)
    check("lift 2 in finite strain", u[2], sum(settlement), 0.02)


for number, part in enumerate([scene_as_it_is, weight_over_the_stage,
                               after_a_gravity_stage, resumed,
                               finite_strain, changed_on_resume], start=1):
    if number in parts:
        part()

if problems:
    sys.exit("FAILED: " + "; ".join(problems))
print("all checks passed")
