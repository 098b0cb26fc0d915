#!/usr/bin/env python3
"""Kills a run with SIGKILL in the middle of a load step, resumes it with
bsmpm --resume and checks that it ends as the same run left alone does:
every step record, error and quantity of summary.json to round-off, and
the same ParaView collection (solution.pvd). Checks on the way that the
killed run left at most two complete checkpoints and that a resumed run
removes a half-written one.

Usage: kill_and_resume.py --bsmpm B --prm P [--np N] [--mpirun M]
           [--set "A/B=v" ...]
"""
import argparse
import json
import os
import pathlib
import shutil
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[2]))
from bsmpm_run import command, kill_session, run  # noqa: E402

parser = argparse.ArgumentParser()
parser.add_argument("--bsmpm", required=True)
parser.add_argument("--prm", required=True)
parser.add_argument("--np", type=int, default=1)
parser.add_argument("--mpirun", default="mpirun")
parser.add_argument("--set", action="append", default=[])
parser.add_argument("--kill-after", type=int, default=2,
                    help="kill once checkpoint-<this> exists")
parser.add_argument("--tolerance", type=float, default=0.,
                    help="relative; 0 asks for every number bitwise")
args = parser.parse_args()


# Every run: a checkpoint and ParaView's files after every step.
SETTINGS = args.set + ["Output/Interval=1", "Output/Timing summary=false",
                       "Output/Checkpoint interval=1"]


def checkpoints(directory):
    return sorted(n for n in os.listdir(directory)
                  if n.startswith("checkpoint-"))


def solver_round_off(path, a, b):
    """Whether a and b are records of the linear solver that may differ when
    the solver itself does not repeat its round-off (--tolerance > 0): its
    relative residual, both at round-off, and the refinement steps it
    took to get there."""
    if args.tolerance == 0:
        return False
    if path.endswith("/refinement_steps"):
        return True
    return (path.endswith("/relative_residual") and a is not None
            and b is not None and max(abs(a), abs(b)) <= 1e-9)


def compare(a, b, path=""):
    """Differences between two summaries, numbers relative to their size."""
    if solver_round_off(path, a, b):
        return []
    if isinstance(a, dict):
        if set(a) != set(b):
            return [f"{path}: keys {sorted(set(a) ^ set(b))}"]
        return sum((compare(a[k], b[k], f"{path}/{k}") for k in a), [])
    if isinstance(a, list):
        if len(a) != len(b):
            return [f"{path}: {len(a)} against {len(b)} entries"]
        return sum((compare(x, y, f"{path}[{i}]")
                    for i, (x, y) in enumerate(zip(a, b))), [])
    if isinstance(a, float) or isinstance(b, float):
        if a is None or b is None:
            return [] if a is b else [f"{path}: {a} against {b}"]
        scale = max(abs(a), abs(b), 1e-300)
        return ([] if abs(a - b) <= args.tolerance * scale else
                [f"{path}: {a!r} against {b!r}"])
    return [] if a == b else [f"{path}: {a!r} against {b!r}"]


work = tempfile.mkdtemp(prefix="bsmpm-resume-")
try:
    whole, killed = os.path.join(work, "whole"), os.path.join(work, "killed")
    run(args.bsmpm, args.prm, args.np, SETTINGS, whole, timeout=300,
        mpirun=args.mpirun)

    # The same run, killed once checkpoint-<k> exists: during step k + 1
    # (or while it writes its checkpoint).
    process = subprocess.Popen(command(args.bsmpm, args.prm, args.np,
                                       SETTINGS, killed, mpirun=args.mpirun),
                               stdout=subprocess.DEVNULL,
                               stderr=subprocess.DEVNULL,
                               start_new_session=True)
    marker = os.path.join(killed, f"checkpoint-{args.kill_after}")
    start = time.time()
    while not os.path.isdir(marker) and process.poll() is None:
        if time.time() - start > 300:
            kill_session(process)
            raise SystemExit("no checkpoint appeared within 300 s")
        time.sleep(0.002)
    if process.poll() is not None:
        raise SystemExit(f"the run ended (code {process.returncode}) before "
                         f"checkpoint-{args.kill_after}: nothing to kill")
    time.sleep(0.05)
    kill_session(process)
    # summary.json is written after every step; a finished run's says so.
    summary = os.path.join(killed, "summary.json")
    if os.path.exists(summary) and \
            json.load(open(summary)).get("status") == "completed":
        raise SystemExit("the run finished before it was killed: give it "
                         "more load steps")
    left = checkpoints(killed)
    complete = [c for c in left if not c.endswith(".tmp")]
    print("killed; left:", ", ".join(left))
    if not 1 <= len(complete) <= 2:
        raise SystemExit(f"{len(complete)} complete checkpoints left, "
                         f"expected 1 or 2")

    # A half-written checkpoint must be ignored and later removed.
    latest = max(complete, key=lambda c: int(c.split("-")[1]))
    half = os.path.join(killed, f"checkpoint-{10**6}.tmp")
    shutil.copytree(os.path.join(killed, latest), half)
    os.remove(os.path.join(half, "state"))

    output = run(args.bsmpm, None, args.np, arguments=["--resume", killed],
                 output=True, timeout=300, mpirun=args.mpirun)[1].stdout
    print(output.splitlines()[0])
    if f"checkpoint-{int(latest.split('-')[1])}" not in output.splitlines()[0]:
        raise SystemExit(f"did not resume from the latest, {latest}")
    if any(c.endswith(".tmp") for c in checkpoints(killed)):
        raise SystemExit("a half-written checkpoint was not removed: "
                         + ", ".join(checkpoints(killed)))
    if len(checkpoints(killed)) > 2:
        raise SystemExit("more than two checkpoints kept: "
                         + ", ".join(checkpoints(killed)))

    summaries = []
    for d in (whole, killed):
        with open(os.path.join(d, "summary.json")) as f:
            s = json.load(f)
            summaries.append({k: s[k] for k in s if k != "timing"})
    problems = compare(*summaries)
    with open(os.path.join(whole, "solution.pvd")) as a, \
            open(os.path.join(killed, "solution.pvd")) as b:
        if a.read() != b.read():
            problems.append("solution.pvd differs")
    for p in problems:
        print("DIFFERENT", p)
    if problems:
        raise SystemExit(1)
    print(f"resumed run equals the whole run ({len(summaries[0]['steps'])} "
          f"steps, np = {args.np})")
finally:
    shutil.rmtree(work, ignore_errors=True)
