#!/usr/bin/env python3
"""Runs a scene and checks which timed phases it went through: a phase that a
scene does not need must never be entered (its TimerOutput section is then
absent from summary.json's timing).

Usage: check_phases.py BSMPM PRM --absent a,b,... --present c,d,... [--set ...]
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile

parser = argparse.ArgumentParser()
parser.add_argument("bsmpm")
parser.add_argument("prm")
parser.add_argument("--absent", default="")
parser.add_argument("--present", default="")
parser.add_argument("--set", action="append", default=[])
args = parser.parse_args()

with tempfile.TemporaryDirectory() as tmp:
    command = [args.bsmpm, args.prm, "--set", f"Output/Directory={tmp}",
               "--set", "Output/Timing summary=false"]
    for s in args.set:
        command += ["--set", s]
    subprocess.run(command, check=True, stdout=subprocess.DEVNULL)
    with open(os.path.join(tmp, "summary.json")) as f:
        timing = json.load(f)["timing"]

failed = False
for phase in filter(None, args.absent.split(",")):
    ok = phase not in timing
    print(f"{phase}: {'absent' if ok else 'PRESENT but not needed'}")
    failed |= not ok
for phase in filter(None, args.present.split(",")):
    ok = phase in timing
    print(f"{phase}: {'present' if ok else 'MISSING'}")
    failed |= not ok
print("phases as expected" if not failed else "FAILED")
sys.exit(1 if failed else 0)
