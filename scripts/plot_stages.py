#!/usr/bin/env python3
"""The figures of doc/stages.md, from runs of the staged scenes.

- stages_wall.png: the thrust on the smooth wall of
  prm/retaining-wall-active.prm against its motion away from the clay, at
  h = 0.5, 0.25 and 0.125 (the at-rest thrust of the own-weight stage at
  zero), with the wedge's and Rankine's active thrusts;
- stages_wall_passive.png: the same for the wall of
  prm/retaining-wall-passive.prm pushed into the clay, with Rankine's
  passive thrust;
- stages_footing.png: the bearing pressure of the strip footing against its
  settlement in the footing stage of prm/strip-footing-after-weight.prm
  (settlement counted from that stage's start), with the weightless
  prm/strip-footing-collapse.prm and Prandtl's (2 + pi) c_u.

Usage: scripts/plot_stages.py --bsmpm build/bsmpm [--output doc/figures]
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
parser.add_argument("--bsmpm", required=True)
parser.add_argument("--output", default=str(root / "doc" / "figures"))
args = parser.parse_args()


def run(prm, settings, directory):
    command = [args.bsmpm, str(root / "prm" / prm),
               "--set", f"Output/Directory={directory}",
               "--set", "Output/Interval=0"]
    for s in settings:
        command += ["--set", s]
    subprocess.run(command, check=True, stdout=subprocess.DEVNULL)
    with open(os.path.join(directory, "summary.json")) as f:
        return json.load(f)


def plot_wall(prm, direction, tmp, references, xlabel, name):
    """The thrust on the wall of @p prm against its motion (the at-rest
    thrust of the own-weight stage at zero; @p direction -1 for a wall
    pushed towards -x) at h = 0.5, 0.25, 0.125, with the lines
    @p references (value, style, label), into @p name."""
    plt.figure(figsize=(6, 4))
    for h, n in [(0.5, 21), (0.25, 41), (0.125, 81)]:
        s = run(prm,
                [f"Background grid/Cell size={h}",
                 f"Boundary curves/Curve 1/Number of points={n}"],
                os.path.join(tmp, f"{prm}-{h}"))
        at_rest = [x for x in s["steps"] if x["stage"] == 1][-1]
        moving = [x for x in s["steps"] if x["stage"] == 2]
        u = [0] + [direction * x["quantities"]["rigid_body_1_displacement_x"]
                   for x in moving]
        f = [at_rest["quantities"]["rigid_body_1_force_x"]] + \
            [x["quantities"]["rigid_body_1_force_x"] for x in moving]
        plt.plot(u, f, marker=".", label=f"h = {h} m")
    for value, style, label in references:
        plt.axhline(value, color="k", ls=style, label=label)
    plt.xlabel(xlabel)
    plt.ylabel("thrust on the wall (kN/m)")
    plt.legend()
    plt.tight_layout()
    plt.savefig(os.path.join(args.output, name), dpi=120)


with tempfile.TemporaryDirectory() as tmp:
    plot_wall("retaining-wall-active.prm", 1, tmp,
              [(120.75, "--", r"wedge: $\gamma H^2/2 - 2 c_u H$"),
               (132.1, ":", r"Rankine with tension crack")],
              "wall moved away from the clay (m)", "stages_wall.png")
    # Finite strain, smooth base.
    plot_wall("retaining-wall-passive.prm", -1, tmp,
              [(320.7, "--", r"Rankine: $\gamma H^2/2 + 2 c_u H$")],
              "wall pushed into the clay (m)", "stages_wall_passive.png")

    # The footing.
    plt.figure(figsize=(6, 4))
    for prm, label in [("strip-footing-after-weight.prm",
                        "after the own-weight stage"),
                       ("strip-footing-collapse.prm", "weightless clay")]:
        s = run(prm, ["Probe/Point=0.05, 4.05"], os.path.join(tmp, prm))
        last = [x for x in s["steps"] if x["stage"] == s["steps"][-1]["stage"]]
        q = [0] + [77.12 * x["load_factor"] for x in last]
        w = [0] + [x["quantities"]["probe_deflection"] for x in last]
        plt.plot(w, q, marker=".", label=label)
    plt.axhline(51.42, color="k", ls="--", label=r"Prandtl $(2+\pi) c_u$")
    plt.xlabel("settlement in the footing stage (m)")
    plt.ylabel("footing pressure (kPa)")
    plt.legend()
    plt.tight_layout()
    plt.savefig(os.path.join(args.output, "stages_footing.png"), dpi=120)
