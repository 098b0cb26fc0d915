#!/usr/bin/env python3
"""How the test scripts start bsmpm: one place for the command line (mpirun
and its flags, the parameter file, --set assignments, the output directory)
and for reading what a run wrote (summary.json).

    import sys, pathlib
    sys.path.insert(0, "<the repository>/tests")
    from bsmpm_run import run
    summary = run(bsmpm, prm, np=2, settings=["Loading/Load steps=2"])

run() is what a script calls for a run it waits for; command() gives the
command line alone, for a script that starts the process itself (to kill
it, or under strace), and kill_session() ends such a process with its
ranks.

As a program it runs bsmpm once and prints nothing unless the run fails
(for tests written in CMake, tests/whole_program/paraview):

    bsmpm_run.py --bsmpm B --prm P [--np N] [--mpirun M] [--directory D]
                 [--set A/B=v]...

and `bsmpm_run.py --mpirun-flags` prints the flags mpirun gets, which
tests/CMakeLists.txt gives deal.II's own mpirun tests too.
"""
import argparse
import json
import os
import pathlib
import signal
import subprocess
import sys
import tempfile

# Open MPI refuses to start as root (CI runs as root) and to start more
# ranks than there are cores unless told.
MPIRUN_FLAGS = ["--allow-run-as-root", "--oversubscribe"]


def command(bsmpm, prm=None, np=1, settings=(), directory=None,
            arguments=(), mpirun="mpirun", mpirun_options=()):
    """The command line of one run: bsmpm on the parameter file @p prm (none
    if None, e.g. with @p arguments ["--resume", DIR]) with the further
    @p arguments, Output/Directory=@p directory (unless None) and each of
    @p settings ("Section/Name=value") as a --set, under
    `mpirun -np @p np` when np > 1 (with @p mpirun_options)."""
    launcher = [] if np == 1 else [mpirun, *MPIRUN_FLAGS, *mpirun_options,
                                   "-np", str(np)]
    line = launcher + [str(pathlib.Path(bsmpm).resolve()), *arguments]
    if prm is not None:
        line.append(str(pathlib.Path(prm).resolve()))
    if directory is not None:
        line += ["--set", f"Output/Directory={directory}"]
    for setting in settings:
        line += ["--set", setting]
    return line


def kill_session(process):
    """SIGKILL to every process of @p process's session (mpirun and its
    ranks; start it with start_new_session=True), by their ids."""
    try:
        session = os.getsid(process.pid)
    except ProcessLookupError:
        process.wait()
        return
    for entry in os.listdir("/proc"):
        if not entry.isdigit():
            continue
        try:
            if os.getsid(int(entry)) == session:
                os.kill(int(entry), signal.SIGKILL)
        except (ProcessLookupError, PermissionError):
            pass
    process.wait()


class RunFailed(SystemExit):
    """A run that ended with an exit code other than 0, or did not end
    within its timeout (returncode None). A SystemExit: a script that does
    not catch it ends with the run's command line and the end of its
    output as the message."""

    def __init__(self, line, returncode, stdout, stderr):
        self.command, self.returncode = line, returncode
        self.stdout, self.stderr = stdout, stderr
        how = ("did not end in time" if returncode is None else
               f"exit code {returncode}")
        super().__init__(f"bsmpm failed ({how}): {' '.join(line)}\n"
                         f"{stdout[-2000:]}{stderr[-2000:]}")


def run(bsmpm, prm, np=1, settings=(), directory=None, *, arguments=(),
        output=False, check=True, timeout=None, mpirun="mpirun", cwd=None):
    """Runs bsmpm (see command() for @p prm, @p np, @p settings and
    @p arguments) and returns its summary.json, parsed (None if the run
    wrote none), or with @p output the pair (summary, result), result the
    subprocess.CompletedProcess with returncode, stdout and stderr.

    The run writes into @p directory, or into a temporary directory that is
    gone on return if None. A run without a parameter file (--resume) is
    not given one: @p directory then says where to read summary.json.

    A run that fails raises RunFailed, unless @p check is False; one that
    takes longer than @p timeout seconds is killed with its ranks and
    raises RunFailed whatever @p check."""
    with tempfile.TemporaryDirectory() as temporary:
        if directory is None and prm is not None:
            directory = temporary
        line = command(bsmpm, prm, np, settings,
                       directory if prm is not None else None, arguments,
                       mpirun)
        # Under a timeout in a session of its own, so that mpirun and its
        # ranks can be killed together.
        process = subprocess.Popen(line, stdout=subprocess.PIPE,
                                   stderr=subprocess.PIPE, text=True,
                                   errors="replace", cwd=cwd,
                                   start_new_session=timeout is not None)
        try:
            stdout, stderr = process.communicate(timeout=timeout)
        except subprocess.TimeoutExpired:
            kill_session(process)
            stdout, stderr = process.communicate()
            raise RunFailed(line, None, stdout, stderr)
        if check and process.returncode != 0:
            raise RunFailed(line, process.returncode, stdout, stderr)
        summary = None
        if directory is not None:
            path = pathlib.Path(directory) / "summary.json"
            if path.is_file():
                summary = json.loads(path.read_text())
    if output:
        return summary, subprocess.CompletedProcess(line, process.returncode,
                                                    stdout, stderr)
    return summary


def check_relative(problems, what, value, expected, tolerance):
    """Prints @p value against @p expected with its relative error, and
    appends @p what to the list @p problems if that exceeds @p tolerance."""
    error = abs(value - expected) / abs(expected)
    print(f"{what}: {value:.10e} (exact {expected:.10e}, relative error "
          f"{error:.2e}, tolerance {tolerance:g})")
    if not error <= tolerance:
        problems.append(what)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--mpirun-flags", action="store_true",
                        help="print the flags mpirun gets and exit")
    parser.add_argument("--bsmpm")
    parser.add_argument("--prm")
    parser.add_argument("--np", type=int, default=1)
    parser.add_argument("--mpirun", default="mpirun")
    parser.add_argument("--directory")
    parser.add_argument("--set", action="append", default=[])
    args = parser.parse_args()
    if args.mpirun_flags:
        print(" ".join(MPIRUN_FLAGS))
        return 0
    if not args.bsmpm or not args.prm:
        parser.error("--bsmpm and --prm are needed")
    run(args.bsmpm, args.prm, args.np, args.set, args.directory,
        mpirun=args.mpirun)
    return 0


if __name__ == "__main__":
    sys.exit(main())
