#!/usr/bin/env python3
"""A checkpoint is written although a killed run left Open MPI's lock of
the grid's data files taken.

Open MPI's shared-memory shared-file-pointer component guards each file it
opens by name with a POSIX semaphore, /dev/shm/sem.OMPIO_<file name>, which
a process killed in the middle of a checkpoint leaves at 0. This script
plants such semaphores (value 0, as a killed writer leaves them) for the
files deal.II writes, runs two load steps with a checkpoint after each (at
np = 1 and, with --np 2, under mpirun) and asks the runs to end within the
timeout; it removes what it planted. Skipped (77) where there is no
/dev/shm.

Usage: stale_file_lock.py --bsmpm B --prm P [--np N] [--mpirun M]
"""
import argparse
import os
import pathlib
import sys

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[2]))
from bsmpm_run import RunFailed, run  # noqa: E402

parser = argparse.ArgumentParser()
parser.add_argument("--bsmpm", required=True)
parser.add_argument("--prm", required=True)
parser.add_argument("--np", type=int, default=1)
parser.add_argument("--mpirun", default="mpirun")
args = parser.parse_args()

SHM = pathlib.Path("/dev/shm")
if not SHM.is_dir():
    sys.exit(77)

# glibc's sem_t is 32 bytes, the count in the first four: all zero is a
# semaphore already taken, with no one waiting.
planted = []
for name in ("triangulation_fixed.data", "triangulation_variable.data"):
    path = SHM / f"sem.OMPIO_{name}"
    if not path.exists():
        path.write_bytes(bytes(32))
        os.chmod(path, 0o666)
        planted.append(path)

try:
    summary = run(args.bsmpm, args.prm, np=args.np, mpirun=args.mpirun,
                  timeout=120,
                  settings=["Loading/Load steps=2", "Output/Interval=0",
                            "Output/Timing summary=false",
                            "Output/Checkpoint interval=1"])
except RunFailed as failure:
    sys.exit(f"FAILED: {failure}")
finally:
    for path in planted:
        path.unlink(missing_ok=True)

steps = len(summary["steps"])
if steps != 2:
    sys.exit(f"FAILED: {steps} steps recorded, 2 expected")
print(f"two steps with a checkpoint after the first, np = {args.np}, "
      f"despite a taken lock ({len(planted)} planted)")
