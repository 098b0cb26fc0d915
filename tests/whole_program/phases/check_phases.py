#!/usr/bin/env python3
"""Runs a scene and checks which timed phases it went through: a phase that a
scene does not need must never be entered (its TimerOutput section is then
absent from summary.json's timing).

Usage: check_phases.py BSMPM PRM --absent a,b,... --present c,d,... [--set ...]
"""
import argparse
import pathlib
import sys

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[2]))
from bsmpm_run import run  # noqa: E402  (tests/bsmpm_run.py)

parser = argparse.ArgumentParser()
parser.add_argument("bsmpm")
parser.add_argument("prm")
parser.add_argument("--absent", default="")
parser.add_argument("--present", default="")
parser.add_argument("--set", action="append", default=[])
args = parser.parse_args()

timing = run(args.bsmpm, args.prm,
             settings=["Output/Timing summary=false"] + args.set)["timing"]

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
