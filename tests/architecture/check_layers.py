#!/usr/bin/env python3
"""The subsystems of bsmpm are layers: a file may include headers of its own
subsystem and of those below it, never of one above (doc/architecture.md).
Checks every header and source of the library, lists each offending include
and exits 1 if there is any."""
import pathlib
import re
import sys

# Bottom to top. The whole analyses (analysis/: the Scene that orders a
# load step, the strength reduction that runs scenes as trials) stand above
# io, and the driver (source/main.cc) above all; the driver's parts
# (command line, parameter files, sweeps, error reports) are io.
LAYERS = ["base", "linear_algebra", "geometry", "materials", "points",
          "bodies", "verification", "boundary", "quadrature", "contact",
          "assembly", "nonlinear", "io", "analysis"]
TOP = len(LAYERS)

root = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else
                    pathlib.Path(__file__).resolve().parents[2])
include = re.compile(r'^\s*#\s*include\s*<bsmpm/(?:(\w+)/)?(\w+)\.h>')


def level(subsystem):
    if subsystem is None:
        return TOP
    if subsystem not in LAYERS:
        raise SystemExit(f"unknown subsystem '{subsystem}': add it to LAYERS "
                         "and to doc/architecture.md")
    return LAYERS.index(subsystem)


problems = []
n_files = 0
for folder in ("include/bsmpm", "source"):
    base = root / folder
    for path in sorted(base.rglob("*")):
        if path.suffix not in (".h", ".cc"):
            continue
        n_files += 1
        relative = path.relative_to(base)
        own = relative.parts[0] if len(relative.parts) > 1 else None
        for number, line in enumerate(path.read_text().splitlines(), 1):
            match = include.match(line)
            if match and level(match.group(1)) > level(own):
                problems.append(f"{folder}/{relative}:{number}: "
                                f"{own or 'top'} includes {match.group(1)}/"
                                f"{match.group(2)}.h from a layer above")

for problem in problems:
    print(problem)
print(f"{n_files} files checked against the layers {' < '.join(LAYERS)}")
if n_files < 40:
    print("too few files found: wrong root?")
    sys.exit(1)
sys.exit(1 if problems else 0)
