#!/usr/bin/env python3
"""Resumes a serial run from its checkpoint while another serial bsmpm
process starts and ends, and checks that every resume succeeds and that
the runs leave nothing behind in TMPDIR.

Serial runs are Open MPI singletons. In Open MPI 4.1 every isolated
singleton has the same job name (0:1), hence the same session directory
<tmp>/ompi.<host>.<uid>/jf.0/1, and each one removes it at MPI_Finalize
(rmdir, it is empty) while others may still be running. The
shared-file-pointer component "sm" of MPI-IO, selected at every
MPI_File_open (deal.II's triangulation load and save), first creates and
removes a probe file in that directory, then Open MPI tries the other
components ("lockedfile" creates and removes <file>.locktest.0 next to
the opened file), and then "sm" creates the file it keeps, again in that
directory: if another singleton ended in between, that fails and the
open with it (MPI_ERR_OTHER, "mca_sharedfp_sm_file_open: Error, unable
to open file for mmap").

That window is a fraction of a millisecond. Here strace holds it open:
the resume's creation of the locktest file of the fixed-size data
returns only after --hold seconds; once the file is seen, another bsmpm
process is started, and it has to end before the hold does. The other
process is by turns one that fails at once (--resume of a directory that
does not exist) and a short run of the same scene; both start and end
MPI. Every process gets a private TMPDIR, so that no process other than
this test's is involved. Without strace the test is skipped (exit 77).

Usage: concurrent_resume.py --bsmpm B --prm P [--tries N] [--hold S]
           [--count]
"""
import argparse
import os
import pathlib
import shutil
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[2]))
from bsmpm_run import command  # noqa: E402  (tests/bsmpm_run.py)

parser = argparse.ArgumentParser()
parser.add_argument("--bsmpm", required=True)
parser.add_argument("--prm", required=True)
parser.add_argument("--tries", type=int, default=2)
parser.add_argument("--hold", type=float, default=6.0,
                    help="seconds the resume is held in the window")
parser.add_argument("--count", action="store_true",
                    help="do all tries and count the failures instead of "
                    "stopping at the first")
args = parser.parse_args()

strace = shutil.which("strace")
if strace is None:
    print("strace not found: not checked")
    raise SystemExit(77)

work = tempfile.mkdtemp(prefix="bsmpm-concurrent-")
tmp = os.path.join(work, "tmp")
os.makedirs(tmp)
environment = dict(os.environ, TMPDIR=tmp)
for name in list(environment):
    # Session directories or components chosen by the caller: not those
    # under test.
    if name.startswith(("OMPI_MCA_orte_", "OMPI_MCA_sharedfp")):
        del environment[name]


def scene(directory, steps):
    """The command line of a run of the scene into @p directory."""
    return command(args.bsmpm, args.prm, directory=directory,
                   settings=["Output/Interval=0", "Output/Timing summary=false",
                             "Output/Checkpoint interval=1",
                             f"Loading/Load steps={steps}"])


def start(cmd):
    return subprocess.Popen(cmd, stdout=subprocess.PIPE,
                            stderr=subprocess.STDOUT, text=True,
                            env=environment)


failures, unchecked = 0, 0
try:
    origin = os.path.join(work, "origin")
    p = start(scene(origin, 2))
    if p.wait(timeout=300) != 0:
        sys.stdout.write(p.stdout.read())
        raise SystemExit("the run to resume from failed")
    # As if killed after the checkpoint of step 1 (the last step writes
    # none).
    shutil.rmtree(os.path.join(origin, "checkpoint-2"), ignore_errors=True)
    os.remove(os.path.join(origin, "summary.json"))

    for attempt in range(args.tries):
        resumed = os.path.join(work, f"resumed-{attempt}")
        shutil.copytree(origin, resumed)
        locktest = os.path.join(resumed, "checkpoint-1",
                                "triangulation_fixed.data.locktest.0")
        resume = start([
            strace, "-f", "-qq", "-o", os.devnull, "-P", locktest,
            "-e", "trace=openat",
            "-e", f"inject=openat:delay_exit={int(args.hold * 1e6)}",
            *command(args.bsmpm, arguments=["--resume", resumed])])
        begin = time.time()
        while not os.path.exists(locktest) and resume.poll() is None:
            time.sleep(0.005)
        other = "none"
        if resume.poll() is None:
            # In the window: another process starts and ends.
            if attempt % 2 == 0:
                other = "a failing bsmpm"
                line = command(args.bsmpm, arguments=[
                    "--resume", os.path.join(work, "does-not-exist")])
            else:
                other = "a short bsmpm run"
                line = scene(os.path.join(work, f"other-{attempt}"), 1)
            held = time.time()
            start(line).wait(timeout=300)
            if time.time() - held > 0.8 * args.hold or resume.poll() is not None:
                other += " (ended too late, give a longer --hold)"
                unchecked += 1
        output = resume.communicate(timeout=300)[0]
        good = (resume.returncode == 0 and os.path.isfile(
            os.path.join(resumed, "summary.json")))
        print(f"resume {attempt + 1}, meanwhile {other}: "
              + ("ok" if good else f"FAILED ({resume.returncode})"))
        if other == "none":
            print("the resume never created " + locktest +
                  ": another Open MPI than 4.1? nothing checked")
            unchecked += 1
        if not good:
            failures += 1
            sys.stdout.write(output[-3000:])
            if not args.count:
                break
        shutil.rmtree(resumed, ignore_errors=True)

    # What the runs' MPI left in TMPDIR after all ended: empty top-level
    # directories only.
    left = []
    for root, dirs, files in os.walk(tmp):
        if root != tmp or files:
            left += [os.path.join(root, n) for n in dirs + files]
    print(f"{failures} of {attempt + 1} resumes failed; left in TMPDIR: "
          + (", ".join(os.path.relpath(n, tmp) for n in left) or "nothing"))
finally:
    shutil.rmtree(work, ignore_errors=True)
if failures or left:
    raise SystemExit(1)
if unchecked:
    raise SystemExit(77)
