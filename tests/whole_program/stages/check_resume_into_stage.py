#!/usr/bin/env python3
"""A checkpoint written at the end of a scene's first stage is resumed into
its second stage with that stage's parameters changed (more load steps), as
a user runs several works from one ground state: the resumed run must take
the changed stage (its steps in summary.json, the stage's limit load as
that of a whole run with the same parameters, to 1e-9), and a change to
the stage already run must be refused with a message that names it.

Usage: check_resume_into_stage.py --bsmpm B --prm P
"""
import argparse
import json
import os
import pathlib
import subprocess
import sys
import tempfile

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[2]))
from bsmpm_run import run  # noqa: E402  (tests/bsmpm_run.py)

parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
parser.add_argument("--bsmpm", required=True)
parser.add_argument("--prm", required=True)
args = parser.parse_args()
problems = []
quiet = ["Output/Interval=0", "Output/Timing summary=false"]

with tempfile.TemporaryDirectory() as directory:
    first = os.path.join(directory, "first")
    whole = os.path.join(directory, "whole")
    # Stage 1 has 2 steps: the checkpoint of step 2 is its end.
    run(args.bsmpm, args.prm, 1,
        quiet + ["Output/Checkpoint interval=2",
                 "Stages/Stage 2/Load steps=1"], first)
    checkpoint = os.path.join(first, "checkpoint-2")
    if not os.path.isdir(checkpoint):
        sys.exit(f"no checkpoint at the end of stage 1 in {first}")
    refused = subprocess.run(
        [args.bsmpm, "--resume", checkpoint,
         "--set", "Stages/Stage 1/Load steps=3"],
        capture_output=True, text=True)
    if refused.returncode == 0 or "Stages/Stage 1/Load steps" not in \
            refused.stderr + refused.stdout:
        problems.append("a change to stage 1 on resume was not refused: "
                        + (refused.stderr + refused.stdout)[-300:])
    resumed = subprocess.run(
        [args.bsmpm, "--resume", checkpoint,
         "--set", "Stages/Stage 2/Load steps=30"],
        capture_output=True, text=True)
    if resumed.returncode != 0:
        sys.exit("the resumed run failed: " + resumed.stderr[-500:])
    with open(os.path.join(first, "summary.json")) as f:
        after = json.load(f)
    reference = run(args.bsmpm, args.prm, 1, quiet, whole)

stage_2 = [s for s in after["steps"] if s["stage"] == 2]
print(f"resumed: {len(stage_2)} steps in stage 2, limit load factor "
      f"{after['quantities'].get('limit_load_factor')}; whole run "
      f"{reference['quantities'].get('limit_load_factor')}")
if after["load_steps"] != 32:
    problems.append(f"load_steps {after['load_steps']}, not 2 + 30")
if len(stage_2) < 20:
    problems.append(f"{len(stage_2)} steps in stage 2: the resumed run did "
                    "not take its 30 steps up to the limit load")
a = after["quantities"].get("limit_load_factor")
b = reference["quantities"].get("limit_load_factor")
if a is None or b is None or abs(a - b) > 1e-9:
    problems.append(f"limit load factor {a} after resuming, {b} in the "
                    "whole run")
for p in problems:
    print("FAILED:", p)
sys.exit(1 if problems else 0)
