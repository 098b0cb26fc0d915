#!/usr/bin/env python3
"""The figure of doc/contact.md's deep penetration: the bearing pressure
q = F_y / (B/2) of the rough rigid footing of prm/strip-footing-rigid.prm
pushed to u/B = 0.5 in finite strain (100 steps), against u/B, at the
cell sizes given, with Prandtl's (2 + pi) c_u of the surface footing.

Each run is the command of doc/contact.md (the grid raised to y = 5.5 m
for the heave, the scene's 161 points on the top curve). Runs take from
seconds (h = 0.25) to about an hour (h = 0.03125); --summaries takes
summary.json files of runs already made instead, in the order of
--cell-sizes.

Usage: scripts/plot_deep_penetration.py --bsmpm build/bsmpm
           [--cell-sizes 0.125 0.0625] [--summaries a.json b.json]
           [--output doc/figures]
"""
import argparse
import json
import os
import pathlib
import subprocess
import tempfile

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

root = pathlib.Path(__file__).resolve().parents[1]
parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
parser.add_argument("--bsmpm", default=str(root / "build" / "bsmpm"))
parser.add_argument("--cell-sizes", type=float, nargs="+",
                    default=[0.25, 0.125, 0.0625])
parser.add_argument("--summaries", nargs="*", default=[])
parser.add_argument("--output", default=str(root / "doc" / "figures"))
args = parser.parse_args()

B = 2.15                    # the footing's width (half of it modelled)
c_u = 17.320508075688775 / 3 ** 0.5
steps = 100


def run(h, directory):
    command = [args.bsmpm, str(root / "prm" / "strip-footing-rigid.prm"),
               "--set", "Material/Kinematics=finite strain",
               "--set", "Background grid/Upper right corner=4, 5.5",
               "--set", f"Background grid/Cell size={h}",
               "--set", f"Loading/Load steps={steps}",
               "--set", f"Rigid body 1/Displacement=0; {-0.5 * B}*t",
               "--set", "Output/Interval=0",
               "--set", f"Output/Directory={directory}"]
    subprocess.run(command, check=True, stdout=subprocess.DEVNULL)
    return os.path.join(directory, "summary.json")


summaries = list(args.summaries)
with tempfile.TemporaryDirectory() as tmp:
    for h in args.cell_sizes[len(summaries):]:
        summaries.append(run(h, os.path.join(tmp, f"h{h}")))
    plt.figure(figsize=(6, 4))
    for h, path in sorted(zip(args.cell_sizes, summaries), reverse=True):
        with open(path) as f:
            steps_run = json.load(f)["steps"]
        u = [-s["quantities"]["rigid_body_1_displacement_y"] / B
             for s in steps_run]
        q = [s["quantities"]["rigid_body_1_force_y"] / (B / 2)
             for s in steps_run]
        plt.plot(u, q, label=f"h = {h} m")
plt.axhline((2 + 3.141592653589793) * c_u, color="k", ls=":",
            label="Prandtl (2 + pi) c_u")
plt.xlabel("u / B")
plt.ylabel("q = F_y / (B/2) (kPa)")
plt.ylim(bottom=0)
plt.legend(loc="lower right")
plt.tight_layout()
os.makedirs(args.output, exist_ok=True)
plt.savefig(os.path.join(args.output, "deep_penetration.png"), dpi=120)
