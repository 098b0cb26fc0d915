#!/usr/bin/env python3
"""The contact's tangent against central differences of its force
(Contact/Check tangent, ContactTangentCheck): on every touching piece in
every Newton iteration, the stiffness on the cell's DoFs and the rigid
body's translation must agree with the differences of the force to
--tolerance (relative to the piece's largest entry). Each run covers
regimes of the contact law and of the contact terms, and must have
compared pieces in them (sliding ones where it says so):

- a rough rigid cylinder pressed into a block and dragged sideways (the
  outline turns: the turning terms of the pressure and of friction), with
  one pressure per cell and with pressures at the grid lines, both with
  the augmented Lagrangian;
- the block on an incline of a frictional plane (sticking in the middle,
  sliding at the ends: the return map's two branches), per cell and at
  the grid lines;
- the rough strip footing pushed by a force (its vertical motion solved
  for: the bordered terms) with the penalty on the tilt of the gap.

A sign or factor error in any term of the tangent gives a difference of
order one (doc/contact.md).
"""
import argparse
import pathlib
import sys
import tempfile

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1]))
from bsmpm_run import run  # noqa: E402

parser = argparse.ArgumentParser(description=__doc__)
parser.add_argument("--bsmpm", required=True)
parser.add_argument("--prm-directory", required=True,
                    help="the repository's prm/ (the strip footing)")
parser.add_argument("--scene-directory", required=True,
                    help="where cylinder_on_block.prm and block_on_plane.prm "
                    "are (tests/whole_program/contact)")
parser.add_argument("--tolerance", type=float, default=1e-6)
args = parser.parse_args()
here = pathlib.Path(args.scene_directory)
prm = pathlib.Path(args.prm_directory)
problems = []

cylinder = ["Rigid body 1/Displacement=0.01*t; -0.02*t",
            "Rigid body 1/Friction=rough",
            "Contact/Method=augmented Lagrangian"]
footing = ["Material/von Mises/Yield stress=1e10",
           "Loading/Load steps=2",
           "Contact/Method=penalty",
           "Contact/Tilt penalty=1",
           "Rigid body 1/Displacement=0; free",
           "Rigid body 1/Force=0; -600*t"]
# name, parameter file, settings, the regimes its pieces must have been
# compared in
cases = [
    ("cylinder dragged, rough, per cell", here / "cylinder_on_block.prm",
     cylinder + ["Contact/Pressure=per cell"], {"stick"}),
    ("cylinder dragged, rough, at grid lines", here / "cylinder_on_block.prm",
     cylinder + ["Contact/Pressure=at grid lines"], {"stick"}),
    ("block on an incline, per cell", here / "block_on_plane.prm",
     ["Contact/Pressure=per cell"], {"stick", "slip"}),
    ("block on an incline, at grid lines", here / "block_on_plane.prm",
     ["Contact/Pressure=at grid lines"], {"stick", "slip"}),
    ("footing under a force, tilt penalty", prm / "strip-footing-rigid.prm",
     footing, {"stick"}),
]

for name, path, settings, regimes in cases:
    with tempfile.TemporaryDirectory() as directory:
        summary = run(args.bsmpm, path, settings=["Output/Interval=0",
                      "Contact/Check tangent=true"] + settings,
                      directory=directory, check=False)
    if summary is None:
        problems.append(f"{name}: the run wrote no summary.json")
        continue
    # A wrong tangent may also stop Newton (a load-controlled run then
    # reports a limit load).
    if summary.get("status") != "completed" or "limit_load_reason" in summary:
        problems.append(f"{name}: the run stopped: {summary.get('status')}, "
                        f"{summary.get('limit_load_reason', '')}")
    if not summary["steps"]:
        continue
    q = summary["steps"][-1]["quantities"]
    error = q["contact_tangent_error"]
    checks = q["contact_tangent_checks"]
    sliding = q["contact_tangent_checks_sliding"]
    print(f"{name}: largest relative difference {error:.3g} over "
          f"{checks:.0f} pieces ({sliding:.0f} sliding)")
    if not error < args.tolerance:
        problems.append(f"{name}: the contact tangent differs from the "
                        f"central differences by {error:.3g}")
    if not checks > 0:
        problems.append(f"{name}: no piece was compared")
    if "slip" in regimes and not sliding > 0:
        problems.append(f"{name}: no sliding piece was compared")
    if "stick" in regimes and not checks > sliding:
        problems.append(f"{name}: no sticking piece was compared")

for p in problems:
    print("FAIL:", p)
sys.exit(1 if problems else 0)
